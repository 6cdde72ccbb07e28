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

#include "physics/impact/ball_cushion_impulse.h"
#include "physics/ode/euler_phases.h"

namespace snooker::physics::cushion {
CushionImpactResult SolveFixedStep(const BallMotion& in, const Model& model,
                                   const ImpulseSolverOptions& opt) {
  CushionImpactResult r;
  State x = Pack(in);
  const double e = model.e;
  const double dp = (1.0 + e) * NormalSpeed(x, model) / model.inv_mass / opt.steps;
  const Mode mode;  // both sliding, no friction at exactly zero slip (the paper's rule)

  EulerPhaseEnds phases(e);
  double p = 0;  // accumulated P_I
  State dx;
  for (std::int32_t n = 0; n < opt.max_steps; ++n) {
    Derivative(x, mode, model, &dx);
    ++r.work.rhs_evals;
    ++r.work.steps;
    const double y0 = NormalSpeed(x, model);
    const double y1 = NormalSpeed(dx, model);
    const double w0 = x[kWork];
    const double t_end = phases.Step(p, dp, y0, y1, w0);
    const double t = std::min(t_end, dp);
    x += t * dx;
    x[kWork] = w0 + t * (y0 + 0.5 * y1 * t);  // exact on the step's linear v_n
    p += t;
    if (t_end <= dp) {
      phases.RecordInto(&r);
      r.impulse_final = p;
      r.out = Unpack(x);
      r.status = ImpactStatus::kOk;
      return r;
    }
  }
  phases.RecordInto(&r);
  r.out = Unpack(x);
  r.impulse_final = p;
  r.status = ImpactStatus::kStepLimit;
  return r;
}

}  // namespace snooker::physics::cushion
