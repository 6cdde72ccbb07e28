// Types shared by the impulse-based impact solvers (ball-ball: physics/impact/ball_ball.h,
// ball-cushion: physics/impact/ball_cushion.h): which integrator and how fine, the status
// of a solve, and the work it took.
#pragma once

#include <cstdint>
#include <string>

namespace snooker::physics {

enum class ImpulseIntegrator : std::uint8_t {
  kFixedStep,  ///< The paper's eq. 14 scheme: explicit Euler with N steps.
  kAdaptive,   ///< Dormand-Prince 5(4), step control, located events, stick law.
};

/// How much precision an impact is solved to: fidelity is a parameter, chosen by
/// the caller for the work it can afford.
enum class ImpulseFidelity : std::uint8_t {
  /// The integrator exactly as configured (`integrator`, `tolerance`, `steps`).
  kExact,
  /// For a planner's search, where thousands of candidate shots are simulated and
  /// the chosen ones are verified with kExact: the adaptive integrator at
  /// kSearchTolerance with Dormand-Prince 5(4), whatever `integrator`, `tolerance` and
  /// `method` say. Measured on the benchmark shot sets (docs/impact-speed.md): at most
  /// 3e-6 m/s (ball-ball) and 2e-5 m/s (cushion) from a converged answer, for about a
  /// quarter of the work of the default tolerance.
  kSearch,
};

/// The explicit Runge-Kutta pair of the adaptive integrator (physics/ode/): both reach
/// any tolerance; they differ in cost (docs/impact-methods.md).
enum class ImpulseMethod : std::uint8_t {
  kDormandPrince54,   ///< 5th order, 6 right-hand sides a step
  kDormandPrince853,  ///< 8th order, 12 a step: fewer steps at tight tolerances
};

/// The tolerance of ImpulseFidelity::kSearch (chosen in docs/impact-speed.md).
inline constexpr double kSearchTolerance = 1e-6;

struct ImpulseSolverOptions {
  /// kSearch overrides `integrator`, `tolerance` and `method` (see ImpulseFidelity).
  ImpulseFidelity fidelity = ImpulseFidelity::kExact;
  ImpulseIntegrator integrator = ImpulseIntegrator::kAdaptive;
  /// kFixedStep: N of eq. 14, the step being dP_I = (1 + e) M ydot_A(0) / N.
  std::int32_t steps = 1000;
  /// kAdaptive: local error per step, relative to the speed scale of the input
  /// (the largest of |v| and R|w| over both balls). Dimensionless.
  double tolerance = 1e-10;
  /// kAdaptive: the Runge-Kutta pair of its non-stiff steps.
  ImpulseMethod method = ImpulseMethod::kDormandPrince54;
  /// Cap on steps (accepted plus rejected) for either integrator. When reached the
  /// solver stops with kStepLimit and returns the state it had reached.
  std::int32_t max_steps = 100'000;
};

enum class ImpactStatus : std::uint8_t {
  kOk,
  /// The bodies are not approaching (for the ball-ball solver: ydot_A <=
  /// kMinApproach * SpeedScale(); a cut of exactly 90 deg leaves ~1e-16 of approach
  /// from rounding). No impact; the output equals the input (a documented no-op).
  kNotApproaching,
  /// NaN or infinite input, an input faster than limits::kMaxImpactSpeedScale, or
  /// parameters / options out of range: the output
  /// equals the input. The solver's Validate function names the bad value.
  kInvalidInput,
  /// The step cap was reached before the end of restitution.
  kStepLimit,
};

const char* ToString(ImpactStatus status);

/// The options a solver runs with: `options` with its fidelity applied (kSearch sets
/// the adaptive integrator at kSearchTolerance with Dormand-Prince 5(4)).
ImpulseSolverOptions EffectiveOptions(const ImpulseSolverOptions& options);

/// True for a fidelity this library knows (an enum read from outside may not be).
bool FidelityValid(ImpulseFidelity fidelity);
/// Empty for a known fidelity; otherwise a message naming the bad value.
std::string ValidateFidelity(ImpulseFidelity fidelity);
/// True for an input speed scale (m/s) a solver accepts: at most
/// limits::kMaxImpactSpeedScale (NaN and infinity are not).
bool SpeedScaleValid(double scale);
/// Empty for a valid speed scale; otherwise a message naming it, `what` saying what
/// the scale measures (each solver's own).
std::string ValidateSpeedScale(double scale, const char* what);
/// Likewise for the Runge-Kutta pair.
bool MethodValid(ImpulseMethod method);
std::string ValidateMethod(ImpulseMethod method);

/// How often a contact changed its regime during the impact (adaptive integrator).
struct ContactTransitions {
  std::uint16_t stick = 0;     ///< slip reached zero and the friction cone held it
  std::uint16_t unstick = 0;   ///< a stuck contact left its friction cone
  std::uint16_t reverse = 0;   ///< slip reached zero and went on in a new direction
};

/// Work done by the integrator.
struct ImpulseWork {
  std::int32_t steps = 0;           ///< accepted steps
  std::int32_t rejected_steps = 0;  ///< steps rejected by error control or event search
  std::int32_t rhs_evals = 0;       ///< right-hand-side evaluations
  std::int32_t events = 0;          ///< located mode switches and phase ends
  /// Impacts answered from a precomputed table instead (physics/impact/impact_table.h;
  /// they add no steps).
  std::int32_t table_lookups = 0;
};

}  // namespace snooker::physics
