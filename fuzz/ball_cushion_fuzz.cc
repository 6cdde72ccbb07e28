// libFuzzer target for the ball-cushion solver (physics/impact/ball_cushion.h). Decodes
// any bytes into an impact (the ball's velocity and spin, the cushion's restitution or
// restitution curve, friction at the nose and on the cloth, the nose's height, the
// ball, the integrator and its setting, the fidelity tier) and checks what must hold
// for every input:
//  * the solver returns (within its step cap) one of its statuses, and the same answer
//    when asked twice;
//  * an accepted impact gives finite output on the cloth (v.z = 0); the ball leaves
//    the cushion (its normal speed no longer approaching); the impulses are ordered
//    (0 <= P_c <= P_f); energy does not rise (beyond the integrator's accuracy at the
//    chosen setting);
//  * rejected or not-approaching input is returned unchanged, and the validator names
//    a bad value exactly when the solver rejects.
// A broken law aborts (libFuzzer then saves the input as a crash-* file).
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "fuzz/impact_fuzz_support.h"
#include "physics/impact/ball_cushion.h"

namespace {

using snooker::fuzz::CheckValidatorAgrees;
using snooker::fuzz::Fail;
using snooker::fuzz::Same;
using snooker::fuzz::Value;
using snooker::fuzz::Vector;
using snooker::physics::BallMotion;
using snooker::physics::BallParams;
using snooker::physics::Vec3;

// Kinetic energy on the cloth: the model ignores the input's vertical velocity and
// leaves none (ball_cushion.h), so it counts the horizontal one only. J.
double Energy(const BallMotion& m, const BallParams& ball) {
  return 0.5 * ball.mass * (m.v.x() * m.v.x() + m.v.y() * m.v.y()) + 0.5 * ball.Inertia() * m.w.squaredNorm();
}

// The decoded impact, for a crash's triage (set SNOOKER_FUZZ_PRINT and run the target
// on the crash-* file).
void Print(const BallMotion& m, const BallParams& ball, const snooker::physics::CushionParams& c,
           const snooker::physics::ImpulseSolverOptions& o, const snooker::physics::CushionImpactResult& r) {
  std::fprintf(stderr, "in v (%.17g, %.17g, %.17g) w (%.17g, %.17g, %.17g)\n", m.v.x(), m.v.y(), m.v.z(),
               m.w.x(), m.w.y(), m.w.z());
  std::fprintf(stderr, "ball R %.17g M %.17g; cushion e %.17g mu_w %.17g mu_s %.17g h %.17g, curve points %d\n",
               ball.radius, ball.mass, c.e_e, c.mu_w, c.mu_s, c.contact_height, c.restitution_curve.points);
  for (int i = 0; i < std::clamp(c.restitution_curve.points, 0, 8); ++i) {
    std::fprintf(stderr, "  knot %.17g m/s e %.17g\n", c.restitution_curve.speed[static_cast<size_t>(i)],
                 c.restitution_curve.e[static_cast<size_t>(i)]);
  }
  std::fprintf(stderr, "integrator %d steps %d tolerance %.3g method %d max_steps %d fidelity %d\n",
               static_cast<int>(o.integrator), o.steps, o.tolerance, static_cast<int>(o.method), o.max_steps,
               static_cast<int>(o.fidelity));
  std::fprintf(stderr, "status %s, out v (%.17g, %.17g) w (%.17g, %.17g, %.17g), P_c %.17g P_f %.17g, %d steps\n",
               snooker::physics::ToString(r.status), r.out.v.x(), r.out.v.y(), r.out.w.x(), r.out.w.y(), r.out.w.z(),
               r.impulse_compression, r.impulse_final, r.work.steps);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace snooker::physics;
  FuzzedDataProvider in(data, size);
  BallMotion m;
  if (in.ConsumeBool()) {  // the notes' incident state: speed, angle to the cushion, spins
    m = CushionIncidentState(Value(in, 0, 10), Value(in, -3.2, 3.2), Value(in, -1000, 1000),
                             Value(in, -1000, 1000));
  } else {  // anything, vertical velocity included (the model ignores it)
    m.v = Vector(in, 10);
    m.w = Vector(in, 1000);
  }
  BallParams ball;
  if (in.ConsumeIntegralInRange<int>(0, 7) == 0) {  // another ball, sometimes a bad one
    ball.radius = Value(in, 0.01, 0.05);
    ball.mass = Value(in, 0.05, 0.5);
  }
  CushionParams cushion = MathavanCushionParams(ball);
  if (in.ConsumeBool()) {
    cushion.e_e = Value(in, 0, 1);
    cushion.mu_w = Value(in, 0, 1);
    cushion.mu_s = Value(in, 0, 1);
    cushion.contact_height = ball.radius * Value(in, 0.9, 2.1);
  }
  if (in.ConsumeIntegralInRange<int>(0, 3) == 0) {  // a restitution curve, knots in any order
    RestitutionCurve& curve = cushion.restitution_curve;
    curve.points = in.ConsumeIntegralInRange<int>(-1, RestitutionCurve::kMaxPoints + 1);
    double speed = 0;
    for (int i = 0; i < std::clamp(curve.points, 0, RestitutionCurve::kMaxPoints); ++i) {
      speed += Value(in, -0.5, 3);
      curve.speed[static_cast<size_t>(i)] = speed;
      curve.e[static_cast<size_t>(i)] = Value(in, 0, 1);
    }
  }
  ImpulseSolverOptions options;
  if (in.ConsumeBool()) {
    options.integrator = ImpulseIntegrator::kFixedStep;
    options.steps = in.ConsumeIntegralInRange<int>(-5, 2000);
  } else {
    options.tolerance = std::pow(10.0, -in.ConsumeFloatingPointInRange<double>(1, 15));
    // The Runge-Kutta pair, sometimes one the library does not know (must be rejected).
    options.method = static_cast<ImpulseMethod>(in.ConsumeIntegralInRange<int>(0, 2));
  }
  if (in.ConsumeIntegralInRange<int>(0, 7) == 0) options.max_steps = in.ConsumeIntegralInRange<int>(-2, 50);
  options.fidelity = static_cast<ImpulseFidelity>(in.ConsumeIntegralInRange<int>(0, 2));

  const CushionImpactResult r = ResolveCushionImpact(m, ball, cushion, options);
  if (std::getenv("SNOOKER_FUZZ_PRINT") != nullptr) Print(m, ball, cushion, options, r);
  const CushionImpactResult again = ResolveCushionImpact(m, ball, cushion, options);
  if (again.status != r.status || !Same(again.out, r.out)) Fail("deterministic", 0, 0);
  CheckValidatorAgrees(ValidateCushionImpact(m, ball, cushion, options), r.status);
  switch (r.status) {
    case ImpactStatus::kOk: {
      const BallMotion& o = r.out;
      if (!(o.v.allFinite() && o.w.allFinite())) Fail("finite output", 0, 0);
      if (o.v.z() != 0) Fail("on the cloth", o.v.z(), 0);
      const double sin_th = CushionSinTheta(ball, cushion);
      const double cos_th = std::sqrt(1 - sin_th * sin_th);
      // Restitution ends the impact where the normal speed has turned: what remains of
      // the approach is the last step's or the event location's rounding.
      const double speed = CushionSpeedScale(m, ball.radius);
      if (o.v.y() * cos_th > 1e-9 * speed) Fail("the ball leaves the cushion", o.v.y() * cos_th, speed);
      if (!(r.impulse_compression >= 0 && r.impulse_final >= r.impulse_compression * (1 - 1e-12))) {
        Fail("0 <= P_c <= P_f", r.impulse_compression, r.impulse_final);
      }
      const double e0 = Energy(m, ball), e1 = Energy(o, ball);
      const ImpulseSolverOptions run = EffectiveOptions(options);  // what was solved
      // Energy may not rise beyond the integrator's own accuracy: a few times the
      // tolerance for the adaptive integrator; 10/N for the fixed-step scheme, whose
      // steps hold their friction to the step's end and so can drive a slip past zero
      // and gain energy at coarse N (CushionEnergy.CoarseFixedStepsGainEnergyWithinTenOverN
      // measures about 1/N).
      const double slack = run.integrator == ImpulseIntegrator::kFixedStep ? 10.0 / run.steps
                                                                            : 20 * run.tolerance + 1e-11;
      if (e1 > e0 * (1 + slack) + 1e-300) Fail("energy rose", e1, e0);
      break;
    }
    case ImpactStatus::kNotApproaching:
    case ImpactStatus::kInvalidInput:
      if (!Same(r.out, m)) Fail("rejected input unchanged", 0, 0);
      break;
    case ImpactStatus::kStepLimit:
      break;  // allowed: the cap is what keeps every call finite
    default:
      Fail("a known status", static_cast<double>(r.status), 0);
  }
  return 0;
}
