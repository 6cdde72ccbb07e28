#include "server/plan_api.h"

#include "planner/planner.h"
#include "server/plan_convert.h"

namespace snooker::server {
namespace {

struct ProgressSink {
  const PlanControl* control;
  const v1::TableState* table;
  const physics::TableModel* model;
  const std::vector<v1::Warning>* warnings;
  std::chrono::steady_clock::time_point start;
};

void ForwardProgress(const planner::PlannedShot& best, void* context) {
  const auto* sink = static_cast<const ProgressSink*>(context);
  v1::PlanResponse partial;
  ToProto(best, *sink->table, *sink->model, partial.add_shots());
  partial.set_elapsed_ms(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - sink->start).count());
  partial.set_final(false);
  for (const v1::Warning& w : *sink->warnings) *partial.add_warnings() = w;
  sink->control->on_progress(partial);
}

}  // namespace

void WarmUpPlanner() { (void)planner::Planner::Default(); }

ApiStatus StatusOf(const planner::PlanAnswer& answer) {
  using planner::PlanStatus;
  const std::string work = std::to_string(answer.simulations) + " simulations";
  switch (answer.status) {
    case PlanStatus::kOk:
    case PlanStatus::kNoPot:
    case PlanStatus::kBudgetSpent: return ApiStatus::Ok();  // an answer; `reason` says why it has no shot
    case PlanStatus::kInvalidRequest: return ApiStatus::Invalid(answer.reason);
    case PlanStatus::kDeadline:
      return {ApiStatus::Code::kDeadlineExceeded,
              "the call's deadline passed before any shot was verified (" + work + "; " + answer.reason + ")"};
    case PlanStatus::kCancelled:
      return {ApiStatus::Code::kCancelled, "the call was cancelled while planning (" + work + ")"};
  }
  return {ApiStatus::Code::kInternal, "unknown plan status " + std::to_string(static_cast<int>(answer.status))};
}

ApiStatus Plan(const v1::PlanRequest& request, v1::PlanResponse* response, const PlanControl& control) {
  const auto start = std::chrono::steady_clock::now();
  // Validate before the planner is first built (its pocket and throw tables take a
  // few thousand simulations once per process): bad input costs nothing.
  PlanBounds bounds;
  bounds.vision_tolerance_mm = control.vision_tolerance_mm;
  bounds.max_budget_ms = control.max_budget_ms;
  PlanCheck check = CheckPlanRequest(request, physics::DefaultTable(), bounds);
  if (!check.errors.empty()) return ApiStatus::Invalid(Describe(check.errors));
  // The planner works from the repaired table; ids (and so the answer) are the same.
  const v1::PlanRequest* planned = &request;
  v1::PlanRequest repaired;
  if (check.repaired) {
    repaired = request;
    *repaired.mutable_table() = std::move(*check.repaired);
    planned = &repaired;
  }
  const planner::Planner& planner = control.planner != nullptr ? *control.planner : planner::Planner::Default();
  planner::PlanRequest p = PlanRequestFrom(*planned, control.default_budget_ms);
  p.deadline = control.deadline;
  p.cancel = control.cancel;
  ProgressSink sink{&control, &planned->table(), planner.config().table, &check.warnings, start};
  if (control.on_progress) {
    p.progress = &ForwardProgress;
    p.progress_context = &sink;
  }
  const planner::PlanAnswer answer = planner.Plan(p);
  ToProto(answer, planned->table(), *planner.config().table, response);
  response->set_final(true);
  for (v1::Warning& w : check.warnings) *response->add_warnings() = std::move(w);
  return StatusOf(answer);
}

}  // namespace snooker::server
