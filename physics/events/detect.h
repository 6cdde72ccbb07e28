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
// Contacts by design. At t = 0 the two may already touch, typically because the
// previous event just resolved them, or because vision placed a ball frozen to a
// cushion or another ball. ClassifyContact says how a gap starts:
//  * kApart: not touching (gap above kContactTolerance).
//  * kApproaching: touching and closing faster than kApproachSpeedTolerance: an
//    impact, an event at t = 0.
//  * kPressing: touching, normal speed within kApproachSpeedTolerance, and the
//    motions accelerate the two into each other faster than
//    kContactAccelTolerance: a resting contact that the closed-form motions would
//    push through. An event at t = 0; the simulator resolves it as a resting
//    contact (physics/sim/simulate.h), after which the pair no longer presses.
//  * kTouching: touching and neither closing nor pressing (separating, or sliding
//    along each other, as a ball frozen to a cushion and played along it). Not an
//    event now: its next contact begins where its normal speed first passes twice
//    kApproachSpeedTolerance inwards (at once if the gap is still within the
//    contact band then, else at the gap's next down-crossing). A gap that stays at
//    zero to rounding (a ball rolling along a cushion) never passes that speed, so
//    rounding noise cannot make an event, and nothing is found before the time
//    the search starts.
// The detectors never return a time before 0 (the caller's current time).
//
// Hot path: no allocation, no exception, no virtual call; every loop has a cap.
#pragma once

#include <cstdint>

#include "physics/core/ball_state.h"
#include "physics/core/params.h"
#include "physics/events/roots.h"
#include "physics/motion/motion.h"
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

/// Normal acceleration below which a touching pair is not pressing together. m/s^2.
/// Well above rounding of the cloth accelerations (~1e-15 m/s^2); a pair pressing
/// slower than this overlaps by at most a t^2 / 2 = 5e-9 m over 10 s.
inline constexpr double kContactAccelTolerance = 1e-10;

/// How a contact starts at t = 0 (see the top of this file).
enum class ContactStart : std::uint8_t { kApart, kApproaching, kPressing, kTouching };
const char* ToString(ContactStart c);

/// Classifies the gap polynomial g (gap units; `gap_per_metre` converts a distance
/// into them: 1 for a linear gap, 2 x the contact distance for a squared one) at t = 0.
ContactStart ClassifyContact(const Poly4& g, double gap_per_metre);

/// Gap polynomials (physics/events/roots.h layout) and their gap units per metre.
struct Gap {
  Poly4 g{};
  double per_metre = 1;
};
/// Two balls of radius `radius` (m): |r_a - r_b|^2 - (2R)^2.
Gap BallBallGap(const PositionPoly& a, const PositionPoly& b, double radius);
/// A ball centre and a straight segment's line: n . (r - p0) - contact_distance.
Gap CushionGap(const PositionPoly& p, const CushionSegment& segment, double contact_distance);
/// A ball and a knuckle (centre distance contact = R' + r_jaw, see DetectBallJaw).
Gap JawGap(const PositionPoly& p, const JawCircle& jaw, double radius);

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
