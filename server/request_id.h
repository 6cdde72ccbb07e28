// Request ids: the name a call goes by in the server's log and in its answer, so
// that a client's record of a call (the robot's log, a trainer app's error report)
// and the server's line for it can be found from each other. A client names its call
// with the `x-request-id` metadata (gRPC) or the `X-Request-Id` header (HTTP); the
// server keeps a name it can print safely and otherwise names the call itself, and
// sends the name back the same way.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace snooker::server {

/// The gRPC metadata key (lower case, as gRPC requires) and the HTTP header.
inline constexpr std::string_view kRequestIdMetadata = "x-request-id";
inline constexpr std::string_view kRequestIdHeader = "X-Request-Id";
/// The longest id kept from a client, bytes.
inline constexpr std::size_t kMaxRequestIdBytes = 128;

/// True for an id the log can carry as it is: 1 to kMaxRequestIdBytes letters, digits
/// and "-_.:/+=@" (a UUID, a ULID, "robot-3:shot-412"); no space, quote or control
/// character that would break the line.
bool IsPrintableRequestId(std::string_view id);

/// A new id: 16 lower-case hex digits, distinct for every call of this process (a
/// bijective mix of a counter from a random start), so ids of two processes are
/// unlikely to meet.
std::string NewRequestId();

/// The id a call goes by: `given` when printable, otherwise (none sent, or one the
/// log could not carry) a new one.
std::string RequestIdFor(std::string_view given);

}  // namespace snooker::server
