#include "planner/safety.h"

#include <algorithm>
#include <cmath>

namespace snooker::planner {

using physics::Vec2;

std::vector<Candidate> SafetyCandidates(const TableState& table, int cue, BallOn on, const PotContext& ctx,
                                        int touching_on, int table_index, const SafetyOptions& options) {
  std::vector<Candidate> out;
  if (cue < 0) return out;
  const Vec2 c = table.balls[static_cast<size_t>(cue)].position;
  const double r = ctx.table->ball_radius();
  Candidate base;
  base.kind = ShotKind::kSafety;
  base.table = table_index;
  base.speed_lo = options.speed_lo;
  base.speed_hi = options.speed_hi;
  if (touching_on >= 0) {
    // Roll away from the touching ball on: it counts as hit.
    Candidate away = base;
    away.object = touching_on;
    away.aim = AimMode::kHeading;
    away.aim_base = Direction(c - table.balls[static_cast<size_t>(touching_on)].position);
    away.aim_range = 80 * physics::kPi / 180;
    out.push_back(away);
  }
  // The balls on with a clear line from the cue ball to their centre's near side,
  // nearest first.
  std::vector<std::pair<double, int>> balls;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    const int k = static_cast<int>(i);
    if (k == cue || k == touching_on || !IsLegalTarget(on, table.balls[i].kind)) continue;
    const Vec2 o = table.balls[i].position;
    const double d = (o - c).norm();
    if (d <= 2 * r) continue;
    // Any contact from full to either edge with a clear path will do: the full one
    // and the two half-ball contacts are checked.
    bool clear = false;
    for (const double cut : {0.0, -0.5236, 0.5236}) {
      const auto h = HeadingForCut(c, o, cut, r);
      if (!h) continue;
      const Vec2 ghost = o - 2 * r * Vec2(std::cos(*h + cut), std::sin(*h + cut));
      if (TravelMargin(c, ghost, 2 * r + ctx.path_clearance, table, cue, k) >= 0 &&
          CueMargin(table, cue, *h, ctx.cue, *ctx.table) >= 0) {
        clear = true;
        break;
      }
    }
    if (clear) balls.emplace_back(d, k);
  }
  std::sort(balls.begin(), balls.end());
  if (static_cast<int>(balls.size()) > options.max_balls) balls.resize(static_cast<size_t>(options.max_balls));
  for (const auto& [d, k] : balls) {
    for (const double side : {-1.0, 1.0}) {
      Candidate s = base;
      s.object = k;  // the ball played; any ball on may be hit first
      s.aim = AimMode::kCut;
      s.aim_base = side * 0.5 * options.max_cut;
      s.aim_range = 0.5 * options.max_cut;
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace snooker::planner
