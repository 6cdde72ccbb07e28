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
                                          const ImpulseSolverOptions& options) {
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
                                            const ImpulseSolverOptions& options) {
  CushionResolution out;
  out.ball = s;
  const Eigen::Matrix3d q = FrameAlong(-normal);  // Y into the cushion
  const CushionImpactResult r =
      ResolveCushionImpact({q * s.v, q * s.w}, ball, cushion, options);
  out.status = r.status;
  out.work = r.work;
  if (r.status != ImpactStatus::kOk) return out;
  out.ball.v = q.transpose() * r.out.v;
  out.ball.w = q.transpose() * r.out.w;
  out.ball = Settle(out.ball, ball);
  return out;
}

}  // namespace snooker::physics
