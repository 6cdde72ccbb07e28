// The Dormand-Prince 5(4) embedded Runge-Kutta pair and the pieces an event-locating
// integrator needs around it: the cubic Hermite interpolant of a step, an Illinois
// root finder and Hairer's PI step-size controller. Internal to physics/.
//
// Header-only templates over a fixed-size Eigen vector: no allocation, no exception,
// no virtual call, every loop capped. Used by the hybrid impulse integrator
// (hybrid_integrator.h).
//
// Reference: Hairer, Norsett & Wanner, Solving ODEs I: II.5 (tableau, FSAL, local
// extrapolation), II.6 (dense output), IV.2 (the PI controller for DOPRI5).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace snooker::physics::ode {

namespace dp54 {
inline constexpr double kA21 = 1.0 / 5;
inline constexpr double kA31 = 3.0 / 40, kA32 = 9.0 / 40;
inline constexpr double kA41 = 44.0 / 45, kA42 = -56.0 / 15, kA43 = 32.0 / 9;
inline constexpr double kA51 = 19372.0 / 6561, kA52 = -25360.0 / 2187,
                        kA53 = 64448.0 / 6561, kA54 = -212.0 / 729;
inline constexpr double kA61 = 9017.0 / 3168, kA62 = -355.0 / 33, kA63 = 46732.0 / 5247,
                        kA64 = 49.0 / 176, kA65 = -5103.0 / 18656;
// 5th-order weights (also the last row of A: the method is FSAL).
inline constexpr double kB1 = 35.0 / 384, kB3 = 500.0 / 1113, kB4 = 125.0 / 192,
                        kB5 = -2187.0 / 6784, kB6 = 11.0 / 84;
// 5th-order minus embedded 4th-order weights.
inline constexpr double kE1 = 71.0 / 57600, kE3 = -71.0 / 16695, kE4 = 71.0 / 1920,
                        kE5 = -17253.0 / 339200, kE6 = 22.0 / 525, kE7 = -1.0 / 40;
// Dense output of order 4 (II.6; the DOPRI5 code).
inline constexpr double kD1 = -12715105075.0 / 11282082432.0,
                        kD3 = 87487479700.0 / 32700410799.0,
                        kD4 = -10690763975.0 / 1880347072.0,
                        kD5 = 701980252875.0 / 199316789632.0,
                        kD6 = -1453857185.0 / 822651844.0, kD7 = 69997945.0 / 29380423.0;
}  // namespace dp54

/// Result of one Dormand-Prince step.
template <class Y>
struct Dp54Result {
  Y y1;               ///< 5th-order solution at the end of the step
  Y k7;               ///< derivative at y1 (the next step's first stage, FSAL)
  Y err;              ///< 5th- minus embedded 4th-order solution: local error estimate
  bool valid = true;  ///< false if a derivative was undefined or y1 is not finite
  /// Stages for the dense output, which is built only when asked for (Dp54Dense):
  /// most steps never need it.
  std::array<Y, 5> k;  // k1, k3, k4, k5, k6
  double h = 0;
};

/// Coefficients r2..r5 of DOPRI5's continuous extension for step s from y0.
template <class Y>
struct Dp54Dense {
  std::array<Y, 4> r;
  Dp54Dense() = default;
  Dp54Dense(const Y& y0, const Dp54Result<Y>& s) {
    using namespace dp54;
    const std::array<Y, 5>& k = s.k;
    r[0] = s.y1 - y0;
    r[1] = s.h * k[0] - r[0];
    r[2] = r[0] - s.h * s.k7 - r[1];
    r[3] = s.h * (kD1 * k[0] + kD3 * k[1] + kD4 * k[2] + kD5 * k[3] + kD6 * k[4] + kD7 * s.k7);
  }
  /// The state at the fraction t in [0, 1] of the step (order 4: as accurate as the
  /// step's own error estimate).
  Y At(const Y& y0, double t) const {
    return y0 + t * (r[0] + (1 - t) * (r[1] + t * (r[2] + (1 - t) * r[3])));
  }
};

/// One step of length `h` from `y0`, whose derivative is `k1`.
/// `rhs(const Y& y, Y* dy) -> bool` evaluates the derivative and returns false where
/// it is undefined; `observe(const Y& y)` is shown every stage argument and y1 (for
/// example to watch a quantity that must keep its sign within the step).
template <class Y, class Rhs, class Observe>
void Dp54Step(const Y& y0, const Y& k1, double h, Rhs&& rhs, Observe&& observe,
              Dp54Result<Y>* out) {
  using namespace dp54;
  Y k2, k3, k4, k5, k6, y;
  bool ok = true;
  y = y0 + h * kA21 * k1;
  observe(y);
  ok &= rhs(y, &k2);
  y = y0 + h * (kA31 * k1 + kA32 * k2);
  observe(y);
  ok &= rhs(y, &k3);
  y = y0 + h * (kA41 * k1 + kA42 * k2 + kA43 * k3);
  observe(y);
  ok &= rhs(y, &k4);
  y = y0 + h * (kA51 * k1 + kA52 * k2 + kA53 * k3 + kA54 * k4);
  observe(y);
  ok &= rhs(y, &k5);
  y = y0 + h * (kA61 * k1 + kA62 * k2 + kA63 * k3 + kA64 * k4 + kA65 * k5);
  observe(y);
  ok &= rhs(y, &k6);
  out->y1 = y0 + h * (kB1 * k1 + kB3 * k3 + kB4 * k4 + kB5 * k5 + kB6 * k6);
  observe(out->y1);
  ok &= rhs(out->y1, &out->k7);
  out->err = h * (kE1 * k1 + kE3 * k3 + kE4 * k4 + kE5 * k5 + kE6 * k6 + kE7 * out->k7);
  out->k = {k1, k3, k4, k5, k6};
  out->h = h;
  out->valid = ok && out->y1.allFinite();
}

/// Cubic Hermite interpolant of a step of length h from (y0, dy0) to (y1, dy1), at the
/// fraction t in [0, 1] of the step. Third order, enough to place a guard's zero for
/// the refinement that follows with real steps.
template <class Y>
Y HermiteAt(const Y& y0, const Y& dy0, const Y& y1, const Y& dy1, double h, double t) {
  const double t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * h * dy0 + (-2 * t3 + 3 * t2) * y1 +
         (t3 - t2) * h * dy1;
}

/// Root of a scalar function on a bracket by the Illinois variant of regula falsi.
/// Needs g(lo) = g_lo > 0 >= g(hi) = g_hi; `guess` is the first point tried when it
/// lies inside the bracket (e.g. a root of an interpolant). Stops at the first x with
/// |g(x)| <= g_tol, when the bracket is narrower than x_tol, or after max_iter
/// evaluations; then returns that x, or else the upper end of the bracket (where
/// g <= 0: the event has happened there).
template <class G>
double IllinoisRoot(G&& g, double lo, double g_lo, double hi, double g_hi, double guess,
                    double x_tol, double g_tol, int max_iter) {
  int side = 0;
  for (int it = 0; it < max_iter && hi - lo > x_tol; ++it) {
    double x = it == 0 ? guess : (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
    if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
    const double gx = g(x);
    if (std::abs(gx) <= g_tol) return x;
    if (gx > 0) {
      lo = x, g_lo = gx;
      if (side == 1) g_hi *= 0.5;
      side = 1;
    } else {
      hi = x, g_hi = gx;
      if (side == -1) g_lo *= 0.5;
      side = -1;
    }
  }
  return hi;
}

/// Step-size controller for an embedded Runge-Kutta pair whose local error is
/// O(h^q) (q = 5 for DOPRI5, 8 for DOP853): Hairer's PI controller (Solving ODEs I,
/// IV.2), h_new = h * safety * err^-(1/q - 0.75 beta) * err_prev^beta, capped by
/// Gustafsson's predictive controller (Solving ODEs II, IV.8, as in RADAU5):
/// h_new = h * safety * err^-1/q * (h / h_acc) * (err_acc / err)^(1/q), with h_acc,
/// err_acc the previous accepted step. The predictive factor extrapolates a trend in
/// the error: where it grows from step to step at a fixed length (a friction
/// direction turning ever faster as its slip nears zero), the PI controller alone
/// overshoots and every other step is rejected. err is the error norm of the step
/// relative to the tolerance (accept when err <= 1). Reset() forgets the history (a
/// mode or clock change: the trend does not carry across it).
class PiStepControl {
 public:
  /// `error_order`: the local error is O(h^error_order) (5 for DOPRI5, 8 for DOP853).
  explicit PiStepControl(int error_order = 5)
      : alpha_(1.0 / error_order - 0.75 * kBeta), inv_order_(1.0 / error_order) {}
  /// Factor for the step size after a step rejected with error norm `err` (> 1).
  double Rejected(double err) const {
    const double f = kSafety * std::pow(std::max(err, kErrFloor), -alpha_);
    return std::isfinite(f) ? std::max(kMinShrink, f) : kMinShrink;
  }
  /// Factor for the next step after a step of length `h` accepted with error norm `err`.
  double Accepted(double err, double h) {
    const double log_err = std::log(std::max(err, kErrFloor));
    double f = kSafety * std::exp(-alpha_ * log_err + kBeta * log_err_prev_);
    if (h_acc_ > 0 && h > 0) {
      const double predictive =
          kSafety * (h / h_acc_) * std::exp(inv_order_ * (log_err_acc_ - 2 * log_err));
      if (std::isfinite(predictive)) f = std::min(f, predictive);
    }
    log_err_prev_ = std::max(log_err, kLogErrPrevFloor);
    h_acc_ = h;
    log_err_acc_ = log_err;
    return std::clamp(f, kMinShrink, kMaxGrow);
  }
  /// Forgets the accepted steps so far (the predictive factor needs two in a row).
  void Reset() { h_acc_ = 0; }

 private:
  static constexpr double kSafety = 0.9;
  static constexpr double kBeta = 0.04;
  static constexpr double kMinShrink = 0.2;
  static constexpr double kMaxGrow = 5.0;
  static constexpr double kErrFloor = 1e-10;
  static constexpr double kLogErrPrevFloor = -9.210340371976182;  // ln 1e-4
  double alpha_;      // exponent of the error in the PI factor
  double inv_order_;  // 1 / error order
  double log_err_prev_ = kLogErrPrevFloor;
  double h_acc_ = 0;        // length of the last accepted step (0: none)
  double log_err_acc_ = 0;  // ln of its error norm
};

}  // namespace snooker::physics::ode
