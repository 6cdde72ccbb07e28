// A shot as the robot plays it: the cue ball's velocity and spin right after the cue
// strikes it. Table frame (types.h): headings are counter-clockwise from +x.
#pragma once

#include <cmath>

#include "physics/core/ball_state.h"
#include "physics/core/types.h"

namespace snooker::physics {

struct Shot {
  /// Cue-ball speed. m/s, >= 0.
  double speed = 0;
  /// Direction of travel, counter-clockwise from +x. rad.
  double heading = 0;
  /// Spin about the horizontal axis z x heading. rad/s; positive = follow (topspin),
  /// negative = draw; a ball rolling at `speed` has topspin = speed / R.
  double topspin = 0;
  /// Z component of the spin (right-hand rule, z up). rad/s; positive is
  /// counter-clockwise seen from above, what a tip struck right of centre imparts.
  double sidespin = 0;
  /// Spin about the heading itself. rad/s; what an elevated cue with side adds
  /// (physics/cue/strike.h). Positive for right side: the cloth's friction then
  /// curves the sliding ball to the right (swerve). Zero for a level cue.
  double swerve_spin = 0;
};

/// Unit vector of a heading (rad): (cos h, sin h).
inline Vec2 HeadingVector(double heading) { return {std::cos(heading), std::sin(heading)}; }

/// The cue ball at `position` right after the strike:
/// v = speed (cos h, sin h, 0), w = topspin (z x heading) + sidespin z
/// + swerve_spin heading.
inline BallState StruckBall(const Shot& shot, const Vec2& position) {
  const Vec2 dir = HeadingVector(shot.heading);
  BallState s;
  s.r = position;
  s.v = Vec3(shot.speed * dir.x(), shot.speed * dir.y(), 0.0);
  // z x heading = (-sin h, cos h, 0): positive topspin rolls the ball forwards.
  s.w = Vec3(-shot.topspin * dir.y() + shot.swerve_spin * dir.x(),
             shot.topspin * dir.x() + shot.swerve_spin * dir.y(), shot.sidespin);
  return s;
}

}  // namespace snooker::physics
