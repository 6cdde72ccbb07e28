#include "server/server.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>

namespace snooker::server {

std::unique_ptr<Server> Server::Start(const std::string& address, std::string* error) {
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  std::unique_ptr<Server> s(new Server());
  grpc::ServerBuilder builder;
  builder.AddListeningPort(address, grpc::InsecureServerCredentials(), &s->port_);
  builder.RegisterService(&s->service_);
  s->server_ = builder.BuildAndStart();
  if (s->server_ == nullptr || s->port_ == 0) {
    if (error != nullptr) *error = "cannot listen on " + address;
    return nullptr;
  }
  s->server_->GetHealthCheckService()->SetServingStatus(kServiceName, true);
  return s;
}

}  // namespace snooker::server
