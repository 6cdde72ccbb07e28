#include "server/connect.h"

#include <google/protobuf/util/json_util.h>

#include <array>
#include <utility>

#include "server/calibrate_api.h"
#include "server/call_cost.h"
#include "server/decode.h"
#include "server/json_input.h"
#include "server/limits.h"
#include "server/metrics.h"

namespace snooker::server::connect {
namespace {

// The media type of a Content-Type: its text before any parameter, without spaces,
// in lower case.
std::string MediaType(std::string_view content_type) {
  const std::size_t semicolon = content_type.find(';');
  std::string_view type = content_type.substr(0, semicolon);
  while (!type.empty() && (type.front() == ' ' || type.front() == '\t')) type.remove_prefix(1);
  while (!type.empty() && (type.back() == ' ' || type.back() == '\t')) type.remove_suffix(1);
  std::string out(type);
  for (char& c : out) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return out;
}

// The length of the UTF-8 sequence at s[i] (1 to 4), or 0 when it is not valid
// UTF-8 (overlong forms and surrogates are not checked: the text is ours or already
// parsed by Protobuf, which checks them).
std::size_t Utf8Length(std::string_view s, std::size_t i) {
  const auto c = static_cast<unsigned char>(s[i]);
  const std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return 0;
  }
  return n;
}

// `text` as a JSON string literal, quotes included; bytes that are not UTF-8 become
// U+FFFD.
std::string JsonString(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      out += "\\u00";
      out += kHex[c >> 4];
      out += kHex[c & 0xF];
    } else if (const std::size_t n = Utf8Length(text, i); n > 0) {
      out.append(text.substr(i, n));
      i += n;
      continue;
    } else {
      out += "\\ufffd";
    }
    ++i;
  }
  return out + "\"";
}

std::string ErrorObject(const Error& error) {
  return "{\"code\": " + JsonString(error.code) + ", \"message\": " + JsonString(error.message) + "}";
}

// A message in one line and at most limits::kMaxMessageBytes.
std::string OneLine(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  if (text.size() > limits::kMaxMessageBytes) text.resize(limits::kMaxMessageBytes);
  return text;
}

// Decode, run, encode: one unary operation of api.h or calibrate_api.h.
template <typename Request, typename Response,
          ApiStatus (*Operation)(const Request&, Response*, const CallLimits&)>
ApiStatus RunUnary(std::string_view bytes, Codec codec, const CallLimits& limits, const PlanControl&,
                   std::string* out, CallCost* cost) {
  Request request;
  if (ApiStatus st = DecodeRequest(bytes, codec, &request); !st.ok()) return st;
  Response response;
  if (ApiStatus st = Operation(request, &response, limits); !st.ok()) return st;
  *cost = CostOf(response);
  return EncodeResponse(response, codec, out);
}

ApiStatus RunPlan(std::string_view bytes, Codec codec, const CallLimits&, const PlanControl& control,
                  std::string* out, CallCost* cost) {
  v1::PlanRequest request;
  if (ApiStatus st = DecodeRequest(bytes, codec, &request); !st.ok()) return st;
  v1::PlanResponse response;
  ApiStatus st = server::Plan(request, &response, control);
  *cost = CostOf(response);
  if (!st.ok()) return st;
  return EncodeResponse(response, codec, out);
}

constexpr std::array<UnaryProcedure, 5> kUnary{{
    {"Collide", false, &RunUnary<v1::CollideRequest, v1::CollideResponse, &server::Collide>},
    {"Simulate", false, &RunUnary<v1::SimulateRequest, v1::SimulateResponse, &server::Simulate>},
    {"GetModel", false, &RunUnary<v1::GetModelRequest, v1::GetModelResponse, &server::GetModel>},
    {"Plan", true, &RunPlan},
    {"Calibrate", false, &RunUnary<v1::CalibrateRequest, v1::CalibrateResponse, &server::Calibrate>},
}};

}  // namespace

std::optional<Codec> UnaryCodec(std::string_view content_type) {
  const std::string type = MediaType(content_type);
  if (type == "application/json") return Codec::kJson;
  if (type == "application/proto") return Codec::kProto;
  return std::nullopt;
}

std::optional<Codec> StreamingCodec(std::string_view content_type) {
  const std::string type = MediaType(content_type);
  if (type == "application/connect+json") return Codec::kJson;
  if (type == "application/connect+proto") return Codec::kProto;
  return std::nullopt;
}

const char* UnaryContentType(Codec codec) {
  return codec == Codec::kJson ? "application/json" : "application/proto";
}

const char* StreamingContentType(Codec codec) {
  return codec == Codec::kJson ? "application/connect+json" : "application/connect+proto";
}

Error ErrorOf(const ApiStatus& status) {
  switch (status.code) {
    case ApiStatus::Code::kInvalidArgument: return {"invalid_argument", 400, status.message};
    case ApiStatus::Code::kResourceExhausted: return {"resource_exhausted", 429, status.message};
    case ApiStatus::Code::kDeadlineExceeded: return {"deadline_exceeded", 504, status.message};
    case ApiStatus::Code::kCancelled: return {"canceled", 499, status.message};
    case ApiStatus::Code::kInternal: return {"internal", 500, status.message};
    case ApiStatus::Code::kOk: break;
  }
  return {"unknown", 500, status.message};
}

Error Unimplemented(std::string message, int http_status) {
  return {"unimplemented", http_status, std::move(message)};
}

Error Unavailable(std::string message) { return {"unavailable", 503, std::move(message)}; }

std::string ErrorJson(const Error& error) { return ErrorObject(error); }

std::string EndStreamJson(const std::optional<Error>& error) {
  return error ? "{\"error\": " + ErrorObject(*error) + "}" : "{}";
}

std::string Envelope(std::uint8_t flags, std::string_view message) {
  const auto n = static_cast<std::uint32_t>(message.size());
  std::string out;
  out.reserve(kEnvelopePrefixBytes + message.size());
  out += static_cast<char>(flags);
  for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((n >> shift) & 0xFF);
  out.append(message);
  return out;
}

ApiStatus OpenEnvelope(std::string_view body, std::string_view* message) {
  if (body.size() < kEnvelopePrefixBytes) {
    return ApiStatus::Invalid("the streaming request has " + std::to_string(body.size()) +
                              " bytes: not an envelope (a flag byte, a 4-byte big-endian length, "
                              "the message)");
  }
  const auto flags = static_cast<std::uint8_t>(body[0]);
  std::uint32_t length = 0;
  for (std::size_t i = 1; i < kEnvelopePrefixBytes; ++i) {
    length = (length << 8) | static_cast<unsigned char>(body[i]);
  }
  const std::size_t rest = body.size() - kEnvelopePrefixBytes;
  if (flags != 0) {
    return ApiStatus::Invalid("the request's envelope has flags " + std::to_string(flags) +
                              ": a request is one uncompressed message (flags 0)");
  }
  if (length != rest) {
    return ApiStatus::Invalid("the request's envelope says " + std::to_string(length) +
                              " bytes but " + std::to_string(rest) +
                              " follow: a PlanStream request is exactly one message");
  }
  *message = body.substr(kEnvelopePrefixBytes);
  return ApiStatus::Ok();
}

ApiStatus ParseTimeout(std::string_view value, std::chrono::milliseconds* timeout) {
  bool digits = !value.empty() && value.size() <= 10;
  std::int64_t ms = 0;
  for (const char c : value) {
    digits = digits && c >= '0' && c <= '9';
    if (digits) ms = ms * 10 + (c - '0');
  }
  if (!digits || ms == 0) {
    return ApiStatus::Invalid("Connect-Timeout-Ms '" + OneLine(std::string(value.substr(0, 32))) +
                              "' is not a positive integer of at most 10 digits (milliseconds)");
  }
  *timeout = std::chrono::milliseconds(ms);
  return ApiStatus::Ok();
}

ApiStatus DecodeRequest(std::string_view bytes, Codec codec, google::protobuf::Message* message) {
  if (codec == Codec::kProto) return ParseRequest(bytes, message);
  message->Clear();
  const std::string type = message->GetDescriptor()->full_name();
  if (bytes.size() > limits::kMaxRequestBytes) {
    return {ApiStatus::Code::kResourceExhausted,
            "the request " + type + " (" + std::to_string(bytes.size()) + " bytes) is larger than " +
                std::to_string(limits::kMaxRequestBytes) + " bytes"};
  }
  if (bytes.find_first_not_of(" \t\r\n") == std::string_view::npos) return ApiStatus::Ok();  // {}
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  const auto status = google::protobuf::util::JsonStringToMessage(
      google::protobuf::StringPiece(bytes.data(), bytes.size()), message, options);
  if (status.ok()) return ApiStatus::Ok();
  message->Clear();
  if (const std::optional<JsonSyntaxError> e = FindJsonSyntaxError(bytes)) {
    return ApiStatus::Invalid(OneLine("the request is not JSON: " + LineColumnText(*e)));
  }
  return ApiStatus::Invalid(OneLine("the request is not a " + type + " in Protobuf's JSON form: " +
                                    std::string(status.message())));
}

ApiStatus EncodeResponse(const google::protobuf::Message& message, Codec codec, std::string* out) {
  if (message.ByteSizeLong() > limits::kMaxResponseBytes) {
    return {ApiStatus::Code::kResourceExhausted,
            "the answer would be larger than " + std::to_string(limits::kMaxResponseBytes) +
                " bytes; ask for less"};
  }
  out->clear();
  if (codec == Codec::kProto) {
    if (message.SerializeToString(out)) return ApiStatus::Ok();
    return {ApiStatus::Code::kInternal, "cannot serialise the answer"};
  }
  google::protobuf::util::JsonPrintOptions options;
  options.always_print_primitive_fields = true;
  const auto status = google::protobuf::util::MessageToJsonString(message, out, options);
  if (status.ok()) return ApiStatus::Ok();
  return {ApiStatus::Code::kInternal, "cannot write the answer as JSON: " + std::string(status.message())};
}

const UnaryProcedure* FindUnary(std::string_view name) {
  for (const UnaryProcedure& p : kUnary) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

const std::string& ProcedureNames() {
  static const std::string names = [] {
    std::string joined;
    for (const char* name : kMethodNames) joined += (joined.empty() ? "" : ", ") + std::string(name);
    return joined;
  }();
  return names;
}

ApiStatus PlanStream(std::string_view bytes, Codec codec, PlanControl control,
                     const std::function<void(std::string envelope)>& progress,
                     std::string* final_envelope, CallCost* cost) {
  v1::PlanRequest request;
  if (ApiStatus st = DecodeRequest(bytes, codec, &request); !st.ok()) return st;
  control.on_progress = [&](const v1::PlanResponse& best) {
    std::string message;
    if (EncodeResponse(best, codec, &message).ok()) progress(Envelope(0, message));
  };
  v1::PlanResponse response;
  ApiStatus st = server::Plan(request, &response, control);
  *cost = CostOf(response);
  if (!st.ok()) return st;
  std::string message;
  if (st = EncodeResponse(response, codec, &message); !st.ok()) return st;
  *final_envelope = Envelope(0, message);
  return ApiStatus::Ok();
}

}  // namespace snooker::server::connect
