// Speed against error of whole shots: for each fidelity setting, the time per shot
// and how far every ball's final position lands from a converged reference, and how
// many shots change a pocket outcome. Prints JSON for tools/shot_speed_error.py.
// Usage: shot_speed_error planner|cushions|break-off SHOTS
// (scripts/shot-speed-error runs it and adds callgrind instruction counts.)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "physics/sim/fidelity.h"
#include "tests/support/scenarios.h"

namespace {

using namespace snooker::physics;

struct Outcome {
  std::vector<Vec2> r;
  std::vector<int> pocket;
  int events = 0;
  SimStatus status = SimStatus::kAtRest;
};

struct Setting {
  std::string name;
  SimParams params;
};

std::vector<Outcome> RunAll(const SimParams& params, const std::vector<std::vector<BallState>>& shots,
                            double* seconds) {
  Simulator sim(DefaultTable(), params);
  std::vector<Outcome> out;
  *seconds = 1e300;
  for (int rep = 0; rep < 3; ++rep) {  // the fastest of three passes: noise only adds time
    out.clear();
    const auto t0 = std::chrono::steady_clock::now();
    for (const auto& balls : shots) {
      Outcome o;
      o.status = sim.Run(balls, RunOptions::Lean());
      o.events = sim.event_count();
      for (size_t i = 0; i < balls.size(); ++i) {
        o.r.push_back(sim.final_balls()[i].r);
        o.pocket.push_back(sim.pocket_of(static_cast<int>(i)));
      }
      out.push_back(std::move(o));
    }
    *seconds = std::min(*seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: shot_speed_error planner|cushions|break-off SHOTS\n");
    return 2;
  }
  const std::string workload = argv[1];
  const int n = std::atoi(argv[2]);
  if (n <= 0 || (workload != "planner" && workload != "cushions" && workload != "break-off")) {
    std::fprintf(stderr, "shot_speed_error: bad workload '%s' or SHOTS '%s'\n", argv[1], argv[2]);
    return 2;
  }
  const std::vector<std::vector<BallState>> shots = scenarios::WorkloadShots(workload, n);
  // The exact solvers at one tolerance, every impact solved (no impact tables): the
  // references, and the tolerance rows (the default tier is the 1e-7 row plus tables).
  auto with_tolerance = [](double tol) {
    SimParams p;
    p.impact_tables = false;
    p.ball_ball_solver.tolerance = p.cushion_solver.tolerance = tol;
    return p;
  };
  constexpr double kReference = 1e-13, kCheck = 1e-12;
  std::vector<Setting> settings;
  for (Fidelity f : {Fidelity::kReference, Fidelity::kDefault, Fidelity::kSearch}) {
    settings.push_back({std::string("tier ") + ToString(f), FidelityParams(f)});
  }
  for (double tol : {1e-12, 1e-10, 1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4}) {
    char name[32];
    std::snprintf(name, sizeof name, "tolerance %g", tol);
    settings.push_back({name, with_tolerance(tol)});
  }
  double ref_seconds = 0, check_seconds = 0, nudged_seconds = 0;
  const std::vector<Outcome> ref = RunAll(with_tolerance(kReference), shots, &ref_seconds);
  // How converged the reference is: the same shots one decade looser.
  const std::vector<Outcome> check = RunAll(with_tolerance(kCheck), shots, &check_seconds);
  // How well conditioned each shot is: the reference again with the cue ball's speed
  // changed by one part in 1e9, and again with its direction turned by 1e-9 rad, both
  // far below any cue's precision. A shot whose balls then move by more than 1 um
  // decides something (a graze, a jaw, a ball running along a cushion) on a knife
  // edge: any numerical error, however small, may flip it, so its error measures the
  // shot, not the integrator. Those shots are counted, and left out of the second set
  // of error columns. (Both nudges: a speed change alone leaves a path's geometry
  // nearly unchanged - the impact maps scale with speed - and misses knife edges of
  // direction, which are the common ones after several cushions.)
  std::vector<std::vector<BallState>> faster = shots, turned = shots;
  for (auto& balls : faster) balls[0].v *= 1 + 1e-9;
  for (auto& balls : turned) {
    const Vec3 v = balls[0].v;
    const double a = 1e-9;
    balls[0].v = Vec3(std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y(), v.z());
  }
  const std::vector<Outcome> nudge_speed = RunAll(with_tolerance(kReference), faster, &nudged_seconds);
  const std::vector<Outcome> nudge_turn = RunAll(with_tolerance(kReference), turned, &nudged_seconds);
  constexpr double kIllConditionedMm = 1e-3;
  std::vector<bool> well(shots.size(), true);
  int ill = 0;
  for (size_t s = 0; s < shots.size(); ++s) {
    for (const std::vector<Outcome>* nudge : {&nudge_speed, &nudge_turn}) {
      for (size_t i = 0; i < ref[s].r.size(); ++i) {
        const bool moved = (*nudge)[s].pocket[i] != ref[s].pocket[i] ||
                           1e3 * ((*nudge)[s].r[i] - ref[s].r[i]).norm() > kIllConditionedMm;
        if (moved && well[s]) well[s] = false, ++ill;
      }
    }
  }
  struct Errors {
    std::vector<double> all, well;  // mm, sorted
    int changed = 0, changed_well = 0, not_at_rest = 0;
  };
  auto compare = [&](const std::vector<Outcome>& got) {
    Errors e;
    for (size_t s = 0; s < got.size(); ++s) {
      bool differs = false;
      e.not_at_rest += got[s].status != SimStatus::kAtRest;
      for (size_t i = 0; i < got[s].r.size(); ++i) {
        differs |= got[s].pocket[i] != ref[s].pocket[i];
        if (got[s].pocket[i] >= 0 || ref[s].pocket[i] >= 0) continue;
        const double mm = 1e3 * (got[s].r[i] - ref[s].r[i]).norm();
        e.all.push_back(mm);
        if (well[s]) e.well.push_back(mm);
      }
      e.changed += differs;
      e.changed_well += differs && well[s];
    }
    std::sort(e.all.begin(), e.all.end());
    std::sort(e.well.begin(), e.well.end());
    return e;
  };
  auto max_of = [](const std::vector<double>& v) { return v.empty() ? 0.0 : v.back(); };
  auto p99_of = [](const std::vector<double>& v) { return v.empty() ? 0.0 : v[v.size() * 99 / 100]; };
  std::printf("{\"workload\": \"%s\", \"shots\": %d, \"reference_tolerance\": %g, \"ill_conditioned\": %d,\n",
              workload.c_str(), n, kReference, ill);
  {
    const Errors e = compare(check);
    std::printf(" \"reference_check\": {\"tolerance\": %g, \"err_mm_max\": %.6g, \"err_mm_max_well\": %.6g, "
                "\"pocket_changes\": %d},\n", kCheck, max_of(e.all), max_of(e.well), e.changed);
  }
  std::printf(" \"settings\": [\n");
  for (size_t k = 0; k < settings.size(); ++k) {
    double seconds = 0;
    const std::vector<Outcome> got = RunAll(settings[k].params, shots, &seconds);
    const Errors e = compare(got);
    long events = 0;
    for (const Outcome& o : got) events += o.events;
    double mean = 0;
    for (double x : e.all) mean += x;
    if (!e.all.empty()) mean /= static_cast<double>(e.all.size());
    std::printf("  {\"name\": \"%s\", \"us_per_shot\": %.3f, \"events_per_shot\": %.2f, \"err_mm_mean\": %.6g, "
                "\"err_mm_p99\": %.6g, \"err_mm_max\": %.6g, \"err_mm_max_well\": %.6g, \"pocket_changes\": %d, "
                "\"pocket_changes_well\": %d, \"not_at_rest\": %d}%s\n",
                settings[k].name.c_str(), 1e6 * seconds / n, static_cast<double>(events) / n, mean, p99_of(e.all),
                max_of(e.all), max_of(e.well), e.changed, e.changed_well, e.not_at_rest,
                k + 1 < settings.size() ? "," : "");
  }
  std::printf(" ]}\n");
  return 0;
}
