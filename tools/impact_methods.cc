// The two Runge-Kutta pairs of the adaptive impact integrator (ImpulseMethod:
// Dormand-Prince 5(4) and 8(5,3)) compared on the benchmark impacts and on whole
// shots, for docs/impact-methods.md (scripts/impact-methods runs it under callgrind
// for the instruction counts).
// Usage:
//   impact_methods errors
//       JSON: for each model, pair and tolerance, the worst error over the benchmark
//       impacts (bench/collision_shots.h) against a converged answer and the work per
//       impact (steps, rejected steps, right-hand sides).
//   impact_methods count ball-ball|cushion dp54|dop853 TOLERANCE RUNS
//       Solves the benchmark impacts RUNS times (for instruction counting).
//   impact_methods shots planner|cushions|break-off SHOTS reference|default BB CU PASSES
//       Simulates the seeded shots of bench/shot_count PASSES times at a fidelity tier
//       with the ball-ball and cushion pairs BB and CU (dp54|dop853).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/collision_shots.h"
#include "physics/sim/fidelity.h"
#include "tests/physics/impact/impact_test_support.h"
#include "tests/support/scenarios.h"

namespace {

using namespace snooker::physics;

bool ParseMethod(const std::string& s, ImpulseMethod* m) {
  if (s == "dp54") *m = ImpulseMethod::kDormandPrince54;
  else if (s == "dop853") *m = ImpulseMethod::kDormandPrince853;
  else return false;
  return true;
}

const char* Name(ImpulseMethod m) {
  return m == ImpulseMethod::kDormandPrince853 ? "dop853" : "dp54";
}

ImpulseSolverOptions Options(ImpulseMethod m, double tol) {
  ImpulseSolverOptions o;
  o.method = m;
  o.tolerance = tol;
  return o;
}

int Errors() {
  const BallParams ball;
  const double mu_s = ClothParams{}.mu_s;
  const CushionParams cushion = TableCushionParams();
  std::vector<ImpactState> bb;
  for (const NamedShot& s : kReportShots) bb.push_back(ReportShotState(s));
  const std::vector<BallMotion> cu = CushionShots();
  // The converged answers: Dormand-Prince 5(4) at 1e-14 (the two pairs agree there to
  // rounding; the spread is printed).
  const ImpulseSolverOptions ref = Options(ImpulseMethod::kDormandPrince54, 1e-14);
  const ImpulseSolverOptions ref8 = Options(ImpulseMethod::kDormandPrince853, 1e-14);
  std::vector<ImpactResult> bb_ref;
  std::vector<CushionImpactResult> cu_ref;
  double spread = 0;
  for (const ImpactState& s : bb) {
    bb_ref.push_back(ResolveImpact(s, ball, {}, mu_s, ref));
    const ImpactResult r8 = ResolveImpact(s, ball, {}, mu_s, ref8);
    spread = std::max(spread, test::MaxDifference(r8.out, bb_ref.back().out, ball.radius));
  }
  for (const BallMotion& m : cu) {
    cu_ref.push_back(ResolveCushionImpact(m, ball, cushion, ref));
    spread = std::max(spread, test::MaxDifference(ResolveCushionImpact(m, ball, cushion, ref8).out,
                                                  cu_ref.back().out, ball.radius));
  }
  std::printf("{\"reference_spread_mps\": %.3g, \"ball_ball_impacts\": %zu, \"cushion_impacts\": %zu,\n"
              " \"rows\": [\n", spread, bb.size(), cu.size());
  bool first = true;
  for (const char* model : {"ball-ball", "cushion"}) {
    for (ImpulseMethod m : {ImpulseMethod::kDormandPrince54, ImpulseMethod::kDormandPrince853}) {
      for (double tol : {1e-5, 1e-6, 1e-8, 1e-9, 1e-10, 1e-12}) {
        const ImpulseSolverOptions o = Options(m, tol);
        double worst = 0, steps = 0, rejected = 0, rhs = 0;
        int n = 0, failed = 0;
        auto add = [&](ImpactStatus status, const ImpulseWork& w, double err) {
          ++n;
          failed += status != ImpactStatus::kOk;
          worst = std::max(worst, err);
          steps += w.steps;
          rejected += w.rejected_steps;
          rhs += w.rhs_evals;
        };
        if (std::string(model) == "ball-ball") {
          for (size_t i = 0; i < bb.size(); ++i) {
            const ImpactResult r = ResolveImpact(bb[i], ball, {}, mu_s, o);
            add(r.status, r.work, test::MaxDifference(r.out, bb_ref[i].out, ball.radius));
          }
        } else {
          for (size_t i = 0; i < cu.size(); ++i) {
            const CushionImpactResult r = ResolveCushionImpact(cu[i], ball, cushion, o);
            add(r.status, r.work, test::MaxDifference(r.out, cu_ref[i].out, ball.radius));
          }
        }
        std::printf("%s  {\"model\": \"%s\", \"method\": \"%s\", \"tolerance\": %g, \"worst_error_mps\": %.3g, "
                    "\"steps\": %.2f, \"rejected\": %.2f, \"rhs\": %.1f, \"failed\": %d}",
                    first ? "" : ",\n", model, Name(m), tol, worst, steps / n, rejected / n, rhs / n, failed);
        first = false;
      }
    }
  }
  std::printf("\n]}\n");
  return 0;
}

int Count(const std::string& model, ImpulseMethod m, double tol, int runs) {
  const BallParams ball;
  const ImpulseSolverOptions o = Options(m, tol);
  double sink = 0;
  if (model == "ball-ball") {
    std::vector<ImpactState> in;
    for (const NamedShot& s : kReportShots) in.push_back(ReportShotState(s));
    for (int r = 0; r < runs; ++r) {
      for (const ImpactState& s : in) sink += ResolveImpact(s, ball, {}, ClothParams{}.mu_s, o).out.c.v.x();
    }
    std::printf("%zu impacts a run\n", in.size());
  } else {
    const std::vector<BallMotion> in = CushionShots();
    const CushionParams cushion = TableCushionParams();
    for (int r = 0; r < runs; ++r) {
      for (const BallMotion& s : in) sink += ResolveCushionImpact(s, ball, cushion, o).out.v.x();
    }
    std::printf("%zu impacts a run\n", in.size());
  }
  return sink == 12345.678 ? 1 : 0;  // keeps the work from being optimised away
}

int Shots(const std::string& workload, int n, const std::string& tier, ImpulseMethod bb,
          ImpulseMethod cu, int passes) {
  const std::vector<std::vector<BallState>> inputs = scenarios::WorkloadShots(workload, n);
  SimParams params = FidelityParams(tier == "reference" ? Fidelity::kReference : Fidelity::kDefault);
  params.ball_ball_solver.method = bb;
  params.cushion_solver.method = cu;
  Simulator sim(DefaultTable(), params);
  long events = 0;
  for (int p = 0; p < passes; ++p) {
    for (const auto& balls : inputs) {
      sim.Run(balls, RunOptions::Lean());
      events += sim.event_count();
    }
  }
  std::printf("%s: %d shots x %d, %ld events\n", workload.c_str(), n, passes, events);
  return 0;
}

int Usage() {
  std::fprintf(stderr,
               "usage: impact_methods errors\n"
               "       impact_methods count ball-ball|cushion dp54|dop853 TOLERANCE RUNS\n"
               "       impact_methods shots planner|cushions|break-off SHOTS reference|default "
               "dp54|dop853 dp54|dop853 PASSES\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> a(argv + 1, argv + argc);
  if (a.size() == 1 && a[0] == "errors") return Errors();
  ImpulseMethod m, m2;
  if (a.size() == 5 && a[0] == "count" && (a[1] == "ball-ball" || a[1] == "cushion") &&
      ParseMethod(a[2], &m) && std::atof(a[3].c_str()) > 0 && std::atoi(a[4].c_str()) > 0) {
    return Count(a[1], m, std::atof(a[3].c_str()), std::atoi(a[4].c_str()));
  }
  if (a.size() == 7 && a[0] == "shots" &&
      (a[1] == "planner" || a[1] == "cushions" || a[1] == "break-off") && std::atoi(a[2].c_str()) > 0 &&
      (a[3] == "reference" || a[3] == "default") && ParseMethod(a[4], &m) && ParseMethod(a[5], &m2) &&
      std::atoi(a[6].c_str()) > 0) {
    return Shots(a[1], std::atoi(a[2].c_str()), a[3], m, m2, std::atoi(a[6].c_str()));
  }
  return Usage();
}
