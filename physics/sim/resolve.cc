#include "physics/sim/resolve.h"

#include "physics/motion/motion.h"
#include "physics/sim/contacts.h"

namespace snooker::physics {

Eigen::Matrix3d FrameAlong(const Vec2& y) {
  Eigen::Matrix3d q;
  q.row(0) << y.y(), -y.x(), 0.0;  // X = Y x Z
  q.row(1) << y.x(), y.y(), 0.0;   // Y
  q.row(2) << 0.0, 0.0, 1.0;       // Z
  return q;
}

namespace {

// A state seen from the impact frame turned by pi about Z: X and Y change sign, and
// the two balls swap places (C at -Y becomes O). Its own inverse.
ImpactState Turned(const ImpactState& s) {
  auto turn = [](const Vec3& v) { return Vec3(-v.x(), -v.y(), v.z()); };
  return {{turn(s.o.v), turn(s.o.w)}, {turn(s.c.v), turn(s.c.w)}};
}

// The table's answer for an impact of a rolling ball on one at rest, in the impact
// frame. The table's C is the moving ball: a as given, or b seen from the turned frame.
bool LookUp(const BallBallTable* table, const ImpactState& in, double radius, ImpactState* out) {
  if (table == nullptr) return false;
  if (table->Lookup(in, radius, out)) return true;
  if (!table->Lookup(Turned(in), radius, out)) return false;
  *out = Turned(*out);
  return true;
}

}  // namespace

BallBallResolution ResolveBallBallOnTable(const BallState& a, const BallState& b,
                                          const BallParams& ball, const BallBallParams& contact,
                                          const ClothParams& cloth,
                                          const ImpulseSolverOptions& options,
                                          const BallBallTable* table) {
  BallBallResolution out;
  out.a = a;
  out.b = b;
  const Vec2 d = b.r - a.r;
  const double n = d.norm();
  if (!(n > 0)) {
    out.status = ImpactStatus::kInvalidInput;
    return out;
  }
  const Eigen::Matrix3d q = FrameAlong(d / n);  // a is C (at -Y), b is O (at +Y)
  ImpactState in;
  in.c = {q * a.v, q * a.w};
  in.o = {q * b.v, q * b.w};
  ImpactState after;  // in the impact frame: from the table where it covers it
  if (LookUp(table, in, ball.radius, &after)) {
    out.work.table_lookups = 1;
  } else {
    const ImpactResult r = ResolveImpact(in, ball, contact, cloth.mu_s, options);
    out.status = r.status;
    out.work = r.work;
    if (r.status != ImpactStatus::kOk) return out;
    after = r.out;
  }
  out.a.v = q.transpose() * after.c.v;
  out.a.w = q.transpose() * after.c.w;
  out.b.v = q.transpose() * after.o.v;
  out.b.w = q.transpose() * after.o.w;
  out.a = Settle(out.a, ball);  // drops the jump (v.z) and reclassifies
  out.b = Settle(out.b, ball);
  return out;
}

CushionResolution ResolveBallCushionOnTable(const BallState& s, const Vec2& normal,
                                            const BallParams& ball, const CushionParams& cushion,
                                            const ImpulseSolverOptions& options,
                                            const CushionTable* table) {
  CushionResolution out;
  out.ball = s;
  const Eigen::Matrix3d q = FrameAlong(-normal);  // Y into the cushion
  const BallMotion in{q * s.v, q * s.w};
  BallMotion after;  // in the cushion frame: from the table where it covers it
  if (table != nullptr &&
      table->Lookup(in, ball.radius, CushionRestitution(cushion, in.v.y()), &after)) {
    out.work.table_lookups = 1;
  } else {
    const CushionImpactResult r = ResolveCushionImpact(in, ball, cushion, options);
    out.status = r.status;
    out.work = r.work;
    if (r.status != ImpactStatus::kOk) return out;
    after = r.out;
  }
  out.ball.v = q.transpose() * after.v;
  out.ball.w = q.transpose() * after.w;
  out.ball = Settle(out.ball, ball);
  return out;
}

namespace {

// Scales what the impact changed of each ball's velocity across the line of
// centres (the friction's part: the throw) by `scale`.
void ScaleThrow(const BallState& a, const BallState& b, const Vec2& n, double scale, BallBallResolution* r) {
  const Vec3 t(-n.y(), n.x(), 0.0);
  r->a.v += (scale - 1) * (r->a.v - a.v).dot(t) * t;
  r->b.v += (scale - 1) * (r->b.v - b.v).dot(t) * t;
}

}  // namespace

PairContactResolution ResolveBallBallContact(const BallState& a, const BallState& b,
                                             ContactStart contact, int level_a, int level_b,
                                             const SimParams& p, const BallBallTable* table) {
  PairContactResolution out;
  out.contact = contact;
  out.a = a;
  out.b = b;
  const Vec2 n = (b.r - a.r).normalized();  // from a to b
  switch (contact) {
    case ContactStart::kApproaching: {
      BallBallResolution r =
          ResolveBallBallOnTable(a, b, p.ball, p.ball_ball, p.cloth, p.ball_ball_solver, table);
      out.work = r.work;
      if (r.status == ImpactStatus::kOk) {
        if (p.throw_scale != 1.0) ScaleThrow(a, b, n, p.throw_scale, &r);
        out.a = AfterImpact(r.a, p);
        out.b = AfterImpact(r.b, p);
        HoldIfReturning(&out.a, &out.b, n, 0, 0, p);
        out.impact = true;
      } else if (r.status == ImpactStatus::kNotApproaching) {
        // The model sees no approach where the detector saw one (rounding at its
        // threshold): take the residue out so the contact is not found again.
        RemoveApproach(&out.a, &out.b, n, p);
        out.contact = ContactStart::kTouching;
      } else {
        out.status = r.status;
      }
      break;
    }
    case ContactStart::kPressing:
      HoldTogether(&out.a, &out.b, n, level_a, level_b, p);
      break;
    case ContactStart::kTouching:
    case ContactStart::kApart: break;  // nothing to resolve
  }
  return out;
}

BoundaryContactResolution ResolveBoundaryContact(const BallState& s, const Vec2& normal,
                                                 ContactStart contact, int level,
                                                 const SimParams& p, const CushionTable* table) {
  BoundaryContactResolution out;
  out.contact = contact;
  out.ball = s;
  switch (contact) {
    case ContactStart::kApproaching: {
      const CushionResolution r =
          ResolveBallCushionOnTable(s, normal, p.ball, p.cushion, p.cushion_solver, table);
      out.work = r.work;
      if (r.status == ImpactStatus::kOk) {
        out.ball = HoldIfReturning(AfterImpact(r.ball, p), normal, p);
      } else if (r.status == ImpactStatus::kNotApproaching) {
        out.ball = Settle(WithoutNormalVelocity(s, normal), p.ball);
        out.contact = ContactStart::kTouching;
      } else {
        out.status = r.status;
      }
      break;
    }
    case ContactStart::kPressing:
      // Pressed a second time at one instant: wedged between contacts; it stops.
      out.ball = level == 0 ? HoldAgainst(s, normal, p) : Stopped(s, p);
      break;
    case ContactStart::kTouching:
    case ContactStart::kApart: break;  // nothing to resolve
  }
  return out;
}

}  // namespace snooker::physics
