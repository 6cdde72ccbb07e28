// The gRPC adapter: proto in -> api.h call -> proto and status out. No logic here.
#pragma once

#include <grpcpp/grpcpp.h>

#include "server/api_status.h"
#include "snooker/v1/service.grpc.pb.h"

namespace snooker::server {

/// Maps an API status to a gRPC status (the only place that does).
grpc::Status ToGrpcStatus(const ApiStatus& status);

class ShotPlannerService final : public v1::ShotPlanner::Service {
 public:
  grpc::Status Collide(grpc::ServerContext* context, const v1::CollideRequest* request,
                       v1::CollideResponse* response) override;
  grpc::Status Simulate(grpc::ServerContext* context, const v1::SimulateRequest* request,
                        v1::SimulateResponse* response) override;
};

}  // namespace snooker::server
