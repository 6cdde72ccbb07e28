// The cushion impact's adaptive solve with DOP853 steps, in a translation unit of its
// own (see ball_cushion_hybrid.h).
#include "physics/impact/ball_cushion_hybrid.h"

namespace snooker::physics::cushion {

CushionImpactResult SolveAdaptiveDop853(const BallMotion& in, const Model& model,
                                        const ImpulseSolverOptions& options) {
  return hybrid::SolveWith<ode::RkMethod::kDop853>(in, model, options);
}

}  // namespace snooker::physics::cushion
