// Speed against error of the ball-cushion solver (physics/impact/ball_cushion.h):
// the adaptive integrator at tolerances 1e-3 ... 1e-12 and the paper's fixed-step
// scheme, over the cushion shot set of bench/collision_shots.h with the table
// simulation's parameters.
//
// Each iteration resolves one impact (cycling through the shots), so the time
// reported is per impact. Counters, computed before timing:
//   vel_err  max |error| of the post-impact velocity and R * spin against the
//            adaptive integrator at tolerance 1e-14, m/s
//   steps, rejected, rhs  mean accepted steps, rejected steps and right-hand-side
//            evaluations per impact
// Run: scripts/speed-error-report (docs/speed-vs-error.md), or
//   build/bench/cushion_impact_bench --benchmark_filter=... for a quick look.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bench/collision_shots.h"

namespace snooker::physics {
namespace {

const std::vector<BallMotion>& Shots() {
  static const std::vector<BallMotion> shots = CushionShots();
  return shots;
}

CushionImpactResult Solve(const BallMotion& in, const ImpulseSolverOptions& options) {
  ImpulseSolverOptions o = options;
  o.max_steps = 100'000'000;
  return ResolveCushionImpact(in, BallParams{}, TableCushionParams(), o);
}

const std::vector<BallMotion>& Reference() {
  static const std::vector<BallMotion> ref = [] {
    std::vector<BallMotion> r;
    ImpulseSolverOptions o;
    o.tolerance = 1e-14;
    for (const BallMotion& s : Shots()) r.push_back(Solve(s, o).out);
    return r;
  }();
  return ref;
}

void ReportErrors(benchmark::State& state, const ImpulseSolverOptions& options) {
  const double radius = BallParams{}.radius;
  double vel = 0, steps = 0, rejected = 0, rhs = 0;
  for (size_t i = 0; i < Shots().size(); ++i) {
    const CushionImpactResult r = Solve(Shots()[i], options);
    const BallMotion& ref = Reference()[i];
    vel = std::max({vel, (r.out.v - ref.v).cwiseAbs().maxCoeff(),
                    radius * (r.out.w - ref.w).cwiseAbs().maxCoeff()});
    steps += r.work.steps;
    rejected += r.work.rejected_steps;
    rhs += r.work.rhs_evals;
  }
  const double n = static_cast<double>(Shots().size());
  state.counters["vel_err"] = vel;
  state.counters["steps"] = steps / n;
  state.counters["rejected"] = rejected / n;
  state.counters["rhs"] = rhs / n;
}

void Time(benchmark::State& state, const ImpulseSolverOptions& options) {
  const BallParams ball;
  const CushionParams cushion = TableCushionParams();
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ResolveCushionImpact(Shots()[i], ball, cushion, options));
    i = (i + 1) % Shots().size();
  }
}

void BM_CushionAdaptive(benchmark::State& state) {  // tolerance 10^-range(0)
  ImpulseSolverOptions o;
  o.tolerance = std::pow(10.0, -static_cast<double>(state.range(0)));
  ReportErrors(state, o);
  Time(state, o);
}
BENCHMARK(BM_CushionAdaptive)->DenseRange(3, 12, 1);

void BM_CushionFixedStep(benchmark::State& state) {
  ImpulseSolverOptions o;
  o.integrator = ImpulseIntegrator::kFixedStep;
  o.steps = static_cast<int>(state.range(0));
  o.max_steps = 100'000'000;
  ReportErrors(state, o);
  Time(state, o);
}
BENCHMARK(BM_CushionFixedStep)->Arg(100)->Arg(1000)->Arg(10000);

}  // namespace
}  // namespace snooker::physics

BENCHMARK_MAIN();
