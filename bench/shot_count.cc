// Simulates a fixed list of seeded shots of one workload, for instruction counting
// under valgrind --tool=callgrind (a repeatable cost on a noisy machine) and for
// profiling. Usage: shot_count planner|cushions|break-off SHOTS [TOLERANCE]
//   planner:   tests/support/scenarios.h PlannerWorkloadShot (8 reds, colours, 0.5-4 m/s)
//   cushions:  CushionsShot (the cue ball alone at 2-4 m/s: several cushions)
//   break-off: RandomBreakOff with the reds 1e-4 m apart
// TOLERANCE sets both impact integrators' tolerance (default: SimParams's).
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "tests/support/scenarios.h"

int main(int argc, char** argv) {
  using namespace snooker::physics;
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: shot_count planner|cushions|break-off SHOTS [TOLERANCE]\n");
    return 2;
  }
  const std::string workload = argv[1];
  const int shots = std::atoi(argv[2]);
  SimParams params;
  if (argc == 4) params.ball_ball_solver.tolerance = params.cushion_solver.tolerance = std::atof(argv[3]);
  if (shots <= 0 || (workload != "planner" && workload != "cushions" && workload != "break-off")) {
    std::fprintf(stderr, "shot_count: bad workload '%s' or SHOTS '%s'\n", argv[1], argv[2]);
    return 2;
  }
  std::mt19937_64 rng(2026);
  std::vector<std::vector<BallState>> inputs;
  for (int i = 0; i < shots; ++i) {
    if (workload == "planner") inputs.push_back(scenarios::PlannerWorkloadShot(rng));
    if (workload == "cushions") inputs.push_back(scenarios::CushionsShot(rng));
    if (workload == "break-off") inputs.push_back(scenarios::RandomBreakOff(1e-4, rng));
  }
  Simulator sim(DefaultTable(), params);
  long events = 0, bb = 0, cushion = 0;
  for (const auto& balls : inputs) {
    sim.Run(balls, RunOptions::Lean());
    events += sim.event_count();
  }
  // One recorded pass for the impact counts.
  for (const auto& balls : inputs) {
    RunOptions o;
    o.record_paths = false;
    sim.Run(balls, o);
    for (const SimEvent& e : sim.events()) {
      bb += e.kind == EventKind::kBallBall;
      cushion += e.kind == EventKind::kCushion || e.kind == EventKind::kKnuckle || e.kind == EventKind::kJawWall;
    }
  }
  std::printf("%s: %d shots, %ld events, %.2f ball-ball and %.2f cushion impacts a shot\n",
              workload.c_str(), shots, events, double(bb) / shots, double(cushion) / shots);
  return 0;
}
