// Building and running the gRPC server: the ShotPlanner service, the standard
// health service (grpc.health.v1) and server reflection.
#pragma once

#include <memory>
#include <string>

#include <grpcpp/grpcpp.h>

#include "server/grpc_service.h"

namespace snooker::server {

/// The health-check service name under which ShotPlanner reports SERVING.
inline constexpr const char* kServiceName = "snooker.v1.ShotPlanner";

class Server {
 public:
  /// Starts listening on `address` ("host:port"; port 0 picks a free port).
  /// Returns nullptr and sets `error` when the address cannot be bound.
  static std::unique_ptr<Server> Start(const std::string& address, std::string* error);

  /// The port actually bound.
  int port() const { return port_; }
  /// Blocks until Shutdown() is called from another thread or a signal handler.
  void Wait() { server_->Wait(); }
  void Shutdown() { server_->Shutdown(); }

 private:
  Server() = default;
  ShotPlannerService service_;
  std::unique_ptr<grpc::Server> server_;
  int port_ = 0;
};

}  // namespace snooker::server
