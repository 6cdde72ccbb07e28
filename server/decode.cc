#include "server/decode.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/stubs/logging.h>
#include <google/protobuf/unknown_field_set.h>

#include <string>

#include "server/limits.h"

namespace snooker::server {

ApiStatus ParseRequest(std::string_view bytes, google::protobuf::Message* message) {
  message->Clear();
  const std::string what = message->GetDescriptor()->full_name() + " (" +
                           std::to_string(bytes.size()) + " bytes)";
  if (bytes.size() > limits::kMaxRequestBytes) {
    return {ApiStatus::Code::kResourceExhausted,
            "the request " + what + " is larger than " + std::to_string(limits::kMaxRequestBytes) +
                " bytes"};
  }
  const int size = static_cast<int>(bytes.size());
  {
    // Protobuf logs a line on stderr for each string that is not UTF-8: a client
    // could fill the server's log with them. The status says it instead.
    google::protobuf::LogSilencer quiet;
    if (message->ParseFromArray(bytes.data(), size)) return ApiStatus::Ok();
  }
  message->Clear();
  // Why: bytes that are wire format but not this message (a nested message that does
  // not parse, a string that is not UTF-8) still parse as a set of unknown fields. (A
  // field of an unexpected wire type is kept as an unknown field: not an error.)
  google::protobuf::UnknownFieldSet wire;
  const bool wire_format = wire.ParseFromArray(bytes.data(), size);
  return ApiStatus::Invalid(
      "the request is not a valid " + what + ": " +
      (wire_format ? "a nested message does not parse, or a string field is not valid UTF-8"
                   : "the bytes are not Protocol Buffers wire format (truncated, or a bad tag "
                     "or length)"));
}

}  // namespace snooker::server
