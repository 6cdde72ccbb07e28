#include "physics/table/table.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace snooker::physics {
namespace {

constexpr double kSqrt2 = 1.41421356237309504880;
constexpr double kSqrt3 = 1.73205080756887729353;

// One jaw before it is built: the end of the cushion nose and the nose's frame.
struct JawFrame {
  Vec2 nose_normal;  // unit, into the playing area
  Vec2 towards;      // unit, along the nose towards the pocket
};

// How a pocket sits on the table: its corner (or middle point) K where the nose
// lines meet, and the frames of its two jaws. A jaw's nose ends at K - h * towards,
// h being half the mouth width (middle) or mouth / sqrt 2 (corner).
struct PocketLayout {
  PocketId id;
  bool corner;
  double kx, ky;  // K in units of (width, length)
  std::array<JawFrame, 2> jaw;
};

const std::array<PocketLayout, kPocketCount>& Layouts() {
  static const std::array<PocketLayout, kPocketCount> kLayouts = {{
      {PocketId::kBaulkLeft, true, 0.0, 0.0, {{{{0, 1}, {-1, 0}}, {{1, 0}, {0, -1}}}}},
      {PocketId::kBaulkRight, true, 1.0, 0.0, {{{{0, 1}, {1, 0}}, {{-1, 0}, {0, -1}}}}},
      {PocketId::kMiddleLeft, false, 0.0, 0.5, {{{{1, 0}, {0, 1}}, {{1, 0}, {0, -1}}}}},
      {PocketId::kMiddleRight, false, 1.0, 0.5, {{{{-1, 0}, {0, 1}}, {{-1, 0}, {0, -1}}}}},
      {PocketId::kTopLeft, true, 0.0, 1.0, {{{{0, -1}, {-1, 0}}, {{1, 0}, {0, 1}}}}},
      {PocketId::kTopRight, true, 1.0, 1.0, {{{{0, -1}, {1, 0}}, {{-1, 0}, {0, 1}}}}},
  }};
  return kLayouts;
}

const char* const kWallNames[kPocketCount][2] = {
    {"baulk-left wall 0", "baulk-left wall 1"},     {"baulk-right wall 0", "baulk-right wall 1"},
    {"middle-left wall 0", "middle-left wall 1"},   {"middle-right wall 0", "middle-right wall 1"},
    {"top-left wall 0", "top-left wall 1"},         {"top-right wall 0", "top-right wall 1"},
};

// A nose segment runs from jaw (pocket a, side sa) to jaw (pocket b, side sb).
struct NoseLayout {
  const char* name;
  PocketId a;
  int sa;
  PocketId b;
  int sb;
};

constexpr std::array<NoseLayout, TableModel::kCushionCount> kNoses = {{
    {"baulk", PocketId::kBaulkLeft, 0, PocketId::kBaulkRight, 0},
    {"top", PocketId::kTopLeft, 0, PocketId::kTopRight, 0},
    {"left-baulk", PocketId::kBaulkLeft, 1, PocketId::kMiddleLeft, 0},
    {"left-top", PocketId::kMiddleLeft, 1, PocketId::kTopLeft, 1},
    {"right-baulk", PocketId::kBaulkRight, 1, PocketId::kMiddleRight, 0},
    {"right-top", PocketId::kMiddleRight, 1, PocketId::kTopRight, 1},
}};

void Check(std::ostringstream& out, bool ok, const char* name, double value, const char* rule) {
  if (ok) return;
  if (out.tellp() > 0) out << "; ";
  out << name << " = " << value << " (must be " << rule << ")";
}

bool Positive(double x) { return std::isfinite(x) && x > 0; }

void CheckPocket(std::ostringstream& out, const PocketShape& p, const char* kind, double radius) {
  const std::string k(kind);
  Check(out, Positive(p.mouth_width) && p.mouth_width > 2 * radius, (k + ".mouth_width").c_str(),
        p.mouth_width, "finite and > 2R, so a ball fits");
  Check(out, Positive(p.knuckle_radius), (k + ".knuckle_radius").c_str(), p.knuckle_radius,
        "a finite number > 0 m");
  Check(out, std::isfinite(p.jaw_angle) && p.jaw_angle > kPi / 2 && p.jaw_angle < kPi,
        (k + ".jaw_angle").c_str(), p.jaw_angle, "in (pi/2, pi) rad");
  Check(out, Positive(p.wall_length), (k + ".wall_length").c_str(), p.wall_length,
        "a finite number > 0 m");
  Check(out, std::isfinite(p.fall_depth) && p.fall_depth >= 0, (k + ".fall_depth").c_str(),
        p.fall_depth, "a finite number >= 0 m");
  Check(out, Positive(p.capture_radius), (k + ".capture_radius").c_str(), p.capture_radius,
        "a finite number > 0 m");
}

// Distance of the last row of reds from the pink spot, along +y. m.
double TriangleDepth(const TableSpec& s, double radius) {
  return 2 * radius + s.apex_gap + 4 * kSqrt3 * radius;
}

// Writes "<name> at (x, y) m" (or "ball <index> ..." for an unnamed ball).
void WriteBall(std::ostringstream& out, std::string_view name, std::size_t index,
               const Vec2& r) {
  if (name.empty()) {
    out << "ball " << index;
  } else {
    out << name;
  }
  out << " at (" << r.x() << ", " << r.y() << ") m";
}

void StartEntry(std::ostringstream& out) {
  if (out.tellp() > 0) out << "; ";
}

}  // namespace

const char* ToString(PocketId id) {
  switch (id) {
    case PocketId::kBaulkLeft: return "baulk-left";
    case PocketId::kBaulkRight: return "baulk-right";
    case PocketId::kMiddleLeft: return "middle-left";
    case PocketId::kMiddleRight: return "middle-right";
    case PocketId::kTopLeft: return "top-left";
    case PocketId::kTopRight: return "top-right";
  }
  return "unknown";
}

const char* ToString(Colour c) {
  switch (c) {
    case Colour::kYellow: return "yellow";
    case Colour::kGreen: return "green";
    case Colour::kBrown: return "brown";
    case Colour::kBlue: return "blue";
    case Colour::kPink: return "pink";
    case Colour::kBlack: return "black";
  }
  return "unknown";
}

double SevenFifthsCushionHeight(const BallParams& ball) { return 1.4 * ball.radius; }

std::string ValidateTableSpec(const TableSpec& s, const BallParams& ball) {
  std::ostringstream out;
  const std::string ball_msg = ValidateBallParams(ball);
  if (!ball_msg.empty()) out << ball_msg;
  const double r = std::isfinite(ball.radius) && ball.radius > 0 ? ball.radius : 0.0;
  Check(out, Positive(s.width), "width", s.width, "a finite number > 0 m");
  Check(out, Positive(s.length), "length", s.length, "a finite number > 0 m");
  Check(out, Positive(s.baulk_line) && s.baulk_line < s.length / 2, "baulk_line", s.baulk_line,
        "in (0, length / 2) m");
  Check(out, Positive(s.d_radius) && s.d_radius < s.baulk_line && s.d_radius < s.width / 2 - r,
        "d_radius", s.d_radius, "in (0, min(baulk_line, width / 2 - R)) m");
  Check(out, Positive(s.black_spot) && s.black_spot < s.length / 4, "black_spot", s.black_spot,
        "in (0, length / 4) m, between the pink spot and the top cushion");
  Check(out, std::isfinite(s.apex_gap) && s.apex_gap >= 0, "apex_gap", s.apex_gap,
        "a finite number >= 0 m");
  Check(out, Positive(s.cushion_height) && s.cushion_height < 2 * r, "cushion_height",
        s.cushion_height, "in (0, 2R) m");
  CheckPocket(out, s.corner, "corner", r);
  CheckPocket(out, s.middle, "middle", r);
  if (out.tellp() > 0) return out.str();

  // Derived room: noses of positive length, reds clear of a ball on the black spot.
  const double corner_leg = s.corner.mouth_width / kSqrt2;
  Check(out, s.width - 2 * corner_leg > 0, "corner.mouth_width", s.corner.mouth_width,
        "small enough to leave a baulk and top cushion");
  Check(out, s.length / 2 - s.middle.mouth_width / 2 - corner_leg > 0, "middle.mouth_width",
        s.middle.mouth_width, "small enough to leave the side cushions");
  const double back_row = 0.75 * s.length + TriangleDepth(s, r);
  Check(out, back_row + 2 * r <= s.length - s.black_spot, "apex_gap", s.apex_gap,
        "small enough that the reds clear a ball on the black spot");
  return out.str();
}

TableModel::TableModel(const TableSpec& spec, const BallParams& ball)
    : spec_(spec), radius_(ball.radius) {
  const std::string error = ValidateTableSpec(spec, ball);
  if (!error.empty()) throw std::invalid_argument("TableModel: " + error);

  const double w = spec.width;
  const double l = spec.length;
  std::array<std::array<Vec2, 2>, kPocketCount> nose_end{};
  for (int p = 0; p < kPocketCount; ++p) {
    const PocketLayout& lay = Layouts()[p];
    const PocketShape& shape = lay.corner ? spec.corner : spec.middle;
    const Vec2 k(lay.kx * w, lay.ky * l);
    const double h = lay.corner ? shape.mouth_width / kSqrt2 : shape.mouth_width / 2;
    const double phi = kPi - shape.jaw_angle;  // turn from nose to wall
    const double rj = shape.knuckle_radius;
    for (int j = 0; j < 2; ++j) {
      const Vec2& n = lay.jaw[j].nose_normal;
      const Vec2& t = lay.jaw[j].towards;
      const Vec2 end = k - h * t;
      const Vec2 centre = end - rj * n;
      const Vec2 wall_normal = n * std::cos(phi) + t * std::sin(phi);
      const Vec2 wall_dir = t * std::cos(phi) - n * std::sin(phi);
      const Vec2 tangent = centre + rj * wall_normal;
      nose_end[p][j] = end;
      jaws_[2 * p + j] = JawCircle{centre, rj, lay.id};
      segments_[kCushionCount + 2 * p + j] =
          CushionSegment{tangent,        tangent + shape.wall_length * wall_dir, wall_normal,
                         SegmentKind::kJawWall, lay.id,           kWallNames[p][j]};
    }
    Pocket& pocket = pockets_[p];
    pocket.id = lay.id;
    pocket.mouth_centre = 0.5 * (nose_end[p][0] + nose_end[p][1]);
    pocket.axis = -(lay.jaw[0].nose_normal + lay.jaw[1].nose_normal).normalized();
    pocket.capture_radius = shape.capture_radius;
    pocket.capture_centre =
        pocket.mouth_centre + (shape.fall_depth + shape.capture_radius) * pocket.axis;
  }
  for (int i = 0; i < kCushionCount; ++i) {
    const NoseLayout& nose = kNoses[i];
    const int a = static_cast<int>(nose.a);
    const int b = static_cast<int>(nose.b);
    segments_[i] = CushionSegment{nose_end[a][nose.sa],
                                  nose_end[b][nose.sb],
                                  Layouts()[a].jaw[nose.sa].nose_normal,
                                  SegmentKind::kCushion,
                                  nose.a,
                                  nose.name};
  }

  const double cx = w / 2;
  const double pink_y = 0.75 * l;
  spots_[static_cast<int>(Colour::kYellow)] = Vec2(cx + spec.d_radius, spec.baulk_line);
  spots_[static_cast<int>(Colour::kGreen)] = Vec2(cx - spec.d_radius, spec.baulk_line);
  spots_[static_cast<int>(Colour::kBrown)] = Vec2(cx, spec.baulk_line);
  spots_[static_cast<int>(Colour::kBlue)] = Vec2(cx, l / 2);
  spots_[static_cast<int>(Colour::kPink)] = Vec2(cx, pink_y);
  spots_[static_cast<int>(Colour::kBlack)] = Vec2(cx, l - spec.black_spot);

  // Touching balls: neighbours in a row 2R apart, rows sqrt(3) R apart.
  const double apex_y = pink_y + 2 * radius_ + spec.apex_gap;
  int i = 0;
  for (int row = 0; row < 5; ++row) {
    for (int k = 0; k <= row; ++k) {
      reds_[i++] = Vec2(cx + (2 * k - row) * radius_, apex_y + row * kSqrt3 * radius_);
    }
  }
}

const TableModel& DefaultTable() {
  static const TableModel table;
  return table;
}

double TableModel::cushion_contact_distance() const {
  const double lift = spec_.cushion_height - radius_;
  return std::sqrt(std::max(0.0, radius_ * radius_ - lift * lift));
}

std::optional<PocketId> TableModel::PocketMouthAt(const Vec2& r) const {
  const double c = cushion_contact_distance();
  if (r.x() >= c && r.y() >= c && r.x() <= spec_.width - c && r.y() <= spec_.length - c) return std::nullopt;
  for (const Pocket& p : pockets_) {
    const PocketShape& shape = Layouts()[static_cast<int>(p.id)].corner ? spec_.corner : spec_.middle;
    // The mouth: across, within its width; along the axis, from the noses' line
    // (less the contact distance) to the capture circle's centre.
    const Vec2 d = r - p.mouth_centre;
    const Vec2 across(-p.axis.y(), p.axis.x());
    const double depth = d.dot(p.axis);
    if (std::abs(d.dot(across)) > shape.mouth_width / 2 || depth < -c || depth > shape.fall_depth + shape.capture_radius) {
      continue;
    }
    if ((r - p.capture_centre).norm() <= p.capture_radius) return std::nullopt;  // it drops
    for (const CushionSegment& seg : segments_) {
      const Vec2 along = seg.p1 - seg.p0;
      const double u = (r - seg.p0).dot(along);
      if (u >= 0 && u <= along.squaredNorm() && seg.normal.dot(r - seg.p0) < c - kPlacementTolerance) {
        return std::nullopt;
      }
    }
    for (const JawCircle& jaw : jaws_) {
      if ((r - jaw.centre).norm() < jaw.radius + c - kPlacementTolerance) return std::nullopt;
    }
    return p.id;
  }
  return std::nullopt;
}

std::string TableModel::ValidatePlacement(std::span<const BallPlacement> balls,
                                          std::size_t max_problems) const {
  std::ostringstream out;
  if (balls.size() > static_cast<std::size_t>(limits::kMaxBalls)) {
    out << balls.size() << " balls: at most " << limits::kMaxBalls << " fit one table";
    return out.str();
  }
  std::size_t problems = 0;
  // True when problem number `problems` is to be written (then starts its entry).
  auto report = [&]() {
    if (problems++ >= max_problems) return false;
    StartEntry(out);
    return true;
  };
  const double r = radius_;
  const double c = cushion_contact_distance();
  const double tol = kPlacementTolerance;
  struct Limit {
    int axis;
    double sign;  // +1: coordinate must be >= bound; -1: <= bound
    double bound;
    const char* cushion;
  };
  const std::array<Limit, 4> limits = {{
      {0, 1, c, "left cushion (x = 0)"},
      {0, -1, spec_.width - c, "right cushion (x = width)"},
      {1, 1, c, "baulk cushion (y = 0)"},
      {1, -1, spec_.length - c, "top cushion (y = length)"},
  }};
  for (std::size_t i = 0; i < balls.size(); ++i) {
    const Vec2& p = balls[i].r;
    if (!p.allFinite()) {
      if (report()) {
        WriteBall(out, balls[i].name, i, p);
        out << ": not a finite position";
      }
      continue;
    }
    if (InPocketMouth(p)) continue;  // on a pocket's lip, past the noses' line
    for (const Limit& lim : limits) {
      const double x = p[lim.axis];
      if (lim.sign * (x - lim.bound) >= -tol) continue;
      if (!report()) continue;
      WriteBall(out, balls[i].name, i, p);
      out << ": " << (lim.axis == 0 ? "x" : "y") << " = " << x
          << " m is closer than the cushion contact distance " << c << " m to the "
          << lim.cushion;
    }
  }
  for (std::size_t i = 0; i < balls.size(); ++i) {
    for (std::size_t j = i + 1; j < balls.size(); ++j) {
      const double d = (balls[i].r - balls[j].r).norm();
      if (!(d < 2 * r - tol)) continue;
      if (!report()) continue;
      WriteBall(out, balls[i].name, i, balls[i].r);
      out << " overlaps ";
      WriteBall(out, balls[j].name, j, balls[j].r);
      out << ": centre distance " << d << " m < 2R = " << 2 * r << " m";
    }
  }
  if (problems > max_problems) {
    StartEntry(out);
    out << "and " << problems - max_problems << " more";
  }
  return out.str();
}

}  // namespace snooker::physics
