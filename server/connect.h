// The Connect protocol (https://connectrpc.com/docs/protocol) for the service, apart
// from any HTTP library: which procedures there are, the codecs (Protobuf's JSON
// mapping and binary), Connect's error codes and their HTTP statuses, the envelopes
// of a streaming call, and the Connect-Timeout-Ms header. server/http_server.cc puts
// it on the wire; every operation is api.h's, plan_api.h's and calibrate_api.h's, as
// the gRPC service's are.
//
//  * Unary calls (Collide, Simulate, GetModel, Plan, Calibrate): POST with
//    Content-Type application/json (the request's JSON) or application/proto (its
//    binary form); the answer is 200 with the response in the same codec, or an
//    error status with the body {"code": "invalid_argument", "message": "..."}.
//  * PlanStream: POST with Content-Type application/connect+json (or
//    connect+proto), the request in one envelope (a flag byte, a 4-byte big-endian
//    length, the message); the answer is 200 with an envelope per message and an
//    end-of-stream envelope (flag 0x02): {} or {"error": {"code", "message"}}.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include <google/protobuf/message.h>

#include "server/api.h"
#include "server/api_status.h"
#include "server/call_cost.h"
#include "server/plan_api.h"

namespace snooker::server::connect {

/// The path prefix of the service's procedures: "/snooker.v1.ShotPlanner/Plan".
inline constexpr std::string_view kServicePath = "/snooker.v1.ShotPlanner/";

/// How a message is written: Protobuf's JSON mapping, or its binary form.
enum class Codec { kJson, kProto };

/// The codec of a unary call's Content-Type ("application/json", "application/proto",
/// parameters such as "; charset=utf-8" allowed), or none.
std::optional<Codec> UnaryCodec(std::string_view content_type);
/// The same for a streaming call ("application/connect+json", "application/connect+proto").
std::optional<Codec> StreamingCodec(std::string_view content_type);
/// The Content-Type of a unary answer in `codec`, and of a stream's.
const char* UnaryContentType(Codec codec);
const char* StreamingContentType(Codec codec);

/// A Connect error: its code ("invalid_argument"), the HTTP status a unary call
/// answers with it, and the message.
struct Error {
  std::string_view code;
  int http_status = 500;
  std::string message;
};
/// The Connect error of a status that is not OK: canceled 499, invalid_argument
/// 400, deadline_exceeded 504, resource_exhausted 429, internal 500.
Error ErrorOf(const ApiStatus& status);
/// What only the HTTP transport answers: a procedure or codec it does not serve
/// (unimplemented, 501 unless the caller says otherwise), or a server shutting down
/// (unavailable, 503).
Error Unimplemented(std::string message, int http_status = 501);
Error Unavailable(std::string message);

/// {"code": "...", "message": "..."}: a unary call's error body.
std::string ErrorJson(const Error& error);
/// A streaming call's end: {} for OK, else {"error": {"code": "...", "message": "..."}}.
std::string EndStreamJson(const std::optional<Error>& error);

/// Envelope flags: the message is compressed (not used here), or is the end of the stream.
inline constexpr std::uint8_t kCompressedFlag = 0x01;
inline constexpr std::uint8_t kEndStreamFlag = 0x02;
/// Bytes of an envelope's prefix (the flag byte and the length).
inline constexpr std::size_t kEnvelopePrefixBytes = 5;
/// `message` in an envelope with `flags`.
std::string Envelope(std::uint8_t flags, std::string_view message);
/// The one message of a streaming request's body: exactly one envelope, not
/// compressed, not marked as the end of the stream. INVALID_ARGUMENT saying what is
/// wrong otherwise.
ApiStatus OpenEnvelope(std::string_view body, std::string_view* message);

/// The Connect-Timeout-Ms header's value: a positive integer of at most 10 digits,
/// ms. INVALID_ARGUMENT naming the header otherwise.
ApiStatus ParseTimeout(std::string_view value, std::chrono::milliseconds* timeout);

/// Reads a request in `codec`. JSON: Protobuf's JSON mapping (lowerCamelCase or the
/// proto's names; an unknown field is an error); INVALID_ARGUMENT names where the
/// text stops being JSON (line and column) or the field Protobuf refuses. Binary:
/// decode.h's ParseRequest. RESOURCE_EXHAUSTED above limits::kMaxRequestBytes.
ApiStatus DecodeRequest(std::string_view bytes, Codec codec, google::protobuf::Message* message);
/// Writes a response in `codec` (JSON: every field, default values too, as the
/// command line's --json prints). RESOURCE_EXHAUSTED when the message is larger than
/// limits::kMaxResponseBytes (its binary size, as gRPC measures it).
ApiStatus EncodeResponse(const google::protobuf::Message& message, Codec codec, std::string* out);

/// One unary procedure: decode, one operation, encode. `plan` is set (and used) for
/// Plan only; `cost` gets the work done, for the log.
struct UnaryProcedure {
  std::string_view name;  ///< "Collide", ...
  bool is_plan = false;   ///< counted among the server's plans (--max-plans)
  ApiStatus (*run)(std::string_view request, Codec codec, const CallLimits& limits,
                   const PlanControl& plan, std::string* response, CallCost* cost);
};
/// The unary procedure of this name ("Plan"), or null.
const UnaryProcedure* FindUnary(std::string_view name);
/// The name of the server-streaming procedure.
inline constexpr std::string_view kPlanStream = "PlanStream";
/// Every procedure's name, comma-separated (for a message about an unknown one): the
/// service's methods, metrics.h's kMethodNames.
const std::string& ProcedureNames();

/// PlanStream's work: decodes the request, plans with `control` (whose on_progress
/// it sets: each progress message goes to `progress` in an envelope) and writes the
/// final answer's envelope into `final_envelope` when the status is OK.
ApiStatus PlanStream(std::string_view request, Codec codec, PlanControl control,
                     const std::function<void(std::string envelope)>& progress,
                     std::string* final_envelope, CallCost* cost);

}  // namespace snooker::server::connect
