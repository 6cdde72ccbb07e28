// Ball-ball collision of Mathavan, Jackson & Parkin (2014), "Numerical simulations
// of the frictional collisions of solid balls on a rough surface", Sports Eng. 17.
//
// The model: two identical balls on the cloth, point contacts at A (ball-ball), D
// (C-cloth) and B (O-cloth); Coulomb friction at every contact; the normal impulse
// P_I at A is the independent variable; the impact ends by Stronge's energetic
// restitution (eqs. 10, 15). Frame, signs and misprints: docs/physics-notes.md
// sections 1-3 and physics/core/types.h. Summary of the frame: line of centres +Y, C
// at -Y, O at +Y, Z up.
//
// Two integrators solve the same impulse ODE, the generic ones of physics/ode/ shared
// with the cushion model (the model itself: ball_ball_hybrid.cc):
//  * kFixedStep: the paper's scheme (eq. 14), explicit Euler in P_I with N steps,
//    first order. The end of compression and the end of restitution are located
//    inside the last step instead of overshooting it. Reproduces the paper.
//  * kAdaptive: the hybrid integrator (physics/ode/hybrid_integrator.h,
//    Dormand-Prince 5(4) with step control), the mode switches located as events on
//    the dense output (slip reaching zero at A, D or B; the vertical slip at A
//    changing sign; an airborne ball landing; a stuck contact leaving its friction
//    cone; the end of compression; the end of restitution) and the stick law applied
//    when a slip reaches zero and the friction cone can hold it (docs/physics-notes.md
//    section 4).
//
// Two extensions of the paper's wording, both needed for a well-posed model and
// documented here (they change nothing in the paper's five shots):
//  * A ball that the vertical friction at A pushes up lifts off (eqs. 6); it is held
//    by the cloth again only once friction has brought its vertical velocity back
//    to zero. So the cloth never pushes on a ball moving away from it and does no
//    work (energy never rises).
//  * At zero slip a contact sticks while the friction that keeps the slip at zero
//    lies inside the friction cone (adaptive integrator). The fixed-step scheme
//    keeps the paper's rule: zero slip, zero friction.
//
// Hot path: no allocation, no exception, no virtual call. Every loop has a cap.
#pragma once

#include <cstdint>
#include <string>

#include "physics/impact/impulse_solver.h"
#include "physics/core/params.h"
#include "physics/core/types.h"

namespace snooker::physics {

/// State of both balls in the collision frame (C at -Y, O at +Y, Z up).
struct ImpactState {
  BallMotion c;  ///< Ball C (the cue ball in the paper).
  BallMotion o;  ///< Ball O (the object ball).
};

/// The paper's incident state, eq. 13: C moves at `speed` (m/s) at the cut angle
/// `cut` (rad) from the line of centres, with topspin `topspin` (rad/s, positive
/// follow: a rolling ball has topspin = speed / R) and sidespin `sidespin` (rad/s,
/// the Z component of C's spin, right-hand rule). O is at rest.
///   v_C = (V0 sin th, V0 cos th, 0), w_C = (-wT cos th, wT sin th, wS).
ImpactState PaperIncidentState(double speed, double topspin, double sidespin, double cut);



/// Approach speeds at or below this fraction of SpeedScale() count as no approach:
/// the impact they would start changes no velocity by more than that fraction.
inline constexpr double kMinApproach = 1e-12;

/// The largest of |v| and R |w| over both balls. m/s.
double SpeedScale(const ImpactState& s, double radius);

struct ImpactResult {
  ImpactStatus status = ImpactStatus::kOk;
  /// Both balls right after the impact (vertical velocities included).
  ImpactState out;
  /// Normal impulse at the end of compression, P_I^c. N s.
  double impulse_compression = 0;
  /// Normal impulse at the end of the impact, P_I^f. N s.
  double impulse_final = 0;
  /// Work of the normal force during compression, W_y(P_I^c) (eq. 10a). J.
  double work_compression = 0;
  ImpulseWork work;
  /// Regime changes at A (ball-ball), D (C-cloth) and B (O-cloth).
  ContactTransitions a, d, b;
  /// Number of times C / O left the cloth during the impact.
  std::uint16_t c_liftoffs = 0, o_liftoffs = 0;
};

/// Solves the impact. Pure and deterministic; allocates nothing, throws nothing.
/// `mu_s` is the ball-cloth sliding friction coefficient.
ImpactResult ResolveImpact(const ImpactState& in, const BallParams& ball,
                           const BallBallParams& contact, double mu_s,
                           const ImpulseSolverOptions& options);

/// Empty when ResolveImpact would accept the input (it may still answer
/// kNotApproaching); otherwise a message naming the bad value.
std::string ValidateImpact(const ImpactState& in, const BallParams& ball,
                           const BallBallParams& contact, double mu_s,
                           const ImpulseSolverOptions& options);

/// Total kinetic energy of both balls, translational and rotational. J.
double KineticEnergy(const ImpactState& s, const BallParams& ball);

}  // namespace snooker::physics
