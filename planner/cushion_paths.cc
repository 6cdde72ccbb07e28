#include "planner/cushion_paths.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "planner/geometry.h"

namespace snooker::planner {

using physics::Vec2;

const char* ToString(CushionLine line) {
  switch (line) {
    case CushionLine::kBaulk: return "baulk";
    case CushionLine::kTop: return "top";
    case CushionLine::kLeft: return "left";
    case CushionLine::kRight: return "right";
  }
  return "unknown";
}

const char* ToString(PathRefusal r) {
  switch (r) {
    case PathRefusal::kNone: return "kept";
    case PathRefusal::kOutside: return "start or target not inside the cushion's contact line";
    case PathRefusal::kOffCushion: return "contact in a pocket mouth or a jaw";
    case PathRefusal::kGlancing: return "incidence too glancing";
    case PathRefusal::kBlocked: return "a leg passes too near a ball";
  }
  return "unknown";
}

ContactLine ContactLineOf(const physics::TableModel& table, CushionLine line) {
  const double c = table.cushion_contact_distance();
  const double w = table.spec().width, l = table.spec().length;
  switch (line) {
    case CushionLine::kBaulk: return {Vec2(0, 1), c};
    case CushionLine::kTop: return {Vec2(0, -1), -(l - c)};
    case CushionLine::kLeft: return {Vec2(1, 0), c};
    case CushionLine::kRight: return {Vec2(-1, 0), -(w - c)};
  }
  return {Vec2(0, 1), c};
}

double CushionPath::LengthAfter(int contact) const {
  double s = 0;
  for (int j = contact + 1; j <= cushions; ++j) s += legs[static_cast<size_t>(j)];
  return s;
}

Vec2 CushionPath::Unfold(int leg, const Vec2& p) const {
  Vec2 q = p;
  for (int i = std::min(leg, cushions) - 1; i >= 0; --i) q = contacts[static_cast<size_t>(i)].contact_line.Mirror(q);
  return q;
}

Vec2 CushionPath::Fold(int leg, const Vec2& p) const {
  Vec2 q = p;
  for (int i = 0; i < std::min(leg, cushions); ++i) q = contacts[static_cast<size_t>(i)].contact_line.Mirror(q);
  return q;
}

namespace {

// The straight nose of `line` whose span holds the contact point, and the distance
// along it to its nearer end; segment -1 when none does (a pocket mouth, off the table).
struct NoseHit {
  int segment = -1;
  double margin = -std::numeric_limits<double>::infinity();
};

NoseHit FindNose(const physics::TableModel& table, const ContactLine& line, const Vec2& point) {
  NoseHit best;
  const auto segments = table.segments();
  for (int i = 0; i < physics::TableModel::kCushionCount; ++i) {
    const physics::CushionSegment& s = segments[static_cast<size_t>(i)];
    if (s.normal.dot(line.normal) < 0.5) continue;
    const Vec2 d = s.p1 - s.p0;
    const double len = d.norm();
    const double along = (point - s.p0).dot(d) / len;
    const double margin = std::min(along, len - along);
    if (margin > best.margin) best = {i, margin};
  }
  return best;
}

}  // namespace

std::optional<CushionPath> MirrorPath(const physics::TableModel& table, const Vec2& start,
                                      const Vec2& target, std::span<const CushionLine> lines,
                                      const CushionPathOptions& options, PathRefusal* why) {
  PathRefusal dummy;
  PathRefusal& reason = why ? *why : dummy;
  reason = PathRefusal::kOutside;
  const int n = static_cast<int>(lines.size());
  if (n < 1 || n > 2 || (n == 2 && lines[0] == lines[1])) return std::nullopt;
  for (int k = 0; k < kCushionLineCount; ++k) {  // the start on the table
    if (!(ContactLineOf(table, static_cast<CushionLine>(k)).Inside(start) >= 0)) return std::nullopt;
  }
  CushionPath path;
  path.cushions = n;
  path.sliding = options.sliding;
  std::array<Vec2, 3> image{};  // image[i]: the target seen across contacts i..n-1
  image[static_cast<size_t>(n)] = target;
  for (int i = n - 1; i >= 0; --i) {
    const ContactLine cl = ContactLineOf(table, lines[static_cast<size_t>(i)]);
    if (cl.Inside(start) < options.min_inside || cl.Inside(target) < options.min_inside) return std::nullopt;
    path.contacts[static_cast<size_t>(i)].line = lines[static_cast<size_t>(i)];
    path.contacts[static_cast<size_t>(i)].contact_line = cl;
    image[static_cast<size_t>(i)] = cl.Mirror(image[static_cast<size_t>(i + 1)]);
  }
  path.points[0] = start;
  for (int i = 0; i < n; ++i) {
    CushionContact& contact = path.contacts[static_cast<size_t>(i)];
    const Vec2 from = path.points[static_cast<size_t>(i)];
    const Vec2 towards = image[static_cast<size_t>(i)];
    const double a = contact.contact_line.Inside(from), b = contact.contact_line.Inside(towards);
    if (!(a > 0) || !(b < 0)) {
      reason = PathRefusal::kOffCushion;
      return std::nullopt;
    }
    contact.point = from + (a / (a - b)) * (towards - from);
    const NoseHit nose = FindNose(table, contact.contact_line, contact.point);
    contact.segment = nose.segment;
    contact.nose_margin = nose.margin;
    if (nose.segment < 0 || nose.margin < options.jaw_margin) {
      reason = PathRefusal::kOffCushion;
      return std::nullopt;
    }
    const Vec2 d = (contact.point - from).normalized();
    contact.incidence = std::acos(std::clamp(-d.dot(contact.contact_line.normal), 0.0, 1.0));
    if (contact.incidence > options.max_incidence) {
      reason = PathRefusal::kGlancing;
      return std::nullopt;
    }
    path.points[static_cast<size_t>(i + 1)] = contact.point;
  }
  path.points[static_cast<size_t>(n + 1)] = target;
  path.length = 0;
  for (int j = 0; j <= n; ++j) {
    const double len = (path.points[static_cast<size_t>(j + 1)] - path.points[static_cast<size_t>(j)]).norm();
    path.legs[static_cast<size_t>(j)] = len;
    path.length += len;
  }
  path.heading = Direction(path.points[1] - start);
  path.final_direction = Direction(target - path.points[static_cast<size_t>(n)]);
  path.bracket = BracketFor(path, options.bracket_floor);
  reason = PathRefusal::kNone;
  return path;
}

double SegmentMargin(const Vec2& a, const Vec2& b, double clearance, const TableState& table,
                     std::span<const int> skip) {
  double margin = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < table.balls.size(); ++i) {
    if (std::find(skip.begin(), skip.end(), static_cast<int>(i)) != skip.end()) continue;
    margin = std::min(margin, SegmentDistance(a, b, table.balls[i].position) - clearance);
  }
  return margin;
}

double LegsMargin(const CushionPath& path, double clearance, const TableState& table, int mover,
                  int other, int target_ball) {
  double margin = std::numeric_limits<double>::infinity();
  for (int j = 0; j < path.leg_count(); ++j) {
    const bool last = j == path.cushions;
    const std::array<int, 3> skip = {mover, other, last ? target_ball : -1};
    margin = std::min(margin, SegmentMargin(path.points[static_cast<size_t>(j)],
                                            path.points[static_cast<size_t>(j + 1)], clearance,
                                            table, skip));
  }
  return margin;
}

namespace {

// Linear interpolation in a table over incidences 0, 5, 15, ..., 75 deg (constant
// beyond 75).
constexpr std::array<double, 9> kIncidences = {0, 5, 15, 25, 35, 45, 55, 65, 75};

double Interpolate(const std::array<double, 9>& values, double incidence) {
  const double deg = std::clamp(std::abs(incidence) * physics::kDegPerRad, 0.0, kIncidences.back());
  size_t i = 1;
  while (i + 1 < kIncidences.size() && kIncidences[i] < deg) ++i;
  const double f = (deg - kIncidences[i - 1]) / (kIncidences[i] - kIncidences[i - 1]);
  return values[i - 1] + f * (values[i] - values[i - 1]);
}

}  // namespace

ReboundError MirrorReboundError(double incidence, bool sliding) {
  // The envelope of the measured eps (deg) over speeds of 1 to 4 m/s and legs of
  // 0.3 to 1 m before and after the cushion (MirrorErrorTable's cases), struck
  // rolling, or (sliding) rolling or stun, widened by a tenth; square on, the
  // rebound stays on the normal.
  static constexpr std::array<double, 9> kRollingLo = {0, -1.6, -4.7, -6.9, -6.6, -5.3, -3.6, -2.0, -0.2};
  static constexpr std::array<double, 9> kRollingHi = {0, 0.1, 0.1, 0.1, 1.5, 4.5, 8.4, 12.9, 14.1};
  static constexpr std::array<double, 9> kSlidingLo = {0, -2.2, -6.0, -8.8, -10.0, -8.8, -6.2, -3.9, -1.5};
  static constexpr std::array<double, 9> kSlidingHi = {0, 0.15, 0.5, 1.1, 4.3, 9.8, 12.3, 16.0, 14.1};
  return {physics::DegToRad(Interpolate(sliding ? kSlidingLo : kRollingLo, incidence)),
          physics::DegToRad(Interpolate(sliding ? kSlidingHi : kRollingHi, incidence))};
}

double ReboundSpeedSensitivity(double incidence, bool sliding) {
  // Root mean square of d(eps)/d(ln speed), deg, over the same cases (by differences
  // of 2 % in speed), rolling, or the larger of rolling and stun.
  static constexpr std::array<double, 9> kRolling = {0, 1.0, 2.9, 4.0, 5.5, 5.3, 6.5, 8.1, 7.5};
  static constexpr std::array<double, 9> kSliding = {0, 1.5, 4.4, 6.4, 8.5, 10.5, 11.4, 12.5, 12.2};
  return physics::DegToRad(Interpolate(sliding ? kSliding : kRolling, incidence));
}

double ReboundHeadingGain(const CushionPath& path, int contact) {
  const CushionContact& c = path.contacts[static_cast<size_t>(contact)];
  const Vec2 out = path.points[static_cast<size_t>(contact + 2)] - c.point;
  const double wider = Cross(c.contact_line.normal, out) >= 0 ? 1.0 : -1.0;
  const double parity = contact % 2 == 0 ? 1.0 : -1.0;
  return parity * wider * path.LengthAfter(contact) / path.length;
}

AimBracket BracketFor(const CushionPath& path, double floor) {
  AimBracket b;
  for (int i = 0; i < path.cushions; ++i) {
    const ReboundError e = MirrorReboundError(path.contacts[static_cast<size_t>(i)].incidence, path.sliding);
    const double g = ReboundHeadingGain(path, i);
    b.lo += std::min(g * e.lo, g * e.hi);
    b.hi += std::max(g * e.lo, g * e.hi);
  }
  b.lo = std::min(b.lo, 0.0) - floor;
  b.hi = std::max(b.hi, 0.0) + floor;
  return b;
}

int AppendCushionPaths(const physics::TableModel& model, const TableState& table, const Vec2& start,
                       const Vec2& target, int max_cushions, double clearance, int mover, int other,
                       int target_ball, const CushionPathOptions& options,
                       std::vector<CushionPath>& out) {
  int added = 0;
  auto consider = [&](std::span<const CushionLine> lines) {
    auto path = MirrorPath(model, start, target, lines, options);
    if (!path || LegsMargin(*path, clearance, table, mover, other, target_ball) < 0) return;
    out.push_back(*path);
    ++added;
  };
  for (int a = 0; a < kCushionLineCount; ++a) {
    const std::array<CushionLine, 1> one = {static_cast<CushionLine>(a)};
    consider(one);
  }
  if (max_cushions < 2) return added;
  for (int a = 0; a < kCushionLineCount; ++a) {
    for (int b = 0; b < kCushionLineCount; ++b) {
      if (a == b) continue;
      const std::array<CushionLine, 2> two = {static_cast<CushionLine>(a), static_cast<CushionLine>(b)};
      consider(two);
    }
  }
  return added;
}

}  // namespace snooker::planner
