#include "physics/sim/resolve.h"


#include "physics/motion/motion.h"

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

}  // namespace snooker::physics
