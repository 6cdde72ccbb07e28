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

/// The room the robot's cue needs behind the cue ball: a straight, level stick of
/// `radius` (m) along the heading, from the ball back over `length` (m) of bed.
struct CueClearance {
  double length = 0.10;
  double radius = 0.007;
};

/// How much room the cue has for a shot from the cue ball (index `cue` of `table`)
/// along `heading`: the smallest gap between the stick and another ball or a
/// cushion (the stick is at the ball's centre height, below the cushion nose, so it
/// cannot pass over a cushion). Negative: the shot cannot be played. m.
double CueMargin(const TableState& table, int cue, double heading, const CueClearance& cue_room,
                 const physics::TableModel& model);

}  // namespace snooker::planner
