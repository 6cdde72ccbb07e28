// The service over HTTP/1.1 with the Connect protocol (connect.h), the web page
// (web/, embedded: web_files.h) and a health check, in the process that serves
// gRPC (server.h starts and stops it). cpp-httplib (Debian's libcpp-httplib-dev)
// carries the bytes; every call runs on the gRPC service's workers with its
// admission, limits, counters and log (ShotPlannerService::Submit).
//
//  * POST /snooker.v1.ShotPlanner/{Collide,Simulate,GetModel,Plan,Calibrate}:
//    Connect unary calls, application/json or application/proto.
//  * POST /snooker.v1.ShotPlanner/PlanStream: Connect server streaming,
//    application/connect+json or connect+proto; each progress message is written as
//    it comes, and a slow reader holds up only its own connection: while a write is
//    in flight only the newest progress message waits.
//  * GET / (web/index.html), GET /NAME (the other files of web/), GET /healthz
//    ("SERVING"; 503 "NOT_SERVING" once shutdown begins).
//
// Security, as the gRPC listener's: plaintext only on a loopback address unless
// allow_insecure, HTTPS with the server's certificate (and client certificates
// with a client CA) otherwise; request bodies at most limits::kMaxRequestBytes;
// answers at most limits::kMaxResponseBytes; no CORS headers unless one origin is
// named; static files with nosniff, no-cache and a Content-Security-Policy of
// default-src 'self'. Requests of a type a browser page on another origin could
// send without asking first (a form's, text/plain) are refused: a call needs
// application/json or application/proto.
#pragma once

#include <chrono>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>

#include "server/grpc_service.h"

namespace snooker::server {

struct TlsOptions;
class TlsReloader;  // tls_context.h

struct HttpOptions {
  /// "host:port" or "[v6]:port"; port 0 picks a free port.
  std::string address;
  /// HTTPS with this certificate and key (and, with a client CA, client
  /// certificates required); null: plaintext, which only a loopback address gets
  /// unless allow_insecure. Read in Start only.
  const TlsOptions* tls = nullptr;
  /// With `tls`'s reload interval, what reads its files again (the server's, shared
  /// with gRPC); null: one of the listener's own.
  std::shared_ptr<TlsReloader> tls_reloader;
  bool allow_insecure = false;
  /// A browser page of this origin ("https://host[:port]") may call the service:
  /// every answer says Access-Control-Allow-Origin: ORIGIN and preflight requests
  /// (OPTIONS) are answered. Empty: no CORS header at all.
  std::string cors_origin;
  /// One line per request; nullptr: nowhere.
  std::ostream* log = nullptr;
  /// Serve only GET /metrics and /healthz (a scraper's listener beside gRPC, with
  /// no API and no page): any other request is 404, another method on them 405.
  bool metrics_only = false;
};

/// Empty when `origin` is one origin ("http://" or "https://", then a host and an
/// optional port, nothing else); otherwise what is wrong.
std::string CheckCorsOrigin(std::string_view origin);

/// Empty when Start would accept the options' address, plaintext rule and origin;
/// otherwise why not (the message names the address or the origin, and says
/// "metrics" for a metrics_only listener, "HTTP" otherwise).
std::string CheckHttpOptions(const HttpOptions& options);

class HttpServer {
 public:
  /// Listens and serves `service`'s calls on another thread. Null with the reason
  /// in `error` when the options are refused (CheckHttpOptions), the certificate or
  /// key does not load, or the address cannot be bound.
  static std::unique_ptr<HttpServer> Start(ShotPlannerService* service, const HttpOptions& options,
                                           std::string* error);
  ~HttpServer();  // Finish(now) if not finished

  /// The port bound.
  int port() const;
  /// "http" or "https".
  const char* scheme() const;

  /// From now on calls are refused (unavailable, 503) and /healthz says
  /// NOT_SERVING; calls in flight go on.
  void BeginShutdown();
  /// Lets the calls in flight finish until `deadline`, then cancels the rest (they
  /// stop at their next interrupt check and answer canceled), waits for their
  /// answers, closes the listener and its connections. Later calls do nothing. A
  /// connection still reading or writing after the keep-alive and I/O timeouts (a
  /// client that trickles) is not waited for: from then on its requests are refused
  /// as the shutdown's and touch neither the service nor the log, and the listener's
  /// objects stay until it ends, so the service may be destroyed after Finish.
  void Finish(std::chrono::steady_clock::time_point deadline);

  struct Impl;

 private:
  explicit HttpServer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace snooker::server
