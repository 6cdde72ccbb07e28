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
  if (table != nullptr) {
    // The table's C is the moving ball, at -Y: a as given, or b in the frame turned
    // by pi about Z (X and Y change sign, so a's and b's states do).
    ImpactState looked_up;
    const Eigen::Matrix3d flip = Eigen::Vector3d(-1, -1, 1).asDiagonal();
    const bool direct = table->Lookup(in, ball.radius, &looked_up);
    const ImpactState turned{{flip * in.o.v, flip * in.o.w}, {flip * in.c.v, flip * in.c.w}};
    const bool swapped = !direct && table->Lookup(turned, ball.radius, &looked_up);
    if (direct || swapped) {
      if (swapped) {
        looked_up = {{flip * looked_up.o.v, flip * looked_up.o.w},
                     {flip * looked_up.c.v, flip * looked_up.c.w}};
      }
      out.work.table_lookups = 1;
      out.a.v = q.transpose() * looked_up.c.v;
      out.a.w = q.transpose() * looked_up.c.w;
      out.b.v = q.transpose() * looked_up.o.v;
      out.b.w = q.transpose() * looked_up.o.w;
      out.a = Settle(out.a, ball);
      out.b = Settle(out.b, ball);
      return out;
    }
  }
  const ImpactResult r = ResolveImpact(in, ball, contact, cloth.mu_s, options);
  out.status = r.status;
  out.work = r.work;
  if (r.status != ImpactStatus::kOk) return out;
  out.a.v = q.transpose() * r.out.c.v;
  out.a.w = q.transpose() * r.out.c.w;
  out.b.v = q.transpose() * r.out.o.v;
  out.b.w = q.transpose() * r.out.o.w;
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
  BallMotion looked_up;
  if (table != nullptr &&
      table->Lookup(in, ball.radius, CushionRestitution(cushion, in.v.y()), &looked_up)) {
    out.work.table_lookups = 1;
    out.ball.v = q.transpose() * looked_up.v;
    out.ball.w = q.transpose() * looked_up.w;
    out.ball = Settle(out.ball, ball);
    return out;
  }
  const CushionImpactResult r = ResolveCushionImpact(in, ball, cushion, options);
  out.status = r.status;
  out.work = r.work;
  if (r.status != ImpactStatus::kOk) return out;
  out.ball.v = q.transpose() * r.out.v;
  out.ball.w = q.transpose() * r.out.w;
  out.ball = Settle(out.ball, ball);
  return out;
}

}  // namespace snooker::physics
