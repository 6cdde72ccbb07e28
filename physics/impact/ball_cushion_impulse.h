// The impulse ODE of the Mathavan et al. (2010) cushion model, shared by the fixed-step
// and the hybrid integrator (physics/ode/). Internal to physics/.
//
// Independent variable: the normal impulse P_I at I (N s). State (7 numbers, cushion
// frame): xdot, ydot, w (3), the work W of the normal force and P_I itself (so that
// the integrator may step in another clock); zdot_G = 0 throughout. Derivatives are
// per unit P_I.
//
// Forces on the ball per unit dP_I (docs/physics-notes.md section 8; s = sin th, c = cos th):
//   normal at I:    -(0, c, s)
//   friction at I:  fx X + fy Y' = (fx, -s fy, c fy), (fx, fy) in the tangent plane
//   cloth at C:     (gx, gy, n_c), n_c = s - c fy from zdot_G = 0 (their eq. 8 with
//                   fy = -mu_w sin Phi while I slides; the stick value of fy otherwise)
// Torques about G, R (fy + gy, s fx - gx, -c fx) (their eqs. 4), so with k = M R^2 / I
// (5/2 for a solid sphere) the slips move as (times 1/M)
//   d u_I = ((1+k) fx + (1-ks) gx,  s c + (s^2+k) fy + (k-s) gy)
//   d u_C = ((1-ks) fx + (1+k) gx,   -c + (k-s) fy + (1+k) gy)
// a symmetric Delassus matrix in which X and Y decouple. Stick friction is what makes
// a stuck slip's rate zero (derived in ComputeForces). Both contacts cannot stick at
// once: that needs ydot = 0 (the Y slips at I and C share wx, so both zero means
// (1 + s) ydot = 0) and friction c/(1+s) at each contact, which the parameter check
// (ValidateCushionParams) excludes.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "physics/impact/ball_cushion.h"
#include "physics/core/params.h"
#include "physics/core/types.h"

namespace snooker::physics::cushion {

using State = Eigen::Matrix<double, 7, 1>;

// Offsets into State.
inline constexpr int kVx = 0;
inline constexpr int kVy = 1;
inline constexpr int kWx = 2;
inline constexpr int kWy = 3;
inline constexpr int kWz = 4;
inline constexpr int kWork = 5;
inline constexpr int kP = 6;

enum Contact : int { kI = 0, kC = 1, kContacts = 2 };

enum class Law : std::uint8_t { kSlide, kStick };

/// The discrete part of the hybrid system, held constant during a step.
struct Mode {
  std::array<Law, kContacts> law{Law::kSlide, Law::kSlide};
  /// Slide direction used while a sliding contact's slip is at most `slip_zero` (the
  /// direction in which the dynamics drive it away from zero). A zero vector means no
  /// friction at exactly zero slip (the paper's rule, used by the fixed-step scheme).
  std::array<Vec2, kContacts> dir0{Vec2::Zero(), Vec2::Zero()};
  /// A frozen sliding contact slides along hold whatever its slip: the hybrid
  /// integrator holds the direction of a slip that heads for zero along a fixed ray,
  /// so that the step stays smooth up to and through the zero it then locates.
  std::array<bool, kContacts> frozen{false, false};
  std::array<Vec2, kContacts> hold{Vec2::Zero(), Vec2::Zero()};
  double slip_zero = 0;  ///< m/s
};

/// Constants of the model, precomputed once per impact.
struct Model {
  double inv_mass = 0;  // 1/M
  double radius = 0;    // R
  double r_over_i = 0;  // R/I
  double k = 0;         // M R^2 / I
  double s = 0;         // sin th
  double c = 0;         // cos th
  double e = 0;         // e_e
  std::array<double, kContacts> mu{0, 0};  // mu_w, mu_s

  Model(const BallParams& ball, const CushionParams& p)
      : inv_mass(1.0 / ball.mass),
        radius(ball.radius),
        r_over_i(ball.radius / ball.Inertia()),
        k(ball.mass * ball.radius * ball.radius / ball.Inertia()),
        s(CushionSinTheta(ball, p)),
        c(std::sqrt(std::max(0.0, 1.0 - s * s))),
        e(p.e_e),
        mu{p.mu_w, p.mu_s} {}
};

inline State Pack(const BallMotion& m) {
  State x;
  x << m.v.x(), m.v.y(), m.w.x(), m.w.y(), m.w.z(), 0.0, 0.0;
  return x;
}

inline BallMotion Unpack(const State& x) {
  BallMotion m;
  m.v = Vec3(x[kVx], x[kVy], 0.0);
  m.w = Vec3(x[kWx], x[kWy], x[kWz]);
  return m;
}

/// Slip at I, (along X, along Y'): xdot + wy R s - wz R c, -ydot s + zdot c + wx R.
/// Linear in the state, so it also maps a derivative to the slip's rate.
inline Vec2 SlipI(const State& x, const Model& p) {
  const double R = p.radius;
  return {x[kVx] + R * (p.s * x[kWy] - p.c * x[kWz]), -p.s * x[kVy] + R * x[kWx]};
}
/// Slip at C on the cloth: (xdot - wy R, ydot + wx R).
inline Vec2 SlipC(const State& x, const Model& p) {
  return {x[kVx] - p.radius * x[kWy], x[kVy] + p.radius * x[kWx]};
}
inline Vec2 Slip(int contact, const State& x, const Model& p) {
  return contact == kI ? SlipI(x, p) : SlipC(x, p);
}

/// Normal speed at I, ydot cos th + zdot sin th with zdot = 0. Positive approaching.
inline double NormalSpeed(const State& x, const Model& p) { return p.c * x[kVy]; }

/// |u|, without hypot's cost where the squares neither overflow nor underflow.
inline double Norm(const Vec2& u) {
  const double n2 = u.x() * u.x() + u.y() * u.y();
  return n2 < 1e300 && n2 > 1e-300 ? std::sqrt(n2) : std::hypot(u.x(), u.y());
}

/// Unit vector along u; `fallback` when |u| is zero, or at most `zero` while a
/// fallback is set.
inline Vec2 Direction(const Vec2& u, const Vec2& fallback, double zero) {
  const double n = Norm(u);
  const bool have_fallback = fallback.x() != 0 || fallback.y() != 0;
  return n > 0 && (n > zero || !have_fallback) ? Vec2(u / n) : fallback;
}

/// Direction of sliding friction's opposite at contact c in mode m.
inline Vec2 SlideDirection(int c, const Vec2& u, const Mode& m) {
  return m.frozen[c] ? m.hold[c] : Direction(u, m.dir0[c], m.slip_zero);
}

/// Forces of one evaluation, per unit dP_I.
struct Forces {
  /// Friction at I as (X, Y') components and at C as (X, Y) components.
  std::array<Vec2, kContacts> f{Vec2::Zero(), Vec2::Zero()};
  /// Cloth normal reaction. Positive under ValidateCushionParams.
  double n_c = 0;
  /// Normal force at a contact (1 at I: the independent variable).
  double Normal(int contact) const { return contact == kI ? 1.0 : n_c; }
};

/// Margin of a contact's friction inside its cone, mu N - |f|.
inline double ConeMargin(int contact, const Forces& f, const Model& p) {
  return p.mu[contact] * f.Normal(contact) - Norm(f.f[contact]);
}

/// Friction and cloth reaction in mode `m`.
/// Stick friction: I stuck and C sliding along d (gx, gy = -mu_s n_c d, n_c = s - c fy):
///   d u_I = 0  =>  fy = ((k-s) mu_s dy s - s c) / (s^2 + k + (k-s) mu_s dy c),
///                  fx = -(1-ks) gx / (1+k);
/// the denominator is positive for mu_s <= 1 since (k-s) c < k. I sliding, C stuck:
///   d u_C = 0  =>  gx = -(1-ks) fx / (1+k),  gy = (c - (k-s) fy) / (1+k).
inline Forces ComputeForces(const State& x, const Mode& m, const Model& p) {
  Forces F;
  const double s = p.s, c = p.c, k = p.k;
  if (m.law[kI] == Law::kSlide) {
    F.f[kI] = -p.mu[kI] * SlideDirection(kI, SlipI(x, p), m);
    F.n_c = s - c * F.f[kI].y();  // eq. 8
    if (m.law[kC] == Law::kSlide) {
      F.f[kC] = -p.mu[kC] * F.n_c * SlideDirection(kC, SlipC(x, p), m);
    } else {
      F.f[kC] = Vec2(-(1 - k * s) * F.f[kI].x(), c - (k - s) * F.f[kI].y()) / (1 + k);
    }
  } else {  // I stuck, C sliding (both stuck is excluded, see the top of this file)
    const Vec2 d = SlideDirection(kC, SlipC(x, p), m);
    const double md = p.mu[kC] * d.y();
    const double fy = ((k - s) * md * s - s * c) / (s * s + k + (k - s) * md * c);
    F.n_c = s - c * fy;
    F.f[kC] = -p.mu[kC] * F.n_c * d;
    F.f[kI] = Vec2(-(1 - k * s) * F.f[kC].x() / (1 + k), fy);
  }
  return F;
}

/// d(state)/dP_I (their eqs. 3-4 restated in docs/physics-notes.md section 8).
inline void Derivative(const State& x, const Mode& m, const Model& p, State* dx,
                       Forces* forces_out = nullptr) {
  const Forces F = ComputeForces(x, m, p);
  const Vec2& f = F.f[kI];
  const Vec2& g = F.f[kC];
  State& d = *dx;
  d[kVx] = (f.x() + g.x()) * p.inv_mass;
  d[kVy] = (-p.c - p.s * f.y() + g.y()) * p.inv_mass;
  d[kWx] = (f.y() + g.y()) * p.r_over_i;
  d[kWy] = (p.s * f.x() - g.x()) * p.r_over_i;
  d[kWz] = -p.c * f.x() * p.r_over_i;
  d[kWork] = NormalSpeed(x, p);
  d[kP] = 1.0;
  if (forces_out != nullptr) *forces_out = F;
}

/// Integrators behind ResolveCushionImpact (ball_cushion_hybrid.cc). Both take
/// validated input with a positive normal speed.
CushionImpactResult SolveFixedStep(const BallMotion& in, const Model& model,
                                   const ImpulseSolverOptions& options);
CushionImpactResult SolveAdaptive(const BallMotion& in, const Model& model,
                                  const ImpulseSolverOptions& options);

}  // namespace snooker::physics::cushion
