// The cue's strike: from what the robot sets (the cue's speed and direction, where
// its tip meets the ball, its elevation) to the cue ball's velocity and spin.
//
// Frame. The cue points along d = (cos e cos h, cos e sin h, -sin e): heading h
// (counter-clockwise from +x, as every heading in physics/), elevation e (the butt
// raised). Looking along d, "right" is s = (sin h, -cos h, 0) and "up" is u = s x d
// (z for a level cue). The tip meets the ball at
//   r = side R s + height R u - c d,   c = R sqrt(1 - side^2 - height^2),
// `side` and `height` being the contact point's offsets from the line through the
// centre parallel to the cue, as fractions of the ball's radius R. The cue's axis is
// then (R + rho) / R times as far off centre, rho the tip's dome radius: the tip's
// sphere touches the ball on the line joining the two centres.
//
// Impulse. Two parts, each one of Alciatore's technical proofs:
//  * along the cue (TP A.30, with the tip's restitution e_t for its elastic 1):
//      J = (1 + e_t) m V / (1 + m / M + 5/2 (side^2 + height^2)),
//    m the ball's mass, M the cue's, V its speed: the normal restitution law at the
//    tip for an impulse along the cue through r. A level strike at height b then
//    gives speed v = J / m and spin 5 v b / (2 R), A.30's result.
//  * across it, to the right (TP A.31, squirt): while they touch, the tip and the
//    ball's contact point keep one velocity along s; the tip's end mass m_e (the
//    last few inches of shaft) is what resists. Solving for the impulse F_s,
//      F_s = -5/2 side (c / R) J / (1 + m / m_e + 5/2 (1 - side^2)),
//    which for height = 0 is A.31's squirt angle atan(|F_s| / J). The ball squirts
//    away from the side struck (right side: to the left).
//    The coupling of F_s back into the axial restitution is left out, as in both
//    proofs: it changes J by a fraction of squirt^2.
// The ball takes v = (J d + F_s s) / m and w = r x (J d + F_s s) / I (I = 2/5 m R^2).
//
// The bed. An elevated cue drives the ball into the slate; the slate's normal
// impulse (through the ball's lowest point, so no torque) takes the downward part
// of v away, and the friction of that impulse is left out. A real ball hops: at
// the bed's restitution it would rise (e_b v_down)^2 / (2 g). Strikes whose hop
// exceeds CueParams::max_hop are refused (StrikeStatus::kHop): the model has no
// flight, and a jump shot is not what it plays.
//
// Swerve is not added here: an elevated strike with side tilts the spin axis
// (w gets a component along the heading, Shot::swerve_spin), and the cloth's
// friction on the sliding ball (physics/motion) curves its path from there.
//
// Miscue: the tip slips when the angle between the cue and the ball's surface
// normal at the contact, asin(sqrt(side^2 + height^2)), exceeds the tip's friction
// angle atan(mu_t): MiscueLimit.
#pragma once

#include <cstdint>
#include <optional>

#include <Eigen/Geometry>

#include "physics/core/params.h"
#include "physics/core/shot.h"
#include "physics/core/types.h"

namespace snooker::physics {

/// The robot's cue and the bed under the ball. Defaults, each with its source, are
/// listed in docs/cue.md.
struct CueParams {
  /// The cue's mass, kg: a 19 oz snooker cue.
  double mass = 0.54;
  /// The tip's dome radius, m (a "dime" dome on a 9.5 mm tip).
  double tip_radius = 0.009;
  /// Normal restitution of the leather tip on the ball (measured 0.71-0.75).
  double tip_restitution = 0.73;
  /// Tip-ball friction coefficient of a chalked tip; sets the miscue limit.
  double tip_friction = 0.6;
  /// The shaft's end mass, kg: what sets squirt. 6 g, a snooker shaft (ash with a
  /// brass ferrule): 2.2 deg of squirt at 0.45 R of side, between the measured
  /// low-deflection (1.8 deg) and standard (2.5 deg) shafts.
  double end_mass = 0.006;
  /// Restitution of the ball's bounce on the slate (hop estimate only).
  double bed_restitution = 0.5;
  /// Largest hop the model accepts, m (a ball that rises more is in flight).
  double max_hop = 2e-3;
};

/// What the robot sets.
struct CueStrike {
  /// The cue's speed at impact, m/s.
  double speed = 0;
  /// The cue's direction, counter-clockwise from +x. rad.
  double heading = 0;
  /// Where the tip meets the ball, fractions of R: right and up as seen along the cue.
  double side = 0;
  double height = 0;
  /// The cue's angle above the bed, rad (the butt raised).
  double elevation = 0;
};

enum class StrikeStatus : std::uint8_t {
  kOk,
  kMiscue,   ///< the contact is beyond the tip's friction angle
  kHop,      ///< the ball would leave the bed by more than max_hop
  kInvalid,  ///< a non-finite or negative speed, or an elevation outside [0, 90) deg
};
const char* ToString(StrikeStatus s);

struct StrikeResult {
  StrikeStatus status = StrikeStatus::kInvalid;
  /// The ball on the bed after the strike (the downward part of v removed).
  Shot shot;
  /// The ball's heading less the cue's, rad: positive (to the left) for right side.
  double squirt = 0;
  /// The ball's velocity and spin right after the tip, before the bed acts. m/s, rad/s.
  Vec3 v = Vec3::Zero();
  Vec3 w = Vec3::Zero();
  /// Impulse along the cue and across it (to the right), N s.
  double axial_impulse = 0;
  double lateral_impulse = 0;
  /// Height the ball would hop (the bed's restitution), m.
  double hop = 0;
};

/// The strike. Everything is computed even when the status refuses it.
StrikeResult Strike(const CueStrike& strike, const CueParams& cue, const BallParams& ball,
                    double gravity);

/// The cue speed whose impulse along the cue gives the ball `ball_speed` along it
/// (TP A.30 with the tip's restitution, inverted), for tip offsets `side` and
/// `height` (fractions of R). m/s.
inline double CueSpeedFor(double ball_speed, double side, double height, const CueParams& cue,
                          const BallParams& ball) {
  return ball_speed * (1 + ball.mass / cue.mass + 2.5 * (side * side + height * height)) / (1 + cue.tip_restitution);
}

/// Largest contact offset sqrt(side^2 + height^2) without a miscue, fraction of R.
double MiscueLimit(const CueParams& cue);

/// TP A.31's squirt angle, rad, for a level strike at `side` (fraction of R); positive.
double SquirtAngle(double side, const CueParams& cue, const BallParams& ball);

/// The strike at `elevation` that gives `shot`'s speed, heading, topspin and
/// sidespin (its swerve spin follows from the elevation): Newton on the two
/// offsets (they alone set the spins per unit speed), then the cue's speed and
/// heading in closed form. nullopt if no offset within the miscue limit gives it.
std::optional<CueStrike> StrikeFor(const Shot& shot, double elevation, const CueParams& cue,
                                   const BallParams& ball, double gravity);

}  // namespace snooker::physics
