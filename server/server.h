// Building and running the gRPC server: the ShotPlanner service, the standard
// health service (grpc.health.v1) and server reflection; and, on a second address,
// the same service over HTTP with the Connect protocol and the web page
// (http_server.h), on the same workers.
//
// Security: a server listens in plaintext only on a loopback address
// (server/address.h) unless allow_insecure says otherwise; anywhere else it needs
// TLS (a certificate and key; with a client CA it also requires and verifies client
// certificates). Every message is bounded (limits::kMaxRequestBytes in,
// kMaxResponseBytes out), as are HTTP/2 streams per connection and metadata.
#pragma once

#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <grpcpp/grpcpp.h>

#include "server/grpc_service.h"
#include "server/http_server.h"
#include "server/limits.h"

namespace snooker::server {

class GrpcTlsFiles;  // tls_context.h

/// The health-check service name under which ShotPlanner reports SERVING.
inline constexpr const char* kServiceName = "snooker.v1.ShotPlanner";

/// TLS for the server, as PEM text (`snooker serve --tls-cert --tls-key
/// --tls-client-ca` read the files).
struct TlsOptions {
  std::string cert_chain_pem;   ///< the server's certificate (and its chain)
  std::string private_key_pem;  ///< its private key
  /// Not empty: clients must present a certificate signed by one of these CAs
  /// (mutual TLS); empty: clients are not asked for one.
  std::string client_ca_pem;
  /// Certificate rotation without a restart (`--tls-reload-s`): a positive interval
  /// has both transports read the files the text above came from again as they
  /// change, checking at most once an interval; the files must then be given (the
  /// client CA's exactly when client_ca_pem is set). Zero: the text above, for the
  /// server's life.
  std::chrono::seconds reload_interval{0};
  std::string cert_chain_file, private_key_file, client_ca_file;
};

/// Empty, or what is wrong with `tls`'s reload settings (the interval out of
/// [0, limits::kMaxTlsReloadSeconds], or a file missing for it).
std::string CheckTlsReload(const TlsOptions& tls);

struct ServerOptions : ServiceOptions {
  /// "host:port"; port 0 picks a free port.
  std::string address = "127.0.0.1:50051";
  /// TLS; none: plaintext, which only a loopback address gets unless allow_insecure.
  std::optional<TlsOptions> tls;
  /// Listen in plaintext on an address that is not loopback (`--insecure`): for a
  /// trusted network or a TLS-terminating proxy in front.
  bool allow_insecure = false;
  /// Shutdown(): how long calls in flight may finish before they are cancelled.
  std::chrono::milliseconds shutdown_grace = limits::kDefaultShutdownGrace;
  /// How long a gRPC connection may be quiet before the server pings it, and how long
  /// it then waits for the answer before closing the connection.
  std::chrono::milliseconds keepalive = limits::kKeepalive;
  std::chrono::milliseconds keepalive_timeout = limits::kKeepaliveTimeout;
  /// Also serve HTTP (Connect, the web page, /healthz) on this "host:port" (`--http`);
  /// empty: no HTTP. The same TLS (then HTTPS) and plaintext rule as `address`.
  std::string http_address;
  /// The one browser origin whose pages may call the HTTP service (CORS,
  /// `--cors-origin`); empty: none.
  std::string cors_origin;
  /// Also serve GET /metrics and /healthz, and nothing else, over HTTP on this
  /// "host:port" (`--metrics`), for a scraper where the service's own HTTP is not
  /// wanted; empty: none. The same TLS and plaintext rule as `address`.
  std::string metrics_address;
};

class Server {
 public:
  /// Starts serving. Returns nullptr and sets `error` when the options are invalid,
  /// plaintext is asked for on an address (gRPC's, HTTP's or metrics') that is not loopback
  /// without allow_insecure, or an address cannot be bound.
  static std::unique_ptr<Server> Start(const ServerOptions& options, std::string* error);
  /// The same with default options on `address`.
  static std::unique_ptr<Server> Start(const std::string& address, std::string* error);

  ~Server();  // Shutdown(0) if not shut down

  /// The port actually bound.
  int port() const { return port_; }
  /// The HTTP port bound (0: no HTTP), and "http" or "https".
  int http_port() const { return http_ ? http_->port() : 0; }
  const char* http_scheme() const { return http_ ? http_->scheme() : ""; }
  /// The metrics listener's port (0: none), and "http" or "https".
  int metrics_port() const { return metrics_ ? metrics_->port() : 0; }
  const char* metrics_scheme() const { return metrics_ ? metrics_->scheme() : ""; }
  /// Blocks until Shutdown() is called from another thread.
  void Wait() { server_->Wait(); }
  /// Stops accepting calls (gRPC's and HTTP's), lets the calls in flight (running
  /// or queued) finish for `grace`, then cancels the rest (they stop at their next
  /// interrupt check and answer CANCELLED), and returns once every call has its
  /// answer and the workers have stopped. Later calls do nothing.
  void Shutdown(std::chrono::milliseconds grace);
  /// Shutdown with the options' shutdown_grace.
  void Shutdown() { Shutdown(shutdown_grace_); }

  CallCounts counts() const { return service_.counts(); }

 private:
  explicit Server(const ServerOptions& options);
  ShotPlannerService service_;
  std::unique_ptr<GrpcTlsFiles> tls_files_;  // before server_, whose certificate watcher reads them
  std::unique_ptr<grpc::Server> server_;
  std::unique_ptr<HttpServer> http_;     // after service_: its calls run there
  std::unique_ptr<HttpServer> metrics_;  // after service_: it reads its counts
  std::chrono::milliseconds shutdown_grace_;
  std::once_flag shutdown_once_;
  int port_ = 0;
};

}  // namespace snooker::server
