// Status of an API call, independent of the transport. The gRPC adapter maps it to
// grpc::Status in exactly one function (server/grpc_service.cc); the command line
// prints it.
#pragma once

#include <string>
#include <utility>

namespace snooker::server {

struct ApiStatus {
  enum class Code {
    kOk,
    kInvalidArgument,    // the request names a bad value; the message says which
    kResourceExhausted,  // a solver reached its step cap, or the answer would be too large
    kDeadlineExceeded,   // the call's wall-time bound passed (client deadline or server maximum)
    kCancelled,          // the caller cancelled the call (or the server is shutting down)
    kInternal,           // a broken invariant; a bug
  };
  Code code = Code::kOk;
  std::string message;

  bool ok() const { return code == Code::kOk; }
  static ApiStatus Ok() { return {}; }
  static ApiStatus Invalid(std::string m) { return {Code::kInvalidArgument, std::move(m)}; }
};

/// "OK", "INVALID_ARGUMENT", ... (gRPC's names).
const char* ToString(ApiStatus::Code code);

}  // namespace snooker::server
