#include "physics/sim/contacts.h"

#include <algorithm>

#include "physics/events/detect.h"
#include "physics/motion/motion.h"

namespace snooker::physics {
namespace {

// Spin about the horizontal axis t = z x n, whose component w_t makes the cloth slip
// along n: u . n = v . n - R w_t.
Vec3 TangentAxis(const Vec2& n) { return {-n.y(), n.x(), 0.0}; }

// A sliding ball whose friction drives it along `into` loses the spin that does: its
// slip along `into` goes to zero, its spin about the tangent axis towards zero, never
// past it.
void Unslip(BallState* s, const Vec2& into, const SimParams& p) {
  if (s->s != MotionState::kSliding || !(ClothSlip(*s, p.ball).dot(into) < 0.0)) return;
  const Vec3 axis = TangentAxis(into);
  const double wt = s->w.dot(axis);
  const double target = s->v.head<2>().dot(into) / p.ball.radius;  // slip along `into` = 0
  const double kept = std::clamp(target, std::min(0.0, wt), std::max(0.0, wt));
  s->w += (kept - wt) * axis;
  *s = Settle(*s, p.ball);
}

// True when the cloth decelerations of a and b press them together along n.
bool Pressing(const BallState& a, const BallState& b, const Vec2& n, const SimParams& p) {
  const PositionPoly pa = PositionPolynomial(a, p.ball, p.cloth);
  const PositionPoly pb = PositionPolynomial(b, p.ball, p.cloth);
  return 2.0 * (pb.a - pa.a).dot(n) < -kContactAccelTolerance;
}

}  // namespace

BallState AfterImpact(const BallState& s, const SimParams& p) {
  const double v = Vec2(s.v.x(), s.v.y()).norm();
  if (v >= p.rest_speed || ClothSlip(s, p.ball).norm() >= p.rest_speed) return s;
  BallState rest = s;
  rest.v.setZero();
  rest.w.x() = rest.w.y() = 0;
  return Settle(rest, p.ball);
}

BallState Stopped(const BallState& s, const SimParams& p) {
  BallState out = s;
  out.v.setZero();
  out.w.x() = out.w.y() = 0.0;
  return Settle(out, p.ball);
}

BallState WithoutNormalVelocity(const BallState& s, const Vec2& n) {
  BallState out = s;
  const double vn = s.v.x() * n.x() + s.v.y() * n.y();
  out.v.x() -= vn * n.x();
  out.v.y() -= vn * n.y();
  return out;
}

BallState HoldAgainst(const BallState& s, const Vec2& n, const SimParams& p) {
  // The boundary's reaction would do the same to the slip over |u_n| / (5/2 mu_s g);
  // doing it at once changes the path by less than the cloth friction over that
  // time. Energy only falls.
  BallState out = WithoutNormalVelocity(s, n);
  const Vec3 t = TangentAxis(n);
  out.w -= out.w.dot(t) * t;
  return Settle(out, p.ball);
}

BallState HoldIfReturning(const BallState& s, const Vec2& n, const SimParams& p) {
  // A sliding ball that leaves the boundary slowly while its friction drives it back
  // would bounce again and again in ever shorter flights (a Zeno sequence). Once a
  // flight would rise less than resting_contact_excursion off the boundary, the ball
  // is held against it instead (a resting contact).
  if (s.s != MotionState::kSliding) return s;
  const PositionPoly poly = PositionPolynomial(s, p.ball, p.cloth);
  const double an = 2.0 * poly.a.dot(n), vn = poly.b.dot(n);
  if (!(an < 0.0) || vn * vn > 2.0 * -an * p.resting_contact_excursion) return s;
  return HoldAgainst(s, n, p);
}

void RemoveApproach(BallState* a, BallState* b, const Vec2& n, const SimParams& p) {
  const double approach = (a->v.head<2>() - b->v.head<2>()).dot(n);
  if (!(approach > 0.0)) return;
  a->v.head<2>() -= 0.5 * approach * n;
  b->v.head<2>() += 0.5 * approach * n;
  *a = Settle(*a, p.ball);
  *b = Settle(*b, p.ball);
}

void HoldTogether(BallState* a, BallState* b, const Vec2& n, int level_a, int level_b,
                  const SimParams& p) {
  // A pressed pair would move as one body, which the closed-form motions cannot
  // express. Each step below only takes energy out, and they stop at the first that
  // leaves the pair not pressing:
  //  1. A sliding ball whose friction drives it into the other loses the spin that
  //     does (Unslip).
  //  2. If both are slower than resting_pair_speed, both stop: they would have
  //     rolled on together at most v^2 / (2 mu_r g) (0.1 mm at 5 mm/s).
  //  3. A ball pressed for the second time at the same instant is wedged between
  //     several contacts (the alternating steps 1 for each would never end): it
  //     stops. Otherwise both lose their velocity and slip along n: the pair stops
  //     along the line of centres and keeps its motion across it.
  RemoveApproach(a, b, n, p);
  Unslip(a, n, p);
  Unslip(b, -n, p);
  if (!Pressing(*a, *b, n, p)) return;
  const double slow = p.resting_pair_speed;
  if (a->v.head<2>().norm() < slow && b->v.head<2>().norm() < slow) {
    *a = Stopped(*a, p);
    *b = Stopped(*b, p);
    return;
  }
  if (level_a > 0 || level_b > 0) {
    if (level_a > 0) *a = Stopped(*a, p);
    if (level_b > 0) *b = Stopped(*b, p);
    return;
  }
  const Vec3 t = TangentAxis(n);
  for (BallState* s : {a, b}) {
    *s = WithoutNormalVelocity(*s, n);
    s->w -= s->w.dot(t) * t;
    *s = Settle(*s, p.ball);
  }
}

void HoldIfReturning(BallState* a, BallState* b, const Vec2& n, int level_a, int level_b,
                     const SimParams& p) {
  const PositionPoly pa = PositionPolynomial(*a, p.ball, p.cloth);
  const PositionPoly pb = PositionPolynomial(*b, p.ball, p.cloth);
  const double an = 2.0 * (pb.a - pa.a).dot(n), vn = (pb.b - pa.b).dot(n);
  if (!(an < 0.0) || vn * vn > 2.0 * -an * p.resting_contact_excursion) return;
  const double mean = 0.5 * (a->v.head<2>() + b->v.head<2>()).dot(n);
  a->v.head<2>() += (mean - a->v.head<2>().dot(n)) * n;
  b->v.head<2>() += (mean - b->v.head<2>().dot(n)) * n;
  *a = Settle(*a, p.ball);
  *b = Settle(*b, p.ball);
  HoldTogether(a, b, n, level_a, level_b, p);
}

}  // namespace snooker::physics
