// Event-time detectors for the event-driven table simulation: pure functions of the
// balls' position polynomials (physics/motion/motion.h) and the table's shapes
// (physics/table/table.h), in the table frame.
//
// Every detector writes a gap polynomial g(t) of degree <= 4 that is > 0 while the
// two are apart, 0 at contact and < 0 when they overlap:
//   ball-ball     |r1(t) - r2(t)|^2 - (2R)^2                      (quartic)
//   ball-cushion  n . (r(t) - p0) - R, contact point on the segment (quadratic)
//   ball-jaw      |r(t) - C|^2 - (R + r_jaw)^2                     (quartic)
//   ball-pocket   |r(t) - C|^2 - r_capture^2                       (quartic)
// and returns the first time in [0, t_max] at which g goes from > 0 to <= 0
// (FindFirstDownCrossing, physics/events/roots.h): the roots are found to full precision,
// so nothing tunnels however fast or short the event, no earlier time overlaps, and
// a tangency (a grazing path) counts as an event. A squared-distance gap needs no
// square root and is exact in its polynomial form.
//
// At t = 0 the pair may already touch, typically because the previous event just
// resolved them. "Touching" means the distance is within kContactTolerance of the
// contact distance (or less: an overlapping input is treated the same way). A
// touching pair is an event at t = 0 when it approaches faster than
// kApproachSpeedTolerance, or when its normal speed is within that tolerance and
// its normal acceleration points inwards (it would overlap at once). Otherwise
// (separating, or resting in contact) the search starts just after 0, so a pair that
// separates and comes back later is still found.
//
// Consequence for the simulator: an event at 0 with (near) zero approach speed
// (inward acceleration) will be reported again until the resolver changes the
// motion; the simulate loop must resolve it as a contact or cap repeated zero-time
// events.
//
// Hot path: no allocation, no exception, no virtual call; every loop has a cap.
#pragma once

#include "physics/core/ball_state.h"
#include "physics/motion/motion.h"
#include "physics/core/params.h"
#include "physics/table/table.h"

namespace snooker::physics {

/// Distance from contact within which two bodies count as touching at t = 0. m.
/// Also the guaranteed accuracy of the distance at a returned event time (actual
/// errors are ~1e-12 m and below).
inline constexpr double kContactTolerance = 1e-9;
/// Normal speed below which a touching pair is neither approaching nor separating.
/// m/s. Above numerical noise (~1e-15 m/s) and above resolver residue; a pair that
/// creeps in slower than this without inward acceleration is not reported, so it can
/// overlap by at most this speed times t_max (1e-8 m over 10 s).
inline constexpr double kApproachSpeedTolerance = 1e-9;

/// Earliest t in [0, t_max] (s) at which balls of radius `radius` (m) moving on `a`
/// and `b` touch (centre distance 2R) while approaching; +infinity if none, or if
/// t_max is NaN or negative. Both polynomials must be valid up to t_max.
double DetectBallBall(const PositionPoly& a, const PositionPoly& b, double radius, double t_max);

/// Earliest t in [0, t_max] (s) at which the ball centre on `p` comes within
/// `contact_distance` (m) of the segment's line from its normal side, moving towards
/// it, with the contact point (the centre's projection) on the segment; +infinity if
/// none. Pass the ball radius R for a nose touching the ball's equator; a nose at
/// height h touches a ball whose centre is sqrt(R^2 - (h - R)^2) from it.
double DetectBallCushion(const PositionPoly& p, const CushionSegment& segment,
                         double contact_distance, double t_max);

/// Earliest t in [0, t_max] (s) at which a ball of radius `radius` (m) on `p` touches
/// the knuckle (centre distance R + jaw.radius) while approaching; +infinity if none.
double DetectBallJaw(const PositionPoly& p, const JawCircle& jaw, double radius, double t_max);

/// Earliest t in [0, t_max] (s) at which the ball centre on `p` enters the pocket's
/// capture circle; 0 if it is already inside or on it; +infinity if none.
double DetectBallPocket(const PositionPoly& p, const Pocket& pocket, double t_max);

/// TransitionTime(s) (physics/motion/motion.h) if it is within [0, t_max] (s); else
/// +infinity.
double DetectTransition(const BallState& s, const BallParams& ball, const ClothParams& cloth,
                        double t_max);

}  // namespace snooker::physics
