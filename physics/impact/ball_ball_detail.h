// Integrators behind ResolveImpact (physics/impact/ball_ball.h). Internal to physics/.
// Both take validated input with ydot_A > 0.
#pragma once

#include "physics/impact/ball_ball.h"
#include "physics/impact/ball_ball_impulse.h"

namespace snooker::physics::detail {

ImpactResult SolveFixedStep(const ImpactState& in, const impulse::Model& model,
                            const ImpulseSolverOptions& options);

ImpactResult SolveAdaptive(const ImpactState& in, const impulse::Model& model,
                           const ImpulseSolverOptions& options);

}  // namespace snooker::physics::detail
