// Helpers the gRPC adapter's methods share (grpc_service.cc, grpc_plan.cc); not an
// interface of the library.
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <string>

namespace snooker::server::service_detail {

/// The call's deadline on the steady clock: the client's, or arrival + max_call when
/// that is earlier (or the client set none).
std::chrono::steady_clock::time_point CallDeadline(std::chrono::system_clock::time_point client,
                                                   std::chrono::steady_clock::time_point arrival,
                                                   std::chrono::milliseconds max_call);

/// The client's deadline has passed (within gRPC's timer grain).
bool ClientDeadlinePassed(std::chrono::system_clock::time_point client);

/// physics::Interrupt's poll for a grpc::CallbackServerContext.
bool IsCancelled(void* context);

/// One call's bytes as one contiguous string.
bool Flatten(const grpc::ByteBuffer& buffer, std::string* out);

}  // namespace snooker::server::service_detail
