// The paper's numerical scheme (Mathavan et al. 2014, section 2.4.3): explicit Euler
// in the normal impulse with the step of eq. 14, dP_I = (1 + e) M ydot_A(0) / N.
//
// Kept as the reference that reproduces the paper. It is first order: the friction
// direction is frozen over each step, so a slip that reaches zero chatters around
// it with an amplitude of one step. Within a step every quantity is linear in P_I
// and the work W (eq. 12, exact for a linear ydot_A) is quadratic, so the end of
// compression (eq. 10d) and the end of restitution (eqs. 10c, 15) are located inside
// the step exactly instead of overshooting it (physics-notes section 4).
#include <algorithm>
#include <cmath>

#include "physics/impact/ball_ball_detail.h"
#include "physics/impact/ball_ball_impulse.h"
#include "physics/ode/euler_phases.h"

namespace snooker::physics::detail {

using impulse::Mode;
using impulse::Model;
using impulse::State;

ImpactResult SolveFixedStep(const ImpactState& in, const Model& model,
                            const ImpulseSolverOptions& opt) {
  ImpactResult r;
  State x = impulse::Pack(in);
  const double e = model.contact.e;
  const double dp = (1.0 + e) * impulse::NormalSpeed(x) / model.inv_mass / opt.steps;  // eq. 14

  EulerPhaseEnds phases(e);
  double p = 0;  // accumulated normal impulse P_I
  State dx;
  for (std::int32_t n = 0; n < opt.max_steps; ++n) {
    // The paper's rules, read off the state at the start of the step: sliding
    // wherever the slip is non-zero, no friction where it is exactly zero; a ball is
    // on the cloth unless it moves upwards.
    Mode m;
    m.c_on_cloth = x[impulse::kVC + 2] <= 0;
    m.o_on_cloth = x[impulse::kVO + 2] <= 0;
    impulse::Derivative(x, m, model, &dx);
    ++r.work.rhs_evals;
    ++r.work.steps;
    const double y0 = impulse::NormalSpeed(x);
    const double y1 = dx[impulse::kVC + 1] - dx[impulse::kVO + 1];
    const double w0 = x[impulse::kWork];
    const double t_end = phases.Step(p, dp, y0, y1, w0);
    const double t = std::min(t_end, dp);
    x += t * dx;
    x[impulse::kWork] = w0 + t * (y0 + 0.5 * y1 * t);  // eq. 12, trapezoid
    p += t;
    if (t_end <= dp) {
      phases.RecordInto(&r);
      r.impulse_final = p;
      r.out = impulse::Unpack(x);
      r.status = ImpactStatus::kOk;
      return r;
    }
  }
  phases.RecordInto(&r);
  r.out = impulse::Unpack(x);
  r.impulse_final = p;
  r.status = ImpactStatus::kStepLimit;
  return r;
}

}  // namespace snooker::physics::detail
