// Speed of the table simulation (physics/simulate.h). Run: build/bench/simulate_bench
//  * BM_TwoBallPot/0 and /1: the same straight pot of one red (cue ball and red
//    moving) on an empty table and on a full table of 22 balls where the other 20
//    are far from the action. Their ratio is the cost of the scene's idle balls.
//  * BM_BreakOff: the cue ball from the D into the full pack, until every ball rests.
// Counters: events per run, impact right-hand-side evaluations per run, pair
// contact checks that reached the quartic solver and that distance culled.
#include <benchmark/benchmark.h>

#include <vector>

#include "physics/simulate.h"

namespace snooker::physics {
namespace {

constexpr double kR = 0.02625;

BallState Rolling(const Vec2& r, const Vec2& dir, double speed) {
  BallState s;
  s.r = r;
  s.v = Vec3(speed * dir.x(), speed * dir.y(), 0);
  s.w = Vec3(-dir.y(), dir.x(), 0) * (speed / kR);
  return s;
}

BallState AtRest(const Vec2& r) {
  BallState s;
  s.r = r;
  return s;
}

const TableModel& Table() {
  static const TableModel table;
  return table;
}

// A full table: the reds in their triangle, the colours on their spots. The pot
// happens near the baulk-left pocket, far from all of them.
std::vector<BallState> FullTable() {
  std::vector<BallState> balls;
  for (const Vec2& r : Table().reds()) balls.push_back(AtRest(r));
  for (int c = 0; c < kColourCount; ++c) {
    if (Colour(c) != Colour::kGreen) balls.push_back(AtRest(Table().spot(Colour(c))));
  }
  balls.push_back(AtRest(Vec2(1.2, 1.2)));  // a 21st and 22nd ball mid-table
  return balls;
}

std::vector<BallState> TwoBallPot(bool full) {
  const Pocket& p = Table().pocket(PocketId::kBaulkLeft);
  const Vec2 red = p.mouth_centre - 0.35 * p.axis;
  std::vector<BallState> balls = {Rolling(red - 0.4 * p.axis, p.axis, 1.5), AtRest(red)};
  if (full) {
    const std::vector<BallState> rest = FullTable();
    balls.insert(balls.end(), rest.begin(), rest.end() - 1);  // 2 + 20 = 22 balls
  }
  return balls;
}

void Report(benchmark::State& state, const Simulator& sim) {
  state.counters["events"] = sim.event_count();
  state.counters["impact_rhs"] = sim.impact_work().rhs_evals;
  state.counters["pair_checks"] = static_cast<double>(sim.pair_checks());
  state.counters["pair_culls"] = static_cast<double>(sim.pair_culls());
}

void BM_TwoBallPot(benchmark::State& state) {
  const std::vector<BallState> balls = TwoBallPot(state.range(0) == 1);
  Simulator sim(Table(), SimParams{});
  for (auto _ : state) benchmark::DoNotOptimize(sim.Run(balls, {}, /*record=*/false));
  state.counters["balls"] = static_cast<double>(balls.size());
  Report(state, sim);
}
BENCHMARK(BM_TwoBallPot)->Arg(0)->Arg(1);

void BM_BreakOff(benchmark::State& state) {
  std::vector<BallState> balls;
  const Vec2 cue(Table().spot(Colour::kBrown).x() + 0.15, Table().spot(Colour::kBrown).y() - 0.1);
  const Vec2 target = Table().reds()[0] + Vec2(0.02, 0.0);
  balls.push_back(Rolling(cue, (target - cue).normalized(), 7.0));
  balls[0].w *= 0.5;
  for (const Vec2& r : Table().reds()) balls.push_back(AtRest(r));
  for (int c = 0; c < kColourCount; ++c) balls.push_back(AtRest(Table().spot(Colour(c))));
  Simulator sim(Table(), SimParams{});
  for (auto _ : state) benchmark::DoNotOptimize(sim.Run(balls, {}, /*record=*/false));
  Report(state, sim);
}
BENCHMARK(BM_BreakOff)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace snooker::physics

BENCHMARK_MAIN();
