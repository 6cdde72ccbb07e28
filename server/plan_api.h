// Plan: the planner behind the API, independent of the transport (as api.h's
// operations): validate, convert, one planner call, convert back. The gRPC Plan and
// PlanStream RPCs (issue 10) and `snooker plan` call this.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>

#include "server/api_status.h"
#include "snooker/v1/plan.pb.h"

namespace snooker::server {

/// What a transport adds to a plan: its deadline, its cancellation, and a sink for
/// the best shot so far.
struct PlanControl {
  /// The plan ends by this time (and by its own budget), returning what it has.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  /// Set from another thread to stop the plan.
  const std::atomic<bool>* cancel = nullptr;
  /// Called, never concurrently, each time the best verified shot improves, with a
  /// response holding that one shot (its potProbability is the fast estimate until
  /// the final answer). For PlanStream.
  std::function<void(const v1::PlanResponse& best_so_far)> on_progress;
};

/// Plans shots for the request's table. INVALID_ARGUMENT names each bad field; an
/// answer without shots is OK with its reason (no pot, or time ran out first).
ApiStatus Plan(const v1::PlanRequest& request, v1::PlanResponse* response,
               const PlanControl& control = {});

}  // namespace snooker::server
