// The service's operations, independent of the transport: the gRPC adapter
// (grpc_service.h) and the command line both call these. Each validates its
// request, converts it (convert.h), makes one library call and converts back.
#pragma once

#include "server/api_status.h"
#include "server/plan_api.h"  // Plan (planner)
#include "physics/table/table.h"
#include "snooker/v1/collide.pb.h"
#include "snooker/v1/simulate.pb.h"

namespace snooker::server {

/// One ball-ball collision (Mathavan et al. 2014) and the slip phases after it.
ApiStatus Collide(const v1::CollideRequest& request, v1::CollideResponse* response);

/// A shot on a table, simulated until every ball is at rest or pocketed.
ApiStatus Simulate(const v1::SimulateRequest& request, v1::SimulateResponse* response);

}  // namespace snooker::server
