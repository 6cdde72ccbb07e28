#include "server/server.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>
#include <grpcpp/security/server_credentials.h>
#include <grpcpp/security/tls_certificate_provider.h>
#include <grpcpp/security/tls_credentials_options.h>

#include "server/address.h"
#include "server/plan_api.h"
#include "server/tls_context.h"

namespace snooker::server {

Server::Server(const ServerOptions& options)
    : service_(options), shutdown_grace_(options.shutdown_grace) {}

std::unique_ptr<Server> Server::Start(const std::string& address, std::string* error) {
  ServerOptions options;
  options.address = address;
  return Start(options, error);
}

namespace {

// Concurrent HTTP/2 streams (calls) per client connection: far above what the worker
// pool takes (its queue refuses the rest), a bound on what one connection can open.
constexpr int kMaxStreamsPerConnection = 1024;
// Request metadata (headers) per call, bytes.
constexpr int kMaxMetadataBytes = 16 * 1024;

// `files`: where gRPC reads a reloaded set (null: the options' text, for the server's life).
std::shared_ptr<grpc::ServerCredentials> Credentials(const ServerOptions& options, const GrpcTlsFiles* files) {
  if (!options.tls) return grpc::InsecureServerCredentials();
  if (files != nullptr) {
    // gRPC's own watcher reads the files every interval; they hold only sets that load.
    namespace ex = grpc::experimental;
    ex::TlsServerCredentialsOptions o(std::make_shared<ex::FileWatcherCertificateProvider>(
        files->identity_file(), files->identity_file(), files->ca_file(),
        static_cast<unsigned>(options.tls->reload_interval.count())));
    o.watch_identity_key_cert_pairs();
    if (files->ca_file().empty()) {
      o.set_cert_request_type(GRPC_SSL_DONT_REQUEST_CLIENT_CERTIFICATE);
    } else {
      o.watch_root_certs();
      o.set_cert_request_type(GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY);
    }
    return grpc::experimental::TlsServerCredentials(o);
  }
  grpc::SslServerCredentialsOptions ssl(
      options.tls->client_ca_pem.empty()
          ? GRPC_SSL_DONT_REQUEST_CLIENT_CERTIFICATE
          : GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY);
  ssl.pem_root_certs = options.tls->client_ca_pem;
  ssl.pem_key_cert_pairs.push_back({options.tls->private_key_pem, options.tls->cert_chain_pem});
  return grpc::SslServerCredentials(ssl);
}

}  // namespace

std::string CheckTlsReload(const TlsOptions& tls) {
  const auto s = tls.reload_interval.count();
  if (s == 0) return "";
  if (s < 0 || s > limits::kMaxTlsReloadSeconds) {
    return "the TLS reload interval " + std::to_string(s) + " s is outside [0, " +
           std::to_string(limits::kMaxTlsReloadSeconds) + "] s";
  }
  if (tls.cert_chain_file.empty() || tls.private_key_file.empty()) {
    return "reloading TLS needs the files of the certificate and its key";
  }
  if (tls.client_ca_file.empty() != tls.client_ca_pem.empty()) {
    return "reloading TLS with a client CA needs its file, and a client CA file needs its text";
  }
  return "";
}

std::unique_ptr<Server> Server::Start(const ServerOptions& options, std::string* error) {
  auto fail = [&](const std::string& why) {
    if (error != nullptr) *error = why;
    return nullptr;
  };
  if (const std::string bad = ValidateServiceOptions(options); !bad.empty()) return fail(bad);
  for (const auto& [name, value] : {std::pair{"keepalive", options.keepalive},
                                    std::pair{"keepalive_timeout", options.keepalive_timeout}}) {
    if (value.count() < 1 || value > limits::kMaxKeepalive) {
      return fail(std::string(name) + " " + std::to_string(value.count()) + " ms is outside [1, " +
                  std::to_string(limits::kMaxKeepalive.count()) + "] ms");
    }
  }
  if (const std::string bad = CheckListenAddress(options.address); !bad.empty()) return fail(bad);
  if (const std::string refusal =
          PlaintextRefusal(options.address, options.tls.has_value(), options.allow_insecure, "listen");
      !refusal.empty()) {
    return fail(refusal);
  }
  if (options.tls && (options.tls->cert_chain_pem.empty() || options.tls->private_key_pem.empty())) {
    return fail("TLS needs both a certificate and its private key");
  }
  if (options.tls) {
    if (const std::string bad = CheckTlsReload(*options.tls); !bad.empty()) return fail(bad);
    if (const std::string bad = CheckTlsText(*options.tls); !bad.empty()) {
      return fail("cannot listen on " + options.address + " with TLS: " + bad);
    }
  }
  HttpOptions http;
  http.address = options.http_address;
  http.tls = options.tls ? &*options.tls : nullptr;
  http.allow_insecure = options.allow_insecure;
  http.cors_origin = options.cors_origin;
  http.log = options.log;
  if (!options.http_address.empty()) {
    if (const std::string bad = CheckHttpOptions(http); !bad.empty()) return fail(bad);
  } else if (!options.cors_origin.empty()) {
    return fail("a CORS origin needs an HTTP address (--http)");
  }
  HttpOptions metrics = http;
  metrics.address = options.metrics_address;
  metrics.cors_origin.clear();
  metrics.metrics_only = true;
  if (!options.metrics_address.empty()) {
    if (const std::string bad = CheckHttpOptions(metrics); !bad.empty()) return fail(bad);
  }
  // The planner's tables are built before the port opens: the first plan after
  // SERVING is as fast as any other.
  WarmUpPlanner();
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  std::unique_ptr<Server> s(new Server(options));
  if (options.tls && options.tls->reload_interval.count() > 0) {
    // One reader of the files for both listeners: each set is read and said once.
    http.tls_reloader = std::make_shared<TlsReloader>(*options.tls, options.log, &s->service_.log_mutex());
    metrics.tls_reloader = http.tls_reloader;
    std::string why;
    s->tls_files_ = GrpcTlsFiles::Start(*options.tls, http.tls_reloader, &why);
    if (s->tls_files_ == nullptr) return fail("cannot listen on " + options.address + " with TLS: " + why);
  }
  grpc::ServerBuilder builder;
  builder.AddListeningPort(options.address, Credentials(options, s->tls_files_.get()), &s->port_);
  builder.AddChannelArgument(GRPC_ARG_MAX_CONCURRENT_STREAMS, kMaxStreamsPerConnection);
  builder.AddChannelArgument(GRPC_ARG_MAX_METADATA_SIZE, kMaxMetadataBytes);
  // Pings on quiet connections, with or without calls, as often as they fall due
  // (gRPC's own default stops after two pings without data).
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIME_MS, static_cast<int>(options.keepalive.count()));
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, static_cast<int>(options.keepalive_timeout.count()));
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_PERMIT_WITHOUT_CALLS, 1);
  builder.AddChannelArgument(GRPC_ARG_HTTP2_MAX_PINGS_WITHOUT_DATA, 0);
  builder.RegisterService(&s->service_);
  builder.SetMaxReceiveMessageSize(static_cast<int>(limits::kMaxRequestBytes));
  // The API bounds its answers below this (limits::kMaxResponseBytes); this is the backstop.
  builder.SetMaxSendMessageSize(static_cast<int>(limits::kMaxResponseBytes + 4096));
  s->server_ = builder.BuildAndStart();
  if (s->server_ == nullptr || s->port_ == 0) {
    // gRPC says why on its log (stderr): a port in use, a bad address, or a
    // certificate or key that does not load.
    s->server_.reset();
    return fail("cannot listen on " + options.address +
                (options.tls ? " (or the TLS certificate or key is not valid PEM, or they do "
                               "not match)"
                             : ""));
  }
  for (auto [listener, listener_options] : {std::pair{&s->http_, &http}, std::pair{&s->metrics_, &metrics}}) {
    if (listener_options->address.empty()) continue;
    std::string why;
    *listener = HttpServer::Start(&s->service_, *listener_options, &why);
    if (*listener == nullptr) {
      s->server_->Shutdown(std::chrono::system_clock::now());
      s->server_.reset();
      return fail(why);
    }
  }
  s->server_->GetHealthCheckService()->SetServingStatus(kServiceName, true);
  return s;
}

Server::~Server() { Shutdown(std::chrono::milliseconds(0)); }

void Server::Shutdown(std::chrono::milliseconds grace) {
  std::call_once(shutdown_once_, [&] {
    const auto deadline = std::chrono::steady_clock::now() + grace;
    if (http_) http_->BeginShutdown();
    if (metrics_) metrics_->BeginShutdown();
    if (server_) {
      server_->GetHealthCheckService()->SetServingStatus(kServiceName, false);
      // Waits for calls in flight until the deadline, then cancels them and waits
      // for their answers (each stops at its next interrupt check).
      server_->Shutdown(std::chrono::system_clock::now() + grace);
    }
    // The HTTP calls get what is left of the same grace.
    if (http_) http_->Finish(deadline);
    if (metrics_) metrics_->Finish(deadline);
    service_.StopWorkers();
  });
}

}  // namespace snooker::server
