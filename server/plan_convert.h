// Plan's conversions between the API (proto/snooker/v1/plan.proto) and the planner
// (planner/planner.h), and its request validation: every error names the API field
// (or ball id) and its value. Kept apart from convert.h, which it builds on (the
// table checks Simulate also makes).
#pragma once

#include <vector>

#include "physics/table/table.h"
#include "planner/builtin_tables.h"
#include "planner/planner.h"
#include "server/convert.h"
#include "server/limits.h"
#include "snooker/v1/model.pb.h"
#include "snooker/v1/plan.pb.h"

namespace snooker::server {

/// The id the answer gives the cue ball placed from hand (PlanRequest.cue_in_hand),
/// in its events and balls_end; no ball of such a request's table may have it.
inline constexpr const char* kPlacedCueId = "cue";

/// What a server allows a plan request (snooker serve's flags).
struct PlanBounds {
  /// The vision repair's tolerance, mm: the default of a request that sets none and
  /// the most one may ask for; 0: no repair (every overlap is an error).
  double vision_tolerance_mm = 0;
  /// The largest time budget a request may ask for, ms.
  double max_budget_ms = limits::kPlanBudgetMs.hi;
};

/// What CheckPlanRequest found, and what the vision repair changed.
struct PlanCheck {
  std::vector<FieldError> errors;
  /// Set when the repair moved a ball: the table with the moved positions.
  std::optional<v1::TableState> repaired;
  /// One per moved ball, in table order.
  std::vector<v1::Warning> warnings;
};

/// Checks the table as Simulate does (with its vision repair within the bounds'
/// tolerance), what only the API has (enum values, the ids of per-ball sigmas, the
/// server's largest budget), and the planner's own rules (planner/validate.h:
/// snooker's counts, the ball on, the ranges of planner/limits.h) renamed to the
/// API's fields and converted to its units; every error names the field and value.
PlanCheck CheckPlanRequest(const v1::PlanRequest& request, const physics::TableModel& table,
                           const PlanBounds& bounds);

/// CheckPlanRequest's errors with the default bounds (no vision repair).
std::vector<FieldError> ValidatePlanRequest(const v1::PlanRequest& request,
                                            const physics::TableModel& table);

/// The planner's request for a validated API request (defaults where unset; an
/// unset time budget takes `default_budget_ms` when given, else the planner's).
planner::PlanRequest PlanRequestFrom(const v1::PlanRequest& request,
                                     std::optional<double> default_budget_ms = std::nullopt);

planner::BallKind BallKindFrom(v1::BallKind kind);
v1::BallKind ToProto(planner::BallKind kind);
std::optional<planner::BallOn> BallOnFrom(v1::BallOn on);

v1::ShotKind ToProto(planner::ShotKind kind);
v1::PotRoute ToProto(planner::PotRoute route);
/// The planner's kind or route for the API's; nullopt for *_UNSPECIFIED or a number
/// that names no value.
std::optional<planner::ShotKind> ShotKindFrom(v1::ShotKind kind);
std::optional<planner::PotRoute> PotRouteFrom(v1::PotRoute route);

/// One planned shot in API form: ball indices become the ids of `table` (the
/// request's), and an index past its balls the placed cue ball's, kPlacedCueId;
/// the pocket and the route for pots only; cue_ball_start only when the cue ball
/// was in hand.
void ToProto(const planner::PlannedShot& shot, const v1::TableState& table,
             const physics::TableModel& model, v1::PlannedShot* out);

/// A built-in table's balls in API form, with their ids, in their order.
void ToProto(const std::vector<planner::NamedBall>& balls, v1::TableState* out);

/// Every built-in table (planner::BuiltinTableList) into GetModel's answer.
void BuiltinTablesToProto(v1::GetModelResponse* response);

/// The planner's answer in API form.
void ToProto(const planner::PlanAnswer& answer, const v1::TableState& table,
             const physics::TableModel& model, v1::PlanResponse* out);

}  // namespace snooker::server
