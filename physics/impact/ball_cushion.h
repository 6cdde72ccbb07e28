// Ball-cushion impact of Mathavan, Jackson & Parkin (2010), "A theoretical analysis
// of billiard ball dynamics under cushion impacts", Proc. IMechE C 224(9), as
// restated in docs/physics-notes.md section 8.
//
// The cushion frame: X along the cushion, Y horizontal towards (into) the cushion,
// Z up; the ball's centre G is R above the cloth. Contacts:
//  * I, with the cushion nose at height h above the cloth, at R (0, cos th, sin th)
//    from G, sin th = (h - R) / R (2/5 for the default h = 7R/5). The normal impulse
//    P_I pushes G along -(0, cos th, sin th). Friction at I (mu_w) lies in the
//    cushion's tangent plane, spanned by X and Y' = (0, -sin th, cos th).
//  * C, with the cloth, at (0, 0, -R). Friction at C (mu_s) lies in the cloth plane.
// Slip at a contact: velocity of the ball's contact point (v + w x r); both the
// cushion and the cloth are at rest. Slip at I is given as (along X, along Y').
//
// Assumptions of the model (the paper's, made explicit):
//  * The cushion's slope holds the ball down: zdot_G = 0 throughout, so the cloth
//    reaction P_C follows from the vertical balance (their eq. 8, generalised to a
//    sticking contact I). ValidateCushion() requires parameters under which the
//    cloth keeps pushing (mu_w cos th < sin th) and the normal speed keeps falling
//    for every friction the cones allow, which bounds the impulse.
//  * The input's vertical velocity is not part of the model (the ball is on the
//    cloth): it is ignored, and the output's is zero.
//  * Coulomb friction at I and C, each opposing its slip; a contact whose slip is
//    zero sticks while the friction that holds it at zero lies inside its cone.
//  * Stronge's energetic restitution e_e: compression ends where the normal speed
//    ydot cos th + zdot sin th reaches 0 (work W_c of the normal force); the impact
//    ends at W = (1 - e_e^2) W_c.
//
// Two integrators of the impulse ODE (independent variable P_I), the generic ones of
// physics/ode/ shared with ball-ball (ball_ball.h; shared types in impulse_solver.h):
// kFixedStep, the paper's explicit Euler with N steps of dP_I = (1 + e_e) M v_n / N
// (v_n the initial normal speed; the impact then takes about N / cos^2 th steps
// without friction, 1.19 N at the default height) and the two phase ends located
// inside the last step; kAdaptive, the hybrid integrator (physics/ode/
// hybrid_integrator.h: Dormand-Prince 5(4) with step control, Rosenbrock 2(3) where a
// small slip makes the problem stiff, events located on the dense output) with this
// model's witnesses and stick law (ball_cushion_hybrid.cc). The model and measured
// figures: docs/cushion-model.md.
//
// Hot path: no allocation, no exception, no virtual call; every loop has a cap.
#pragma once

#include <array>
#include <string>

#include "physics/impact/impulse_solver.h"
#include "physics/core/params.h"
#include "physics/core/types.h"

namespace snooker::physics {

/// Restitution as a function of the impact: a piecewise-linear curve of e against
/// the ball centre's horizontal approach speed towards the cushion (m/s), constant
/// beyond its ends. Empty (points = 0): CushionParams::e_e for every impact.
struct RestitutionCurve {
  static constexpr int kMaxPoints = 8;
  std::array<double, kMaxPoints> speed{};  ///< m/s, strictly increasing
  std::array<double, kMaxPoints> e{};      ///< energetic restitution at each speed, in [0, 1]
  int points = 0;
};

/// The curve that makes this model reproduce the rebounds Mathavan et al. (2009)
/// measured (31 shots, rolling ball, square on, snooker): v_out = -0.0877 v^2 +
/// 1.131 v - 0.0953 m/s for v in 0.28-3.5 m/s. With the constant e_e = 0.98 the
/// model rebounds at 0.911 v at every speed, up to 0.4 m/s faster than measured at
/// 3.5 m/s; the measured ratio falls with speed. The knots are the e that matches
/// the measured fit at each speed (capped at 1, where the model with e = 1 is still
/// within 0.03 m/s below the fit). docs/cushion-model.md shows the derivation.
RestitutionCurve MeasuredReboundCurve();

/// Parameters of the Mathavan et al. (2010) cushion model (snooker values).
struct CushionParams {
  /// Energetic coefficient of restitution (Stronge), dimensionless, in [0, 1].
  /// Used when restitution_curve is empty.
  double e_e = 0.98;
  /// Speed-dependent restitution; empty by default (the paper's constant e_e).
  RestitutionCurve restitution_curve;
  /// Ball-cushion sliding friction coefficient at I, dimensionless.
  double mu_w = 0.14;
  /// Ball-cloth sliding friction coefficient at C during the impact, dimensionless.
  double mu_s = 0.212;
  /// Height of the cushion's contact point (the nose) above the cloth, h. m.
  /// Default 7R/5 for the default BallParams radius (0.02625 m); use
  /// MathavanCushionParams() for another ball. Must lie in (R, 2R).
  double contact_height = 7.0 / 5.0 * 0.02625;
};

/// The paper's parameters for a ball of the given radius (contact height 7R/5).
CushionParams MathavanCushionParams(const BallParams& ball);

/// The restitution of an impact whose ball approaches at `approach_speed` (m/s,
/// horizontal, towards the cushion): the curve if it has points, else e_e.
double CushionRestitution(const CushionParams& cushion, double approach_speed);

/// The incident state of docs/physics-notes.md section 8, in the cushion frame: the
/// ball arrives at `speed` (m/s) at angle `alpha` (rad) to the cushion line
/// (pi/2: square on) with topspin `topspin` (rad/s; rolling: speed / R) and
/// sidespin `sidespin` (rad/s, the Z component of the spin):
///   v = (V0 cos a, V0 sin a, 0), w = (-wT sin a, wT cos a, wS).
BallMotion CushionIncidentState(double speed, double alpha, double topspin, double sidespin);

/// The speed scale of an input, m/s: the larger of its horizontal speed and R |w| (the
/// vertical velocity is not part of the model).
double CushionSpeedScale(const BallMotion& in, double radius);

/// sin th of the contact normal at I: (h - R) / R.
double CushionSinTheta(const BallParams& ball, const CushionParams& cushion);

struct CushionImpactResult {
  /// kNotApproaching: normal speed ydot cos th <= 0, no impact. kInvalidInput: NaN or
  /// infinite input, a speed scale beyond limits::kMaxImpactSpeedScale, or bad
  /// parameters / options (ValidateCushionImpact names them).
  /// Both leave `out` equal to the input. kStepLimit: the cap was reached; `out` is
  /// the state reached.
  ImpactStatus status = ImpactStatus::kOk;
  /// The ball right after the impact, cushion frame: v in m/s (v.z() = 0), w in rad/s.
  BallMotion out;
  /// Normal impulse at I at the end of compression, P_c. N s.
  double impulse_compression = 0;
  /// Normal impulse at I at the end of the impact, P_f. N s.
  double impulse_final = 0;
  /// Work of the normal force during compression, W_c. J.
  double work_compression = 0;
  /// Integrator effort (for kFixedStep: steps = Euler steps, events = phase ends).
  ImpulseWork work;
  /// Regime changes at the cushion contact I and the cloth contact C (kAdaptive; the
  /// fixed-step scheme keeps the paper's rule, zero slip gives zero friction, and
  /// reports none).
  ContactTransitions cushion, cloth;
};

/// The loosest tolerance the adaptive cushion solver integrates at: a looser request
/// is solved at this one. Far above it one step may cover the whole impact with an
/// error estimate far below its error: over 10^5 random impacts, solved unclamped, the
/// kinetic energy rose by up to 370 % at 0.1 and by 30 % at 0.03, and not
/// at all at 1e-2 and below; the clamp keeps a factor of ten from that
/// (CushionEnergy.LooseTolerancesAreSolvedAtTheLoosestThatHolds).
inline constexpr double kLoosestCushionTolerance = 1e-3;

/// Solves the impact of a ball on a cushion. `in` is the ball's state in the cushion
/// frame. Pure and deterministic; allocates nothing, throws nothing.
CushionImpactResult ResolveCushionImpact(const BallMotion& in, const BallParams& ball,
                                         const CushionParams& cushion,
                                         const ImpulseSolverOptions& options);

/// Empty when the parameters are acceptable; otherwise a message naming each bad value.
std::string ValidateCushionParams(const BallParams& ball, const CushionParams& cushion);

/// Empty when ResolveCushionImpact would accept the input (it may still answer
/// kNotApproaching); otherwise a message naming each bad value.
std::string ValidateCushionImpact(const BallMotion& in, const BallParams& ball,
                                  const CushionParams& cushion,
                                  const ImpulseSolverOptions& options);

}  // namespace snooker::physics
