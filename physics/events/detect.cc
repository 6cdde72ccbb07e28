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
Gap SquaredDistanceGap(const Vec2& dc, const Vec2& db, const Vec2& da, double contact) {
  const double n = dc.norm();
  return {{(n - contact) * (n + contact), 2.0 * dc.dot(db), db.dot(db) + 2.0 * dc.dot(da),
           2.0 * db.dot(da), da.dot(da)},
          2.0 * contact};
}

// For a touching pair that neither approaches nor presses at 0: the first time in
// (0, t_max] at which it makes contact again, or +infinity. The pair may stay in
// contact (rolling along a cushion), drift apart, or drift apart and come back
// (a slow separation that its decelerations turn round). Its next contact begins
// where it starts to approach faster than the tolerance: at the first time t1 its
// normal speed passes 2 x kApproachSpeedTolerance inwards (so that the resolver
// sees an approach there). If the gap is still within the contact band at t1, that
// is the contact; if it has opened beyond it, the contact is the gap's next
// down-crossing after t1. A gap that stays at zero to rounding never passes the
// speed threshold, so rounding noise cannot make an event.
double NextContactWhileTouching(const Gap& gap, double t_max) {
  Poly4 speed = DifferentiatePoly(gap.g);  // g'(t) + 2 x tolerance: > 0 until it approaches
  speed[0] += 2.0 * kApproachSpeedTolerance * gap.per_metre;
  const double t1 = FindFirstDownCrossing(speed, 0.0, t_max);
  if (!(t1 <= t_max)) return kInf;
  if (EvaluatePoly(gap.g, t1) <= kContactTolerance * gap.per_metre) return t1;
  return FindFirstDownCrossing(gap.g, t1, t_max);
}

// First contact of a gap in [0, t_max]: at 0 for an impact or a pressing contact;
// after the gap opens for a touching one; else the first down-crossing.
double FirstContact(const Gap& gap, double t_max) {
  if (!(t_max >= 0.0)) return kInf;
  switch (ClassifyContact(gap.g, gap.per_metre)) {
    case ContactStart::kApproaching:
    case ContactStart::kPressing: return 0.0;
    case ContactStart::kTouching: return NextContactWhileTouching(gap, t_max);
    case ContactStart::kApart: break;
  }
  return FindFirstDownCrossing(gap.g, 0.0, t_max);
}

}  // namespace

const char* ToString(ContactStart c) {
  switch (c) {
    case ContactStart::kApart: return "apart";
    case ContactStart::kApproaching: return "approaching";
    case ContactStart::kPressing: return "pressing";
    case ContactStart::kTouching: return "touching";
  }
  return "unknown";
}

ContactStart ClassifyContact(const Poly4& g, double gap_per_metre) {
  if (!(g[0] <= kContactTolerance * gap_per_metre)) return ContactStart::kApart;
  const double rate = kApproachSpeedTolerance * gap_per_metre;
  if (g[1] < -rate) return ContactStart::kApproaching;
  // g[2] is half the gap's second derivative: the normal acceleration is
  // 2 g[2] / gap_per_metre (for a squared-distance gap at contact and at rest
  // relative to each other; a tangential relative speed adds the curvature term
  // |d'|^2 > 0, which separates convex bodies).
  if (g[1] <= rate && 2.0 * g[2] < -kContactAccelTolerance * gap_per_metre) {
    return ContactStart::kPressing;
  }
  return ContactStart::kTouching;
}

Gap BallBallGap(const PositionPoly& a, const PositionPoly& b, double radius) {
  return SquaredDistanceGap(a.c - b.c, a.b - b.b, a.a - b.a, 2.0 * radius);
}

Gap CushionGap(const PositionPoly& p, const CushionSegment& segment, double contact_distance) {
  const Vec2& n = segment.normal;
  return {{n.dot(p.c - segment.p0) - contact_distance, n.dot(p.b), n.dot(p.a), 0.0, 0.0}, 1.0};
}

Gap JawGap(const PositionPoly& p, const JawCircle& jaw, double radius) {
  return SquaredDistanceGap(p.c - jaw.centre, p.b, p.a, radius + jaw.radius);
}

double DetectBallBall(const PositionPoly& a, const PositionPoly& b, double radius, double t_max) {
  return FirstContact(BallBallGap(a, b, radius), t_max);
}

double DetectBallCushion(const PositionPoly& p, const CushionSegment& segment,
                         double contact_distance, double t_max) {
  if (!(t_max >= 0.0)) return kInf;
  const Gap gap = CushionGap(p, segment, contact_distance);
  const Vec2 along = segment.p1 - segment.p0;
  const double length2 = along.squaredNorm();
  const auto on_segment = [&](double t) {
    const double s = (p.At(t) - segment.p0).dot(along);
    return s >= 0.0 && s <= length2;
  };
  double t = 0.0;
  switch (ClassifyContact(gap.g, gap.per_metre)) {
    case ContactStart::kApproaching:
    case ContactStart::kPressing:
      if (on_segment(0.0)) return 0.0;
      break;
    case ContactStart::kTouching: {
      // Along the line of a segment the ball touches (a ball frozen to a cushion).
      const double next = NextContactWhileTouching(gap, t_max);
      if (!(next <= t_max)) return kInf;
      if (EvaluatePoly(gap.g, next) <= kContactTolerance * gap.per_metre) {
        if (on_segment(next)) return next;
      }
      t = next;
      break;
    }
    case ContactStart::kApart: break;
  }
  for (int i = 0; i < kMaxSegmentCrossings; ++i) {
    t = FindFirstDownCrossing(gap.g, t, t_max);
    if (!(t <= t_max)) return kInf;
    if (on_segment(t)) return t;
  }
  return kInf;
}

double DetectBallJaw(const PositionPoly& p, const JawCircle& jaw, double radius, double t_max) {
  return FirstContact(JawGap(p, jaw, radius), t_max);
}

double DetectBallPocket(const PositionPoly& p, const Pocket& pocket, double t_max) {
  if (!(t_max >= 0.0)) return kInf;
  const Poly4 g = SquaredDistanceGap(p.c - pocket.capture_centre, p.b, p.a, pocket.capture_radius).g;
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
