// The resting-contact rules of the table simulation: what becomes of a contact that
// an impact model alone would turn into an endless sequence of ever smaller impacts.
// Table frame (X across, Y along, Z up); every normal n is horizontal and of unit
// length.
//
//  * After an impact a ball whose centre and cloth contact both move slower than
//    SimParams::rest_speed is set at rest (AfterImpact): a slow ball pushing a
//    resting one would otherwise collide with it again and again (inelastic
//    collapse).
//  * A pressing contact (no normal speed, the cloth driving the two together) is a
//    resting contact. Against a fixed boundary (cushion nose, jaw wall, knuckle) the
//    ball loses its normal velocity and the spin that drives its slip into the
//    boundary (HoldAgainst). Two pressed balls lose the spin that drives them
//    together and, if rolling still presses them, stop together when slow or lose
//    their motion along the line of centres (HoldTogether).
//  * After an impact, a pair (or a ball and a boundary) that the cloth would bring
//    back together within a flight of SimParams::resting_contact_excursion is held
//    in contact instead (HoldIfReturning): no Zeno sequence of ever shorter flights.
//
// Every rule only takes kinetic energy out. The cluster resolution of near-
// simultaneous impacts is in physics/sim/cluster.h. Pure functions of their inputs;
// no allocation, no exception.
#pragma once

#include "physics/core/ball_state.h"
#include "physics/core/types.h"
#include "physics/sim/sim_params.h"

namespace snooker::physics {

/// `s` after an impact with SimParams::rest_speed applied: if both its centre and
/// its cloth contact move slower than rest_speed (m/s), at rest with its Z spin kept;
/// otherwise unchanged.
BallState AfterImpact(const BallState& s, const SimParams& p);

/// `s` with v = 0 and no horizontal spin (its Z spin kept), settled.
BallState Stopped(const BallState& s, const SimParams& p);

/// `s` with the component of its velocity along `n` removed (not settled).
BallState WithoutNormalVelocity(const BallState& s, const Vec2& n);

/// A ball held against a fixed boundary whose normal, from the boundary to the ball,
/// is `n`: no normal velocity and none of the spin that drives its cloth slip along
/// n, so the slip (and the friction) has no normal component left. Settled.
BallState HoldAgainst(const BallState& s, const Vec2& n, const SimParams& p);

/// After an impact on a fixed boundary (normal `n` from it to the ball): `s` held
/// against it (HoldAgainst) if `s` slides and its friction would bring it back
/// within a flight of resting_contact_excursion; otherwise `s`.
BallState HoldIfReturning(const BallState& s, const Vec2& n, const SimParams& p);

/// Splits a rounding-level normal approach of two touching balls (`n` from a to b)
/// evenly between them, so the contact is not found again. Both settled.
void RemoveApproach(BallState* a, BallState* b, const Vec2& n, const SimParams& p);

/// Two touching balls that the cloth presses together (`n` from a to b). `level_a`
/// and `level_b` count the pressing contacts each ball had resolved earlier at the
/// same instant: a ball pressed a second time at one instant is wedged and stops.
void HoldTogether(BallState* a, BallState* b, const Vec2& n, int level_a, int level_b,
                  const SimParams& p);

/// The ball-ball twin of HoldIfReturning: after an impact, two balls whose
/// decelerations bring them back together within a flight of
/// resting_contact_excursion share their normal velocity (a plastic impact) and are
/// held together (HoldTogether).
void HoldIfReturning(BallState* a, BallState* b, const Vec2& n, int level_a, int level_b,
                     const SimParams& p);

}  // namespace snooker::physics
