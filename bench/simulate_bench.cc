// Speed of the table simulation (physics/sim/simulate.h), Google Benchmark.
//  * BM_TwoBallPot/0 and /1: the same straight pot (cue ball and red moving) on an
//    empty table and on a full table of 22 balls; their ratio is what the idle balls
//    cost. Wall-clock times on a shared machine are noisy: scripts/simulation-
//    benchmarks also counts instructions (bench/simulate_count under callgrind).
//  * BM_BreakOff: the cue ball from the D into the full pack, until every ball rests.
// Counters: events per run, impact right-hand-side evaluations per run, pair
// contact checks that reached the quartic solver and that the bounds culled.
#include <benchmark/benchmark.h>

#include "tests/support/scenarios.h"

namespace snooker::physics::bench {
namespace {

using scenarios::BreakOff;
using scenarios::TwoBallPot;

void Run(benchmark::State& state, const std::vector<BallState>& balls) {
  Simulator sim(DefaultTable(), SimParams{});
  const RunOptions lean = RunOptions::Lean();
  for (auto _ : state) benchmark::DoNotOptimize(sim.Run(balls, lean));
  state.counters["balls"] = static_cast<double>(balls.size());
  state.counters["events"] = sim.event_count();
  state.counters["impact_rhs"] = sim.impact_work().rhs_evals;
  state.counters["pair_checks"] = static_cast<double>(sim.pair_checks());
  state.counters["pair_culls"] = static_cast<double>(sim.pair_culls());
}

void BM_TwoBallPot(benchmark::State& state) { Run(state, TwoBallPot(state.range(0) == 1)); }
BENCHMARK(BM_TwoBallPot)->Arg(0)->Arg(1);

void BM_BreakOff(benchmark::State& state) { Run(state, BreakOff()); }
BENCHMARK(BM_BreakOff)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace snooker::physics::bench

BENCHMARK_MAIN();
