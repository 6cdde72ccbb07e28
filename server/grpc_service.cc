#include "server/grpc_service.h"

#include <exception>
#include <string>

#include "server/api.h"

namespace snooker::server {
namespace {

// Runs an API call so that no exception leaves a service method.
template <typename Call>
grpc::Status Guarded(Call&& call) {
  try {
    return ToGrpcStatus(call());
  } catch (const std::exception& e) {
    return {grpc::StatusCode::INTERNAL, std::string("internal error: ") + e.what()};
  } catch (...) {
    return {grpc::StatusCode::INTERNAL, "internal error"};
  }
}

}  // namespace

grpc::Status ToGrpcStatus(const ApiStatus& status) {
  switch (status.code) {
    case ApiStatus::Code::kOk: return grpc::Status::OK;
    case ApiStatus::Code::kInvalidArgument:
      return {grpc::StatusCode::INVALID_ARGUMENT, status.message};
    case ApiStatus::Code::kResourceExhausted:
      return {grpc::StatusCode::RESOURCE_EXHAUSTED, status.message};
    case ApiStatus::Code::kInternal: return {grpc::StatusCode::INTERNAL, status.message};
  }
  return {grpc::StatusCode::UNKNOWN, status.message};
}

grpc::Status ShotPlannerService::Collide(grpc::ServerContext* /*context*/,
                                         const v1::CollideRequest* request,
                                         v1::CollideResponse* response) {
  return Guarded([&] { return server::Collide(*request, response); });
}

grpc::Status ShotPlannerService::Simulate(grpc::ServerContext* /*context*/,
                                          const v1::SimulateRequest* request,
                                          v1::SimulateResponse* response) {
  return Guarded([&] { return server::Simulate(*request, response); });
}

}  // namespace snooker::server
