// The impulse ODE of Mathavan et al. (2014), shared by the fixed-step and the
// adaptive integrator. Internal to physics/.
//
// Independent variable: the normal impulse P_I at A (N s). State (13 numbers):
// v_C, w_C, v_O, w_O (collision frame) and the work W of the normal force (eq. 10a).
// Derivatives are per unit P_I: dv/dP_I in (m/s)/(N s) and so on.
//
// Forces per unit dP_I (paper Fig. 3, eqs. 3, 4, 6-8):
//   on C at A: (f1, -1, f2), on O at A: (-f1, 1, -f2), where (f1, f2) = -mu_bb u_A/|u_A|
//     is the friction on C opposing the slip u_A = (xdot_A, zdot_A) of C on O (eq. 6).
//   Both balls get the same torque from A: R (f2, 0, -f1) (eq. 3d-3f and O's twin).
//   The cloth reacts only on a ball that f2 pushes down and that is on the cloth:
//   N_C = max(0, -f2) (eq. 7a), N_O = max(0, f2) (eq. 7b); the other ball is airborne.
//   Cloth friction on a supported ball (eq. 8): sliding -mu_s N u/|u| with u the slip
//   at D (or B) (eq. 9), or, when stuck, the friction that keeps that slip at zero.
#pragma once

#include <cmath>
#include <cstdint>

#include "physics/params.h"
#include "physics/types.h"

namespace snooker::physics::impulse {

using State = Eigen::Matrix<double, 13, 1>;

// Offsets into State.
inline constexpr int kVC = 0;
inline constexpr int kWC = 3;
inline constexpr int kVO = 6;
inline constexpr int kWO = 9;
inline constexpr int kWork = 12;

enum class Law : std::uint8_t { kSlide, kStick };

/// The discrete part of the hybrid system, held constant during a step.
struct Mode {
  Law a = Law::kSlide;  ///< ball-ball contact A
  Law d = Law::kSlide;  ///< C on the cloth
  Law b = Law::kSlide;  ///< O on the cloth
  bool c_on_cloth = true;
  bool o_on_cloth = true;
  /// Slide direction used while a sliding contact's slip is exactly zero (the
  /// direction the dynamics drive it). Zero vector: no friction at zero slip (the
  /// paper's "rolling" rule).
  Vec2 a_dir0 = Vec2::Zero();
  Vec2 d_dir0 = Vec2::Zero();
  Vec2 b_dir0 = Vec2::Zero();
};

/// Constants of the model, precomputed once per impact.
struct Model {
  double inv_mass = 0;     // 1/M
  double radius = 0;       // R
  double r_over_i = 0;     // R/I
  double mu_s = 0;         // ball-cloth friction
  BallBallParams contact;  // mu_bb, e, law

  Model(const BallParams& ball, const BallBallParams& c, double mu_s_in)
      : inv_mass(1.0 / ball.mass),
        radius(ball.radius),
        r_over_i(ball.radius / ball.Inertia()),
        mu_s(mu_s_in),
        contact(c) {}
};

inline State Pack(const ImpactState& s) {
  State x;
  x.segment<3>(kVC) = s.c.v;
  x.segment<3>(kWC) = s.c.w;
  x.segment<3>(kVO) = s.o.v;
  x.segment<3>(kWO) = s.o.w;
  x[kWork] = 0;
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
/// Normal relative velocity at A, ydot_A (eq. 5c). Positive while approaching.
inline double NormalSpeed(const State& x) { return x[kVC + 1] - x[kVO + 1]; }

/// Unit vector along u, or `fallback` when u is exactly zero.
inline Vec2 Direction(const Vec2& u, const Vec2& fallback) {
  const double n = u.norm();
  return n > 0 ? Vec2(u / n) : fallback;
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
  if (m.a == Law::kStick) return Vec2::Zero();
  const Vec2 u = SlipA(x, p.radius);
  const double s = u.norm();
  return -BallBallFriction(p.contact, s) * Direction(u, m.a_dir0);
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
  // (1/M + R^2/I) M = 1 + R r_over_i M = 7/2 for a solid sphere, kept general.
  const double k = 1.0 + R * p.r_over_i / p.inv_mass;
  const double kz = R * p.r_over_i / p.inv_mass;  // R^2 M / I = 5/2
  f.n_c = m.c_on_cloth ? std::max(0.0, -f2) : 0.0;
  f.n_o = m.o_on_cloth ? std::max(0.0, f2) : 0.0;
  f.stick_d = Vec2(-f1, 1.0 - kz * f2) / k;
  f.stick_b = Vec2(f1, -1.0 - kz * f2) / k;
  if (f.n_c > 0) {
    f.f_d = m.d == Law::kStick
                ? f.stick_d
                : Vec2(-p.mu_s * f.n_c * Direction(SlipD(x, R), m.d_dir0));
  }
  if (f.n_o > 0) {
    f.f_b = m.b == Law::kStick
                ? f.stick_b
                : Vec2(-p.mu_s * f.n_o * Direction(SlipB(x, R), m.b_dir0));
  }
  return f;
}

/// d(state)/dP_I (eqs. 3, 4, 10a).
inline void Derivative(const State& x, const Mode& m, const Model& p, State* dx,
                       Forces* forces_out = nullptr) {
  const Forces f = ComputeForces(x, m, p);
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
  if (forces_out != nullptr) *forces_out = f;
}

}  // namespace snooker::physics::impulse
