// Simulates a fixed list of seeded shots of one workload, for instruction counting
// under valgrind --tool=callgrind (a repeatable cost on a noisy machine) and for
// profiling. Usage: shot_count planner|cushions|break-off SHOTS [SETTING] [--counts]
//   planner:   tests/support/scenarios.h PlannerWorkloadShot (8 reds, colours, 0.5-4 m/s)
//   cushions:  CushionsShot (the cue ball alone at 2-4 m/s: several cushions)
//   break-off: RandomBreakOff with the reds 1e-4 m apart
// SETTING: a fidelity tier (reference, default, search; physics/sim/fidelity.h) or a
// number, both impact integrators' tolerance (default: SimParams's). --passes P runs
// the shots P times (default 1): the instructions of P = 2 less those of P = 1 are
// the simulation's alone, without start-up and shot generation. --counts adds a
// recorded pass that counts the impacts (not for instruction counting). --no-table
// solves every impact (SimParams::impact_tables off).
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "physics/sim/fidelity.h"
#include "tests/support/scenarios.h"

int main(int argc, char** argv) {
  using namespace snooker::physics;
  if (argc < 3 || argc > 7) {
    std::fprintf(stderr, "usage: shot_count planner|cushions|break-off SHOTS [SETTING] [--passes=P] [--counts] [--no-table]\n");
    return 2;
  }
  const std::string workload = argv[1];
  const int shots = std::atoi(argv[2]);
  SimParams params;
  bool counts = false, table = true;
  int passes = 1;
  for (int a = 3; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--counts") {
      counts = true;
    } else if (arg == "--no-table") {
      table = false;
    } else if (arg.rfind("--passes=", 0) == 0) {
      passes = std::max(1, std::atoi(arg.c_str() + 9));
    } else if (arg == "reference" || arg == "default" || arg == "search") {
      params = FidelityParams(arg == "reference" ? Fidelity::kReference
                              : arg == "default" ? Fidelity::kDefault
                                                 : Fidelity::kSearch);
    } else {
      params.ball_ball_solver.tolerance = params.cushion_solver.tolerance = std::atof(arg.c_str());
    }
  }
  if (shots <= 0 || (workload != "planner" && workload != "cushions" && workload != "break-off")) {
    std::fprintf(stderr, "shot_count: bad workload '%s' or SHOTS '%s'\n", argv[1], argv[2]);
    return 2;
  }
  params.impact_tables = params.impact_tables && table;
  const std::vector<std::vector<BallState>> inputs = scenarios::WorkloadShots(workload, shots);
  Simulator sim(DefaultTable(), params);
  long events = 0, bb = 0, cushion = 0, lookups = 0;
  for (int pass = 0; pass < passes; ++pass) {
    for (const auto& balls : inputs) {
      sim.Run(balls, RunOptions::Lean());
      events += sim.event_count();
    }
  }
  // A recorded pass for the impact counts.
  for (const auto& balls : inputs) {
    if (!counts) break;
    RunOptions o;
    o.record_paths = false;
    sim.Run(balls, o);
    lookups += sim.impact_work().table_lookups;
    for (const SimEvent& e : sim.events()) {
      bb += e.kind == EventKind::kBallBall;
      cushion += e.kind == EventKind::kCushion || e.kind == EventKind::kKnuckle || e.kind == EventKind::kJawWall;
    }
  }
  std::printf("%s: %d shots, %ld events, %.2f ball-ball and %.2f cushion impacts a shot"
              " (%.2f from the table)\n",
              workload.c_str(), shots, events, double(bb) / shots, double(cushion) / shots,
              double(lookups) / shots);
  return 0;
}
