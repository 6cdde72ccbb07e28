// Helpers shared by the impact tests (tests/physics/impact/) and the impact report
// tools (tools/impact_methods, tools/impact_tables): solver options, distances between
// outcomes in velocity units, and names for gtest's messages. Not part of the library.
#pragma once

#include <algorithm>
#include <ostream>

#include "physics/impact/ball_ball.h"
#include "physics/impact/ball_cushion.h"

namespace snooker::physics {

// gtest prints these by name ("ok", "step limit reached"), not as "1-byte object <03>".
inline void PrintTo(ImpactStatus status, std::ostream* os) { *os << ToString(status); }
inline void PrintTo(ImpulseIntegrator integrator, std::ostream* os) {
  *os << (integrator == ImpulseIntegrator::kFixedStep ? "fixed step" : "adaptive");
}
inline void PrintTo(ImpulseFidelity fidelity, std::ostream* os) {
  *os << (fidelity == ImpulseFidelity::kSearch ? "search" : "exact");
}

namespace test {

/// Rounding allowance for laws that hold exactly in exact arithmetic. Relative.
inline constexpr double kRoundingRel = 1e-12;

/// The paper's fixed-step scheme with N steps. An impact takes about N / 2 steps
/// (ball-ball) or N / cos^2(th) (cushion, more with friction); the cap leaves room.
inline ImpulseSolverOptions FixedStep(int n) {
  ImpulseSolverOptions o;
  o.integrator = ImpulseIntegrator::kFixedStep;
  o.steps = n;
  o.max_steps = 100 * n + 1000;
  return o;
}

/// The hybrid integrator at `tolerance` (default: the library's default) with the
/// Runge-Kutta pair `method` (default: the library's default).
inline ImpulseSolverOptions Adaptive(double tolerance = ImpulseSolverOptions{}.tolerance,
                                     ImpulseMethod method = ImpulseSolverOptions{}.method) {
  ImpulseSolverOptions o;
  o.integrator = ImpulseIntegrator::kAdaptive;
  o.tolerance = tolerance;
  o.method = method;
  return o;
}

/// The search fidelity tier.
inline ImpulseSolverOptions Search() {
  ImpulseSolverOptions o;
  o.fidelity = ImpulseFidelity::kSearch;
  return o;
}

/// Largest difference of two ball-ball outcomes in velocity units: |dv| and R |dw| of
/// both balls, componentwise. m/s.
inline double MaxDifference(const ImpactState& a, const ImpactState& b, double radius) {
  return std::max({(a.c.v - b.c.v).cwiseAbs().maxCoeff(), (a.o.v - b.o.v).cwiseAbs().maxCoeff(),
                   radius * (a.c.w - b.c.w).cwiseAbs().maxCoeff(),
                   radius * (a.o.w - b.o.w).cwiseAbs().maxCoeff()});
}

/// The same for one ball (a cushion impact's outcome). m/s.
inline double MaxDifference(const BallMotion& a, const BallMotion& b, double radius) {
  return std::max((a.v - b.v).cwiseAbs().maxCoeff(), radius * (a.w - b.w).cwiseAbs().maxCoeff());
}

}  // namespace test
}  // namespace snooker::physics
