#include "planner/break_off.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "planner/geometry.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

// The rack's back row: the last five of TableModel::reds(), from -x to +x.
constexpr int kBackLeft = physics::kRedCount - 5;
constexpr int kBackRight = physics::kRedCount - 1;

// Caps of the scans: cut steps (0.1 deg steps up to 90 deg) and placements per side.
constexpr double kMaxCutSteps = 900;
constexpr int kMaxPlacementsPerSide = 32;

// The red of `table` within `tolerance` of `slot`, or -1.
int RedAt(const TableState& table, const Vec2& slot, double tolerance) {
  for (size_t i = 0; i < table.balls.size(); ++i) {
    if (table.balls[i].kind == BallKind::kRed && (table.balls[i].position - slot).norm() <= tolerance) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

bool Free(const Vec2& p, const TableState& table, double distance) {
  return std::none_of(table.balls.begin(), table.balls.end(),
                      [&](const Ball& b) { return (b.position - p).norm() < distance; });
}

// The straight path from `from` to the contact of cut `cut` on ball `target`
// passes every other ball by `clearance`.
bool CutClear(const TableState& table, const Vec2& from, int target, double cut, double radius,
              double clearance) {
  const Vec2 o = table.balls[static_cast<size_t>(target)].position;
  const auto h = HeadingForCut(from, o, cut, radius);
  if (!h) return false;
  const double d = (o - from).norm();
  const double b = 2 * radius * std::sin(cut);
  const double along = std::sqrt(d * d - b * b) - std::sqrt(std::max(0.0, 4 * radius * radius - b * b));
  const Vec2 g = from + along * Vec2(std::cos(*h), std::sin(*h));
  for (size_t i = 0; i < table.balls.size(); ++i) {
    if (static_cast<int>(i) == target) continue;
    if (SegmentDistance(from, g, table.balls[i].position) < clearance) return false;
  }
  return true;
}

// The clear run of cuts of sign `sign` nearest the full ball: [fullest, thinnest]
// as magnitudes, or nullopt.
std::optional<std::pair<double, double>> ClearCuts(const TableState& table, const Vec2& from, int target,
                                                   double sign, double radius, const BreakOffOptions& o) {
  const double clearance = 2 * radius + o.path_clearance;
  const int steps = o.cut_step > 0 ? static_cast<int>(std::clamp(o.max_cut / o.cut_step, 0.0, kMaxCutSteps)) : 0;
  std::optional<std::pair<double, double>> run;
  for (int k = 0; k <= steps; ++k) {
    const double c = k * o.cut_step;
    const bool clear = CutClear(table, from, target, sign * c, radius, clearance);
    if (clear && !run) run = std::make_pair(c, c);
    if (clear) run->second = c;
    if (!clear && run) break;
  }
  return run;
}

// The cut of `target` from `from` meets a red first (the target or another).
bool MeetsARed(const TableState& table, const Vec2& from, int target, double cut, double radius) {
  const auto h = HeadingForCut(from, table.balls[static_cast<size_t>(target)].position, cut, radius);
  if (!h) return false;
  const int first = FirstBallMet(table, from, *h, radius);
  return first >= 0 && table.balls[static_cast<size_t>(first)].kind == BallKind::kRed;
}

// The free placements on one side (right: towards the yellow), from the brown
// outwards: placements_per_side points evenly between the brown spot and the side's
// spot, line_inset behind the baulk line, each ball_clearance clear of every ball.
std::vector<Vec2> Placements(const TableState& table, const physics::TableModel& model, const BreakOffOptions& o,
                             bool right) {
  const Vec2 brown = model.spot(physics::Colour::kBrown);
  const double sign = right ? 1.0 : -1.0;
  const int n = std::clamp(o.placements_per_side, 0, kMaxPlacementsPerSide);
  std::vector<Vec2> out;
  for (int k = 1; k <= n; ++k) {
    const double f = static_cast<double>(k) / (n + 1);
    const Vec2 p(brown.x() + sign * f * model.spec().d_radius, brown.y() - o.line_inset);
    if (Free(p, table, 2 * model.ball_radius() + o.ball_clearance)) out.push_back(p);
  }
  return out;
}

// A soft break's cuts: this either side of the full ball, rad.
constexpr double kSoftCutRange = 6.0 * physics::kPi / 180;

}  // namespace

std::vector<BreakOffCandidate> BreakOffCandidates(const TableState& table, const physics::TableModel& model,
                                                  const BreakOffOptions& options) {
  std::vector<BreakOffCandidate> out;
  const double r = model.ball_radius();
  for (const bool right : {true, false}) {
    const Vec2 slot = model.reds()[static_cast<size_t>(right ? kBackRight : kBackLeft)];
    const int target = RedAt(table, slot, options.rack_tolerance);
    if (target < 0) continue;
    const double sign = right ? 1.0 : -1.0;
    for (const Vec2& p : Placements(table, model, options, right)) {
      const auto cuts = ClearCuts(table, p, target, sign, r, options);
      if (!cuts) continue;
      BreakOffCandidate c;
      c.placement = p;
      c.target = target;
      c.target_position = table.balls[static_cast<size_t>(target)].position;
      c.right = right;
      const double nominal = std::min(cuts->first + options.nominal_offset, cuts->second);
      c.cut = sign * nominal;
      c.cut_lo = right ? cuts->first : -cuts->second;
      c.cut_hi = right ? cuts->second : -cuts->first;
      c.heading = *HeadingForCut(p, c.target_position, c.cut, r);
      c.speed = options.speed;
      c.sidespin = -sign * options.side;
      out.push_back(c);
    }
  }
  return out;
}

std::vector<BreakOffCandidate> SoftBreakCandidates(const TableState& table, const physics::TableModel& model,
                                                   const BreakOffOptions& options) {
  std::vector<BreakOffCandidate> out;
  if (!options.soft_break) return out;
  const double r = model.ball_radius();
  for (const bool right : {true, false}) {
    for (const Vec2& p : Placements(table, model, options, right)) {
      // The nearest red whose centre line from p meets a red first.
      int target = -1;
      double nearest = std::numeric_limits<double>::infinity();
      for (size_t i = 0; i < table.balls.size(); ++i) {
        if (table.balls[i].kind != BallKind::kRed) continue;
        const double d = (table.balls[i].position - p).norm();
        if (!(d < nearest)) continue;
        if (!MeetsARed(table, p, static_cast<int>(i), 0.0, r)) continue;
        target = static_cast<int>(i);
        nearest = d;
      }
      if (target < 0) continue;
      // The run of cuts about the full ball that meet a red first.
      double lo = 0, hi = 0;
      const double step = options.cut_step > 0 ? options.cut_step : kSoftCutRange;
      while (hi + step <= kSoftCutRange && MeetsARed(table, p, target, hi + step, r)) hi += step;
      while (lo - step >= -kSoftCutRange && MeetsARed(table, p, target, lo - step, r)) lo -= step;
      BreakOffCandidate c;
      c.placement = p;
      c.target = target;
      c.target_position = table.balls[static_cast<size_t>(target)].position;
      c.right = right;
      c.cut = 0;
      c.cut_lo = lo;
      c.cut_hi = hi;
      c.heading = *HeadingForCut(p, c.target_position, 0.0, r);
      c.speed = options.soft_speed;
      c.soft = true;
      out.push_back(c);
    }
  }
  return out;
}

bool IsBreakOffTable(const TableState& table, bool cue_in_hand, const physics::TableModel& model,
                     const BreakOffOptions& options) {
  if (!cue_in_hand || table.cue_index() >= 0 || table.reds() != physics::kRedCount) return false;
  // Rack positions are 2R apart and the tolerance is far below R: a red is within
  // it of one position at most, so a red found for each of the 15 positions means
  // 15 distinct reds.
  for (const Vec2& slot : model.reds()) {
    if (RedAt(table, slot, options.rack_tolerance) < 0) return false;
  }
  return true;
}

}  // namespace snooker::planner
