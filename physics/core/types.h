// Units and frames used throughout physics/.
//
// Units: SI everywhere inside the library: metres, seconds, kilograms, radians,
// m/s, rad/s, newton-seconds (N s) for impulse, joules for work and energy.
// Degrees appear only at the edges (command line, API), in names ending in _deg.
//
// Two frames are used:
//  * The collision frame of Mathavan, Jackson & Parkin (2014), Figs. 2-3: the line
//    of centres is +Y, ball C sits at -Y and ball O at +Y, their contact A is at
//    height R above the cloth, Z points up and X completes a right-handed frame.
//    Contact points: A at +R*Y from C and -R*Y from O; D (C on the cloth) and
//    B (O on the cloth) at -R*Z from each centre.
//  * The table frame (table sim): X across the table, Y along it, Z up.
//
// The slip at a contact is the velocity of the first body's contact point minus
// that of the second body's, each being v + w x r.
#pragma once

#include <cmath>

#include <Eigen/Core>

namespace snooker::physics {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

/// Velocity of a ball's centre (m/s) and its angular velocity (rad/s), in the
/// frame of the surrounding context.
struct BallMotion {
  Vec3 v = Vec3::Zero();
  Vec3 w = Vec3::Zero();
};

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDegPerRad = 180.0 / kPi;

inline constexpr double DegToRad(double deg) { return deg / kDegPerRad; }
inline constexpr double RadToDeg(double rad) { return rad * kDegPerRad; }

/// std::remainder(a, 2 pi): an angle reduced to [-pi, pi], to the same bits. An angle
/// already in that range is its own remainder (the quotient rounds to 0, ties to even
/// at +-pi), so it skips the library call, which costs as much as an atan2 and is
/// on the planner's hot path.
inline double RemainderTwoPi(double a) {
  return a >= -kPi && a <= kPi ? a : std::remainder(a, 2 * kPi);
}

}  // namespace snooker::physics
