// Runs one simulation scenario (tests/support/scenarios.h) a fixed number of times,
// for instruction counting under valgrind --tool=callgrind: a repeatable cost on a
// noisy machine. Usage: simulate_count SCENARIO RUNS
#include <cstdio>
#include <cstdlib>
#include <string>

#include "tests/support/scenarios.h"

int main(int argc, char** argv) {
  using namespace snooker::physics;
  if (argc != 3) {
    std::fprintf(stderr, "usage: simulate_count pot-empty|pot-full|break-off RUNS\n");
    return 2;
  }
  const auto balls = scenarios::Scenario(argv[1]);
  const int runs = std::atoi(argv[2]);
  if (balls.empty() || runs <= 0) {
    std::fprintf(stderr, "simulate_count: unknown scenario '%s' or bad RUNS '%s'\n", argv[1], argv[2]);
    return 2;
  }
  Simulator sim(DefaultTable(), SimParams{});
  int events = 0;
  for (int i = 0; i < runs; ++i) {
    sim.Run(balls, RunOptions::Lean());
    events += sim.event_count();
  }
  std::printf("%s: %d runs, %d events\n", argv[1], runs, events);
  return 0;
}
