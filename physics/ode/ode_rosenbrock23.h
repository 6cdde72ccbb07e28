// The Rosenbrock 2(3) method of Shampine & Reichelt ("The MATLAB ODE Suite", SIAM J.
// Sci. Comput. 18, 1997; MATLAB's ode23s): linearly implicit, L-stable, second order
// with a third-order error estimate. Internal to physics/.
//
// For the stiff stretches of an otherwise non-stiff problem, where an explicit
// method's step is held down by stability rather than accuracy (in the impulse ODEs:
// a contact that slides with a tiny slip, whose direction relaxes at a rate ~ 1/|u|).
// Header-only, templates over fixed-size Eigen types: no allocation, no exception.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Core>

namespace snooker::physics::ode {

/// LU factorisation with partial pivoting of a small fixed-size matrix, in place and
/// sized at compile time: Eigen's PartialPivLU runs its blocked, runtime-strided
/// path even at 7 x 7, several times the arithmetic's cost. A zero pivot leaves a
/// zero on the diagonal and solve() then gives non-finite values, which the caller's
/// finiteness check rejects.
template <class Mat>
class SmallLu {
 public:
  static constexpr int kN = Mat::RowsAtCompileTime;
  explicit SmallLu(const Mat& a) : lu_(a) {
    for (int k = 0; k < kN; ++k) {
      int p = k;
      for (int i = k + 1; i < kN; ++i) {
        if (std::abs(lu_(i, k)) > std::abs(lu_(p, k))) p = i;
      }
      perm_[k] = p;
      if (p != k) lu_.row(p).swap(lu_.row(k));
      const double pivot = lu_(k, k);
      if (pivot == 0) continue;
      for (int i = k + 1; i < kN; ++i) {
        const double l = lu_(i, k) / pivot;
        lu_(i, k) = l;
        if (l == 0) continue;
        for (int j = k + 1; j < kN; ++j) lu_(i, j) -= l * lu_(k, j);
      }
    }
  }
  /// x with A x = b.
  template <class Y>
  typename Y::PlainObject solve(const Y& b) const {
    typename Y::PlainObject x = b;
    for (int k = 0; k < kN; ++k) {
      if (perm_[k] != k) std::swap(x[k], x[perm_[k]]);
    }
    for (int i = 1; i < kN; ++i) {
      for (int j = 0; j < i; ++j) x[i] -= lu_(i, j) * x[j];
    }
    for (int i = kN - 1; i >= 0; --i) {
      for (int j = i + 1; j < kN; ++j) x[i] -= lu_(i, j) * x[j];
      x[i] /= lu_(i, i);
    }
    return x;
  }

 private:
  Mat lu_;
  int perm_[kN];
};

/// Result of one Rosenbrock 2(3) step.
template <class Y>
struct Ros23Result {
  Y y1;               ///< second-order solution at the end of the step
  Y k7;               ///< derivative at y1 (reused as the next step's F0)
  Y err;              ///< local error estimate (third-order comparison)
  bool valid = true;  ///< false if a derivative was undefined or y1 is not finite
};

/// One step of length h from y0 of the autonomous system y' = f(y), given f0 = f(y0)
/// and the Jacobian `jac` = df/dy at y0. `rhs` and `observe` as for Dp54Step.
template <class Y, class Jac, class Rhs, class Observe>
void Ros23Step(const Y& y0, const Y& f0, const Jac& jac, double h, Rhs&& rhs,
               Observe&& observe, Ros23Result<Y>* out) {
  const double d = 1.0 / (2.0 + std::sqrt(2.0));
  const double e32 = 6.0 + std::sqrt(2.0);
  const Jac w = Jac::Identity() - (h * d) * jac;
  const SmallLu<Jac> lu(w);
  bool ok = true;
  const Y k1 = lu.solve(f0);
  Y y = y0 + (0.5 * h) * k1;
  observe(y);
  Y f1;
  ok &= rhs(y, &f1);
  const Y k2 = Y(lu.solve(Y(f1 - k1))) + k1;
  out->y1 = y0 + h * k2;
  observe(out->y1);
  ok &= rhs(out->y1, &out->k7);
  const Y k3 = lu.solve(Y(out->k7 - e32 * (k2 - f1) - 2.0 * (k1 - f0)));
  out->err = (h / 6.0) * (k1 - 2.0 * k2 + k3);
  out->valid = ok && out->y1.allFinite() && out->err.allFinite();
}

/// Step-size factor after a Rosenbrock 2(3) step with error norm `err` (relative to
/// the tolerance): the error is O(h^3).
inline double Ros23StepFactor(double err) {
  const double f = 0.9 * std::pow(std::max(err, 1e-10), -1.0 / 3.0);
  return std::isfinite(f) ? std::min(std::max(f, 0.2), 5.0) : 0.2;
}

}  // namespace snooker::physics::ode
