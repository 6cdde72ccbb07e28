// What a call's answer says it cost, for the call log: simulations run (a fit's
// model evaluations for Calibrate), the same count whichever transport carried it.
#pragma once

#include <cstdint>

#include "snooker/v1/calibrate.pb.h"
#include "snooker/v1/collide.pb.h"
#include "snooker/v1/model.pb.h"
#include "snooker/v1/plan.pb.h"
#include "snooker/v1/simulate.pb.h"

namespace snooker::server {

inline std::int64_t SimulationsOf(const v1::CollideResponse&) { return 0; }
inline std::int64_t SimulationsOf(const v1::SimulateResponse&) { return 1; }
inline std::int64_t SimulationsOf(const v1::GetModelResponse&) { return 0; }
inline std::int64_t SimulationsOf(const v1::CalibrateResponse& r) { return r.evaluations(); }
inline std::int64_t SimulationsOf(const v1::PlanResponse& r) { return r.simulations(); }

}  // namespace snooker::server
