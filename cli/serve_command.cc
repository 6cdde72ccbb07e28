// snooker serve: the gRPC service (snooker.v1.ShotPlanner, grpc.health.v1.Health,
// reflection) until SIGINT or SIGTERM.
#include <csignal>
#include <iostream>

#include "cli/args.h"
#include "cli/commands.h"
#include "server/server.h"

namespace snooker::cli {

int RunServe(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args(argv, {"address"}, {"help"});
  if (args.error().empty() && args.Switch("help")) {
    out << "usage: snooker serve [--address HOST:PORT]\n\n"
           "Serves snooker.v1.ShotPlanner (proto/snooker/v1/service.proto) with the gRPC\n"
           "health service and reflection until SIGINT or SIGTERM.\n\n"
           "  --address HOST:PORT   where to listen (default 127.0.0.1:50051; port 0 picks\n"
           "                        a free port, printed on start)\n";
    return kExitOk;
  }
  const auto address = args.Text("address", "127.0.0.1:50051");
  if (!args.error().empty()) {
    err << "snooker serve: " << args.error() << "\n";
    return kExitUsage;
  }
  // Block the stop signals before gRPC starts its threads, then wait for one here:
  // the shutdown then runs on this thread, not inside a signal handler.
  sigset_t stop;
  sigemptyset(&stop);
  sigaddset(&stop, SIGINT);
  sigaddset(&stop, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop, nullptr);
  std::string error;
  auto server = server::Server::Start(*address, &error);
  if (!server) {
    err << "snooker serve: " << error << "\n";
    return kExitFailure;
  }
  out << "snooker: serving snooker.v1.ShotPlanner on port " << server->port() << " ("
      << *address << ")" << std::endl;
  int signal = 0;
  sigwait(&stop, &signal);
  out << "snooker: signal " << signal << ", shutting down" << std::endl;
  server->Shutdown();
  return kExitOk;
}

}  // namespace snooker::cli
