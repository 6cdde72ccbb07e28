#include "planner/layout.h"

#include <algorithm>
#include <cmath>

#include "planner/geometry.h"
#include "planner/pot_estimate.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

// Cap on the cut steps tried each side of the straight pot.
constexpr double kMaxCutSteps = 90;

const PocketModel& PocketsOf(const LayoutOptions& options) {
  return options.pockets != nullptr ? *options.pockets : PocketModel::Default();
}

// The segment [a, b] passes every object ball but `skip` (the cue ball is no
// obstacle) by `clearance` (geometry.h's SegmentDistance, squared: this is the
// layout's inner loop).
bool Clear(const Vec2& a, const Vec2& b, double clearance, const TableState& table, int skip) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double inv = len2 > 0 ? 1 / len2 : 0.0;
  const double c2 = clearance * clearance;
  // The segment's box widened by the clearance: a ball outside it is clear.
  const double x0 = std::min(a.x(), b.x()) - clearance, x1 = std::max(a.x(), b.x()) + clearance;
  const double y0 = std::min(a.y(), b.y()) - clearance, y1 = std::max(a.y(), b.y()) + clearance;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    const Vec2& p = table.balls[i].position;
    if (p.x() < x0 || p.x() > x1 || p.y() < y0 || p.y() > y1) continue;
    if (static_cast<int>(i) == skip || table.balls[i].kind == BallKind::kCue) continue;
    const Vec2 ap = p - a;
    const double t = std::clamp(ap.dot(d) * inv, 0.0, 1.0);
    if ((ap - t * d).squaredNorm() < c2) return false;
  }
  return true;
}

// Distance from p to the nearest cushion contact line, inside the bed (negative
// outside it). m.
double BedGap(const Vec2& p, const physics::TableModel& model) {
  const double d = model.cushion_contact_distance();
  const double w = model.spec().width, l = model.spec().length;
  return std::min({p.x() - d, w - d - p.x(), p.y() - d, l - d - p.y()});
}

// How far a ball centre can go from p along unit u before leaving the bed widened
// by `slack` (0 when p is already outside it that way). m.
double RunToEdge(const Vec2& p, const Vec2& u, const physics::TableModel& model, double slack) {
  const double d = model.cushion_contact_distance() - slack;
  const double lo[2] = {d, d};
  const double hi[2] = {model.spec().width - d, model.spec().length - d};
  double t = model.spec().length + model.spec().width;
  for (int axis = 0; axis < 2; ++axis) {
    if (u[axis] > 0) t = std::min(t, (hi[axis] - p[axis]) / u[axis]);
    if (u[axis] < 0) t = std::min(t, (lo[axis] - p[axis]) / u[axis]);
  }
  return std::max(0.0, t);
}

// The smallest cut (0, then +-cut_step, ... up to max_cut) with a cue-ball run to
// the ghost ball g for an object ball leaving along `theta` (unit vector u): fills
// the pot's cut, cue and heading, or returns false.
bool Approach(const TableState& table, int ball, const Vec2& g, double theta, const Vec2& u,
              const physics::TableModel& model, const LayoutOptions& options, LayoutPot* pot) {
  const double clearance = 2 * model.ball_radius() + options.path_clearance;
  const int steps = options.cut_step > 0
                        ? static_cast<int>(std::clamp(options.max_cut / options.cut_step + 1e-9, 0.0, kMaxCutSteps))
                        : 0;
  for (int k = 0; k <= 2 * steps; ++k) {
    const double cut = options.cut_step * ((k + 1) / 2) * (k % 2 == 1 ? 1 : -1);
    // The heading is u turned by -cut; the cue ball comes from behind it.
    const Vec2 heading = k == 0 ? u : std::cos(cut) * u - std::sin(cut) * Left(u);
    const Vec2 back = -heading;
    const double run = std::min(options.cue_distance, RunToEdge(g, back, model, options.touch_gap));
    if (run < options.min_cue_run) continue;
    const Vec2 cue = g + run * back;
    if (Clear(cue, g, clearance, table, ball)) {
      pot->cut = cut;
      pot->cue = cue;
      pot->heading = WrapAngle(theta - cut);
      return true;
    }
  }
  return false;
}

// A pot's line before its paths are checked: the object ball's direction (theta,
// unit vector u) aimed at the window's centre, the window, the point aimed at in
// the mouth, and the window's half-width over the distance to it, which with the
// cut's cosine sets the chance (Chance); the straight pot's is the largest.
struct Aim {
  physics::PocketId pocket = physics::PocketId::kBaulkLeft;
  double theta = 0;
  Vec2 u = Vec2::Zero();
  PocketWindow window;
  Vec2 mouth = Vec2::Zero();
  double ratio = 0;
};

// P = 2 Phi(w cos(cut) / (2 L line_sigma)) - 1, from ratio = w / (2 L) x cos(cut).
double Chance(double ratio, const LayoutOptions& options) {
  if (!(options.line_sigma > 0)) return ratio > 0 ? 1.0 : 0.0;
  return std::max(0.0, 2 * NormalCdf(ratio / options.line_sigma) - 1);
}

std::optional<Aim> AimAt(const Vec2& o, physics::PocketId pocket, const physics::TableModel& model,
                         const LayoutOptions& options) {
  const PocketModel& pockets = PocketsOf(options);
  const physics::Pocket& p = model.pocket(pocket);
  const Vec2 q = p.mouth_centre - o;
  const double l0 = q.norm();
  if (!(l0 > 0)) return std::nullopt;
  // The pocket's angular reach first (a dot product, as position.cc does): past
  // its largest tabulated approach, plus a margin for the window's offset, the
  // window is empty.
  if (q.dot(p.axis) < pockets.ReachCosine(pocket) * l0) return std::nullopt;
  // Aim at the window's centre (the window taken along the line to the mouth's
  // centre: it changes little over the fraction of a degree to the window's).
  Aim aim;
  aim.pocket = pocket;
  const double phi = Direction(q);
  aim.window = pockets.Window(pocket, phi, kTypicalArrivalSpeed);
  const double s = aim.window.centre() / l0;
  if (aim.window.empty || std::abs(s) >= 1) return std::nullopt;
  const Vec2 q1 = q / l0;
  aim.u = std::sqrt(1 - s * s) * q1 + s * Left(q1);
  aim.theta = phi + std::asin(s);
  aim.mouth = p.mouth_centre + aim.window.centre() * Left(aim.u);
  aim.ratio = aim.window.width() / (2 * (aim.mouth - o).norm());
  return aim;
}

// The paths of an aimed pot: the object ball's line, the ghost ball, an approach.
std::optional<LayoutPot> Judge(const TableState& table, int ball, const Aim& aim,
                               const physics::TableModel& model, const LayoutOptions& options) {
  const double r = model.ball_radius();
  const Vec2 o = table.balls[static_cast<size_t>(ball)].position;
  const double clearance = 2 * r + options.path_clearance;
  if (!Clear(o, aim.mouth, clearance, table, ball)) return std::nullopt;
  // A ghost ball within touch_gap past a contact line counts as on the bed (a ball
  // frozen to a cushion is potted along it with the cue ball on the cushion).
  const Vec2 g = o - 2 * r * aim.u;
  if (BedGap(g, model) < -options.touch_gap || !Clear(g, g, clearance, table, ball)) return std::nullopt;
  LayoutPot pot;
  pot.object_direction = aim.theta;
  if (!Approach(table, ball, g, aim.theta, aim.u, model, options, &pot)) return std::nullopt;
  pot.chance = aim.ratio * std::cos(pot.cut);  // the ratio until the caller wants the chance
  return pot;
}

}  // namespace

std::optional<LayoutPot> OpenPot(const TableState& table, int ball, physics::PocketId pocket,
                                 const physics::TableModel& model, const LayoutOptions& options) {
  const auto aim = AimAt(table.balls[static_cast<size_t>(ball)].position, pocket, model, options);
  if (!aim) return std::nullopt;
  auto pot = Judge(table, ball, *aim, model, options);
  if (pot) pot->chance = Chance(pot->chance, options);
  return pot;
}

double Pottability(const TableState& table, int ball, const physics::TableModel& model,
                   const LayoutOptions& options) {
  // The pockets by their straight pot's ratio, the largest first; the paths are
  // checked in that order until no pocket left can enter the best two (the chance
  // rises with the ratio, and a cut only lowers it).
  Aim aims[physics::kPocketCount];
  int n = 0;
  const Vec2 o = table.balls[static_cast<size_t>(ball)].position;
  for (int k = 0; k < physics::kPocketCount; ++k) {
    if (const auto aim = AimAt(o, static_cast<physics::PocketId>(k), model, options)) aims[n++] = *aim;
  }
  // Ties in pocket order (as added): a stable order with no temporary buffer.
  std::sort(aims, aims + n, [](const Aim& a, const Aim& b) {
    return a.ratio != b.ratio ? a.ratio > b.ratio : a.pocket < b.pocket;
  });
  double best = 0, second = 0;  // ratios
  for (int i = 0; i < n && aims[i].ratio > second; ++i) {
    const auto pot = Judge(table, ball, aims[i], model, options);
    const double p = pot ? pot->chance : 0.0;
    if (p > best) {
      second = best;
      best = p;
    } else if (p > second) {
      second = p;
    }
  }
  return options.pocket_weights[0] * (best > 0 ? Chance(best, options) : 0.0) +
         options.pocket_weights[1] * (second > 0 ? Chance(second, options) : 0.0);
}

namespace {

// Why a red is or is not tied up: touching (kTouching), closed to every pocket
// (kClosed), or the first pocket found open (its PocketId, >= 0).
constexpr int kTouching = -2;
constexpr int kClosed = -1;

int RedState(const TableState& table, int ball, const physics::TableModel& model,
             const LayoutOptions& options) {
  const Vec2 o = table.balls[static_cast<size_t>(ball)].position;
  if (BedGap(o, model) < options.touch_gap) return kTouching;
  const double near = 2 * model.ball_radius() + options.touch_gap;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    if (static_cast<int>(i) == ball || table.balls[i].kind == BallKind::kCue) continue;
    if ((table.balls[i].position - o).squaredNorm() < near * near) return kTouching;
  }
  for (int k = 0; k < physics::kPocketCount; ++k) {
    if (OpenPot(table, ball, static_cast<physics::PocketId>(k), model, options)) return k;
  }
  return kClosed;
}

}  // namespace

bool TiedUp(const TableState& table, int ball, const physics::TableModel& model,
            const LayoutOptions& options) {
  return RedState(table, ball, model, options) < 0;
}

namespace {

// Where two tables differ: the object balls that `before` has and `after` has not
// at the same place (same kind, same centre to the bit), and the other way round;
// at most kMaxChanged of each.
constexpr int kMaxChanged = 2 * physics::limits::kMaxBalls;
struct Points {
  Vec2 at[kMaxChanged];
  int count = 0;
  bool overflow = false;
};
struct Changes {
  Points removed, added;
};

int SamePlace(const TableState& table, const Ball& b) {
  for (size_t j = 0; j < table.balls.size(); ++j) {
    if (table.balls[j].kind == b.kind && table.balls[j].position == b.position) return static_cast<int>(j);
  }
  return -1;
}

void Unmatched(const TableState& from, const TableState& other, Points* out) {
  for (const Ball& b : from.balls) {
    if (b.kind == BallKind::kCue || SamePlace(other, b) >= 0) continue;
    if (out->count == kMaxChanged) {
      out->overflow = true;
      return;
    }
    out->at[out->count++] = b.position;
  }
}

// A ball at `o` that did not move can be judged otherwise only when a point of
// `points` lies within reach of its approaches (every ghost ball is 2R from o and
// every cue-ball run at most cue_distance), its touching distance, or a line to a
// pocket (`pocket`, or every pocket when -1; aimed within half a mouth of the
// mouth's centre).
bool Near(const Vec2& o, const Points& points, int pocket, const physics::TableModel& model,
          const LayoutOptions& options) {
  const double r = model.ball_radius();
  const double near = std::max(options.cue_distance + 4 * r, 2 * r + options.touch_gap) + options.path_clearance;
  const double half_mouth = 0.5 * std::max(model.spec().corner.mouth_width, model.spec().middle.mouth_width);
  const double line = 2 * r + options.path_clearance + half_mouth;
  for (int k = 0; k < points.count; ++k) {
    const Vec2& p = points.at[k];
    if ((p - o).squaredNorm() < near * near) return true;
    for (int q = 0; q < physics::kPocketCount; ++q) {
      if (pocket >= 0 && q != pocket) continue;
      if (SegmentDistance(o, model.pocket(static_cast<physics::PocketId>(q)).mouth_centre, p) < line) return true;
    }
  }
  return false;
}

// Whether the result of a ball that lies where it lay before still holds. Balls
// that arrive can only close lines, balls that leave only open them: a free red
// holds unless a ball arrives near its open pocket's line; a tied red unless a ball
// leaves near any; a colour's chances move either way, so it holds unless any
// change comes near any of its lines.
bool Holds(const Ball& b, int red_state, const Changes& c, const physics::TableModel& model,
           const LayoutOptions& options) {
  if (b.kind == BallKind::kRed) {
    if (red_state >= 0) return !Near(b.position, c.added, red_state, model, options);
    return !Near(b.position, c.removed, -1, model, options);
  }
  return !Near(b.position, c.added, -1, model, options) && !Near(b.position, c.removed, -1, model, options);
}

// The summary of `table`; with `before` and its summary, each ball that lies where
// it lay there and whose result still holds keeps it.
LayoutSummary Summarize(const TableState& table, const TableState* before, const LayoutSummary* known,
                        const physics::TableModel& model, const LayoutOptions& options) {
  Changes changes;
  if (before != nullptr) {
    Unmatched(*before, table, &changes.removed);
    Unmatched(table, *before, &changes.added);
  }
  const bool reuse = before != nullptr && !changes.removed.overflow && !changes.added.overflow;
  LayoutSummary out;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    const Ball& b = table.balls[i];
    const bool colour = IsColour(b.kind);
    if (b.kind != BallKind::kRed && !colour) continue;
    if (colour && out.colour_present[static_cast<size_t>(ColourOf(b.kind))]) continue;  // the first counts
    const int j = reuse ? SamePlace(*before, b) : -1;
    const auto jj = static_cast<size_t>(j);
    const bool kept = j >= 0 && j < physics::limits::kMaxBalls &&
                      Holds(b, known->red_state[jj], changes, model, options);
    double result = 0;
    int red_state = kClosed;
    if (kept) {
      result = known->ball[jj];
      red_state = known->red_state[jj];
    } else if (b.kind == BallKind::kRed) {
      red_state = RedState(table, static_cast<int>(i), model, options);
      result = red_state < 0 ? 1.0 : 0.0;
    } else {
      result = Pottability(table, static_cast<int>(i), model, options);
    }
    if (i < out.ball.size()) {
      out.ball[i] = result;
      out.red_state[i] = static_cast<std::int8_t>(red_state);
    }
    if (b.kind == BallKind::kRed) {
      ++out.reds;
      out.tied_reds += result > 0 ? 1 : 0;
    } else {
      const auto c = static_cast<size_t>(ColourOf(b.kind));
      out.colour_present[c] = true;
      out.colour_pottability[c] = result;
    }
  }
  return out;
}

}  // namespace

LayoutSummary SummarizeLayout(const TableState& table, const physics::TableModel& model,
                              const LayoutOptions& options) {
  return Summarize(table, nullptr, nullptr, model, options);
}

double LayoutChange(const TableState& before, const LayoutSummary& before_summary, const TableState& after,
                    const physics::TableModel& model, const LayoutOptions& options) {
  const bool same = before.balls.size() == after.balls.size() &&
                    std::equal(before.balls.begin(), before.balls.end(), after.balls.begin(),
                               [](const Ball& a, const Ball& b) {
                                 return a.kind == b.kind && a.position == b.position;
                               });
  if (same) return 0;
  const LayoutSummary& a = before_summary;
  const LayoutSummary b = Summarize(after, &before, &before_summary, model, options);
  double change = -options.tied_red_cost * (b.tied_reds - a.tied_reds);
  for (int c = 0; c < physics::kColourCount; ++c) {
    const auto k = static_cast<size_t>(c);
    if (!a.colour_present[k] || !b.colour_present[k]) continue;
    const int value = Value(KindOf(static_cast<physics::Colour>(c)));
    change += options.colour_weight * value * (b.colour_pottability[k] - a.colour_pottability[k]);
  }
  return change;
}

double LayoutChange(const TableState& before, const TableState& after,
                    const physics::TableModel& model, const LayoutOptions& options) {
  return LayoutChange(before, SummarizeLayout(before, model, options), after, model, options);
}

}  // namespace snooker::planner
