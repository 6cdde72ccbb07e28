// The paper's numerical scheme for the cushion impact (Mathavan et al. 2010): explicit
// Euler in the normal impulse P_I with N steps of dP_I = (1 + e_e) M v_n / N, v_n the
// initial normal speed ydot cos th.
//
// Kept as the reference the adaptive integrator must converge to. It is first order:
// friction directions are frozen over each step (the paper's rule: zero slip gives
// zero friction), so a slip that reaches zero chatters around it with an amplitude of
// one step. Within a step every quantity is linear in P_I, so the work W of the
// normal force is accumulated exactly on it (quadratic in P_I, not the left-point
// sum) and the end of compression and the end of restitution are located inside the
// step instead of overshooting it (physics-notes section 4). The frictionless impact
// is then solved exactly, whatever N.
#include <cmath>

#include "physics/ball_cushion_impulse.h"

namespace snooker::physics::cushion {
namespace {

// Smallest t in [lo, hi] where a + b t + c t^2 goes from > 0 to <= 0. Returns hi + 1
// when it stays positive. Bisection: exact enough, never fails, capped.
double FirstDownCrossing(double a, double b, double c, double lo, double hi) {
  auto f = [&](double t) { return a + t * (b + t * c); };
  if (f(lo) <= 0) return lo;
  if (f(hi) > 0) return hi + 1;
  for (int i = 0; i < 200 && hi - lo > 0; ++i) {  // 200 halvings reach double spacing
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (f(mid) > 0 ? lo : hi) = mid;
  }
  return hi;
}

}  // namespace

CushionImpactResult SolveFixedStep(const BallMotion& in, const Model& model,
                                   const ImpulseSolverOptions& opt) {
  CushionImpactResult r;
  State x = Pack(in);
  const double e = model.e;
  const double dp = (1.0 + e) * NormalSpeed(x, model) / model.inv_mass / opt.steps;
  const Mode mode;  // both sliding, no friction at exactly zero slip (the paper's rule)

  bool compressed = false;
  double target = 0;  // W at the end of restitution, (1 - e^2) W_c
  double p = 0;       // accumulated P_I
  State dx;
  for (std::int32_t n = 0; n < opt.max_steps; ++n) {
    Derivative(x, mode, model, &dx);
    ++r.work.rhs_evals;
    ++r.work.steps;
    // Within the step: v_n(t) = y0 + y1 t, W(t) = w0 + y0 t + y1 t^2 / 2.
    const double y0 = NormalSpeed(x, model);
    const double y1 = NormalSpeed(dx, model);
    const double w0 = x[kWork];
    double t_end = dp + 1;  // no end in this step
    double t_start = 0;
    if (!compressed) {
      const double tc = FirstDownCrossing(y0, y1, 0.0, 0.0, dp);
      if (tc <= dp) {
        compressed = true;
        r.impulse_compression = p + tc;
        r.work_compression = w0 + tc * (y0 + 0.5 * y1 * tc);
        target = (1.0 - e * e) * r.work_compression;
        ++r.work.events;
        t_start = tc;
      }
    }
    if (compressed) t_end = FirstDownCrossing(w0 - target, y0, 0.5 * y1, t_start, dp);
    if (t_end <= dp) {
      x += t_end * dx;
      r.impulse_final = p + t_end;
      ++r.work.events;
      r.out = Unpack(x);
      r.status = ImpactStatus::kOk;
      return r;
    }
    x += dp * dx;
    x[kWork] = w0 + dp * (y0 + 0.5 * y1 * dp);  // exact on the step's linear v_n
    p += dp;
  }
  r.out = Unpack(x);
  r.impulse_final = p;
  r.status = ImpactStatus::kStepLimit;
  return r;
}

}  // namespace snooker::physics::cushion
