// The planner against its time budget (Google Benchmark): elapsed wall time per
// plan over many seeded tables, as a fraction of the budget. Not a timed test: the
// machine is shared; scripts/planner-report runs it and keeps the table in docs/.
//  * BM_PlanBudget/<budget ms>/<reds>: plans seeded mid-frame tables (the self-play's:
//    colours on their spots, the cue ball free) with 8 reds or 15 (22 balls), one
//    table per iteration. Counters: the median, 99th percentile and largest elapsed
//    time over the budget, simulations per plan, shots found.
//  * BM_PlanWork/<simulations>: the same with the simulation cap binding (budget
//    60 s): time per simulation of the whole planner (search, verification, Monte
//    Carlo), the rate the planner's budget calibration assumes.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "planner/planner.h"
#include "planner/selfplay.h"

namespace snooker::planner::bench {
namespace {

std::vector<TableState> Tables(int reds, int count) {
  std::vector<TableState> tables;
  for (int k = 0; k < count; ++k) {
    Rng rng(DeriveSeed(2024, static_cast<std::uint64_t>(reds), static_cast<std::uint64_t>(k)));
    tables.push_back(RandomFrame(rng, reds, physics::DefaultTable()));
  }
  return tables;
}

void BM_PlanBudget(benchmark::State& state) {
  const double budget_ms = static_cast<double>(state.range(0));
  const std::vector<TableState> tables = Tables(static_cast<int>(state.range(1)), 64);
  const Planner& planner = Planner::Default();
  std::vector<double> ratio;
  double sims = 0, shots = 0;
  size_t k = 0;
  for (auto _ : state) {
    PlanRequest r;
    r.table = tables[k % tables.size()];
    r.seed = k;
    r.time_budget = budget_ms * 1e-3;
    const auto t0 = std::chrono::steady_clock::now();
    const PlanAnswer a = planner.Plan(r);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(elapsed);
    ratio.push_back(elapsed / r.time_budget);
    sims += static_cast<double>(a.simulations);
    shots += static_cast<double>(a.shots.size());
    ++k;
  }
  state.counters["budget_ms"] = budget_ms;
  state.counters["elapsed_p50"] = Percentile(ratio, 0.5);
  state.counters["elapsed_p99"] = Percentile(ratio, 0.99);
  state.counters["elapsed_max"] = *std::max_element(ratio.begin(), ratio.end());
  state.counters["simulations"] = sims / static_cast<double>(k);
  state.counters["shots"] = shots / static_cast<double>(k);
}
BENCHMARK(BM_PlanBudget)
    ->ArgsProduct({{10, 30, 100, 300}, {8, 15}})
    ->Iterations(64)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

void BM_PlanWork(benchmark::State& state) {
  const std::vector<TableState> tables = Tables(8, 16);
  const Planner& planner = Planner::Default();
  double sims = 0;
  size_t k = 0;
  for (auto _ : state) {
    PlanRequest r;
    r.table = tables[k % tables.size()];
    r.seed = k;
    r.time_budget = 60;
    r.max_simulations = state.range(0);
    if (state.range(1) > 0) r.position_spread = static_cast<double>(state.range(1));
    sims += static_cast<double>(planner.Plan(r).simulations);
    ++k;
  }
  state.counters["simulations"] = sims / static_cast<double>(k);
  state.counters["wall_us_per_simulation"] =
      benchmark::Counter(sims * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
// The second argument is the request's position_spread (0: unset): what valuing the
// position over the cue ball's end spread costs at equal simulations.
BENCHMARK(BM_PlanWork)->Args({400, 0})->Args({400, 2})->Iterations(32)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace snooker::planner::bench

BENCHMARK_MAIN();
