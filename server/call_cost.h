// What a call's answer says it cost, for the call log and the metrics: simulations
// run (a fit's model evaluations for Calibrate) and whether a plan was cut short, the
// same whichever transport carried it.
#pragma once

#include <cstdint>

#include "snooker/v1/calibrate.pb.h"
#include "snooker/v1/collide.pb.h"
#include "snooker/v1/model.pb.h"
#include "snooker/v1/plan.pb.h"
#include "snooker/v1/simulate.pb.h"

namespace snooker::server {

struct CallCost {
  std::int64_t simulations = 0;  ///< whole-table simulations run
  /// A plan that the clock or a cancel stopped before its cap (PlanResponse.cut_short),
  /// or refused as its deadline passed before it started.
  bool cut_short = false;
};

inline CallCost CostOf(const v1::CollideResponse&) { return {}; }
inline CallCost CostOf(const v1::SimulateResponse&) { return {1}; }
inline CallCost CostOf(const v1::GetModelResponse&) { return {}; }
inline CallCost CostOf(const v1::CalibrateResponse& r) { return {r.evaluations()}; }
inline CallCost CostOf(const v1::PlanResponse& r) { return {r.simulations(), r.cut_short()}; }

}  // namespace snooker::server
