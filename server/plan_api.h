// Plan: the planner behind the API, independent of the transport (as api.h's
// operations): validate (with the vision repair), convert, one planner call, convert
// back. The gRPC Plan and PlanStream RPCs (grpc_service.h) and `snooker plan` call
// this.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>

#include "server/api_status.h"
#include "planner/planner.h"
#include "server/limits.h"
#include "snooker/v1/plan.pb.h"

namespace snooker::server {

/// What a transport adds to a plan: its deadline, its cancellation, a sink for the
/// best shot so far, and the server's bounds.
struct PlanControl {
  /// The plan ends by this time (and by its own budget), returning what it has.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  /// Set from another thread to stop the plan.
  const std::atomic<bool>* cancel = nullptr;
  /// Called, never concurrently, each time the best verified shot improves, with a
  /// response holding that one shot (its potProbability is the fast estimate until
  /// the final answer), final = false, the elapsed time and the repair's warnings.
  /// For PlanStream.
  std::function<void(const v1::PlanResponse& best_so_far)> on_progress;
  /// The vision repair's tolerance, mm: a request's default and its largest (0: no
  /// repair). The defaults here are the local command's; a server passes its flags.
  double vision_tolerance_mm = limits::kDefaultVisionToleranceMm;
  /// A request's time budget when it sets none, and the largest it may ask for, ms.
  double default_budget_ms = limits::kDefaultPlanBudgetMs;
  double max_budget_ms = limits::kPlanBudgetMs.hi;
  /// The planner (its physical model: `--model`); nullptr: planner::Planner::Default().
  const planner::Planner* planner = nullptr;
};

/// Builds the planner and its pocket and throw tables (a few thousand simulations,
/// about 0.2 s, once per process) so that no call pays for them: a server does this
/// before it reports SERVING.
void WarmUpPlanner();

/// The API status of a planner's answer, the one mapping of every planner outcome:
/// shots, no pot and a spent budget are OK (an answer without shots has its
/// reason); an invalid request is INVALID_ARGUMENT, the caller's deadline before any
/// shot DEADLINE_EXCEEDED, a cancelled plan CANCELLED.
ApiStatus StatusOf(const planner::PlanAnswer& answer);

/// Plans shots for the request's table. INVALID_ARGUMENT names each bad field and
/// value; otherwise StatusOf the planner's answer, which `response` holds whatever
/// the status (final = true, the work done, the vision repair's warnings).
ApiStatus Plan(const v1::PlanRequest& request, v1::PlanResponse* response,
               const PlanControl& control = {});

}  // namespace snooker::server
