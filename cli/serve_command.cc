// snooker serve: the gRPC service (snooker.v1.ShotPlanner, grpc.health.v1.Health,
// reflection) and, with --http, the same service over HTTP (the Connect protocol,
// the web page, /healthz, /metrics) until SIGINT or SIGTERM; then calls in flight may finish
// for a bounded time and are cancelled after it.
#include <grpc/support/log.h>
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>

#include "cli/args.h"
#include "cli/model_file.h"
#include "cli/commands.h"
#include "server/convert.h"
#include "server/limits.h"
#include "server/read_file.h"
#include "server/server.h"

namespace snooker::cli {
namespace {

// Below this many open files a busy server may run out of descriptors.
constexpr rlim_t kOpenFilesWanted = 4096;

// Every connection takes a descriptor, and gRPC (1.51, Debian 12's) stops accepting
// connections for good once accept4 fails for want of one. So the soft limit is raised
// to the hard one, which any process may do, and a limit that stays low is warned of.
// (HTTP's library waits on its sockets with poll, which takes descriptors of any size.)
void RaiseOpenFileLimit(std::ostream& err) {
  rlimit limit{};
  if (getrlimit(RLIMIT_NOFILE, &limit) != 0) return;
  if (limit.rlim_cur < limit.rlim_max) {
    rlimit raised = limit;
    raised.rlim_cur = limit.rlim_max;
    if (setrlimit(RLIMIT_NOFILE, &raised) == 0) limit = raised;
  }
  if (limit.rlim_cur < kOpenFilesWanted) {
    err << "snooker serve: warning: only " << limit.rlim_cur
        << " open files allowed (ulimit -Hn): each connection takes one, and the gRPC "
           "port stops accepting connections for good once they run out; raise it to "
        << kOpenFilesWanted << " or more\n";
  }
}

// Set when gRPC says its listener failed to accept a connection ("Failed accept4",
// for want of a descriptor or of memory): the listener then stops for good (gRPC 1.51,
// tcp_server_posix.cc), and a server nobody can reach must not look healthy.
std::atomic<bool> g_listener_lost{false};

// gRPC's log on stderr as gRPC writes it (severity, file:line, message), watched
// for the listener's end, which stops the server (SIGTERM to itself, with the reason
// kept) so that whatever supervises it starts it again.
void GrpcLog(gpr_log_func_args* args) {
  const char* slash = std::strrchr(args->file, '/');
  std::fprintf(stderr, "%s %s:%d] %s\n", gpr_log_severity_string(args->severity),
               slash != nullptr ? slash + 1 : args->file, args->line, args->message);
  if (args->severity == GPR_LOG_SEVERITY_ERROR && std::strncmp(args->message, "Failed accept4", 14) == 0 &&
      !g_listener_lost.exchange(true)) {
    kill(getpid(), SIGTERM);
  }
}

std::string Help() {
  namespace lim = server::limits;
  auto num = [](double x) { return server::FormatNumber(x); };
  std::ostringstream h;
  h << "usage: snooker serve [--address HOST:PORT] [--tls-cert CERT.pem --tls-key KEY.pem\n"
       "                     [--tls-client-ca CA.pem] [--tls-reload-s S] | --insecure]\n"
       "                     [--max-call-ms MS]\n"
       "                     [--shutdown-grace-ms MS] [--workers N] [--max-queued N]\n"
       "                     [--max-plans N] [--default-budget-ms MS] [--max-budget-ms MS]\n"
       "                     [--vision-tolerance-mm MM] [--model FILE]\n"
       "                     [--http HOST:PORT [--cors-origin ORIGIN]] [--metrics HOST:PORT]\n\n"
       "Serves snooker.v1.ShotPlanner (proto/snooker/v1/service.proto) with the gRPC\n"
       "health service and reflection until SIGINT or SIGTERM; with --http also over\n"
       "HTTP in the same process, on the same workers and limits. One line per call on\n"
       "stderr: method, peer, status, latency, simulations, request and response bytes.\n\n"
       "  --address HOST:PORT      where to listen (default 127.0.0.1:50051; port 0 picks\n"
       "                           a free port, printed on start). An address that is not\n"
       "                           loopback (127.0.0.0/8, ::1, localhost, unix:) needs TLS\n"
       "                           or --insecure\n"
       "  --http HOST:PORT         also serve HTTP/1.1 here (port 0 picks a free port,\n"
       "                           printed on start): the Connect protocol (POST\n"
       "                           /snooker.v1.ShotPlanner/Plan with a JSON body, ...),\n"
       "                           the web page at /, GET /healthz and GET /metrics\n"
       "                           (Prometheus). HTTPS with the TLS flags; plaintext off\n"
       "                           loopback only with --insecure\n"
       "  --cors-origin ORIGIN     let pages of this one origin (https://host[:port]) call\n"
       "                           the HTTP service from a browser (default: no CORS)\n"
       "  --metrics HOST:PORT      also serve GET /metrics (Prometheus) and /healthz here,\n"
       "                           and nothing else: for a scraper without the HTTP API.\n"
       "                           HTTPS with the TLS flags; plaintext off loopback only\n"
       "                           with --insecure\n"
       "  --tls-cert CERT.pem      serve TLS with this certificate (chain), PEM\n"
       "  --tls-key KEY.pem        and its private key, PEM\n"
       "  --tls-client-ca CA.pem   require client certificates signed by this CA (mutual TLS)\n"
       "  --tls-reload-s S         read the TLS files again when they change, checking at\n"
       "                           most every S s, so that a rotated certificate is served\n"
       "                           without a restart; swap each new set in whole, key and\n"
       "                           certificate at once (default 0: read once; at most "
    << lim::kMaxTlsReloadSeconds << ")\n"
       "  --insecure               allow plaintext on an address that is not loopback (a\n"
       "                           trusted network, or a TLS-terminating proxy in front)\n"
       "  --max-call-ms MS         longest wall time of one call, ms: a call ends at its\n"
       "                           client's deadline or after MS, whichever is first, with\n"
       "                           DEADLINE_EXCEEDED (default "
    << lim::kDefaultMaxCall.count() << ", 1 to " << lim::kMaxCallMsLimit
    << ")\n"
       "  --shutdown-grace-ms MS   on SIGINT/SIGTERM, calls in flight may finish for MS,\n"
       "                           then are cancelled (default "
    << lim::kDefaultShutdownGrace.count() << ", 0 to " << lim::kMaxShutdownGraceMs
    << ")\n"
       "  --workers N              calls computed at once (default: one per hardware\n"
       "                           thread, at most "
    << lim::kMaxWorkers
    << ")\n"
       "  --max-queued N           calls waiting for a worker; more are refused with\n"
       "                           RESOURCE_EXHAUSTED (default "
    << lim::kDefaultMaxQueued << ", at most " << lim::kMaxQueuedLimit
    << ")\n"
       "  --max-plans N            plans in the server at once (running or waiting); more\n"
       "                           are refused at once with RESOURCE_EXHAUSTED (default "
    << lim::kDefaultMaxPlans << ",\n                           at most " << lim::kMaxPlansLimit
    << ")\n"
       "  --default-budget-ms MS   a plan's time budget when its request gives none, ms\n"
       "                           (default "
    << num(lim::kDefaultPlanBudgetMs)
    << ")\n"
       "  --max-budget-ms MS       the largest budget a plan may ask for, ms (default "
    << num(lim::kDefaultMaxPlanBudgetMs) << ",\n                           "
    << num(lim::kPlanBudgetMs.lo) << " to " << num(lim::kPlanBudgetMs.hi)
    << ")\n"
       "  --vision-tolerance-mm MM balls overlapping, or past a cushion, by at most MM are\n"
       "                           moved apart or back with a warning; more is an error\n"
       "                           (default "
    << num(lim::kDefaultVisionToleranceMm) << ", " << num(lim::kVisionToleranceMm.lo) << " to "
    << num(lim::kVisionToleranceMm.hi) << "; 0: no repair)\n"
    << "  --model FILE             simulate and plan with this physical model (a model file,\n"
       "                           JSON of snooker.v1.PhysicsModel; GetModel reports it;\n"
       "                           default: the default model)\n";
  return h.str();
}

// Reads a PEM file for a TLS flag; false with the reason on `err`.
bool ReadPem(const std::string& flag, const std::string& path, std::string* pem, std::ostream& err) {
  std::string why;
  if (!server::ReadInputFile(path, pem, &why)) {
    err << "snooker serve: --" << flag << " cannot read '" << path << "': " << why << "\n";
    return false;
  }
  if (pem->find("-----BEGIN ") == std::string::npos) {
    err << "snooker serve: --" << flag << " '" << path << "' is not a PEM file\n";
    return false;
  }
  return true;
}

// The TLS files of --tls-cert, --tls-key and --tls-client-ca into `options`, to be
// read again every `reload_s` seconds when that is positive; false with the reason
// on `err`.
bool ReadTls(const std::string& cert, const std::string& key, const std::string& client_ca, std::int64_t reload_s,
             server::ServerOptions* options, std::ostream& err) {
  server::TlsOptions tls;
  if (!ReadPem("tls-cert", cert, &tls.cert_chain_pem, err) || !ReadPem("tls-key", key, &tls.private_key_pem, err) ||
      (!client_ca.empty() && !ReadPem("tls-client-ca", client_ca, &tls.client_ca_pem, err))) {
    return false;
  }
  if (reload_s > 0) {
    tls.reload_interval = std::chrono::seconds(reload_s);
    tls.cert_chain_file = cert;
    tls.private_key_file = key;
    tls.client_ca_file = client_ca;
  }
  options->tls = std::move(tls);
  return true;
}

// --http, --cors-origin and --metrics as the server will take them (whether TLS is given, not
// its files, which are read later); false with the reason on `err`.
bool HttpFlagsOk(const std::string& http, const std::string& cors_origin, const std::string& metrics, bool tls,
                 bool insecure, std::ostream& err) {
  if (!cors_origin.empty() && http.empty()) {
    err << "snooker serve: --cors-origin needs --http\n";
    return false;
  }
  const server::TlsOptions some_tls;
  for (const bool metrics_only : {false, true}) {
    server::HttpOptions check;
    check.address = metrics_only ? metrics : http;
    if (check.address.empty()) continue;
    check.allow_insecure = insecure;
    check.cors_origin = metrics_only ? "" : cors_origin;
    check.metrics_only = metrics_only;
    check.tls = tls ? &some_tls : nullptr;
    if (const std::string bad = server::CheckHttpOptions(check); !bad.empty()) {
      err << "snooker serve: " << bad << "\n";
      return false;
    }
  }
  return true;
}

// The lines that say where the server listens: HTTP's first, so that whoever waits
// for "on port" finds both.
void PrintListening(const server::Server& server, const server::ServerOptions& options, std::ostream& out) {
  if (server.http_port() != 0) {
    const std::string& http = options.http_address;
    out << "snooker: serving HTTP (Connect protocol, web page, /healthz, /metrics) at " << server.http_scheme() << "://"
        << http.substr(0, http.rfind(':')) << ":" << server.http_port() << "/" << std::endl;
  }
  if (server.metrics_port() != 0) {
    const std::string& metrics = options.metrics_address;
    out << "snooker: serving metrics (/metrics, /healthz) at " << server.metrics_scheme() << "://"
        << metrics.substr(0, metrics.rfind(':')) << ":" << server.metrics_port() << "/metrics" << std::endl;
  }
  out << "snooker: serving snooker.v1.ShotPlanner on port " << server.port() << " (" << options.address << ", "
      << (!options.tls ? "plaintext"
                       : options.tls->client_ca_pem.empty() ? "TLS" : "TLS with client certificates")
      << ")" << std::endl;
}

}  // namespace

int RunServe(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  namespace lim = server::limits;
  Args args(argv,
            {"address", "max-call-ms", "shutdown-grace-ms", "workers", "max-queued", "tls-cert",
             "tls-key", "tls-client-ca", "tls-reload-s", "max-plans", "default-budget-ms", "max-budget-ms",
             "vision-tolerance-mm", "model", "http", "cors-origin", "metrics"},
            {"help", "insecure"});
  if (args.error().empty() && args.Switch("help")) {
    out << Help();
    return kExitOk;
  }
  server::ServerOptions options;
  const auto address = args.Text("address", options.address);
  const auto max_call = args.Integer("max-call-ms", lim::kDefaultMaxCall.count(), 1, lim::kMaxCallMsLimit);
  const auto grace = args.Integer("shutdown-grace-ms", lim::kDefaultShutdownGrace.count(), 0,
                                  lim::kMaxShutdownGraceMs);
  const auto workers = args.Integer("workers", 0, 1, lim::kMaxWorkers);
  const auto queued = args.Integer("max-queued", lim::kDefaultMaxQueued, 0, lim::kMaxQueuedLimit);
  const auto plans = args.Integer("max-plans", lim::kDefaultMaxPlans, 1, lim::kMaxPlansLimit);
  const auto budget = args.Number("default-budget-ms", lim::kDefaultPlanBudgetMs);
  const auto max_budget = args.Number("max-budget-ms", lim::kDefaultMaxPlanBudgetMs);
  const auto tolerance = args.Number("vision-tolerance-mm", lim::kDefaultVisionToleranceMm);
  const auto cert = args.Text("tls-cert", "");
  const auto key = args.Text("tls-key", "");
  const auto client_ca = args.Text("tls-client-ca", "");
  const auto reload = args.Integer("tls-reload-s", 0, 0, lim::kMaxTlsReloadSeconds);
  const auto http = args.Text("http", "");
  const auto cors_origin = args.Text("cors-origin", "");
  const auto metrics = args.Text("metrics", "");
  if (args.error().empty()) {
    if (cert->empty() != key->empty()) {
      err << "snooker serve: --tls-cert and --tls-key go together\n";
      return kExitUsage;
    }
    if (!client_ca->empty() && cert->empty()) {
      err << "snooker serve: --tls-client-ca needs --tls-cert and --tls-key\n";
      return kExitUsage;
    }
    if (*reload > 0 && cert->empty()) {
      err << "snooker serve: --tls-reload-s needs --tls-cert and --tls-key\n";
      return kExitUsage;
    }
    if (!cert->empty() && args.Switch("insecure")) {
      err << "snooker serve: --insecure and TLS (--tls-cert) exclude each other\n";
      return kExitUsage;
    }
    if (!HttpFlagsOk(*http, *cors_origin, *metrics, !cert->empty(), args.Switch("insecure"), err)) {
      return kExitUsage;
    }
  }
  if (!args.error().empty()) {
    err << "snooker serve: " << args.error() << "\n(see snooker serve --help)\n";
    return kExitUsage;
  }
  bool model_ok = true;
  options.model = ModelFlag(args, "snooker serve", err, &model_ok);
  if (!model_ok) return kExitUsage;
  options.address = *address;
  options.max_call = std::chrono::milliseconds(*max_call);
  options.shutdown_grace = std::chrono::milliseconds(*grace);
  options.workers = static_cast<int>(*workers);
  options.max_queued = static_cast<int>(*queued);
  options.max_plans = static_cast<int>(*plans);
  options.default_plan_budget_ms = *budget;
  options.max_plan_budget_ms = *max_budget;
  options.vision_tolerance_mm = *tolerance;
  options.allow_insecure = args.Switch("insecure");
  options.http_address = *http;
  options.cors_origin = *cors_origin;
  options.metrics_address = *metrics;
  options.log = &err;
  if (const std::string bad = server::ValidateServiceOptions(options); !bad.empty()) {
    err << "snooker serve: " << bad << "\n(see snooker serve --help)\n";
    return kExitUsage;
  }
  if (!cert->empty() && !ReadTls(*cert, *key, *client_ca, *reload, &options, err)) return kExitUsage;
  // Block the stop signals before gRPC starts its threads, then wait for one here:
  // the shutdown then runs on this thread, not inside a signal handler.
  sigset_t stop;
  sigemptyset(&stop);
  sigaddset(&stop, SIGINT);
  sigaddset(&stop, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop, nullptr);
  // A log reader that goes away (a pipe to a log shipper that restarts) must not stop
  // the service: without this a write to its pipe raises SIGPIPE, which ends the
  // process. Ignored, the write fails, the line is counted lost, the call answered.
  std::signal(SIGPIPE, SIG_IGN);
  RaiseOpenFileLimit(err);
  gpr_set_log_function(&GrpcLog);
  std::string error;
  auto server = server::Server::Start(options, &error);
  if (!server) {
    err << "snooker serve: " << error << "\n";
    return kExitFailure;
  }
  PrintListening(*server, options, out);
  int signal = 0;
  sigwait(&stop, &signal);
  const bool listener_lost = g_listener_lost.load();
  const server::CallCounts at_signal = server->counts();
  out << "snooker: "
      << (listener_lost ? std::string("the gRPC port stopped accepting connections")
                        : "signal " + std::to_string(signal))
      << ", shutting down: " << at_signal.in_flight() << " calls in flight may finish for up to "
      << options.shutdown_grace.count() << " ms" << std::endl;
  server->Shutdown();
  const server::CallCounts done = server->counts();
  out << "snooker: stopped after " << done.finished << " calls (" << done.with(grpc::StatusCode::OK)
      << " OK, " << done.with(grpc::StatusCode::CANCELLED) << " cancelled)";
  if (done.log_lines_lost > 0) out << "; " << done.log_lines_lost << " of their log lines were lost";
  out << std::endl;
  if (listener_lost) {
    err << "snooker serve: gRPC stopped accepting connections on its port and does not start "
           "again (its \"Failed accept4\" above); stopped, to be started again\n";
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace snooker::cli
