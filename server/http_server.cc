#include "server/http_server.h"

#include <openssl/ssl.h>
#include <sys/socket.h>

#include <algorithm>
#include <condition_variable>
#include <functional>
#include <future>
#include <limits>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <system_error>
#include <thread>
#include <utility>

#include "server/address.h"
#include "server/connect.h"
#include "server/limits.h"
#include "server/log_line.h"
#include "server/metrics.h"
#include "server/request_id.h"
#include "server/server.h"
#include "server/tls_context.h"
#include "server/web_files.h"
#include "server/worker_pool.h"

// Last: through <resolv.h> it defines the macro _res, a name Eigen's headers use.
#include <httplib.h>

namespace snooker::server {
namespace {

using Clock = std::chrono::steady_clock;
using connect::Codec;

// What the connection's thread knows of the request it serves: when it arrived, and
// whether its call wrote its own log line (the service's, as a gRPC call's).
thread_local Clock::time_point t_arrival;
thread_local bool t_logged = false;
// Its request id (request_id.h), empty before the router has seen it.
thread_local std::string t_request_id;

// Paths longer than this are refused before routing (the router's regular
// expressions then only see short ones).
constexpr std::size_t kMaxPathBytes = 1024;

// "ipv4:127.0.0.1:51000" or "ipv6:[::1]:51000", as gRPC names its peers.
std::string PeerOf(const httplib::Request& req) {
  if (req.remote_addr.empty()) return "unknown";  // a request line that did not parse
  const bool v6 = req.remote_addr.find(':') != std::string::npos;
  return (v6 ? "ipv6:[" + req.remote_addr + "]" : "ipv4:" + req.remote_addr) + ":" +
         std::to_string(req.remote_port);
}

// Printable ASCII of `text`, at most `max` bytes: for a log line.
std::string Printable(std::string_view text, std::size_t max = 200) {
  std::string out;
  for (const char c : text.substr(0, max)) out += (c >= 0x20 && c < 0x7F) ? c : '?';
  if (text.size() > max) out += "...";
  return out;
}

// --- Answers -------------------------------------------------------------------------

// What an answer of cpp-httplib's own with `status` refused, for its body.
std::string RefusalMessage(const httplib::Request& req, int status) {
  switch (status) {
    case 400:
      return req.method.empty() ? "the request is not HTTP/1.x that this server reads"
                                : "method " + Printable(req.method, 16) +
                                      " is not served here (GET, HEAD, POST, OPTIONS), or the request does not read";
    case 413: return "the request body is larger than " + std::to_string(limits::kMaxRequestBytes) + " bytes";
    case 414:
      return "the request's URI is longer than " + std::to_string(CPPHTTPLIB_REQUEST_URI_MAX_LENGTH) + " bytes";
    default: return "refused with HTTP status " + std::to_string(status);
  }
}

void ReplyText(httplib::Response& res, int status, const std::string& text) {
  res.status = status;
  res.set_content(text + "\n", "text/plain; charset=utf-8");
}

// A unary call's error: its HTTP status and the Connect error body.
void ReplyError(httplib::Response& res, const connect::Error& error) {
  res.status = error.http_status;
  res.set_content(connect::ErrorJson(error), "application/json");
}

// A streaming call that ends before it starts: 200, and the end-of-stream message
// with the error.
void ReplyEndStream(httplib::Response& res, Codec codec, const connect::Error& error) {
  res.status = 200;
  res.set_content(connect::Envelope(connect::kEndStreamFlag, connect::EndStreamJson(error)),
                  connect::StreamingContentType(codec));
}

void ReplyNotAllowed(httplib::Response& res, const char* allow, bool rpc) {
  res.set_header("Allow", allow);
  if (rpc) {
    ReplyError(res, connect::Unimplemented("a procedure takes POST", 405));
  } else {
    ReplyText(res, 405, std::string("method not allowed: ") + allow);
  }
}

// The request's body, at most `limit` bytes (decompressed): RESOURCE_EXHAUSTED beyond,
// INVALID_ARGUMENT when it does not read. A body left unread closes the connection.
ApiStatus ReadBody(const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& reader,
                   std::size_t limit, std::string* body) {
  // The body's framing (RFC 9112, 6.3): chunked, or one Content-Length of digits, or
  // neither, and then there is no body. A length given twice or not in digits leaves
  // where the request ends unknown (a proxy may have read it otherwise): refused.
  if (!req.has_header("Transfer-Encoding")) {
    const std::size_t lengths = req.get_header_value_count("Content-Length");
    if (lengths == 0) return ApiStatus::Ok();
    const std::string length = req.get_header_value("Content-Length");
    const bool digits = !length.empty() && length.size() <= 19 &&
                        std::all_of(length.begin(), length.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (lengths > 1 || !digits) {
      res.set_header("Connection", "close");
      return ApiStatus::Invalid(lengths > 1 ? "Content-Length is given " + std::to_string(lengths) + " times"
                                            : "Content-Length '" + Printable(length, 40) +
                                                  "' is not a whole number of bytes");
    }
  }
  bool too_large = false;
  const bool read = reader([&](const char* data, std::size_t n) {
    if (body->size() + n > limit) {
      too_large = true;
      return false;
    }
    body->append(data, n);
    return true;
  });
  if (read) return ApiStatus::Ok();
  body->clear();
  res.set_header("Connection", "close");
  if (too_large || res.status == 413) {
    return {ApiStatus::Code::kResourceExhausted,
            "the request body is larger than " + std::to_string(limit) + " bytes"};
  }
  if (res.status == 415) {
    return ApiStatus::Invalid("Content-Encoding '" + Printable(req.get_header_value("Content-Encoding"), 40) +
                              "' is not one of identity, gzip, deflate, br");
  }
  return ApiStatus::Invalid("the request body does not read (it ended early, or its chunks are malformed)");
}

// The call's own checks of its headers: the protocol version and the timeout.
ApiStatus CheckCallHeaders(const httplib::Request& req, std::optional<std::chrono::milliseconds>* timeout) {
  if (req.has_header("Connect-Protocol-Version") && req.get_header_value("Connect-Protocol-Version") != "1") {
    return ApiStatus::Invalid("Connect-Protocol-Version '" +
                              Printable(req.get_header_value("Connect-Protocol-Version"), 40) +
                              "' is not 1");
  }
  if (req.has_header("Connect-Timeout-Ms")) {
    std::chrono::milliseconds ms{};
    if (ApiStatus st = connect::ParseTimeout(req.get_header_value("Connect-Timeout-Ms"), &ms); !st.ok()) {
      return st;
    }
    *timeout = ms;
  }
  return ApiStatus::Ok();
}

// A unary call's answer, from its worker to the connection's thread.
struct UnaryResult {
  std::mutex mu;
  std::condition_variable done_cv;
  bool done = false;
  ApiStatus status;
  std::string body;
};

// A stream's messages, from the planner (and its worker) to the connection's thread,
// which writes them as the gRPC PlanStream's reactor does: a progress message that
// finds the writer idle is the next write; one that comes while a write is in
// flight waits, and only the newest does (an older one is dropped); the final answer
// drops the one waiting, and is followed by the end of the stream.
struct StreamState {
  ShotPlannerService* service = nullptr;
  std::mutex mu;
  std::condition_variable changed;
  std::optional<std::string> next;     // the next write
  std::optional<std::string> pending;  // the newest progress while a write is in flight
  bool writing = false;
  std::string final_envelope;  // set by the worker before `completed`
  bool completed = false;
  ApiStatus status;

  void Progress(std::string envelope) {
    std::lock_guard<std::mutex> lock(mu);
    if (completed) return;
    if (!writing && !next) {
      next = std::move(envelope);
    } else {
      if (pending) service->CountProgress(false);
      pending = std::move(envelope);
    }
    changed.notify_all();
  }
  void Complete(const ApiStatus& st) {
    std::lock_guard<std::mutex> lock(mu);
    completed = true;
    status = st;
    if (pending) service->CountProgress(false);  // the final answer supersedes it
    pending.reset();
    changed.notify_all();
  }
  // The connection's thread: waits for the next message and writes it; false when
  // the client is gone. `*progress_sent` says whether a progress message went out
  // (counted by the caller, which knows whether the service is still there).
  bool WriteNext(httplib::DataSink& sink, bool* progress_sent) {
    *progress_sent = false;
    std::unique_lock<std::mutex> lock(mu);
    changed.wait(lock, [this] { return next.has_value() || completed; });
    if (next) {
      const std::string bytes = std::move(*next);
      next.reset();
      writing = true;
      lock.unlock();
      const bool ok = sink.write(bytes.data(), bytes.size());
      lock.lock();
      writing = false;
      next = std::move(pending);
      pending.reset();
      *progress_sent = ok;
      return ok;
    }
    std::string tail = status.ok() ? std::move(final_envelope) : std::string();
    tail += connect::Envelope(connect::kEndStreamFlag,
                              connect::EndStreamJson(status.ok() ? std::nullopt
                                                                 : std::optional(connect::ErrorOf(status))));
    lock.unlock();
    if (!sink.write(tail.data(), tail.size())) return false;
    sink.done();
    return true;
  }
};

}  // namespace

std::string CheckCorsOrigin(std::string_view origin) {
  std::string_view rest = origin;
  if (rest.starts_with("https://")) {
    rest.remove_prefix(8);
  } else if (rest.starts_with("http://")) {
    rest.remove_prefix(7);
  } else {
    return "--cors-origin '" + Printable(origin) +
           "' is not an origin: it starts with http:// or https:// (one origin, no wildcard)";
  }
  const bool host_chars = !rest.empty() && rest.size() <= 260 && std::all_of(rest.begin(), rest.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '-' ||
           c == ':' || c == '[' || c == ']';
  });
  if (!host_chars) {
    return "--cors-origin '" + Printable(origin) +
           "' is not an origin: after the scheme comes a host and an optional port, nothing else "
           "(no path, no '/')";
  }
  return "";
}

std::string CheckHttpOptions(const HttpOptions& options) {
  const std::string what = options.metrics_only ? "metrics" : "HTTP";
  std::string host;
  int port = 0;
  if (!SplitHostPort(options.address, &host, &port)) {
    const std::string why = CheckListenAddress(options.address);
    return what + " address '" + options.address + "': " +
           (why.empty() ? what + " listens on HOST:PORT (not a Unix socket)" : why);
  }
  if (std::string refusal = PlaintextRefusal(options.address, options.tls != nullptr, options.allow_insecure,
                                             "serve " + what);
      !refusal.empty()) {
    return refusal;
  }
  if (!options.cors_origin.empty()) return CheckCorsOrigin(options.cors_origin);
  return "";
}

struct HttpServer::Impl {
  ShotPlannerService* service = nullptr;
  std::string cors_origin;
  bool metrics_only = false;
  std::ostream* log = nullptr;
  bool tls = false;
  std::optional<std::int64_t> certificate_expiry;  // the start's certificate's
  std::shared_ptr<TlsReloader> tls_reloader;       // before http, which calls it
  std::unique_ptr<httplib::Server> http;
  std::thread listener;
  std::future<void> listener_done;
  int port = 0;

  std::mutex mu;
  std::condition_variable idle;
  bool shutting_down = false;
  // Set when the stop gave up on a connection (a client that trickles): the service
  // and the log may be gone before that connection's handlers run to their end, so
  // they no longer touch them, and this object outlives them (HttpServer's destructor).
  bool orphaned = false;
  int service_users = 0;  // handlers in WithService's `use` now
  std::set<std::shared_ptr<ShotPlannerService::TransportCall>> in_flight;
  std::once_flag finished;

  // Runs `use` (brief: it touches the service or the log) unless orphaned; false then.
  // Not under `mu`, so that a log write that stalls holds up no other handler; the
  // stop waits for the uses under way before it orphans.
  template <typename Use>
  bool WithService(Use&& use) {
    {
      std::lock_guard<std::mutex> lock(mu);
      if (orphaned) return false;
      ++service_users;
    }
    struct Leave {
      Impl* impl;
      ~Leave() {
        std::lock_guard<std::mutex> lock(impl->mu);
        if (--impl->service_users == 0) impl->idle.notify_all();
      }
    } leave{this};
    use();
    return true;
  }

  void Configure();
  void ConfigureMetricsOnly();
  void OnGet(const httplib::Request& req, httplib::Response& res);
  void OnBody(const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& reader);
  void OnOptions(const httplib::Request& req, httplib::Response& res);
  void Unary(const connect::UnaryProcedure& procedure, const httplib::Request& req, httplib::Response& res,
             std::string body, const ApiStatus& read);
  void Stream(const httplib::Request& req, httplib::Response& res, std::string body, const ApiStatus& read);
  // A new call in flight, or nullptr once the server shuts down.
  std::shared_ptr<ShotPlannerService::TransportCall> Admit(const httplib::Request& req, std::string_view method,
                                                          std::optional<std::chrono::milliseconds> timeout,
                                                          std::size_t request_bytes, bool is_plan);
  void Release(const std::shared_ptr<ShotPlannerService::TransportCall>& call);
  void Log(const httplib::Request& req, const httplib::Response& res);
  void WriteLine(const httplib::Request& req, const httplib::Response& res, Clock::time_point arrival,
                 const std::string& request_id);
  void Stop(Clock::time_point deadline);
};

namespace {

// The threads that serve the connections, as many as the system starts of the
// kHttpConnectionThreads asked for (httplib's own pool aborted the process when one
// would not start), and with none the listener's own. Stopping runs what is queued.
class ConnectionThreads : public httplib::TaskQueue {
 public:
  ConnectionThreads()
      : pool_(limits::kHttpConnectionThreads, std::numeric_limits<int>::max(),
              WorkerPool::Start::kAsManyAsPossible) {}
  void enqueue(std::function<void()> fn) override { pool_.TrySubmit(std::move(fn)); }
  void shutdown() override { pool_.Stop(); }

 private:
  WorkerPool pool_;
};

// The page's file a GET of `path` serves ("/" is index.html), or nullptr.
const WebFile* WebFileAt(std::string_view path) {
  if (path == "/") return FindWebFile("index.html");
  return path.size() > 1 && path.find('/', 1) == std::string_view::npos ? FindWebFile(path.substr(1)) : nullptr;
}

}  // namespace

void HttpServer::Impl::Configure() {
  httplib::Server& s = *http;
  s.new_task_queue = [] { return new ConnectionThreads(); };
  // SO_REUSEADDR only: cpp-httplib's default also sets SO_REUSEPORT, with which a
  // second server could share the port unnoticed.
  s.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  s.set_payload_max_length(limits::kMaxRequestBytes + connect::kEnvelopePrefixBytes);
  s.set_keep_alive_timeout(limits::kHttpKeepAliveSeconds);
  s.set_keep_alive_max_count(limits::kHttpKeepAliveRequests);
  s.set_read_timeout(limits::kHttpIoTimeoutSeconds);
  s.set_write_timeout(limits::kHttpIoTimeoutSeconds);
  httplib::Headers headers{{"X-Content-Type-Options", "nosniff"}};
  if (!cors_origin.empty()) {
    headers.emplace("Access-Control-Allow-Origin", cors_origin);
    headers.emplace("Access-Control-Expose-Headers", std::string(kRequestIdHeader));
  }
  s.set_default_headers(headers);
  s.set_logger([this](const httplib::Request& req, const httplib::Response& res) { Log(req, res); });
  s.set_pre_routing_handler([](const httplib::Request& req, httplib::Response& res) {
    t_arrival = Clock::now();
    t_logged = false;
    t_request_id = RequestIdFor(req.get_header_value(std::string(kRequestIdHeader).c_str()));
    res.set_header(std::string(kRequestIdHeader), t_request_id);
    if (req.path.size() <= kMaxPathBytes) return httplib::Server::HandlerResponse::Unhandled;
    res.set_header("Connection", "close");
    ReplyText(res, 404, "not found");
    return httplib::Server::HandlerResponse::Handled;
  });
  // What cpp-httplib refuses before any handler runs (a method it does not serve, a
  // request line it cannot read, a URI longer than it reads) comes with an empty body:
  // the answer then says what was refused, as a Connect error on the service's paths
  // and as text elsewhere (a URI too long is refused before its path is read: text).
  // Answers of ours keep their bodies.
  s.set_error_handler(httplib::Server::HandlerWithResponse([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
    const std::string message = RefusalMessage(req, res.status);
    // The request was not read through: nothing after it on the connection can be.
    res.set_header("Connection", "close");
    if (req.path.starts_with(connect::kServicePath)) {
      const std::string_view code = res.status == 413 ? "resource_exhausted" : "invalid_argument";
      res.set_content(connect::ErrorJson({code, res.status, message}), "application/json");
    } else {
      res.set_content(message + "\n", "text/plain; charset=utf-8");
    }
    return httplib::Server::HandlerResponse::Handled;
  }));
  if (metrics_only) return ConfigureMetricsOnly();
  s.Get(".*", [this](const httplib::Request& req, httplib::Response& res) { OnGet(req, res); });
  s.Options(".*", [this](const httplib::Request& req, httplib::Response& res) { OnOptions(req, res); });
  auto body = [this](const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& reader) {
    OnBody(req, res, reader);
  };
  s.Post(".*", body);
  s.Put(".*", body);
  s.Patch(".*", body);
  s.Delete(".*", body);
}

void HttpServer::Impl::ConfigureMetricsOnly() {
  httplib::Server& s = *http;
  auto served = [](const httplib::Request& req) { return req.path == "/metrics" || req.path == "/healthz"; };
  const std::string not_here = "not found: this listener serves GET /metrics and /healthz only";
  s.Get(".*", [this, served, not_here](const httplib::Request& req, httplib::Response& res) {
    if (!served(req)) return ReplyText(res, 404, not_here);
    OnGet(req, res);
  });
  auto other = [served, not_here](const httplib::Request& req, httplib::Response& res) {
    if (!served(req)) return ReplyText(res, 404, not_here);
    ReplyNotAllowed(res, "GET, HEAD", false);
  };
  s.Post(".*", other);
  s.Put(".*", other);
  s.Patch(".*", other);
  s.Delete(".*", other);
  s.Options(".*", other);
}

void HttpServer::Impl::OnGet(const httplib::Request& req, httplib::Response& res) {
  if (req.path == "/healthz") {
    std::lock_guard<std::mutex> lock(mu);
    res.set_header("Cache-Control", "no-store");
    ReplyText(res, shutting_down ? 503 : 200, shutting_down ? "NOT_SERVING" : "SERVING");
    return;
  }
  if (req.path == "/metrics") {
    res.status = 200;
    res.set_header("Cache-Control", "no-store");
    std::string text;
    if (!WithService([&] {  // the reloader logs under the service's lock
          const auto expiry =
              tls_reloader != nullptr ? tls_reloader->Expiry(certificate_expiry) : certificate_expiry;
          text = MetricsText(service->counts(), expiry);
        })) {
      return ReplyText(res, 503, "NOT_SERVING");
    }
    res.set_content(std::move(text), "text/plain; version=0.0.4; charset=utf-8");
    return;
  }
  if (req.path.starts_with(connect::kServicePath)) return ReplyNotAllowed(res, "POST, OPTIONS", true);
  const WebFile* file = WebFileAt(req.path);
  if (file == nullptr) return ReplyText(res, 404, "not found");
  res.status = 200;
  res.set_content(std::string(file->bytes), std::string(file->content_type));
  res.set_header("Cache-Control", "no-cache");
  res.set_header("Content-Security-Policy", "default-src 'self'");
}

void HttpServer::Impl::OnOptions(const httplib::Request& req, httplib::Response& res) {
  const bool rpc = req.path.starts_with(connect::kServicePath);
  res.status = 204;
  res.set_header("Allow", rpc ? "POST, OPTIONS" : "GET, HEAD, OPTIONS");
  if (!rpc || cors_origin.empty()) return;
  // A preflight: what the page of the origin (named in every answer) may send.
  res.set_header("Access-Control-Allow-Methods", "POST");
  res.set_header("Access-Control-Allow-Headers",
                 "Content-Type, Connect-Protocol-Version, Connect-Timeout-Ms, " + std::string(kRequestIdHeader));
  res.set_header("Access-Control-Max-Age", "7200");
}

void HttpServer::Impl::OnBody(const httplib::Request& req, httplib::Response& res,
                              const httplib::ContentReader& reader) {
  std::string body;
  const ApiStatus read =
      ReadBody(req, res, reader, limits::kMaxRequestBytes + connect::kEnvelopePrefixBytes, &body);
  if (!req.path.starts_with(connect::kServicePath)) {
    const bool known = req.path == "/healthz" || req.path == "/metrics" || WebFileAt(req.path) != nullptr;
    return known ? ReplyNotAllowed(res, "GET, HEAD, OPTIONS", false) : ReplyText(res, 404, "not found");
  }
  if (req.method != "POST") return ReplyNotAllowed(res, "POST, OPTIONS", true);
  const std::string_view name = std::string_view(req.path).substr(connect::kServicePath.size());
  if (name == connect::kPlanStream) return Stream(req, res, std::move(body), read);
  if (const connect::UnaryProcedure* procedure = connect::FindUnary(name)) {
    return Unary(*procedure, req, res, std::move(body), read);
  }
  ReplyError(res, connect::Unimplemented("snooker.v1.ShotPlanner has no procedure '" + Printable(name, 64) +
                                             "'; it has " + connect::ProcedureNames(),
                                         404));
}

std::shared_ptr<ShotPlannerService::TransportCall> HttpServer::Impl::Admit(
    const httplib::Request& req, std::string_view method, std::optional<std::chrono::milliseconds> timeout,
    std::size_t request_bytes, bool is_plan) {
  // Under the lock: the stop, which sets shutting_down first, then waits for the calls
  // in flight, does not return while the service is in use here.
  std::lock_guard<std::mutex> lock(mu);
  if (shutting_down) return nullptr;
  auto call = std::make_shared<ShotPlannerService::TransportCall>();
  call->method = std::string(method);
  call->peer = PeerOf(req);
  call->request_id = t_request_id;
  call->arrival = t_arrival;
  call->deadline = service->DeadlineOf(t_arrival, timeout);
  call->request_bytes = request_bytes;
  call->is_plan = is_plan;
  call->log_extra = tls ? " transport=https" : " transport=http";
  in_flight.insert(call);
  return call;
}

void HttpServer::Impl::Release(const std::shared_ptr<ShotPlannerService::TransportCall>& call) {
  std::lock_guard<std::mutex> lock(mu);
  in_flight.erase(call);
  if (in_flight.empty()) idle.notify_all();
}

void HttpServer::Impl::Unary(const connect::UnaryProcedure& procedure, const httplib::Request& req,
                             httplib::Response& res, std::string body, const ApiStatus& read) {
  const std::optional<Codec> codec = connect::UnaryCodec(req.get_header_value("Content-Type"));
  if (!codec) {
    res.set_header("Accept-Post", "application/json, application/proto");
    return ReplyError(res, connect::Unimplemented(
                               "Content-Type '" + Printable(req.get_header_value("Content-Type"), 60) +
                                   "' is not application/json or application/proto",
                               415));
  }
  std::optional<std::chrono::milliseconds> timeout;
  if (!read.ok()) return ReplyError(res, connect::ErrorOf(read));
  if (ApiStatus st = CheckCallHeaders(req, &timeout); !st.ok()) return ReplyError(res, connect::ErrorOf(st));
  auto call = Admit(req, procedure.name, timeout, body.size(), procedure.is_plan);
  if (call == nullptr) return ReplyError(res, connect::Unavailable("the server is shutting down"));
  auto result = std::make_shared<UnaryResult>();
  service->Submit(
      call,
      [&procedure, codec, body = std::move(body), result](const CallLimits& limits, const PlanControl& plan,
                                                          ShotPlannerService::Work* work, std::size_t* bytes) {
        const ApiStatus st = procedure.run(body, *codec, limits, plan, &result->body, work);
        *bytes = result->body.size();
        return st;
      },
      [result](const ApiStatus& st) {
        std::lock_guard<std::mutex> lock(result->mu);
        result->status = st;
        result->done = true;
        result->done_cv.notify_all();
      });
  {
    std::unique_lock<std::mutex> lock(result->mu);
    result->done_cv.wait(lock, [&] { return result->done; });
  }
  Release(call);
  t_logged = true;  // the service wrote the call's line
  if (!result->status.ok()) return ReplyError(res, connect::ErrorOf(result->status));
  res.status = 200;
  res.set_content(std::move(result->body), connect::UnaryContentType(*codec));
}

void HttpServer::Impl::Stream(const httplib::Request& req, httplib::Response& res, std::string body,
                              const ApiStatus& read) {
  const std::optional<Codec> codec = connect::StreamingCodec(req.get_header_value("Content-Type"));
  if (!codec) {
    res.set_header("Accept-Post", "application/connect+json, application/connect+proto");
    return ReplyError(res, connect::Unimplemented(
                               "PlanStream streams: Content-Type '" +
                                   Printable(req.get_header_value("Content-Type"), 60) +
                                   "' is not application/connect+json or application/connect+proto",
                               415));
  }
  std::optional<std::chrono::milliseconds> timeout;
  std::string_view message;
  ApiStatus st = read;
  if (st.ok()) st = CheckCallHeaders(req, &timeout);
  if (st.ok()) st = connect::OpenEnvelope(body, &message);
  if (!st.ok()) return ReplyEndStream(res, *codec, connect::ErrorOf(st));
  auto call = Admit(req, connect::kPlanStream, timeout, body.size(), true);
  if (call == nullptr) return ReplyEndStream(res, *codec, connect::Unavailable("the server is shutting down"));
  auto state = std::make_shared<StreamState>();
  state->service = service;
  service->Submit(
      call,
      [codec, request = std::string(message), state](const CallLimits&, const PlanControl& plan,
                                                     ShotPlannerService::Work* work, std::size_t* bytes) {
        std::string final_envelope;
        const ApiStatus status = connect::PlanStream(
            request, *codec, plan, [&state](std::string envelope) { state->Progress(std::move(envelope)); },
            &final_envelope, work);
        *bytes = final_envelope.size();
        std::lock_guard<std::mutex> lock(state->mu);
        state->final_envelope = std::move(final_envelope);
        return status;
      },
      [state](const ApiStatus& status) { state->Complete(status); });
  t_logged = true;  // the service writes the call's line
  res.status = 200;
  res.set_chunked_content_provider(
      connect::StreamingContentType(*codec),
      [this, state](std::size_t, httplib::DataSink& sink) {
        bool progress_sent = false;
        const bool ok = state->WriteNext(sink, &progress_sent);
        if (progress_sent) WithService([&] { service->CountProgress(true); });
        return ok;
      },
      [this, call](bool success) {
        if (!success) call->cancel.store(true);  // the client is gone: stop planning
        Release(call);
      });
}

void HttpServer::Impl::Log(const httplib::Request& req, const httplib::Response& res) {
  const Clock::time_point arrival = std::exchange(t_arrival, Clock::time_point{});
  const std::string request_id = std::exchange(t_request_id, std::string());
  if (std::exchange(t_logged, false) || log == nullptr) return;
  WithService([&] { WriteLine(req, res, arrival, request_id); });
}

void HttpServer::Impl::WriteLine(const httplib::Request& req, const httplib::Response& res,
                                 Clock::time_point arrival, const std::string& request_id) {
  WriteLogLine(*log, service->log_mutex(), [&](std::ostream& line) {
    line << "snooker: http method=" << Printable(req.method, 16) << " path=" << Printable(req.path)
         << " peer=" << PeerOf(req);
    if (!request_id.empty()) line << " request_id=" << request_id;
    line << " status=" << res.status;
    // A request that did not parse never reached the router, which notes the arrival.
    if (arrival != Clock::time_point{}) {
      line << " latency_ms=" << std::chrono::duration<double, std::milli>(Clock::now() - arrival).count();
    }
    line << " response_bytes=" << res.body.size() << "\n";
  });
}

void HttpServer::Impl::Stop(Clock::time_point deadline) {
  {
    std::unique_lock<std::mutex> lock(mu);
    shutting_down = true;
    idle.wait_until(lock, deadline, [this] { return in_flight.empty(); });
    // The grace is over: the rest stop at their next interrupt check.
    for (const auto& call : in_flight) call->cancel.store(true);
    idle.wait_for(lock, std::chrono::seconds(limits::kHttpIoTimeoutSeconds), [this] { return in_flight.empty(); });
  }
  http->stop();
  // Connections end after their request, an idle one within the keep-alive
  // timeout. One that still reads or writes after that (a client that trickles) is
  // not waited for: its handlers leave the service and the log alone from here on,
  // and this object lives until the listener ends (HttpServer's destructor).
  const auto wait = std::chrono::seconds(limits::kHttpKeepAliveSeconds + limits::kHttpIoTimeoutSeconds + 1);
  if (listener_done.wait_for(wait) == std::future_status::ready) {
    listener.join();
  } else {
    std::unique_lock<std::mutex> lock(mu);
    orphaned = true;
    idle.wait(lock, [this] { return service_users == 0; });
  }
}

HttpServer::HttpServer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

HttpServer::~HttpServer() {
  Finish(Clock::now());
  if (!impl_->orphaned) return;
  // The listener still serves a connection: it and this object go when it ends.
  Impl* impl = impl_.release();
  try {
    std::thread([impl] {
      const std::unique_ptr<Impl> owned(impl);
      owned->listener.join();
    }).detach();
  } catch (const std::system_error&) {
    // No thread to wait with: the objects are left to the process's exit.
  }
}

int HttpServer::port() const { return impl_->port; }

const char* HttpServer::scheme() const { return impl_->tls ? "https" : "http"; }

void HttpServer::BeginShutdown() {
  std::lock_guard<std::mutex> lock(impl_->mu);
  impl_->shutting_down = true;
}

void HttpServer::Finish(Clock::time_point deadline) {
  std::call_once(impl_->finished, [&] { impl_->Stop(deadline); });
}

std::unique_ptr<HttpServer> HttpServer::Start(ShotPlannerService* service, const HttpOptions& options,
                                              std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error != nullptr) *error = why;
    return nullptr;
  };
  if (std::string bad = CheckHttpOptions(options); !bad.empty()) return fail(bad);
  std::string host;
  int port = 0;
  SplitHostPort(options.address, &host, &port);
  auto impl = std::make_unique<Impl>();
  impl->service = service;
  impl->cors_origin = options.cors_origin;
  impl->metrics_only = options.metrics_only;
  impl->log = options.log;
  impl->tls = options.tls != nullptr;
  if (options.tls != nullptr) {
    std::string why;
    impl->certificate_expiry = CertificateExpiry(options.tls->cert_chain_pem);
    if (options.tls->reload_interval.count() > 0) {
      impl->tls_reloader = options.tls_reloader != nullptr
                               ? options.tls_reloader
                               : std::make_shared<TlsReloader>(*options.tls, options.log, &service->log_mutex());
    }
    TlsReloader* reloader = impl->tls_reloader.get();
    impl->http = std::make_unique<httplib::SSLServer>([&](SSL_CTX& ctx) {
      if (!SetUpTls(ctx, *options.tls, &why)) return false;
      if (reloader != nullptr) reloader->Install(ctx);
      return true;
    });
    if (!impl->http->is_valid()) return fail("cannot serve HTTPS on " + options.address + ": " + why);
  } else {
    impl->http = std::make_unique<httplib::Server>();
  }
  impl->Configure();
  impl->port = port == 0 ? impl->http->bind_to_any_port(host) : (impl->http->bind_to_port(host, port) ? port : -1);
  if (impl->port <= 0) {
    return fail("cannot listen on " + options.address + (options.metrics_only ? " for metrics" : " for HTTP") +
                " (is the port in use?)");
  }
  std::promise<void> done;
  impl->listener_done = done.get_future();
  httplib::Server* http = impl->http.get();
  impl->listener = std::thread([http, done = std::move(done)]() mutable {
    http->listen_after_bind();
    done.set_value();
  });
  // Until it runs, stopping it would not stop it.
  while (!impl->http->is_running() &&
         impl->listener_done.wait_for(std::chrono::milliseconds(1)) != std::future_status::ready) {
  }
  return std::unique_ptr<HttpServer>(new HttpServer(std::move(impl)));
}

}  // namespace snooker::server
