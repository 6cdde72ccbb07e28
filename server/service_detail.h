// Helpers the gRPC adapter's methods share (grpc_service.cc, grpc_plan.cc); not an
// interface of the library.
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <cstddef>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>

#include "server/api_status.h"

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
  std::string request_id;  ///< the call's name in the log and the answer (request_id.h)
  std::chrono::steady_clock::time_point arrival;
  std::chrono::steady_clock::time_point deadline;
  std::chrono::system_clock::time_point client_deadline;
  std::size_t request_bytes = 0;
};
/// Fills `info` for a call that just arrived, and names it in the answer's initial
/// metadata with its request id (the client's, or a new one).
void Arrived(grpc::CallbackServerContext* context, const grpc::ByteBuffer* request,
             std::chrono::milliseconds max_call, CallInfo* info);

/// Runs `body` (returning an ApiStatus) and maps what it throws: out of memory to
/// RESOURCE_EXHAUSTED, anything else to INTERNAL. No exception leaves.
template <typename Body>
ApiStatus Guarded(Body&& body) noexcept {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    return {ApiStatus::Code::kResourceExhausted, "out of memory"};
  } catch (const std::exception& e) {
    return {ApiStatus::Code::kInternal, std::string("internal error: ") + e.what()};
  } catch (...) {
    return {ApiStatus::Code::kInternal, "internal error"};
  }
}

/// The answer to a call the server cannot even take (out of memory on arrival).
ApiStatus CannotTake(const std::exception& e);

/// A call about to start on a worker after waiting for one: DEADLINE_EXCEEDED when
/// its deadline passed meanwhile, CANCELLED when the client cancelled it; nullopt
/// when it may start. `what` names the work ("the call", "the plan").
std::optional<ApiStatus> RefuseLateStart(const CallInfo& call, bool cancelled, const char* what);

/// gRPC cancels a call when the client's deadline passes: a CANCELLED status then
/// is the deadline's, and says so.
ApiStatus DeadlineIfClientLate(ApiStatus status, const CallInfo& call);

/// One call's bytes as one contiguous string.
bool Flatten(const grpc::ByteBuffer& buffer, std::string* out);

}  // namespace snooker::server::service_detail
