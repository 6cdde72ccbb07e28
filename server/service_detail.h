// Helpers the gRPC adapter's methods share (grpc_service.cc, grpc_plan.cc); not an
// interface of the library.
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <cstddef>
#include <new>
#include <stdexcept>
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

/// What every call keeps of its arrival: the context, the request, who sent it, when,
/// and by when it must end (the client's deadline or arrival + max_call, whichever is
/// first).
struct CallInfo {
  grpc::CallbackServerContext* context = nullptr;
  const grpc::ByteBuffer* request = nullptr;
  std::string peer;
  std::chrono::steady_clock::time_point arrival;
  std::chrono::steady_clock::time_point deadline;
  std::chrono::system_clock::time_point client_deadline;
  std::size_t request_bytes = 0;
};
/// Fills `info` for a call that just arrived.
void Arrived(grpc::CallbackServerContext* context, const grpc::ByteBuffer* request,
             std::chrono::milliseconds max_call, CallInfo* info);

/// Runs `body` (returning a grpc::Status) and maps what it throws: out of memory to
/// RESOURCE_EXHAUSTED, anything else to INTERNAL. No exception leaves.
template <typename Body>
grpc::Status Guarded(Body&& body) noexcept {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED, "out of memory"};
  } catch (const std::exception& e) {
    return {grpc::StatusCode::INTERNAL, std::string("internal error: ") + e.what()};
  } catch (...) {
    return {grpc::StatusCode::INTERNAL, "internal error"};
  }
}

/// One call's bytes as one contiguous string.
bool Flatten(const grpc::ByteBuffer& buffer, std::string* out);

}  // namespace snooker::server::service_detail
