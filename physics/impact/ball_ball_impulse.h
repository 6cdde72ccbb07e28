// The impulse ODE of Mathavan et al. (2014), shared by the fixed-step and the hybrid
// integrator (physics/ode/). Internal to physics/.
//
// Independent variable: the normal impulse P_I at A (N s). State (14 numbers):
// v_C, w_C, v_O, w_O (collision frame), the work W of the normal force (eq. 10a) and
// P_I itself (so that the integrator may step in another clock). Derivatives are per
// unit P_I: dv/dP_I in (m/s)/(N s) and so on.
//
// Forces per unit dP_I (paper Fig. 3, eqs. 3, 4, 6-8):
//   on C at A: (f1, -1, f2), on O at A: (-f1, 1, -f2), where (f1, f2) = -mu_bb u_A/|u_A|
//     is the friction on C opposing the slip u_A = (xdot_A, zdot_A) of C on O (eq. 6).
//   Both balls get the same torque from A: R (f2, 0, -f1) (eq. 3d-3f and O's twin).
//   The cloth reacts only on a ball that f2 pushes down and that is on the cloth:
//   N_C = max(0, -f2) (eq. 7a), N_O = max(0, f2) (eq. 7b); the other ball is airborne.
//   Cloth friction on a supported ball (eq. 8): sliding -mu_s N u/|u| with u the slip
//   at D (or B) (eq. 9), or, when stuck, the friction that keeps that slip at zero.
// A sliding contact may have its direction held ("frozen", Mode::hold): the hybrid
// integrator holds the direction of a slip that heads for zero along a ray, so that
// the right-hand side stays smooth up to and through the zero it then locates.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "physics/impact/ball_ball.h"
#include "physics/core/params.h"
#include "physics/core/types.h"

namespace snooker::physics::impulse {

using State = Eigen::Matrix<double, 14, 1>;

// Offsets into State.
inline constexpr int kVC = 0;
inline constexpr int kWC = 3;
inline constexpr int kVO = 6;
inline constexpr int kWO = 9;
inline constexpr int kWork = 12;
inline constexpr int kP = 13;

/// The contacts: A (ball-ball), D (C on the cloth), B (O on the cloth).
enum Contact : int { kA = 0, kD = 1, kB = 2, kContacts = 3 };

/// Friction law of one contact.
enum class Law : std::uint8_t {
  /// Sliding: friction opposes the slip, -mu N u/|u|; none at exactly zero slip
  /// (the paper's "rolling" rule).
  kSlide,
  /// Sliding that has just started from zero slip at a cloth contact (D or B).
  /// While |u| is small the slip direction is a fast variable: it relaxes towards
  /// the drive a (the slip rate from all other forces) at the rate |a|/|u|, and the
  /// friction makes the slip equation stiff (rate mu N (7/2M) / |u|). This law uses
  /// the quasi-steady direction instead: the drive's direction, lagging it by
  /// delta = |u| (d angle(a)/dP_I) / |a| (first order in |u|).
  kSlideSlaved,
  /// Stuck: the friction that keeps the slip constant (inside the cone).
  kStick,
};

/// The discrete part of the hybrid system, held constant during a step.
struct Mode {
  std::array<Law, kContacts> law{Law::kSlide, Law::kSlide, Law::kSlide};  // A, D, B
  /// A sliding contact with frozen[c] slides along hold[c] whatever its slip.
  std::array<bool, kContacts> frozen{false, false, false};
  std::array<Vec2, kContacts> hold{Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
  /// Direction a sliding cloth contact leaves zero slip along (its drive), used while
  /// its slip is at most slip_zero. Zero: no friction at exactly zero slip (the
  /// paper's rule, used by the fixed-step scheme).
  std::array<Vec2, kContacts> dir0{Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
  double slip_zero = 0;  ///< m/s
  bool c_on_cloth = true;
  bool o_on_cloth = true;
};

/// Constants of the model, precomputed once per impact.
struct Model {
  double inv_mass = 0;     // 1/M
  double radius = 0;       // R
  double r_over_i = 0;     // R/I
  double mu_s = 0;         // ball-cloth friction
  double kz = 0;           // R^2 M / I (5/2 for a solid sphere)
  double inv_k = 0;        // 1 / (1 + R^2 M / I) (2/7)
  BallBallParams contact;  // mu_bb, e, law

  Model(const BallParams& ball, const BallBallParams& c, double mu_s_in)
      : inv_mass(1.0 / ball.mass),
        radius(ball.radius),
        r_over_i(ball.radius / ball.Inertia()),
        mu_s(mu_s_in),
        kz(ball.radius * ball.radius * ball.mass / ball.Inertia()),
        inv_k(1.0 / (1.0 + ball.radius * ball.radius * ball.mass / ball.Inertia())),
        contact(c) {}
};

inline State Pack(const ImpactState& s) {
  State x;
  x.segment<3>(kVC) = s.c.v;
  x.segment<3>(kWC) = s.c.w;
  x.segment<3>(kVO) = s.o.v;
  x.segment<3>(kWO) = s.o.w;
  x[kWork] = 0;
  x[kP] = 0;
  return x;
}

inline ImpactState Unpack(const State& x) {
  ImpactState s;
  s.c.v = x.segment<3>(kVC);
  s.c.w = x.segment<3>(kWC);
  s.o.v = x.segment<3>(kVO);
  s.o.w = x.segment<3>(kWO);
  return s;
}

/// Slip of C on O at A, (xdot_A, zdot_A) (eqs. 5a, 5b, 11b).
inline Vec2 SlipA(const State& x, double R) {
  return {x[kVC + 0] - R * x[kWC + 2] - x[kVO + 0] - R * x[kWO + 2],
          x[kVC + 2] + R * x[kWC + 0] - x[kVO + 2] + R * x[kWO + 0]};
}
/// Slip of C on the cloth at D, (xdot_D, ydot_D) (eqs. 9a, 9b, 11e).
inline Vec2 SlipD(const State& x, double R) {
  return {x[kVC + 0] - R * x[kWC + 1], x[kVC + 1] + R * x[kWC + 0]};
}
/// Slip of O on the cloth at B (eqs. 9c, 9d, 11f).
inline Vec2 SlipB(const State& x, double R) {
  return {x[kVO + 0] - R * x[kWO + 1], x[kVO + 1] + R * x[kWO + 0]};
}
/// Slip at contact c. Linear in the state, so it also maps a derivative to a rate.
inline Vec2 Slip(int c, const State& x, double R) {
  return c == kA ? SlipA(x, R) : c == kD ? SlipD(x, R) : SlipB(x, R);
}
/// Normal relative velocity at A, ydot_A (eq. 5c). Positive while approaching.
inline double NormalSpeed(const State& x) { return x[kVC + 1] - x[kVO + 1]; }

/// Unit vector along u, or zero when u is exactly zero.
inline Vec2 Direction(const Vec2& u) {
  const double n2 = u.squaredNorm();
  return n2 > 0 ? Vec2(u / std::sqrt(n2)) : Vec2::Zero();
}

/// Forces of one evaluation, per unit dP_I, exposed for event guards.
struct Forces {
  Vec2 f_a = Vec2::Zero();  ///< friction on C at A, (x, z); on O it is the negative
  double n_c = 0;           ///< cloth normal on C
  double n_o = 0;           ///< cloth normal on O
  Vec2 f_d = Vec2::Zero();  ///< cloth friction on C at D, (x, y)
  Vec2 f_b = Vec2::Zero();  ///< cloth friction on O at B, (x, y)
  Vec2 stick_d = Vec2::Zero();  ///< friction that would keep the slip at D constant
  Vec2 stick_b = Vec2::Zero();  ///< friction that would keep the slip at B constant
};

/// The friction at A, given the mode.
inline Vec2 FrictionA(const State& x, const Mode& m, const Model& p) {
  if (m.law[kA] == Law::kStick) return Vec2::Zero();
  const Vec2 u = SlipA(x, p.radius);
  const bool constant = p.contact.friction_law == BallBallFrictionLaw::kConstant;
  if (m.frozen[kA]) {
    return -(constant ? p.contact.mu_bb : BallBallFriction(p.contact, u.norm())) * m.hold[kA];
  }
  const double s2 = u.squaredNorm();
  if (!(s2 > 0)) return Vec2::Zero();
  const double s = std::sqrt(s2);
  return -((constant ? p.contact.mu_bb : BallBallFriction(p.contact, s)) / s) * u;
}

/// Direction of a sliding (kSlide) contact's slip in mode m: held if frozen, the
/// leave direction dir0 while the slip is within slip_zero, else u/|u|.
inline Vec2 SlideDirection(int c, const Vec2& u, const Mode& m) {
  if (m.frozen[c]) return m.hold[c];
  const double n2 = u.squaredNorm();
  if (n2 <= m.slip_zero * m.slip_zero && (m.dir0[c].x() != 0 || m.dir0[c].y() != 0)) {
    return m.dir0[c];
  }
  return n2 > 0 ? Vec2(u / std::sqrt(n2)) : Vec2::Zero();
}

/// Cloth friction at contact c (D or B) with normal force n, slip u and stick
/// friction `stick` (the friction that would hold the slip constant). `lag` is the
/// slaved direction's lag behind the drive, rad.
inline Vec2 ClothFriction(int c, const Mode& m, double n, const Vec2& u, const Vec2& stick,
                          double mu_s, double lag = 0) {
  if (!(n > 0)) return Vec2::Zero();
  switch (m.law[c]) {
    case Law::kStick: return stick;
    case Law::kSlideSlaved: {
      // The slip points along the drive -stick, rotated back by `lag`; friction
      // opposes it.
      const Vec2 d = Direction(stick);
      if (lag == 0) return mu_s * n * d;
      const double cl = std::cos(lag), sl = std::sin(lag);
      return mu_s * n * Vec2(cl * d.x() + sl * d.y(), -sl * d.x() + cl * d.y());
    }
    case Law::kSlide: break;
  }
  return -mu_s * n * SlideDirection(c, u, m);
}

/// Cloth forces on C (at D) and O (at B) given the friction at A.
/// The stick friction follows from requiring d(u_D)/dP_I = 0: the cloth friction
/// F changes u_D by (1/M + R^2/I) F = (7/2) F / M, the rest of the forces by
/// (f1, -1 + (R^2/I) M f2) / M, so F = -(2/7) (f1, -1 + 2.5 f2) for a solid sphere.
inline Forces ComputeForces(const State& x, const Mode& m, const Model& p) {
  Forces f;
  f.f_a = FrictionA(x, m, p);
  const double f1 = f.f_a.x();
  const double f2 = f.f_a.y();
  const double R = p.radius;
  f.n_c = m.c_on_cloth ? std::max(0.0, -f2) : 0.0;
  f.n_o = m.o_on_cloth ? std::max(0.0, f2) : 0.0;
  f.stick_d = Vec2(-f1, 1.0 - p.kz * f2) * p.inv_k;
  f.stick_b = Vec2(f1, -1.0 - p.kz * f2) * p.inv_k;
  if (f.n_c > 0) f.f_d = ClothFriction(kD, m, f.n_c, SlipD(x, R), f.stick_d, p.mu_s);
  if (f.n_o > 0) f.f_b = ClothFriction(kB, m, f.n_o, SlipB(x, R), f.stick_b, p.mu_s);
  return f;
}

/// d(state)/dP_I for given forces (eqs. 3, 4, 10a).
inline void DerivativeFromForces(const State& x, const Forces& f, const Model& p, State* dx) {
  const double f1 = f.f_a.x();
  const double f2 = f.f_a.y();
  const double im = p.inv_mass;
  const double ri = p.r_over_i;
  State& d = *dx;
  d[kVC + 0] = (f1 + f.f_d.x()) * im;
  d[kVC + 1] = (-1.0 + f.f_d.y()) * im;
  d[kVC + 2] = (f2 + f.n_c) * im;
  d[kWC + 0] = (f2 + f.f_d.y()) * ri;
  d[kWC + 1] = -f.f_d.x() * ri;
  d[kWC + 2] = -f1 * ri;
  d[kVO + 0] = (-f1 + f.f_b.x()) * im;
  d[kVO + 1] = (1.0 + f.f_b.y()) * im;
  d[kVO + 2] = (-f2 + f.n_o) * im;
  d[kWO + 0] = (f2 + f.f_b.y()) * ri;
  d[kWO + 1] = -f.f_b.x() * ri;
  d[kWO + 2] = -f1 * ri;
  d[kWork] = NormalSpeed(x);
  d[kP] = 1.0;
}

/// Rate of change of the friction at A along the trajectory, per unit P_I, from the
/// state's derivative dx.
inline Vec2 FrictionARate(const State& x, const State& dx, const Mode& m, const Model& p) {
  if (m.law[kA] == Law::kStick || m.frozen[kA]) return Vec2::Zero();
  const Vec2 u = SlipA(x, p.radius);
  const double s = u.norm();
  if (!(s > 0)) return Vec2::Zero();
  const Vec2 uh = u / s;
  const Vec2 du = SlipA(dx, p.radius);
  const double ds = uh.dot(du);
  Vec2 rate = -BallBallFriction(p.contact, s) * (du - ds * uh) / s;  // turning of u/|u|
  if (p.contact.friction_law != BallBallFrictionLaw::kConstant) {  // d mu/ds along the way
    rate -= BallBallFrictionSlope(p.contact, s) * ds * uh;
  }
  return rate;
}

/// Lag of a slaved slide's direction behind its drive: |u| (d angle/dP_I) / |drive|,
/// with the drive -stick (M / k) and d(stick)/dP_I = dstick. Capped at 0.1 rad,
/// beyond which the quasi-steady picture no longer holds (the solver hands over).
inline double SlavedLag(const Vec2& u, const Vec2& stick, const Vec2& dstick, const Model& p) {
  const double n2 = stick.squaredNorm();
  if (!(n2 > 0)) return 0;
  const double turn = (stick.x() * dstick.y() - stick.y() * dstick.x()) / n2;  // rad/(N s)
  const double drive = p.inv_mass * std::sqrt(n2) / p.inv_k;  // |drive| = k |stick| / M
  return std::clamp(u.norm() * turn / drive, -0.1, 0.1);
}

/// d(stick friction at D or B)/dP_I from the rate of the friction at A.
inline Vec2 StickRate(int c, const Vec2& dfa, const Model& p) {
  return c == kD ? Vec2(-dfa.x() * p.inv_k, -p.kz * dfa.y() * p.inv_k)
                 : Vec2(dfa.x() * p.inv_k, -p.kz * dfa.y() * p.inv_k);
}

/// Is a slaved slide with normal force n and stick friction `stick` in the stiff,
/// quasi-steady regime, where friction nearly balances the drive (friction's effect
/// on the slip above half the drive's)? Only there is its lag meaningful.
inline bool SlavedStiff(double n, const Vec2& stick, double mu_s) {
  return mu_s * n > 0.5 * stick.norm();
}

/// d(state)/dP_I (eqs. 3, 4, 10a). A slaved cloth slide in its stiff regime takes a
/// second pass for its lag, which needs the rate of change of the friction at A.
inline void Derivative(const State& x, const Mode& m, const Model& p, State* dx,
                       Forces* forces_out = nullptr) {
  Forces f = ComputeForces(x, m, p);
  DerivativeFromForces(x, f, p, dx);
  const bool slaved_d =
      m.law[kD] == Law::kSlideSlaved && f.n_c > 0 && SlavedStiff(f.n_c, f.stick_d, p.mu_s);
  const bool slaved_b =
      m.law[kB] == Law::kSlideSlaved && f.n_o > 0 && SlavedStiff(f.n_o, f.stick_b, p.mu_s);
  if (slaved_d || slaved_b) {
    const Vec2 dfa = FrictionARate(x, *dx, m, p);
    const double R = p.radius;
    if (slaved_d) {
      const Vec2 u = SlipD(x, R);
      f.f_d = ClothFriction(kD, m, f.n_c, u, f.stick_d, p.mu_s,
                            SlavedLag(u, f.stick_d, StickRate(kD, dfa, p), p));
    }
    if (slaved_b) {
      const Vec2 u = SlipB(x, R);
      f.f_b = ClothFriction(kB, m, f.n_o, u, f.stick_b, p.mu_s,
                            SlavedLag(u, f.stick_b, StickRate(kB, dfa, p), p));
    }
    DerivativeFromForces(x, f, p, dx);
  }
  if (forces_out != nullptr) *forces_out = f;
}

}  // namespace snooker::physics::impulse
