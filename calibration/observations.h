// What a calibration is fitted to: measurements of one table, as plain structs.
//
// Three kinds, each answering a different part of the model (calibration/fit.h):
//  * ThrowObservation: one ball-ball collision, its input and the object ball's
//    measured throw. Answers the ball-ball friction law.
//  * CushionObservation: one ball into one cushion, its approach and the measured
//    rebound. Answers the cushion's friction and restitution.
//  * TrackedShot: a whole shot as a vision system saw it, the balls' positions at
//    known times after the strike. Answers the cloth (sliding and rolling friction,
//    spin decay), and with the strike in the cue's terms the cue (squirt, the tip's
//    restitution); its ball-ball collisions answer the friction law too.
//
// Units and frames: SI (m, s, rad, m/s, rad/s); positions in the table frame
// (physics/core/types.h, x across from the left cushion nose, y along from the baulk
// cushion nose). Degrees appear only at the edges, not here.
//
// Validate checks a whole set before a fit and names the first bad value of each
// bad observation, its index and the rule it breaks.
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "physics/core/shot.h"
#include "physics/core/types.h"
#include "physics/cue/strike.h"

namespace snooker::calibration {

/// One ball-ball collision: a cue ball into an object ball at rest.
struct ThrowObservation {
  /// Cut angle: between the cue ball's incident velocity and the line of centres.
  /// rad, in [0, kMaxCut] (0: full ball). The sign is not used: throw is measured
  /// towards the cue ball's tangential motion, whichever side that is.
  double cut = 0;
  /// Exactly one of the two speeds, m/s, in (0, kMaxSpeed]: the cue ball's incident
  /// speed, or the object ball's speed right after the impact (what a camera over
  /// the object ball's path measures most easily). With the object ball's speed
  /// the prediction solves for the incident speed that gives it.
  std::optional<double> cue_ball_speed;
  std::optional<double> object_ball_speed;
  /// The cue ball's spin at impact (physics::PaperIncidentState): topspin about the
  /// horizontal axis across its path, rad/s (0: a stun shot, speed / R: rolling;
  /// negative: draw), and sidespin, the vertical component, rad/s (positive
  /// counter-clockwise seen from above). |spin| <= physics::limits::kMaxSpin. Both
  /// are held fixed when the incident speed is solved for.
  double topspin = 0;
  double sidespin = 0;
  /// Measured throw, rad: the angle from the line of centres to the object ball's
  /// direction right after the impact, positive when it is turned towards the side
  /// the cue ball's tangential velocity points (the usual cut-induced throw).
  double measured_throw = 0;
};

/// One ball into one straight cushion (the cushion frame of physics/impact/
/// ball_cushion.h: the approach angle is measured from the cushion line).
struct CushionObservation {
  /// Approach speed, m/s, in (0, kMaxSpeed].
  double speed = 0;
  /// Angle between the approach and the cushion line, rad, in (0, pi): pi/2 is
  /// square on.
  double angle = 0;
  /// Spin at impact (physics::CushionIncidentState): topspin, rad/s (rolling:
  /// speed / R), and sidespin, the vertical component, rad/s.
  double topspin = 0;
  double sidespin = 0;
  /// Measured rebound right after the impact: speed, m/s, in [0, kMaxSpeed], and
  /// optionally the angle between the rebound and the cushion line, rad, in (0, pi)
  /// (pi/2: straight back; below pi/2: on along the cushion's direction of the
  /// approach).
  double rebound_speed = 0;
  std::optional<double> rebound_angle;
};

/// Where the balls were seen at one time after the strike.
struct Sighting {
  /// Time after the strike, s, > 0.
  double t = 0;
  /// One position per ball of the shot, in its order, table frame, m. A ball not
  /// seen (pocketed, hidden) is NaN in both coordinates.
  std::vector<physics::Vec2> positions;
};

/// A whole shot as tracked by vision.
struct TrackedShot {
  /// Every ball at rest before the strike, table frame, m (at most
  /// physics::limits::kMaxBalls), and which of them is the cue ball.
  std::vector<physics::Vec2> balls;
  int cue_ball = 0;
  /// The strike: in the robot's terms (the cue's speed, heading, tip offsets,
  /// elevation; the model's cue turns it into the ball's motion, so these shots
  /// answer the cue's parameters), or as the cue ball's velocity and spin.
  std::variant<physics::CueStrike, physics::Shot> strike;
  /// At increasing times.
  std::vector<Sighting> sightings;
};

struct Observations {
  std::vector<ThrowObservation> throws;
  std::vector<CushionObservation> rebounds;
  std::vector<TrackedShot> shots;
};

/// Ranges Validate applies.
inline constexpr double kMaxSpeed = 10.0;          ///< m/s, any ball or cue speed
inline constexpr double kMaxCut = 89.0 * physics::kPi / 180;  ///< rad
inline constexpr double kMaxThrow = physics::kPi / 4;         ///< |throw|, rad
inline constexpr double kMaxSightingTime = 600.0;  ///< s, the simulator's own time cap
/// How far outside the playing area (the rectangle of the cushion noses) a seen
/// ball may be, m: a ball in a pocket's mouth, plus vision's error.
inline constexpr double kTableMargin = 0.05;
/// Identical inputs whose measurements differ by more than these contradict each
/// other (repeats scatter by far less on a real table): throw 3 deg, rebound
/// speed 0.25 m/s, rebound angle 5 deg.
inline constexpr double kThrowContradiction = 3.0 * physics::kPi / 180;  ///< rad
inline constexpr double kReboundSpeedContradiction = 0.25;                ///< m/s
inline constexpr double kReboundAngleContradiction = 5.0 * physics::kPi / 180;  ///< rad

/// O(n log n) in the observations. Empty when the set can be fitted from; otherwise one message per bad
/// observation, "; "-separated, each naming it and its bad value:
/// "throw[3].object_ball_speed = nan (must be a finite number in (0, 10] m/s)".
/// Refused: no observation at all; a single throw or a single rebound (a kind that
/// is given needs at least 2 points); values out of range or not finite; a throw
/// without exactly one speed; identical inputs whose measurements contradict each
/// other (above; one message per input, naming its two most different
/// measurements); a tracked shot with no sightings, times not increasing, a
/// position count that is not the ball count, a seen ball off the table, balls
/// overlapping or outside the playing area at the start, or a bad strike.
std::string Validate(const Observations& observations);

}  // namespace snooker::calibration
