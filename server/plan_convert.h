// Plan's conversions between the API (proto/snooker/v1/plan.proto) and the planner
// (planner/planner.h), and its request validation: every error names the API field
// (or ball id) and its value. Kept apart from convert.h, which it builds on (the
// table checks Simulate also makes).
#pragma once

#include <vector>

#include "physics/table/table.h"
#include "planner/planner.h"
#include "server/convert.h"
#include "snooker/v1/plan.pb.h"

namespace snooker::server {

/// Largest plan budget a request may ask for, ms.
inline constexpr double kMaxPlanBudgetMs = 60'000;

/// Checks the table (as Simulate does, plus at most 15 reds and one ball of each
/// colour, a ball on that is on the table), the limits, the noise, the budget and
/// the counts.
std::vector<FieldError> ValidatePlanRequest(const v1::PlanRequest& request,
                                            const physics::TableModel& table);

/// The planner's request for a validated API request (defaults where unset).
planner::PlanRequest PlanRequestFrom(const v1::PlanRequest& request);

planner::BallKind BallKindFrom(v1::BallKind kind);
v1::BallKind ToProto(planner::BallKind kind);
std::optional<planner::BallOn> BallOnFrom(v1::BallOn on);

/// One planned shot in API form; ball indices become the table's ids.
void ToProto(const planner::PlannedShot& shot, const v1::TableState& table,
             const physics::TableModel& model, v1::PlannedShot* out);

/// The planner's answer in API form.
void ToProto(const planner::PlanAnswer& answer, const v1::TableState& table,
             const physics::TableModel& model, v1::PlanResponse* out);

}  // namespace snooker::server
