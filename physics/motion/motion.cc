#include "physics/motion/motion.h"

#include <cmath>
#include <limits>

#include "physics/motion/slip_phase.h"

namespace snooker::physics {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// sliding -> rolling -> spinning -> stationary: three transitions at most, plus
// the final partial phase.
constexpr int kMaxPhases = 4;

Vec2 Horizontal(const Vec3& v) { return {v.x(), v.y()}; }

// Horizontal spin of a ball rolling at centre velocity v: u = 0 gives
// wx = -vy / R and wy = vx / R.
void SetRollingSpin(BallState* s, double radius) {
  s->w.x() = -s->v.y() / radius;
  s->w.y() = s->v.x() / radius;
}

// The ball at rest with Z spin wz: spinning, or stationary when wz is negligible.
void SetAtRest(BallState* s, double wz) {
  s->v = Vec3::Zero();
  const bool spins = std::abs(wz) > kSpinTolerance;
  s->w = Vec3(0.0, 0.0, spins ? wz : 0.0);
  s->s = spins ? MotionState::kSpinning : MotionState::kStationary;
}

Vec2 UnitOrZero(const Vec2& x) {
  const double n = x.norm();
  return n > 0.0 ? Vec2(x / n) : Vec2::Zero();
}

// Centre deceleration of the state (m/s^2) and its direction.
double Deceleration(const BallState& s, const ClothParams& cloth) {
  if (s.s == MotionState::kSliding) return cloth.mu_s * cloth.g;
  if (s.s == MotionState::kRolling) return cloth.mu_r * cloth.g;
  return 0.0;
}

// The state at the transition (time `t_end` after s), applied exactly.
BallState Transition(const BallState& s, double t_end, const BallParams& ball,
                     const ClothParams& cloth) {
  BallState out = s;
  const double wz = SpinAfter(s.w.z(), cloth.spin_decel, t_end);
  out.r = PositionPolynomial(s, ball, cloth).At(t_end);
  switch (s.s) {
    case MotionState::kSliding: {
      // v_S = v - (2/7) u (section 2.5); then the slip is zero: rolling spin.
      const Vec2 v = Horizontal(s.v) - (2.0 / 7.0) * ClothSlip(s, ball);
      if (v.norm() <= kSpeedTolerance) {
        SetAtRest(&out, wz);
      } else {
        out.v = Vec3(v.x(), v.y(), 0.0);
        SetRollingSpin(&out, ball.radius);
        out.w.z() = wz;
        out.s = MotionState::kRolling;
      }
      break;
    }
    case MotionState::kRolling: SetAtRest(&out, wz); break;
    case MotionState::kSpinning: SetAtRest(&out, 0.0); break;
    case MotionState::kStationary:
    case MotionState::kPocketed: break;
  }
  return out;
}

// The state t (< transition time) after s, within its phase.
BallState WithinPhase(const BallState& s, double t, const BallParams& ball,
                      const ClothParams& cloth) {
  if (s.s == MotionState::kStationary || s.s == MotionState::kPocketed) return s;
  BallState out = s;
  out.r = PositionPolynomial(s, ball, cloth).At(t);
  out.w.z() = SpinAfter(s.w.z(), cloth.spin_decel, t);
  out.v.z() = 0.0;
  const double dv = Deceleration(s, cloth) * t;
  switch (s.s) {
    case MotionState::kSliding: {
      const Vec2 u_hat = UnitOrZero(ClothSlip(s, ball));
      const Vec2 v = Horizontal(s.v) - dv * u_hat;
      // Friction torque changes the spin by (5 mu_s g / (2R)) t (z x u^).
      const double dw = 2.5 * dv / ball.radius;
      out.v.x() = v.x();
      out.v.y() = v.y();
      out.w.x() = s.w.x() - dw * u_hat.y();
      out.w.y() = s.w.y() + dw * u_hat.x();
      break;
    }
    case MotionState::kRolling: {
      const Vec2 v = Horizontal(s.v) - dv * UnitOrZero(Horizontal(s.v));
      out.v.x() = v.x();
      out.v.y() = v.y();
      SetRollingSpin(&out, ball.radius);
      break;
    }
    case MotionState::kSpinning:
    case MotionState::kStationary:
    case MotionState::kPocketed: break;
  }
  return out;
}

}  // namespace

Vec2 ClothSlip(const BallState& s, const BallParams& ball) {
  return {s.v.x() - ball.radius * s.w.y(), s.v.y() + ball.radius * s.w.x()};
}

MotionState ClassifyMotion(const BallState& s, const BallParams& ball) {
  if (s.s == MotionState::kPocketed) return MotionState::kPocketed;
  if (ClothSlip(s, ball).norm() > kSlipTolerance) return MotionState::kSliding;
  if (Horizontal(s.v).norm() > kSpeedTolerance) return MotionState::kRolling;
  if (std::abs(s.w.z()) > kSpinTolerance) return MotionState::kSpinning;
  return MotionState::kStationary;
}

BallState Settle(const BallState& s, const BallParams& ball) {
  BallState out = s;
  out.v.z() = 0.0;
  out.s = ClassifyMotion(s, ball);
  switch (out.s) {
    case MotionState::kRolling: SetRollingSpin(&out, ball.radius); break;
    case MotionState::kSpinning:
    case MotionState::kStationary: SetAtRest(&out, s.w.z()); break;
    case MotionState::kSliding:
    case MotionState::kPocketed: break;
  }
  return out;
}

double TransitionTime(const BallState& s, const BallParams& ball, const ClothParams& cloth) {
  switch (s.s) {
    case MotionState::kSliding: {
      const double decel = cloth.mu_s * cloth.g;
      if (!(decel > 0.0)) return kInf;
      return 2.0 * ClothSlip(s, ball).norm() / (7.0 * decel);  // eq. 19
    }
    case MotionState::kRolling: {
      const double decel = cloth.mu_r * cloth.g;
      return decel > 0.0 ? Horizontal(s.v).norm() / decel : kInf;
    }
    case MotionState::kSpinning:
      return cloth.spin_decel > 0.0 ? std::abs(s.w.z()) / cloth.spin_decel : kInf;
    case MotionState::kStationary:
    case MotionState::kPocketed: return kInf;
  }
  return kInf;
}

PositionPoly PositionPolynomial(const BallState& s, const BallParams& ball,
                                const ClothParams& cloth) {
  PositionPoly p;
  p.c = s.r;
  if (s.s == MotionState::kSliding) {
    p.b = Horizontal(s.v);
    p.a = -0.5 * Deceleration(s, cloth) * UnitOrZero(ClothSlip(s, ball));
  } else if (s.s == MotionState::kRolling) {
    p.b = Horizontal(s.v);
    p.a = -0.5 * Deceleration(s, cloth) * UnitOrZero(p.b);
  }
  return p;
}

BallState Evolve(const BallState& s, double t, const BallParams& ball, const ClothParams& cloth) {
  if (!(t >= 0.0)) return s;
  const double t_end = TransitionTime(s, ball, cloth);
  if (std::isinf(t_end)) return std::isinf(t) ? s : WithinPhase(s, t, ball, cloth);
  if (t >= t_end) return Transition(s, t_end, ball, cloth);
  return WithinPhase(s, t, ball, cloth);
}

BallState EvolveThrough(const BallState& s, double t, const BallParams& ball,
                        const ClothParams& cloth) {
  if (!(t >= 0.0)) return s;
  BallState cur = s;
  double left = t;
  for (int phase = 0; phase < kMaxPhases; ++phase) {
    const double t_end = TransitionTime(cur, ball, cloth);
    if (left < t_end || std::isinf(t_end)) return Evolve(cur, left, ball, cloth);
    cur = Evolve(cur, t_end, ball, cloth);
    left -= t_end;
  }
  return cur;
}

double KineticEnergy(const BallState& s, const BallParams& ball) {
  return 0.5 * ball.mass * s.v.squaredNorm() + 0.5 * ball.Inertia() * s.w.squaredNorm();
}

}  // namespace snooker::physics
