// snooker serve: the gRPC service (snooker.v1.ShotPlanner, grpc.health.v1.Health,
// reflection) until SIGINT or SIGTERM; then calls in flight may finish for a bounded
// time and are cancelled after it.
#include <csignal>
#include <iostream>
#include <sstream>

#include "cli/args.h"
#include "cli/commands.h"
#include "server/limits.h"
#include "server/server.h"

namespace snooker::cli {
namespace {

std::string Help() {
  namespace lim = server::limits;
  std::ostringstream h;
  h << "usage: snooker serve [--address HOST:PORT] [--max-call-ms MS] [--shutdown-grace-ms MS]\n"
       "                     [--workers N] [--max-queued N]\n\n"
       "Serves snooker.v1.ShotPlanner (proto/snooker/v1/service.proto) with the gRPC\n"
       "health service and reflection until SIGINT or SIGTERM. One line per call on\n"
       "stderr: method, peer, status, latency, request and response bytes.\n\n"
       "  --address HOST:PORT      where to listen (default 127.0.0.1:50051; port 0 picks\n"
       "                           a free port, printed on start)\n"
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
    << lim::kDefaultMaxQueued << ", at most " << lim::kMaxQueuedLimit << ")\n";
  return h.str();
}

}  // namespace

int RunServe(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  namespace lim = server::limits;
  Args args(argv, {"address", "max-call-ms", "shutdown-grace-ms", "workers", "max-queued"},
            {"help"});
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
  if (!args.error().empty()) {
    err << "snooker serve: " << args.error() << "\n(see snooker serve --help)\n";
    return kExitUsage;
  }
  options.address = *address;
  options.max_call = std::chrono::milliseconds(*max_call);
  options.shutdown_grace = std::chrono::milliseconds(*grace);
  options.workers = static_cast<int>(*workers);
  options.max_queued = static_cast<int>(*queued);
  options.log = &err;
  // Block the stop signals before gRPC starts its threads, then wait for one here:
  // the shutdown then runs on this thread, not inside a signal handler.
  sigset_t stop;
  sigemptyset(&stop);
  sigaddset(&stop, SIGINT);
  sigaddset(&stop, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop, nullptr);
  std::string error;
  auto server = server::Server::Start(options, &error);
  if (!server) {
    err << "snooker serve: " << error << "\n";
    return kExitFailure;
  }
  out << "snooker: serving snooker.v1.ShotPlanner on port " << server->port() << " ("
      << *address << ")" << std::endl;
  int signal = 0;
  sigwait(&stop, &signal);
  const server::CallCounts at_signal = server->counts();
  out << "snooker: signal " << signal << ", shutting down: " << at_signal.in_flight()
      << " calls in flight may finish for up to " << options.shutdown_grace.count() << " ms"
      << std::endl;
  server->Shutdown();
  const server::CallCounts done = server->counts();
  out << "snooker: stopped after " << done.finished << " calls (" << done.with(grpc::StatusCode::OK)
      << " OK, " << done.with(grpc::StatusCode::CANCELLED) << " cancelled)" << std::endl;
  return kExitOk;
}

}  // namespace snooker::cli
