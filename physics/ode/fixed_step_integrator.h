// The paper's fixed-step scheme (Mathavan et al. 2014, eq. 14) as one generic
// integrator for every impulse model (physics/impact/): explicit Euler in the normal
// impulse P_I with a constant step, the paper's rule for friction (read off the state
// at the start of each step), and the two phase ends located inside the step.
// Internal to physics/.
//
// Within an explicit Euler step every quantity is linear in P_I, so the normal speed
// is y0 + y1 t and the work of the normal force (eq. 12, exact for it) is
// w0 + y0 t + y1 t^2 / 2: the end of compression (eq. 10d: normal speed 0) and the end
// of restitution (eqs. 10c, 15: W = (1 - e^2) W_c) are located in the step exactly
// instead of overshooting it (docs/physics-notes.md section 5).
#pragma once

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>

#include "physics/ode/hybrid_integrator.h"

namespace snooker::physics::ode {

/// First t in [lo, hi] where a + b t + c t^2 goes from > 0 to <= 0, for the two uses
/// here: a linear function (c = 0) and a concave one (c < 0) positive at lo. lo if it
/// is already <= 0 there; +infinity when there is none (not hi + 1, which rounds to
/// hi once hi passes 2^53). Closed form with the cancellation-free quadratic formula,
/// clamped into the bracket.
inline double FirstDownCrossing(double a, double b, double c, double lo, double hi) {
  auto f = [&](double t) { return a + t * (b + t * c); };
  if (f(lo) <= 0) return lo;
  if (f(hi) > 0) return std::numeric_limits<double>::infinity();
  double t;
  if (c == 0) {
    t = -a / b;
  } else {
    // Roots of c t^2 + b t + a: q = -(b + sign(b) sqrt(b^2 - 4ac)) / 2, t = q/c or a/q.
    // With f(lo) > 0 >= f(hi) and c < 0 the crossing is the larger root.
    const double disc = std::sqrt(std::max(0.0, b * b - 4 * a * c));
    const double q = -0.5 * (b + std::copysign(disc, b));
    const double t1 = q / c, t2 = q != 0 ? a / q : t1;
    t = std::max(t1, t2);
  }
  return std::clamp(t, lo, hi);
}

/// Follows compression and restitution through the steps of the scheme.
class EulerPhaseEnds {
 public:
  /// `e`: the energetic coefficient of restitution.
  explicit EulerPhaseEnds(double e) : e_(e) {}

  /// The step from impulse p (N s) of length dp with normal speed y0 + y1 t (m/s) and
  /// work w0 + y0 t + y1 t^2 / 2 (J): records the end of compression if it lies in
  /// the step and returns the t in [0, dp] where the impact ends, or +infinity.
  double Step(double p, double dp, double y0, double y1, double w0) {
    double start = 0;
    if (!compressed_) {
      const double tc = FirstDownCrossing(y0, y1, 0.0, 0.0, dp);
      if (tc > dp) return std::numeric_limits<double>::infinity();
      compressed_ = true;
      impulse_compression_ = p + tc;
      work_compression_ = w0 + tc * (y0 + 0.5 * y1 * tc);
      target_ = (1.0 - e_ * e_) * work_compression_;  // eq. 10c
      ++events_;
      start = tc;
    }
    const double t = FirstDownCrossing(w0 - target_, y0, 0.5 * y1, start, dp);
    if (t <= dp) ++events_;
    return t;
  }

  /// Copies P_c (N s), W_c (J) and the phase ends located so far into a result.
  template <class Result>
  void RecordInto(Result* r) const {
    r->impulse_compression = impulse_compression_;
    r->work_compression = work_compression_;
    r->work.events = events_;
  }

 private:
  double e_;
  bool compressed_ = false;
  double target_ = 0;  // W at the end of restitution
  double impulse_compression_ = 0, work_compression_ = 0;
  std::int32_t events_ = 0;
};

/// A model for the fixed-step scheme: its state (a fixed-size Eigen vector with the
/// work W of the normal force at kWork; P_I is counted by the integrator) and the
/// paper's derivative, whose friction law is read off the state alone.
template <class M>
concept FixedStepImpulseModel =
    requires(const M& m, const typename M::State& x, typename M::State* dx) {
      { M::kWork } -> std::convertible_to<int>;
      { m.PaperDerivative(x, dx) } -> std::same_as<void>;
      { m.NormalSpeed(x) } -> std::same_as<double>;
    };

struct FixedStepResult {
  HybridStatus status = HybridStatus::kStepLimit;
  double impulse_compression = 0;  ///< P_c, N s
  double work_compression = 0;     ///< W_c, J
  double impulse_final = 0;        ///< P_f, N s
  HybridWork work;                 ///< steps = Euler steps, events = phase ends
};

/// Integrates *x with steps of dP_I = dp until the end of restitution (energetic
/// restitution e) or max_steps steps. The normal speed must be linear in the state
/// (it maps the derivative to its rate).
template <FixedStepImpulseModel Model>
FixedStepResult IntegrateFixedStep(const Model& model, double e, double dp,
                                   std::int32_t max_steps, typename Model::State* x) {
  FixedStepResult r;
  EulerPhaseEnds phases(e);
  double p = 0;  // accumulated normal impulse P_I
  typename Model::State dx;
  for (std::int32_t n = 0; n < max_steps; ++n) {
    model.PaperDerivative(*x, &dx);
    ++r.work.rhs_evals;
    ++r.work.steps;
    const double y0 = model.NormalSpeed(*x);
    const double y1 = model.NormalSpeed(dx);
    const double w0 = (*x)[Model::kWork];
    const double t_end = phases.Step(p, dp, y0, y1, w0);
    const double t = std::min(t_end, dp);
    *x += t * dx;
    (*x)[Model::kWork] = w0 + t * (y0 + 0.5 * y1 * t);  // eq. 12, exact on the step
    p += t;
    if (t_end <= dp) {
      r.status = HybridStatus::kFinished;
      break;
    }
  }
  phases.RecordInto(&r);
  r.impulse_final = p;
  return r;
}

}  // namespace snooker::physics::ode
