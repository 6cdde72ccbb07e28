// Closed-form motion of one ball on the cloth between events (table frame: X across,
// Y along, Z up; the centre is R above the cloth). docs/physics-notes.md sections 6
// and 9; Mathavan, Jackson & Parkin (2014) section 2.5.
//
// Each MotionState has a closed form with constant acceleration of the centre, so
// the centre moves on r(t) = c + b t + a t^2 until the state's next transition:
//  * sliding: the contact slip u = (vx - R wy, vy + R wx) keeps its direction u^;
//    friction -mu_s M g u^ gives v(t) = v0 - mu_s g t u^ and changes the horizontal
//    spin by (5 mu_s g / (2R)) t (z x u^); u shrinks at (7/2) mu_s g and reaches 0 at
//    T_s = 2|u| / (7 mu_s g) (eq. 19), then the ball rolls (or is at rest). The
//    velocity may pass through zero and reverse while sliding (a draw shot).
//  * rolling: rolling resistance decelerates the centre at mu_r g along v; the spin
//    keeps the rolling condition u = 0; the ball stops at |v| / (mu_r g).
//  * spinning: at rest with Z spin only; ends when the Z spin reaches 0.
//  * stationary and pocketed: nothing happens.
// Z spin (sidespin) decays at ClothParams::spin_decel in every state (eq. 21).
//
// Decisions:
//  * A transition is applied exactly: Evolve to the transition time sets the new
//    state's defining quantity to exactly zero (slip after sliding, velocity after
//    rolling, Z spin after spinning), so no drift accumulates over many events.
//  * The vertical velocity an impact may leave (a small "jump", paper section 2.2)
//    is dropped: every function here uses the horizontal part of v, and Settle and
//    Evolve return v.z = 0. The ball is taken to stay on the cloth.
//  * The functions trust BallState::s. After changing v or w outside this file (a
//    collision), call Settle to reclassify the state with the tolerances below.
//  * A friction or deceleration coefficient of 0 makes that state last forever
//    (transition time +infinity); nothing divides by it.
//
// Hot path: no allocation, no exception, no virtual call; every loop has a cap.
#pragma once

#include "physics/core/ball_state.h"
#include "physics/core/params.h"
#include "physics/core/types.h"

namespace snooker::physics {

/// Contact slip below which a ball counts as rolling. m/s. A slip this small would
/// end within 1e-9 / (3.5 mu_s g) ~ 1.4e-10 s, moving the ball by less than 1e-9 m.
inline constexpr double kSlipTolerance = 1e-9;
/// Centre speed below which a non-sliding ball counts as at rest. m/s (it would stop
/// within 1e-9 / (mu_r g) ~ 8e-9 s, moving by less than 1e-17 m).
inline constexpr double kSpeedTolerance = 1e-9;
/// Z spin below which a ball at rest counts as stationary. rad/s (it would stop
/// within 1e-9 / 22 s).
inline constexpr double kSpinTolerance = 1e-9;

/// The centre's path r(t) = c + b t + a t^2 in the table frame, valid from the
/// state it was made from until that state's next transition.
struct PositionPoly {
  /// Position at t = 0. m.
  Vec2 c = Vec2::Zero();
  /// Velocity at t = 0. m/s.
  Vec2 b = Vec2::Zero();
  /// Half the (constant) acceleration. m/s^2.
  Vec2 a = Vec2::Zero();

  /// Position at time t (s) after the state. m.
  Vec2 At(double t) const { return c + t * (b + t * a); }
  /// Velocity at time t (s) after the state. m/s.
  Vec2 VelocityAt(double t) const { return b + 2.0 * t * a; }
};

/// Horizontal slip of the ball's contact point on the cloth, (vx - R wy, vy + R wx).
/// m/s, table frame.
Vec2 ClothSlip(const BallState& s, const BallParams& ball);

/// The motion state that `s`'s velocity and spin call for, with the tolerances
/// above: kPocketed stays kPocketed; else sliding if |u| > kSlipTolerance; else
/// rolling if |v| > kSpeedTolerance; else spinning if |wz| > kSpinTolerance; else
/// stationary.
MotionState ClassifyMotion(const BallState& s, const BallParams& ball);

/// `s` with its MotionState set by ClassifyMotion and the residues that the
/// tolerances ignored removed: rolling gets the exact rolling spin for its
/// velocity; spinning and stationary get v = 0 and zero horizontal spin
/// (stationary also wz = 0); v.z is always set to 0.
BallState Settle(const BallState& s, const BallParams& ball);

/// Time from `s` to its next transition (s): sliding -> rolling/at rest after
/// 2|u| / (7 mu_s g); rolling -> spinning/stationary after |v| / (mu_r g);
/// spinning -> stationary after |wz| / spin_decel. +infinity when there is none
/// (stationary, pocketed, or a zero coefficient).
double TransitionTime(const BallState& s, const BallParams& ball, const ClothParams& cloth);

/// The centre's path from `s`, valid for t in [0, TransitionTime(s)].
PositionPoly PositionPolynomial(const BallState& s, const BallParams& ball,
                                const ClothParams& cloth);

/// The state `t` seconds after `s` without crossing a transition: t is clamped to
/// [0, TransitionTime(s)]. When t reaches the transition time the new state is set
/// exactly there (e.g. after sliding the slip is exactly 0 and the state rolling).
/// A NaN or negative t returns `s` unchanged.
BallState Evolve(const BallState& s, double t, const BallParams& ball, const ClothParams& cloth);

/// The state `t` seconds after `s`, crossing as many transitions as needed (at
/// most sliding -> rolling -> spinning -> stationary). A NaN or negative t
/// returns `s` unchanged.
BallState EvolveThrough(const BallState& s, double t, const BallParams& ball,
                        const ClothParams& cloth);

/// Kinetic energy of one ball, translational and rotational (all three spin
/// axes, full 3D velocity). J.
double KineticEnergy(const BallState& s, const BallParams& ball);

}  // namespace snooker::physics
