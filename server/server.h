// Building and running the gRPC server: the ShotPlanner service, the standard
// health service (grpc.health.v1) and server reflection.
#pragma once

#include <chrono>
#include <memory>
#include <mutex>
#include <string>

#include <grpcpp/grpcpp.h>

#include "server/grpc_service.h"
#include "server/limits.h"

namespace snooker::server {

/// The health-check service name under which ShotPlanner reports SERVING.
inline constexpr const char* kServiceName = "snooker.v1.ShotPlanner";

struct ServerOptions : ServiceOptions {
  /// "host:port"; port 0 picks a free port.
  std::string address = "127.0.0.1:50051";
  /// Shutdown(): how long calls in flight may finish before they are cancelled.
  std::chrono::milliseconds shutdown_grace = limits::kDefaultShutdownGrace;
};

class Server {
 public:
  /// Starts serving. Returns nullptr and sets `error` when the address cannot be bound.
  static std::unique_ptr<Server> Start(const ServerOptions& options, std::string* error);
  /// The same with default options on `address`.
  static std::unique_ptr<Server> Start(const std::string& address, std::string* error);

  ~Server();  // Shutdown(0) if not shut down

  /// The port actually bound.
  int port() const { return port_; }
  /// Blocks until Shutdown() is called from another thread.
  void Wait() { server_->Wait(); }
  /// Stops accepting calls, lets the calls in flight (running or queued) finish for
  /// `grace`, then cancels the rest (they stop at their next interrupt check and
  /// answer CANCELLED), and returns once every call has its answer and the workers
  /// have stopped. Later calls do nothing.
  void Shutdown(std::chrono::milliseconds grace);
  /// Shutdown with the options' shutdown_grace.
  void Shutdown() { Shutdown(shutdown_grace_); }

  CallCounts counts() const { return service_.counts(); }

 private:
  explicit Server(const ServerOptions& options);
  ShotPlannerService service_;
  std::unique_ptr<grpc::Server> server_;
  std::chrono::milliseconds shutdown_grace_;
  std::once_flag shutdown_once_;
  int port_ = 0;
};

}  // namespace snooker::server
