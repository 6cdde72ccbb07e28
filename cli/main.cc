// The `snooker` command.
#include <cerrno>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "server/build_info.h"

namespace {

constexpr const char* kUsage = R"(usage: snooker <command> [options]

commands:
  collide    resolve one ball-ball collision (Mathavan et al. 2014)
  simulate   simulate a shot on a table until every ball is at rest
  plan       plan the shots that pot a ball on and leave the cue ball well
  selfplay   the planner plays breaks alone: mean break, pot rate, planning time
  match      two players play whole frames by the rules: frames, points, breaks, fouls
  model      the physical model in use (ball, cloth, ball-ball, cushion, cue)
  record     tracked shots made in a model of a table, with vision noise
  calibrate  fit the physical model to observations of a table
  serve      run the gRPC service (snooker.v1.ShotPlanner)
  loadtest   load-test a server on this machine: throughput, latency, errors
  demo       start the service and use it on built-in examples
  version    which build this is: version and commit (also --version)
  help       this text

'snooker <command> --help' explains a command's options.
)";

using Runner = int (*)(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// A command, and whether what it writes to the standard output is its answer. Such
// output that did not all arrive (a full disk, a closed descriptor) fails the
// command, with a word on stderr: a tool reading a truncated answer must not be told
// it is whole. `serve`'s stdout only says where it listens, and a clean stop stays a
// clean stop.
struct Command {
  const char* name;
  Runner run;
  bool answers_on_stdout;
};

constexpr Command kCommands[] = {
    {"collide", snooker::cli::RunCollide, true},   {"simulate", snooker::cli::RunSimulate, true},
    {"plan", snooker::cli::RunPlan, true},         {"selfplay", snooker::cli::RunSelfPlay, true},
    {"match", snooker::cli::RunMatch, true},       {"model", snooker::cli::RunModel, true},
    {"record", snooker::cli::RunRecord, true},     {"calibrate", snooker::cli::RunCalibrate, true},
    {"serve", snooker::cli::RunServe, false},      {"loadtest", snooker::cli::RunLoadTest, true},
    {"demo", snooker::cli::RunDemo, true},
};

int CheckOutput(const std::string& command, int status) {
  errno = 0;
  std::cout.flush();
  if (std::cout) return status;
  const int error = errno;
  std::cerr << "snooker " << command << ": cannot write the standard output"
            << (error != 0 ? std::string(" (") + std::strerror(error) + ")" : std::string()) << std::endl;
  return status == snooker::cli::kExitOk ? snooker::cli::kExitFailure : status;
}

int Run(int argc, char** argv) {
  using namespace snooker::cli;
  if (argc < 2) {
    std::cerr << kUsage;
    return kExitUsage;
  }
  const std::string name = argv[1];
  const std::vector<std::string> args(argv + 2, argv + argc);
  for (const Command& command : kCommands) {
    if (name != command.name) continue;
    const int status = command.run(args, std::cout, std::cerr);
    return command.answers_on_stdout ? CheckOutput(name, status) : status;
  }
  if (name == "--version" || name == "version") {
    std::cout << "snooker " << snooker::server::kBuildVersion << " (commit " << snooker::server::kBuildCommit
              << ")\n";
    return CheckOutput(name, kExitOk);
  }
  if (name == "help" || name == "--help" || name == "-h") {
    std::cout << kUsage;
    return CheckOutput(name, kExitOk);
  }
  std::cerr << "snooker: unknown command '" << name << "'\n\n" << kUsage;
  return kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  // An allocation failure (or any other escaped exception) is reported, never an abort.
  try {
    return Run(argc, argv);
  } catch (const std::bad_alloc&) {
    std::cerr << "snooker: out of memory" << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "snooker: internal error: " << e.what() << std::endl;
  } catch (...) {
    std::cerr << "snooker: internal error" << std::endl;
  }
  return snooker::cli::kExitFailure;
}
