// snooker demo: the main job on an embedded default. For now: the collision of the
// paper's first shot (Tables 1-2, row 1), printed readably.
#include "cli/commands.h"

namespace snooker::cli {

int RunDemo(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  if (!args.empty()) {
    err << "snooker demo: takes no arguments (got '" << args[0] << "')\n";
    return kExitUsage;
  }
  out << "The first shot of Mathavan et al. (2014), Tables 1-2: a rolling cue ball at\n"
         "1.539 m/s cut at 33.83 deg. Paper's predictions: cue ball 0.914 m/s at 31.93 deg,\n"
         "object ball 0.831 m/s at 32.20 deg (after each ball's slip).\n\n";
  // Rolling: topspin = V0 / R.
  return RunCollide({"--speed", "1.539", "--topspin", "58.62857142857143", "--cut-deg", "33.83"},
                    out, err);
}

}  // namespace snooker::cli
