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

#include "physics/ball_ball_detail.h"
#include "physics/ball_ball_impulse.h"

namespace snooker::physics::detail {

using impulse::Law;
using impulse::Mode;
using impulse::Model;
using impulse::State;

namespace {

// First t in [lo, hi] where a + b t + c t^2 goes from > 0 to <= 0, for the two
// uses here: a linear function (c = 0) and a concave one (c < 0) that is positive
// at lo. Returns hi + 1 when there is none. Closed form with the cancellation-free
// quadratic formula; the result is clamped into the bracket.
double FirstDownCrossing(double a, double b, double c, double lo, double hi) {
  auto f = [&](double t) { return a + t * (b + t * c); };
  if (f(lo) <= 0) return lo;
  if (f(hi) > 0) return hi + 1;
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

}  // namespace

ImpactResult SolveFixedStep(const ImpactState& in, const Model& model,
                            const ImpulseSolverOptions& opt) {
  ImpactResult r;
  State x = impulse::Pack(in);
  const double e = model.contact.e;
  const double dp = (1.0 + e) * impulse::NormalSpeed(x) / model.inv_mass / opt.steps;  // eq. 14

  bool compressed = false;  // compression over
  double target = 0;        // W at the end of restitution, (1 - e^2) W_c (eq. 10c)
  double p = 0;             // accumulated normal impulse P_I
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

    // Within the step: ydot_A(t) = y0 + y1 t, W(t) = w0 + y0 t + y1 t^2 / 2.
    const double y0 = impulse::NormalSpeed(x);
    const double y1 = dx[impulse::kVC + 1] - dx[impulse::kVO + 1];
    const double w0 = x[impulse::kWork];
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
    if (compressed) {
      t_end = FirstDownCrossing(w0 - target, y0, 0.5 * y1, t_start, dp);
    }
    if (t_end <= dp) {
      x += t_end * dx;
      x[impulse::kWork] = w0 + t_end * (y0 + 0.5 * y1 * t_end);
      r.impulse_final = p + t_end;
      ++r.work.events;
      r.out = impulse::Unpack(x);
      r.status = ImpactStatus::kOk;
      return r;
    }
    x += dp * dx;
    x[impulse::kWork] = w0 + dp * (y0 + 0.5 * y1 * dp);  // eq. 12, trapezoid
    p += dp;
  }
  r.out = impulse::Unpack(x);
  r.impulse_final = p;
  r.status = ImpactStatus::kStepLimit;
  return r;
}

}  // namespace snooker::physics::detail
