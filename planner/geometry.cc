#include "planner/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/core/shot.h"

namespace snooker::planner {

using physics::Vec2;
using physics::Vec3;

double WrapAngle(double a) {
  if (!std::isfinite(a)) return a;
  a = physics::RemainderTwoPi(a);
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

int FirstBallMet(const TableState& table, const Vec2& from, double heading, double radius, int skip) {
  const Vec2 u = physics::HeadingVector(heading);
  int first = -1;
  double nearest = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < table.balls.size(); ++i) {
    if (static_cast<int>(i) == skip) continue;
    const Vec2 to = table.balls[i].position - from;
    const double along = to.dot(u);
    const double across = Cross(u, to);
    if (along <= 0 || std::abs(across) >= 2 * radius) continue;
    const double travel = along - std::sqrt(4 * radius * radius - across * across);
    if (travel < nearest) {
      nearest = travel;
      first = static_cast<int>(i);
    }
  }
  return first;
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

double CueMarginAt(const TableState& table, int cue, double heading, double elevation, double tip_height,
                   const CueClearance& cue_room, const physics::TableModel& model) {
  const double r = model.ball_radius();
  const Vec2 c = table.balls[static_cast<size_t>(cue)].position;
  const Vec2 back = -Vec2(std::cos(heading), std::sin(heading));
  const double w = model.spec().width, l = model.spec().length;
  if (elevation <= 0 && tip_height == 0) {
    const Vec2 tip = c + r * back, butt = c + (r + cue_room.length) * back;
    double margin = PathMargin(tip, butt, r + cue_room.radius, table, cue, -1);
    // The stick's edge against the four cushion lines (the playing area's rectangle).
    for (const Vec2& p : {tip, butt}) {
      margin = std::min({margin, p.x() - cue_room.radius, w - p.x() - cue_room.radius,
                         p.y() - cue_room.radius, l - p.y() - cue_room.radius});
    }
    return margin;
  }
  // The raised stick: from the contact point back along the cue until it has
  // covered `length` of bed. Along the cue the contact is c R behind the centre and
  // h R above it (c = sqrt(1 - h^2)), in the cue's own frame.
  const double h = std::clamp(tip_height, -0.99, 0.99), ch = std::sqrt(1 - h * h);
  const double ce = std::cos(elevation), se = std::sin(elevation);
  const Vec3 centre(c.x(), c.y(), r);
  const Vec3 up_back(back.x() * ce, back.y() * ce, se);  // from the ball towards the butt
  const Vec3 up(-back.x() * se, -back.y() * se, ce);     // the cue's "up"
  const Vec3 tip = centre + r * (ch * up_back + h * up);
  const double span = cue_room.length / ce;
  double margin = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < table.balls.size(); ++i) {
    if (static_cast<int>(i) == cue) continue;
    const Vec3 b(table.balls[i].position.x(), table.balls[i].position.y(), r);
    const double t = std::clamp((b - tip).dot(up_back), 0.0, span);
    margin = std::min(margin, (b - (tip + t * up_back)).norm() - r - cue_room.radius);
  }
  // Each cushion: the stick's edge inside the nose line, or above the nose where it
  // crosses the nose line and above the top where it crosses the top's line (it
  // only rises from there).
  const Vec2 tip_h(tip.x(), tip.y());
  const Vec2 normals[4] = {Vec2(1, 0), Vec2(-1, 0), Vec2(0, 1), Vec2(0, -1)};
  const double offsets[4] = {0, w, 0, l};  // inside = n . p + offset
  const double lift = cue_room.radius / ce;  // the stick's underside below its axis
  for (int k = 0; k < 4; ++k) {
    const double inside0 = normals[k].dot(tip_h) + offsets[k] - cue_room.radius;
    const double rate = normals[k].dot(back) * ce;  // d(inside)/dt, per m of stick
    if (inside0 >= 0 && inside0 + rate * span >= 0) {
      margin = std::min(margin, std::min(inside0, inside0 + rate * span));
      continue;
    }
    const double nose = model.spec().cushion_height;
    for (const auto& [setback, height] : {std::pair{0.0, nose}, std::pair{cue_room.cushion_top_setback,
                                                                           cue_room.cushion_top}}) {
      const double t_cross = std::max(0.0, (inside0 + setback) / -rate);
      margin = std::min(margin, tip.z() + t_cross * se - lift - height);
    }
  }
  return margin;
}

std::optional<double> CueElevation(const TableState& table, int cue, double heading, double tip_height,
                                   const CueClearance& cue_room, const physics::TableModel& model) {
  const int steps = std::min(89, static_cast<int>(std::floor(physics::RadToDeg(cue_room.max_elevation) + 1e-9)));
  for (int deg = 0; deg <= steps; ++deg) {
    const double e = physics::DegToRad(deg);
    if (CueMarginAt(table, cue, heading, e, deg == 0 ? 0.0 : tip_height, cue_room, model) >= 0) return e;
  }
  return std::nullopt;
}

double CueMargin(const TableState& table, int cue, double heading, const CueClearance& cue_room,
                 const physics::TableModel& model) {
  const double level = CueMarginAt(table, cue, heading, 0.0, 0.0, cue_room, model);
  if (level >= 0) return level;
  const auto e = CueElevation(table, cue, heading, kMaxTipOffset, cue_room, model);
  return e ? CueMarginAt(table, cue, heading, *e, kMaxTipOffset, cue_room, model) : level;
}

}  // namespace snooker::planner
