// The ball-ball impact's adaptive solve with DOP853 steps, in a translation unit of
// its own (see ball_ball_hybrid.h).
#include "physics/impact/ball_ball_hybrid.h"

namespace snooker::physics::detail {

ImpactResult SolveAdaptiveDop853(const ImpactState& in, const impulse::Model& model,
                                 const ImpulseSolverOptions& options) {
  return hybrid::SolveWith<ode::RkMethod::kDop853>(in, model, options);
}

}  // namespace snooker::physics::detail
