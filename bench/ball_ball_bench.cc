// Speed against error of the ball-ball solver (physics/impact/ball_ball.h): the paper's
// fixed-step scheme at N = 10 ... 1e6 and the adaptive integrator at tolerances
// 1e-3 ... 1e-12, over the shot set of bench/collision_shots.h.
//
// Each iteration resolves one collision (cycling through the shots), so the time
// reported is per collision. Before timing, each benchmark computes its worst
// errors over the shots against a converged reference and reports them as counters:
//   vel_err    max |error| of the post-impact velocities and R * spins, m/s
//   angle_err  max |error| of both balls' exit angles after their slip, deg
//   steps, rejected, rhs  mean accepted steps, rejected steps and right-hand-side
//              evaluations per collision
// Run: scripts/speed-error-report (writes docs/speed-vs-error.*), or
//   build/bench/ball_ball_bench --benchmark_filter=... for a quick look.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bench/collision_shots.h"
#include "physics/impact/ball_ball.h"
#include "physics/motion/slip_phase.h"

namespace snooker::physics {
namespace {

struct Outcome {
  ImpactState out;
  double cue_exit_deg, object_exit_deg;
  ImpulseWork work;
};

Outcome Solve(const NamedShot& shot, const ImpulseSolverOptions& options) {
  const BallParams ball;
  const ClothParams cloth;
  const ImpactState in = ReportShotState(shot);
  ImpulseSolverOptions o = options;
  o.max_steps = 100'000'000;
  const ImpactResult r = ResolveImpact(in, ball, {}, cloth.mu_s, o);
  const Vec2 incoming(in.c.v.x(), in.c.v.y());
  return {r.out,
          RadToDeg(AngleBetween(SlipPhaseEnd(r.out.c, ball, cloth).velocity, incoming)),
          RadToDeg(AngleBetween(SlipPhaseEnd(r.out.o, ball, cloth).velocity, incoming)), r.work};
}

// The reference: the adaptive integrator at tolerance 1e-14 (its agreement with
// tolerance 1e-13 is reported as the counter ref_spread of BM_Reference).
const std::vector<Outcome>& Reference() {
  static const std::vector<Outcome> ref = [] {
    std::vector<Outcome> r;
    ImpulseSolverOptions o;
    o.tolerance = 1e-14;
    for (const NamedShot& s : kReportShots) r.push_back(Solve(s, o));
    return r;
  }();
  return ref;
}

void ReportErrors(benchmark::State& state, const ImpulseSolverOptions& options) {
  const double radius = BallParams{}.radius;
  double vel = 0, angle = 0, steps = 0, rejected = 0, rhs = 0;
  for (size_t i = 0; i < kReportShots.size(); ++i) {
    const Outcome o = Solve(kReportShots[i], options);
    steps += o.work.steps;
    rejected += o.work.rejected_steps;
    rhs += o.work.rhs_evals;
    const Outcome& r = Reference()[i];
    vel = std::max({vel, (o.out.c.v - r.out.c.v).cwiseAbs().maxCoeff(),
                    (o.out.o.v - r.out.o.v).cwiseAbs().maxCoeff(),
                    radius * (o.out.c.w - r.out.c.w).cwiseAbs().maxCoeff(),
                    radius * (o.out.o.w - r.out.o.w).cwiseAbs().maxCoeff()});
    angle = std::max({angle, std::abs(o.cue_exit_deg - r.cue_exit_deg),
                      std::abs(o.object_exit_deg - r.object_exit_deg)});
  }
  const double n = static_cast<double>(kReportShots.size());
  state.counters["vel_err"] = vel;
  state.counters["angle_err"] = angle;
  state.counters["steps"] = steps / n;
  state.counters["rejected"] = rejected / n;
  state.counters["rhs"] = rhs / n;
}

void Time(benchmark::State& state, const ImpulseSolverOptions& options) {
  std::vector<ImpactState> inputs;
  for (const NamedShot& s : kReportShots) inputs.push_back(ReportShotState(s));
  const BallParams ball;
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ResolveImpact(inputs[i], ball, {}, 0.21, options));
    i = (i + 1) % inputs.size();
  }
}

void BM_FixedStep(benchmark::State& state) {
  ImpulseSolverOptions o;
  o.integrator = ImpulseIntegrator::kFixedStep;
  o.steps = static_cast<int>(state.range(0));
  o.max_steps = 100'000'000;
  ReportErrors(state, o);
  Time(state, o);
}
BENCHMARK(BM_FixedStep)
    ->Arg(10)->Arg(30)->Arg(100)->Arg(300)->Arg(1000)->Arg(3000)->Arg(10000)->Arg(30000)
    ->Arg(100000)->Arg(300000)->Arg(1000000);

void BM_Adaptive(benchmark::State& state) {  // tolerance 10^-range(0)
  ImpulseSolverOptions o;
  o.tolerance = std::pow(10.0, -static_cast<double>(state.range(0)));
  ReportErrors(state, o);
  Time(state, o);
}
BENCHMARK(BM_Adaptive)->DenseRange(3, 12, 1);

// How converged the reference is: tolerance 1e-13 against 1e-14.
void BM_Reference(benchmark::State& state) {
  ImpulseSolverOptions o;
  o.tolerance = 1e-13;
  ReportErrors(state, o);
  state.counters["ref_spread"] = state.counters["vel_err"];
  Time(state, o);
}
BENCHMARK(BM_Reference);

}  // namespace
}  // namespace snooker::physics

BENCHMARK_MAIN();
