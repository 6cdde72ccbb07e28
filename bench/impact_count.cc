// Resolves the impacts of the benchmark shot sets (bench/collision_shots.h) a fixed
// number of times, for instruction counting under valgrind --tool=callgrind: a
// repeatable cost on a noisy machine. Uses only the public solver API, so the same
// file builds against an older revision for before/after ratios
// (scripts/impact-speed-report).
// Usage: impact_count ball-ball|cushion TOLERANCE RUNS
// Prints the impacts solved and the mean work per impact.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/collision_shots.h"

int main(int argc, char** argv) {
  using namespace snooker::physics;
  if (argc != 4) {
    std::fprintf(stderr, "usage: impact_count ball-ball|cushion TOLERANCE RUNS\n");
    return 2;
  }
  const std::string kind = argv[1];
  ImpulseSolverOptions options;
  options.tolerance = std::atof(argv[2]);
  const int runs = std::atoi(argv[3]);
  if ((kind != "ball-ball" && kind != "cushion") || runs <= 0) {
    std::fprintf(stderr, "impact_count: bad kind '%s' or RUNS '%s'\n", argv[1], argv[3]);
    return 2;
  }
  const BallParams ball;
  long impacts = 0, failed = 0;
  double steps = 0, rejected = 0, rhs = 0;
  auto count = [&](const ImpactStatus status, const ImpulseWork& w) {
    ++impacts;
    steps += w.steps;
    rejected += w.rejected_steps;
    rhs += w.rhs_evals;
    failed += status != ImpactStatus::kOk;
  };
  if (kind == "ball-ball") {
    std::vector<ImpactState> in;
    for (const NamedShot& s : kReportShots) in.push_back(ReportShotState(s));
    for (int r = 0; r < runs; ++r) {
      for (const ImpactState& s : in) {
        const ImpactResult res = ResolveImpact(s, ball, {}, ClothParams{}.mu_s, options);
        count(res.status, res.work);
      }
    }
  } else {
    const std::vector<BallMotion> in = CushionShots();
    const CushionParams cushion = TableCushionParams();
    for (int r = 0; r < runs; ++r) {
      for (const BallMotion& s : in) {
        const CushionImpactResult res = ResolveCushionImpact(s, ball, cushion, options);
        count(res.status, res.work);
      }
    }
  }
  const double n = static_cast<double>(impacts);
  std::printf("%s tolerance %g: %ld impacts (%ld not ok), per impact: %.2f steps, %.2f rejected, "
              "%.1f rhs\n",
              kind.c_str(), options.tolerance, impacts, failed, steps / n, rejected / n, rhs / n);
  return failed == 0 ? 0 : 1;
}
