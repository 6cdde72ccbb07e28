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
// obstacle) by `clearance`.
bool Clear(const Vec2& a, const Vec2& b, double clearance, const TableState& table, int skip) {
  for (size_t i = 0; i < table.balls.size(); ++i) {
    if (static_cast<int>(i) == skip || table.balls[i].kind == BallKind::kCue) continue;
    if (SegmentDistance(a, b, table.balls[i].position) < clearance) return false;
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
// the ghost ball g for an object ball leaving along `theta`: fills the pot's cut,
// cue and heading, or returns false.
bool Approach(const TableState& table, int ball, const Vec2& g, double theta,
              const physics::TableModel& model, const LayoutOptions& options, LayoutPot* pot) {
  const double clearance = 2 * model.ball_radius() + options.path_clearance;
  const int steps = options.cut_step > 0
                        ? static_cast<int>(std::clamp(options.max_cut / options.cut_step + 1e-9, 0.0, kMaxCutSteps))
                        : 0;
  for (int k = 0; k <= 2 * steps; ++k) {
    const double cut = options.cut_step * ((k + 1) / 2) * (k % 2 == 1 ? 1 : -1);
    const double h = theta - cut;
    const Vec2 back(-std::cos(h), -std::sin(h));
    const double run = std::min(options.cue_distance, RunToEdge(g, back, model, options.touch_gap));
    if (run < options.min_cue_run) continue;
    const Vec2 cue = g + run * back;
    if (Clear(cue, g, clearance, table, ball)) {
      pot->cut = cut;
      pot->cue = cue;
      pot->heading = WrapAngle(h);
      return true;
    }
  }
  return false;
}

}  // namespace

std::optional<LayoutPot> OpenPot(const TableState& table, int ball, physics::PocketId pocket,
                                 const physics::TableModel& model, const LayoutOptions& options) {
  const PocketModel& pockets = PocketsOf(options);
  const double r = model.ball_radius();
  const Vec2 o = table.balls[static_cast<size_t>(ball)].position;
  const physics::Pocket& p = model.pocket(pocket);
  const Vec2 q = p.mouth_centre - o;
  const double l0 = q.norm();
  if (!(l0 > 0)) return std::nullopt;
  // Aim at the window's centre, in two passes (as pot_estimate.cc does).
  double theta = Direction(q);
  PocketWindow window;
  for (int pass = 0; pass < 2; ++pass) {
    window = pockets.Window(pocket, theta, kTypicalArrivalSpeed);
    if (window.empty || std::abs(window.centre()) >= l0) return std::nullopt;
    theta = Direction(q) + std::asin(window.centre() / l0);
  }
  const Vec2 u(std::cos(theta), std::sin(theta));
  const double clearance = 2 * r + options.path_clearance;
  const Vec2 mouth = p.mouth_centre + window.centre() * Left(u);
  if (!Clear(o, mouth, clearance, table, ball)) return std::nullopt;
  // A ghost ball within touch_gap past a contact line counts as on the bed (a ball
  // frozen to a cushion is potted along it with the cue ball on the cushion).
  const Vec2 g = o - 2 * r * u;
  if (BedGap(g, model) < -options.touch_gap || !Clear(g, g, clearance, table, ball)) return std::nullopt;
  LayoutPot pot;
  pot.object_direction = theta;
  if (!Approach(table, ball, g, theta, model, options, &pot)) return std::nullopt;
  const double sigma = (mouth - o).norm() * options.line_sigma / std::cos(pot.cut);
  pot.chance = sigma > 0 ? std::max(0.0, 2 * NormalCdf(window.width() / (2 * sigma)) - 1) : 1.0;
  return pot;
}

double Pottability(const TableState& table, int ball, const physics::TableModel& model,
                   const LayoutOptions& options) {
  double best = 0, second = 0;
  for (int k = 0; k < physics::kPocketCount; ++k) {
    const auto pot = OpenPot(table, ball, static_cast<physics::PocketId>(k), model, options);
    const double p = pot ? pot->chance : 0.0;
    if (p > best) {
      second = best;
      best = p;
    } else if (p > second) {
      second = p;
    }
  }
  return options.pocket_weights[0] * best + options.pocket_weights[1] * second;
}

bool TiedUp(const TableState& table, int ball, const physics::TableModel& model,
            const LayoutOptions& options) {
  const Vec2 o = table.balls[static_cast<size_t>(ball)].position;
  if (BedGap(o, model) < options.touch_gap) return true;
  const double near = 2 * model.ball_radius() + options.touch_gap;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    if (static_cast<int>(i) == ball || table.balls[i].kind == BallKind::kCue) continue;
    if ((table.balls[i].position - o).norm() < near) return true;
  }
  for (int k = 0; k < physics::kPocketCount; ++k) {
    if (OpenPot(table, ball, static_cast<physics::PocketId>(k), model, options)) return false;
  }
  return true;
}

LayoutSummary SummarizeLayout(const TableState& table, const physics::TableModel& model,
                              const LayoutOptions& options) {
  LayoutSummary out;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    const BallKind kind = table.balls[i].kind;
    if (kind == BallKind::kRed) {
      ++out.reds;
      if (TiedUp(table, static_cast<int>(i), model, options)) ++out.tied_reds;
    } else if (IsColour(kind)) {
      const auto c = static_cast<size_t>(ColourOf(kind));
      if (out.colour_present[c]) continue;  // a second ball of a colour: the first counts
      out.colour_present[c] = true;
      out.colour_pottability[c] = Pottability(table, static_cast<int>(i), model, options);
    }
  }
  return out;
}

double LayoutChange(const TableState& before, const TableState& after,
                    const physics::TableModel& model, const LayoutOptions& options) {
  const bool same = before.balls.size() == after.balls.size() &&
                    std::equal(before.balls.begin(), before.balls.end(), after.balls.begin(),
                               [](const Ball& a, const Ball& b) {
                                 return a.kind == b.kind && a.position == b.position;
                               });
  if (same) return 0;
  const LayoutSummary a = SummarizeLayout(before, model, options);
  const LayoutSummary b = SummarizeLayout(after, model, options);
  double change = -options.tied_red_cost * (b.tied_reds - a.tied_reds);
  for (int c = 0; c < physics::kColourCount; ++c) {
    const auto k = static_cast<size_t>(c);
    if (!a.colour_present[k] || !b.colour_present[k]) continue;
    const int value = Value(KindOf(static_cast<physics::Colour>(c)));
    change += options.colour_weight * value * (b.colour_pottability[k] - a.colour_pottability[k]);
  }
  return change;
}

}  // namespace snooker::planner
