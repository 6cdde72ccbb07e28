#include "planner/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace snooker::planner {

using physics::Vec2;

double WrapAngle(double a) {
  if (!std::isfinite(a)) return a;
  a = std::remainder(a, 2 * physics::kPi);
  return a <= -physics::kPi ? a + 2 * physics::kPi : a;
}

std::optional<double> HeadingForCut(const Vec2& cue, const Vec2& object, double cut, double radius) {
  const Vec2 d = object - cue;
  const double dist = d.norm();
  if (!(std::abs(cut) < physics::kPi / 2) || !(dist >= 2 * radius)) return std::nullopt;
  const double s = 2 * radius * std::sin(cut) / dist;
  if (std::abs(s) > 1) return std::nullopt;
  return WrapAngle(Direction(d) - std::asin(s));
}

std::optional<GhostAim> AimAlong(const Vec2& cue, const Vec2& object, double object_direction,
                                 double radius) {
  GhostAim aim;
  aim.ghost = object - 2 * radius * Vec2(std::cos(object_direction), std::sin(object_direction));
  const Vec2 path = aim.ghost - cue;
  if ((object - cue).norm() <= 2 * radius || path.norm() <= 0) return std::nullopt;
  aim.heading = Direction(path);
  aim.cut = WrapAngle(object_direction - aim.heading);
  if (!(std::abs(aim.cut) < physics::kPi / 2)) return std::nullopt;
  return aim;
}

double SegmentDistance(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double u = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + u * d)).norm();
}

double PathMargin(const Vec2& a, const Vec2& b, double clearance, const TableState& table,
                  int skip_a, int skip_b) {
  double margin = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < table.balls.size(); ++i) {
    const int k = static_cast<int>(i);
    if (k == skip_a || k == skip_b) continue;
    margin = std::min(margin, SegmentDistance(a, b, table.balls[i].position) - clearance);
  }
  return margin;
}

double TravelMargin(const Vec2& a, const Vec2& b, double clearance, const TableState& table, int skip_a,
                    int skip_b) {
  const Vec2 d = b - a;
  double margin = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < table.balls.size(); ++i) {
    const int k = static_cast<int>(i);
    if (k == skip_a || k == skip_b) continue;
    const Vec2& p = table.balls[i].position;
    if ((p - a).dot(d) <= 0) continue;  // the path only moves away from it
    margin = std::min(margin, SegmentDistance(a, b, p) - clearance);
  }
  return margin;
}

double CueMargin(const TableState& table, int cue, double heading, const CueClearance& cue_room,
                 const physics::TableModel& model) {
  const double r = model.ball_radius();
  const Vec2 c = table.balls[static_cast<size_t>(cue)].position;
  const Vec2 back = -Vec2(std::cos(heading), std::sin(heading));
  const Vec2 tip = c + r * back, butt = c + (r + cue_room.length) * back;
  double margin = PathMargin(tip, butt, r + cue_room.radius, table, cue, -1);
  // The stick's edge against the four cushion lines (the playing area's rectangle).
  const double w = model.spec().width, l = model.spec().length;
  for (const Vec2& p : {tip, butt}) {
    margin = std::min({margin, p.x() - cue_room.radius, w - p.x() - cue_room.radius,
                       p.y() - cue_room.radius, l - p.y() - cue_room.radius});
  }
  return margin;
}

}  // namespace snooker::planner
