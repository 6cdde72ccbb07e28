#include "physics/motion/slip_phase.h"

#include <algorithm>
#include <cmath>

namespace snooker::physics {

Vec2 ClothSlip(const BallMotion& m, double radius) {
  return {m.v.x() - radius * m.w.y(), m.v.y() + radius * m.w.x()};
}

double SpinAfter(double wz, double spin_decel, double t) {
  const double drop = spin_decel * t;
  if (wz > 0) return std::max(0.0, wz - drop);  // eq. 21a, 21c
  if (wz < 0) return std::min(0.0, wz + drop);  // eq. 21b, 21c
  return 0.0;
}

SlipEnd SlipPhaseEnd(const BallMotion& m, const BallParams& ball, const ClothParams& cloth) {
  SlipEnd end;
  const Vec2 v(m.v.x(), m.v.y());
  const Vec2 u = ClothSlip(m, ball.radius);
  const double slip = u.norm();
  const double decel = cloth.mu_s * cloth.g;  // centre deceleration while sliding
  end.time = decel > 0 ? 2.0 * slip / (7.0 * decel) : 0.0;
  end.velocity = slip > 0 && decel > 0 ? Vec2(v - (2.0 / 7.0) * u) : v;
  end.speed = end.velocity.norm();
  const Vec2 accel = slip > 0 ? Vec2(-decel * u / slip) : Vec2::Zero();
  end.displacement = v * end.time + 0.5 * accel * end.time * end.time;
  end.sidespin = SpinAfter(m.w.z(), cloth.spin_decel, end.time);
  return end;
}

double AngleBetween(const Vec2& a, const Vec2& b) {
  const double na = a.norm(), nb = b.norm();
  if (na == 0 || nb == 0) return 0.0;
  // atan2 of cross and dot is accurate at all angles, unlike acos of the dot.
  return std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b));
}

}  // namespace snooker::physics
