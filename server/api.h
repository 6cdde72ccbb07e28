// The service's operations, independent of the transport: the gRPC adapter
// (grpc_service.h) and the command line both call these. Each validates its
// request, converts it (convert.h), makes one library call and converts back.
//
// Every call's work is bounded: by the request's validated ranges (server/limits.h,
// physics/core/limits.h), by the size of its answer (CallLimits::max_response_bytes)
// and by CallLimits::interrupt, a wall-time deadline and a cancellation test checked
// inside long simulations.
#pragma once

#include <cstddef>

#include "physics/model/model.h"
#include "physics/sim/simulate.h"
#include "server/plan_api.h"  // Plan (planner)
#include "physics/table/table.h"
#include "server/api_status.h"
#include "server/limits.h"
#include "snooker/v1/collide.pb.h"
#include "snooker/v1/model.pb.h"
#include "snooker/v1/simulate.pb.h"

namespace snooker::server {

/// What bounds one call besides its request.
struct CallLimits {
  /// Deadline and cancellation (physics::Interrupt), checked every few events of a
  /// simulation and once after a collision: a call stopped by it answers
  /// DEADLINE_EXCEEDED once the deadline has passed, otherwise CANCELLED.
  physics::Interrupt interrupt;
  /// A response that would be larger is refused with RESOURCE_EXHAUSTED.
  std::size_t max_response_bytes = limits::kMaxResponseBytes;
  /// The vision repair's tolerance, mm: the default of a request that sets none and
  /// the most one may ask for (0: no repair).
  double vision_tolerance_mm = limits::kDefaultVisionToleranceMm;
  /// A plan's time budget when its request sets none, and the largest it may ask for, ms.
  double default_plan_budget_ms = limits::kDefaultPlanBudgetMs;
  double max_plan_budget_ms = limits::kDefaultMaxPlanBudgetMs;
  /// What GetModel reports as the server's bounds (workers, queue, ...); nullptr:
  /// the defaults of server/limits.h and the fields above.
  const v1::ServiceLimits* service = nullptr;
  /// The physical model calls simulate with (a model file's, `--model`); nullptr:
  /// the default model. A Collide request's own parameters still override it.
  const physics::Model* model = nullptr;
  const physics::Model& physics_model() const {
    static const physics::Model kDefault;
    return model != nullptr ? *model : kDefault;
  }
};

/// One ball-ball collision (Mathavan et al. 2014) and the slip phases after it.
/// Its work is bounded by the step cap (at most 4 x limits::kMaxFixedSteps steps);
/// the interrupt is checked when it ends.
ApiStatus Collide(const v1::CollideRequest& request, v1::CollideResponse* response,
                  const CallLimits& limits = {});

/// A shot on a table, simulated until every ball is at rest or pocketed (or a cap is
/// reached); the interrupt is checked every interrupt.check_every events. Small
/// overlaps and cushion overshoots are repaired first (the vision tolerance), each
/// moved ball reported in the response's warnings.
ApiStatus Simulate(const v1::SimulateRequest& request, v1::SimulateResponse* response,
                   const CallLimits& limits = {});

/// The model the server works with: the default table's geometry, its physical
/// model (limits.model: ball, cloth, ball-ball, cushion, cue; also in model-file
/// form), the simulation defaults, and the server's bounds (limits.service, or the
/// defaults).
ApiStatus GetModel(const v1::GetModelRequest& request, v1::GetModelResponse* response,
                   const CallLimits& limits = {});

/// The ServiceLimits of a server with these call limits and the defaults of
/// server/limits.h for the rest (workers 0: one per hardware thread).
v1::ServiceLimits DefaultServiceLimits(const CallLimits& limits);

}  // namespace snooker::server
