#include "server/plan_api.h"

#include "planner/planner.h"
#include "server/plan_convert.h"

namespace snooker::server {
namespace {

struct ProgressSink {
  const PlanControl* control;
  const v1::TableState* table;
  const physics::TableModel* model;
};

void ForwardProgress(const planner::PlannedShot& best, void* context) {
  const auto* sink = static_cast<const ProgressSink*>(context);
  v1::PlanResponse partial;
  ToProto(best, *sink->table, *sink->model, partial.add_shots());
  sink->control->on_progress(partial);
}

}  // namespace

ApiStatus Plan(const v1::PlanRequest& request, v1::PlanResponse* response, const PlanControl& control) {
  // Validate before the planner is first built (its pocket and throw tables take a
  // few thousand simulations once per process): bad input costs nothing.
  const std::vector<FieldError> errors = ValidatePlanRequest(request, physics::DefaultTable());
  if (!errors.empty()) return ApiStatus::Invalid(Describe(errors));
  const planner::Planner& planner = planner::Planner::Default();
  planner::PlanRequest p = PlanRequestFrom(request);
  p.deadline = control.deadline;
  p.cancel = control.cancel;
  ProgressSink sink{&control, &request.table(), planner.config().table};
  if (control.on_progress) {
    p.progress = &ForwardProgress;
    p.progress_context = &sink;
  }
  const planner::PlanAnswer answer = planner.Plan(p);
  if (answer.status == planner::PlanStatus::kInvalidRequest) {
    // The API checks should have caught it: the library names its own field.
    return ApiStatus::Invalid(answer.reason);
  }
  ToProto(answer, request.table(), *planner.config().table, response);
  return ApiStatus::Ok();
}

}  // namespace snooker::server
