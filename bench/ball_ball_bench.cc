// Speed of the ball-ball collision solver (physics/ball_ball.h) on the paper's five
// shots: the fixed-step scheme at several N and the adaptive integrator at several
// tolerances. Run: build/bench/ball_ball_bench
#include <benchmark/benchmark.h>

#include <cmath>

#include "physics/ball_ball.h"
#include "tests/physics/paper_shots.h"

namespace snooker::physics {
namespace {

ImpactState Shot(int i) {
  const PaperShot& s = kPaperShots[static_cast<size_t>(i)];
  return PaperIncidentState(s.speed, s.speed / BallParams{}.radius, 0.0, DegToRad(s.cut_deg));
}

void BM_FixedStep(benchmark::State& state) {
  ImpulseSolverOptions o;
  o.integrator = ImpulseIntegrator::kFixedStep;
  o.steps = static_cast<int>(state.range(0));
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ResolveImpact(Shot(i), {}, {}, 0.21, o));
    i = (i + 1) % 5;
  }
}
BENCHMARK(BM_FixedStep)->RangeMultiplier(10)->Range(10, 100000);

void BM_Adaptive(benchmark::State& state) {
  ImpulseSolverOptions o;
  o.tolerance = std::pow(10.0, -static_cast<double>(state.range(0)));
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ResolveImpact(Shot(i), {}, {}, 0.21, o));
    i = (i + 1) % 5;
  }
}
BENCHMARK(BM_Adaptive)->DenseRange(4, 12, 2);

}  // namespace
}  // namespace snooker::physics

BENCHMARK_MAIN();
