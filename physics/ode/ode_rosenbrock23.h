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

#include <Eigen/LU>

namespace snooker::physics::ode {

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
  const Eigen::PartialPivLU<Jac> lu(w);
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
