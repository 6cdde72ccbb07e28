#include "physics/events/detect.h"

#include <cmath>
#include <limits>

#include "physics/events/roots.h"

namespace snooker::physics {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A quadratic gap has at most two roots, so at most two crossings lie outside the
// segment before the search runs out; the cap leaves room to spare.
constexpr int kMaxSegmentCrossings = 4;

// |d(t)|^2 - contact^2 for d(t) = dc + db t + da t^2. The constant term is formed as
// (|dc| - contact)(|dc| + contact), accurate when the two nearly touch.
Poly4 SquaredDistanceGap(const Vec2& dc, const Vec2& db, const Vec2& da, double contact) {
  const double n = dc.norm();
  return {(n - contact) * (n + contact), 2.0 * dc.dot(db), db.dot(db) + 2.0 * dc.dot(da),
          2.0 * db.dot(da), da.dot(da)};
}

// True when the gap says "touching at t = 0 and about to overlap". `gap_per_metre`
// converts distances into gap units: 1 for a linear gap, 2 * contact distance for a
// squared-distance gap (its derivative with respect to the distance at contact).
bool StartsInContact(const Poly4& g, double gap_per_metre) {
  if (!(g[0] <= kContactTolerance * gap_per_metre)) return false;
  const double rate = kApproachSpeedTolerance * gap_per_metre;
  if (g[1] < -rate) return true;           // approaching
  return g[1] <= rate && g[2] < 0.0;       // tangential, accelerating inwards
}

double FirstContact(const Poly4& g, double gap_per_metre, double t_max) {
  if (!(t_max >= 0.0)) return kInf;
  if (StartsInContact(g, gap_per_metre)) return 0.0;
  return FindFirstDownCrossing(g, 0.0, t_max);
}

double CircleContact(const PositionPoly& p, const Vec2& centre, double contact, double t_max) {
  return FirstContact(SquaredDistanceGap(p.c - centre, p.b, p.a, contact), 2.0 * contact, t_max);
}

}  // namespace

double DetectBallBall(const PositionPoly& a, const PositionPoly& b, double radius, double t_max) {
  const double contact = 2.0 * radius;
  const Poly4 g = SquaredDistanceGap(a.c - b.c, a.b - b.b, a.a - b.a, contact);
  return FirstContact(g, 2.0 * contact, t_max);
}

double DetectBallCushion(const PositionPoly& p, const CushionSegment& segment,
                         double contact_distance, double t_max) {
  if (!(t_max >= 0.0)) return kInf;
  const Vec2& n = segment.normal;
  const Vec2 along = segment.p1 - segment.p0;
  const double length2 = along.squaredNorm();
  const Poly4 g = {n.dot(p.c - segment.p0) - contact_distance, n.dot(p.b), n.dot(p.a), 0.0, 0.0};
  const auto on_segment = [&](double t) {
    const double s = (p.At(t) - segment.p0).dot(along);
    return s >= 0.0 && s <= length2;
  };
  if (StartsInContact(g, 1.0) && on_segment(0.0)) return 0.0;
  double t = 0.0;
  for (int i = 0; i < kMaxSegmentCrossings; ++i) {
    t = FindFirstDownCrossing(g, t, t_max);
    if (!(t <= t_max)) return kInf;
    if (on_segment(t)) return t;
  }
  return kInf;
}

double DetectBallJaw(const PositionPoly& p, const JawCircle& jaw, double radius, double t_max) {
  return CircleContact(p, jaw.centre, radius + jaw.radius, t_max);
}

double DetectBallPocket(const PositionPoly& p, const Pocket& pocket, double t_max) {
  if (!(t_max >= 0.0)) return kInf;
  const Poly4 g = SquaredDistanceGap(p.c - pocket.capture_centre, p.b, p.a, pocket.capture_radius);
  if (g[0] <= 0.0) return 0.0;
  return FindFirstDownCrossing(g, 0.0, t_max);
}

double DetectTransition(const BallState& s, const BallParams& ball, const ClothParams& cloth,
                        double t_max) {
  if (!(t_max >= 0.0)) return kInf;
  const double t = TransitionTime(s, ball, cloth);
  return t <= t_max ? t : kInf;
}

}  // namespace snooker::physics
