// Plane geometry of a pot (table frame, m, rad; headings counter-clockwise from +x).
//
// The cut angle c of a shot is the signed angle from the cue ball's heading to the
// object ball's departure direction (the line of centres at contact), counter-
// clockwise positive, in (-90, 90) deg: with c > 0 the cue ball takes the object
// ball on its right-hand side (seen along the shot) and sends it to the left.
// Between the strike and the first contact the cue ball runs straight: the cloth
// friction acts along the heading (its slip is (v - R topspin) along the heading and
// sidespin adds none), so the cut fixes the heading exactly:
//   sin(phi0 - h) = 2R sin(c) / d,  phi0 = the direction from cue ball to object ball,
//   d their distance (the ghost-ball construction).
#pragma once

#include <optional>
#include <span>

#include "physics/core/types.h"
#include "planner/rules.h"

namespace snooker::planner {

/// The angle in (-pi, pi].
double WrapAngle(double a);
/// Counter-clockwise angle of v from +x. rad.
inline double Direction(const physics::Vec2& v) { return std::atan2(v.y(), v.x()); }
/// 2-D cross product a.x b.y - a.y b.x (positive when b is counter-clockwise of a).
inline double Cross(const physics::Vec2& a, const physics::Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}
/// a turned by +90 deg (its left normal).
inline physics::Vec2 Left(const physics::Vec2& a) { return {-a.y(), a.x()}; }

/// Heading (rad) that realises cut `cut` (rad) on the object ball at `object` from
/// the cue ball at `cue`, balls of radius `radius`; nullopt when |cut| >= 90 deg or
/// the balls are closer than 2R.
std::optional<double> HeadingForCut(const physics::Vec2& cue, const physics::Vec2& object,
                                    double cut, double radius);

/// The cut (rad) that sends the object ball along `object_direction` (rad) by the
/// ghost-ball construction, and the heading that plays it; nullopt when the ghost
/// ball cannot be reached (a cut of 90 deg or more, or balls touching).
struct GhostAim {
  double cut = 0;       ///< rad
  double heading = 0;   ///< rad
  physics::Vec2 ghost = physics::Vec2::Zero();  ///< cue-ball centre at contact, m
};
std::optional<GhostAim> AimAlong(const physics::Vec2& cue, const physics::Vec2& object,
                                 double object_direction, double radius);

/// The ball of `table` a ball of `radius` (m) moving straight from `from` along
/// `heading` (rad) meets first, skipping the index `skip` (the moving ball itself
/// when it is in the table), or -1. A ball it touches and leaves behind is not met.
int FirstBallMet(const TableState& table, const physics::Vec2& from, double heading, double radius,
                 int skip = -1);

/// Distance from p to the segment [a, b]. m.
double SegmentDistance(const physics::Vec2& a, const physics::Vec2& b, const physics::Vec2& p);

/// Smallest distance from the segment [a, b] to the centre of any ball of `table`
/// except the indices `skip_a` and `skip_b`, minus `clearance`: >= 0 when a ball
/// centre moving from a to b passes every other ball with `clearance` to spare
/// (2R for a ball's path). +infinity on an empty table. m.
double PathMargin(const physics::Vec2& a, const physics::Vec2& b, double clearance,
                  const TableState& table, int skip_a, int skip_b);

/// PathMargin for a ball travelling from a to b: balls it moves away from at a
/// (their nearest point on the path is a itself: behind it, or touching it on the
/// side it leaves) are no obstacle, so a cue ball frozen to a ball can play away
/// from it. m.
double TravelMargin(const physics::Vec2& a, const physics::Vec2& b, double clearance,
                    const TableState& table, int skip_a, int skip_b);

/// The room the robot's cue needs behind the cue ball: a straight stick of `radius`
/// (m) along the heading, from the ball back over `length` (m) of bed, level when
/// that clears and otherwise raised (the butt up) by as little as clears, up to
/// `max_elevation`.
struct CueClearance {
  double length = 0.10;
  double radius = 0.007;
  /// Steepest cue, rad (25 deg: over a cushion with the ball frozen to it; the
  /// strike's hop limit, physics/cue/strike.h, allows only soft shots that steep).
  double max_elevation = 25.0 * physics::kPi / 180;
  /// The cushion in the stick's way (seen from the side): its nose at the table's
  /// cushion height on the nose line, its top `cushion_top` (m) above the bed
  /// `cushion_top_setback` (m) behind the nose line, the rail behind it no higher.
  double cushion_top = 0.042;
  double cushion_top_setback = 0.015;
};

/// How much room the cue has for a shot from the cue ball (index `cue` of `table`)
/// along `heading` at `elevation` (rad), the tip meeting the ball `tip_height` (a
/// fraction of R, up as seen along the cue) above the centre line: the smallest gap
/// between the stick and another ball (3-D: a raised stick rises behind the ball),
/// or a cushion (a level stick at the ball's height cannot pass over one; a raised
/// one must clear the nose and the top where it crosses them). The stick's axis is
/// taken through the contact point (the tip's dome moves it by a few mm). Negative:
/// the shot cannot be played so. m.
double CueMarginAt(const TableState& table, int cue, double heading, double elevation, double tip_height,
                   const CueClearance& cue_room, const physics::TableModel& model);

/// The lowest elevation in whole degrees up to cue_room.max_elevation at which the
/// cue clears (CueMarginAt >= 0) with the tip at `tip_height`, rad; nullopt when
/// none does.
std::optional<double> CueElevation(const TableState& table, int cue, double heading, double tip_height,
                                   const CueClearance& cue_room, const physics::TableModel& model);

/// How much room the cue has along `heading` as the robot would play it: the level
/// centre-line margin when it clears; otherwise CueMarginAt at the lowest elevation
/// that clears with the tip as high as kMaxTipOffset allows (the level margin when
/// none does). m.
double CueMargin(const TableState& table, int cue, double heading, const CueClearance& cue_room,
                 const physics::TableModel& model);

/// The largest tip offset the planner plays, fraction of R: under the default cue's
/// miscue limit (0.51, physics/cue/strike.h) with room for the robot's noise.
inline constexpr double kMaxTipOffset = 0.45;

}  // namespace snooker::planner
