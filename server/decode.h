// Request bytes to messages, with a reason when they are not one. gRPC's generated
// synchronous service answers INTERNAL with an empty message when a request does
// not parse; the service takes the raw bytes instead (grpc_service.h) and parses
// them here, as does the request fuzz target (fuzz/request_fuzz.cc).
#pragma once

#include <string_view>

#include <google/protobuf/message.h>

#include "server/api_status.h"

namespace snooker::server {

/// Parses `bytes` into `message` (cleared first). INVALID_ARGUMENT naming the message
/// type, the size and the reason when they are not a valid message of that type;
/// RESOURCE_EXHAUSTED above limits::kMaxRequestBytes.
ApiStatus ParseRequest(std::string_view bytes, google::protobuf::Message* message);

}  // namespace snooker::server
