#include "server/server.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>

namespace snooker::server {

Server::Server(const ServerOptions& options)
    : service_(options), shutdown_grace_(options.shutdown_grace) {}

std::unique_ptr<Server> Server::Start(const std::string& address, std::string* error) {
  ServerOptions options;
  options.address = address;
  return Start(options, error);
}

std::unique_ptr<Server> Server::Start(const ServerOptions& options, std::string* error) {
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  std::unique_ptr<Server> s(new Server(options));
  grpc::ServerBuilder builder;
  builder.AddListeningPort(options.address, grpc::InsecureServerCredentials(), &s->port_);
  builder.RegisterService(&s->service_);
  builder.SetMaxReceiveMessageSize(static_cast<int>(limits::kMaxRequestBytes));
  // The API bounds its answers below this (limits::kMaxResponseBytes); this is the backstop.
  builder.SetMaxSendMessageSize(static_cast<int>(limits::kMaxResponseBytes + 4096));
  s->server_ = builder.BuildAndStart();
  if (s->server_ == nullptr || s->port_ == 0) {
    if (error != nullptr) *error = "cannot listen on " + options.address;
    s->server_.reset();
    return nullptr;
  }
  s->server_->GetHealthCheckService()->SetServingStatus(kServiceName, true);
  return s;
}

Server::~Server() { Shutdown(std::chrono::milliseconds(0)); }

void Server::Shutdown(std::chrono::milliseconds grace) {
  std::call_once(shutdown_once_, [&] {
    if (server_) {
      server_->GetHealthCheckService()->SetServingStatus(kServiceName, false);
      // Waits for calls in flight until the deadline, then cancels them and waits
      // for their answers (each stops at its next interrupt check).
      server_->Shutdown(std::chrono::system_clock::now() + grace);
    }
    service_.StopWorkers();
  });
}

}  // namespace snooker::server
