#include "planner/fallback.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "planner/cushion_paths.h"
#include "planner/geometry.h"
#include "planner/robustness.h"
#include "planner/rules.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

// One aim to try: a heading, and whether it reaches its ball off a cushion.
struct Aim {
  double heading;
  bool cushion;
};

// Headings at `ball` from the cue ball: across its visible width, then along the
// cushion paths' brackets.
std::vector<Aim> AimsAt(const TableState& table, int cue, int ball, const PotContext& ctx,
                        const FallbackOptions& options) {
  std::vector<Aim> aims;
  const Vec2 c = table.balls[static_cast<size_t>(cue)].position;
  const Vec2 o = table.balls[static_cast<size_t>(ball)].position;
  const double r = ctx.table->ball_radius();
  const double d = (o - c).norm();
  const double half = d > 2 * r ? std::asin(std::min(1.0, 2 * r / d)) * 0.9 : 0.0;
  const double direct = Direction(o - c);
  const int n = std::max(1, options.headings);
  for (int k = 0; k < n; ++k) {
    const double f = n == 1 ? 0.0 : -1.0 + 2.0 * k / (n - 1);
    aims.push_back({WrapAngle(direct + f * half), false});
  }
  std::vector<CushionPath> paths;
  AppendCushionPaths(*ctx.table, table, c, o, 2, 2 * r + ctx.path_clearance, cue, ball, ball, CushionPathOptions{},
                     paths);
  for (const CushionPath& p : paths) {
    for (int k = 0; k < n; ++k) {
      const double f = n == 1 ? 0.5 : static_cast<double>(k) / (n - 1);
      aims.push_back({WrapAngle(p.heading + p.bracket.lo + f * p.bracket.width()), true});
    }
  }
  return aims;
}

// The ball a foul nominates: with any colour on the lowest-valued colour on the
// table (the penalty is at least the nominated ball's value), else `ball`.
int Nomination(const TableState& table, BallOn on, int ball) {
  if (on != BallOn::kAnyColour) return ball;
  int best = ball;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    const BallKind k = table.balls[i].kind;
    if (IsColour(k) && Value(k) < Value(table.balls[static_cast<size_t>(best)].kind)) best = static_cast<int>(i);
  }
  return best;
}

}  // namespace

std::optional<FallbackShot> FindLegalStroke(const TableState& table, int cue, BallOn on, const PotContext& ctx,
                                            const SearchSettings& settings, ShotSimulator& sim,
                                            const physics::Interrupt& interrupt, const FallbackOptions& options) {
  if (cue < 0) return std::nullopt;
  const Vec2 c = table.balls[static_cast<size_t>(cue)].position;
  std::vector<std::pair<double, int>> balls;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    if (static_cast<int>(i) != cue && IsLegalTarget(on, table.balls[i].kind)) {
      balls.emplace_back((table.balls[i].position - c).norm(), static_cast<int>(i));
    }
  }
  std::sort(balls.begin(), balls.end());
  if (static_cast<int>(balls.size()) > options.max_balls) balls.resize(static_cast<size_t>(options.max_balls));
  PotContext after_ctx = ctx;
  after_ctx.position_sigma.clear();
  const RobotLimits& lim = settings.limits;
  const std::vector<int> touching = TouchingCueBall(table, *ctx.table);
  std::optional<FallbackShot> best, best_foul;
  int simulations = 0;
  auto finish = [&]() {
    std::optional<FallbackShot>& answer = best || !options.allow_foul ? best : best_foul;
    if (answer) answer->simulations = simulations;
    return answer;
  };
  std::vector<Vec2> finals;
  LeaveScratch scratch;  // the tables each stroke leaves, and their lines into the pockets
  // Plays `heading` at both speeds, aimed at `ball`; false when the cap or the
  // interrupt ends the scan.
  auto try_heading = [&](double heading, int ball) {
    if (CueMargin(table, cue, heading, lim.cue, *ctx.table) < 0) return true;
    const Vec2 u(std::cos(heading), std::sin(heading));
    if (std::any_of(touching.begin(), touching.end(), [&](int i) {
          return PlaysInto(u, table.balls[static_cast<size_t>(i)].position - c);
        })) {
      return true;
    }
    // Level and central where the cue clears, else raised, the tip as high as the
    // request's topspin limit allows.
    const double high = std::min(kMaxTipOffset, lim.max_topspin_fraction / 2.5);
    const auto elevation = CueElevation(table, cue, heading, high, lim.cue, *ctx.table);
    if (!elevation) return true;
    for (const double v : {options.soft, options.firm}) {
      if (simulations >= options.max_simulations || interrupt.Due()) return false;
      const physics::CueParams& cue_params = ctx.cue_params();
      const physics::BallParams& ball_params = sim.params().ball;
      physics::CueStrike k;
      k.heading = heading;
      k.elevation = *elevation;
      k.height = *elevation > 0 ? high : 0.0;
      k.speed = std::clamp(physics::CueSpeedFor(std::clamp(v, lim.min_speed, lim.max_speed), 0.0, k.height,
                                                cue_params, ball_params),
                           lim.min_cue_speed, lim.max_cue_speed);
      physics::StrikeResult struck = physics::Strike(k, cue_params, ball_params, sim.params().cloth.g);
      if (struck.status == physics::StrikeStatus::kHop) {
        // Raised, the fastest stroke that keeps the ball on the bed (the hop goes as v^2).
        k.speed *= 0.98 * std::sqrt(cue_params.max_hop / struck.hop);
        struck = physics::Strike(k, cue_params, ball_params, sim.params().cloth.g);
      }
      const physics::Shot& shot = struck.shot;
      if (struck.status != physics::StrikeStatus::kOk || !WithinLimits(shot, lim, ball_params.radius) ||
          !CueWithinLimits(k, lim)) {
        continue;
      }
      const ShotSetup setup{&table, cue, ball, physics::PocketId::kBaulkLeft, on, ShotKind::kSafety, -1,
                            TouchingBallOn(table, on, *ctx.table)};
      ++simulations;
      const ShotOutcome& out = sim.Run(setup, shot, {}, ShotSimulator::Mode::kToRest, interrupt);
      if (out.status != physics::SimStatus::kAtRest) continue;  // interrupted, or failed
      finals.clear();
      for (const physics::BallState& b : sim.final_balls()) finals.push_back(b.r);
      if (!out.success) {
        if (best || !options.allow_foul || out.foul == Foul::kNone) continue;
        ShotSetup as_foul = setup;
        as_foul.kind = ShotKind::kFoul;
        as_foul.object = Nomination(table, on, ball);
        const double score = MonteCarloScore(as_foul, out, finals, after_ctx, settings, &scratch).score;
        if (!best_foul || score > best_foul->score) {
          best_foul = FallbackShot{ShotKind::kFoul, as_foul.object, k, shot, score, 0};
        }
        continue;
      }
      const double score =
          ScoreSafety(table, on, out.first_hit, finals, out.potted, after_ctx, settings, &scratch).score;
      if (!best || score > best->score) {
        best = FallbackShot{out.cue_cushions_first > 0 ? ShotKind::kEscape : ShotKind::kSafety, out.first_hit, k,
                            shot, score, 0};
      }
    }
    return true;
  };
  for (const auto& [distance, ball] : balls) {
    for (const Aim& aim : AimsAt(table, cue, ball, ctx, options)) {
      if (!try_heading(aim.heading, ball)) return finish();
    }
    if (best) break;  // a legal stroke on the nearest reachable ball will do
  }
  // Nothing the robot can play at a ball on (its cue cannot reach those headings,
  // or they push a touching ball): any heading it can play, around the cue ball;
  // one may still reach a ball on off the cushions, or else foul least.
  if (!best && !best_foul && !balls.empty()) {
    const int n = std::max(1, options.ring_headings);
    const double from = Direction(table.balls[static_cast<size_t>(balls.front().second)].position - c);
    for (int k = 0; k < n; ++k) {
      if (!try_heading(WrapAngle(from + 2 * physics::kPi * k / n), balls.front().second)) return finish();
    }
  }
  return finish();
}

}  // namespace snooker::planner
