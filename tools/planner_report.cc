// planner_report: the planner's measurements for docs/planner.md, as JSON on stdout
// (scripts/planner-report runs it and tools/planner_report.py writes the document).
//
//   planner_report estimate [POSITION_MM]  the fast pot estimate against Monte Carlo
//       with the full simulator: seeded two-ball positions, every candidate pocket,
//       the plain rolling pot the estimate assumes (RollingPotShot), 400 samples.
//   planner_report fidelity                what the planner's simulator tiers and
//       cheaper settings cost and change: the same shots at the search's and the
//       default tier and with the solvers alone at several tolerances, with and
//       without the early stop, against the converged tier run to the end.
//   planner_report search                  the search's choices at equal work: local
//       algorithm, global stage, throw prediction; each variant plans the same
//       tables and its best shot is judged by an independent Monte Carlo.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "physics/sim/fidelity.h"
#include "planner/planner.h"
#include "planner/robustness.h"
#include "planner/selfplay.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

// CPU time of this thread, s: less disturbed than wall time by the other jobs of a
// shared machine (they still share caches and the memory bus).
double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Two balls at seeded random places: the cue ball and a red.
TableState TwoBalls(std::uint64_t seed) {
  Rng rng(seed);
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(rng.Uniform(0.1, 1.68), rng.Uniform(0.1, 3.47))},
             {BallKind::kRed, Vec2(rng.Uniform(0.1, 1.68), rng.Uniform(0.1, 3.47))}};
  return t;
}

int Estimate(double position_mm) {
  const Planner& planner = Planner::Default();
  ShotSimulator sim(physics::DefaultTable(), planner.config().full);
  constexpr int kSamples = 400;
  std::printf("{\"position_mm\": %g, \"samples\": %d, \"pots\": [\n", position_mm, kSamples);
  bool first = true;
  int count = 0;
  for (std::uint64_t f = 0; count < 120 && f < 400; ++f) {
    const TableState t = TwoBalls(DeriveSeed(4242, f));
    if ((t.balls[0].position - t.balls[1].position).norm() < 0.06) continue;
    PlanRequest req;
    req.table = t;
    req.noise.position = position_mm * 1e-3;
    const PotContext ctx = planner.ContextFor(req);
    for (const Candidate& c : EnumerateCandidates(t, BallOn::kRed, ctx).candidates) {
      const auto shot = RollingPotShot(t.balls[0].position, t.balls[1].position, c.estimate,
                                       planner.config().full);
      if (!shot) continue;
      const ShotSetup setup{&t, 0, 1, c.pocket, BallOn::kRed};
      // The estimate is of the object ball dropping into the pocket (what happens to
      // the cue ball afterwards is the search's business): run to the end and count
      // the object ball's drops.
      const bool nominal = sim.Run(setup, *shot, {}, ShotSimulator::Mode::kFull, {}).object_pocket ==
                           static_cast<int>(c.pocket);
      Rng mc(DeriveSeed(77, f, static_cast<std::uint64_t>(c.pocket)));
      std::vector<Vec2> truth;
      int dropped = 0;
      for (int k = 0; k < kSamples; ++k) {
        SampleTruePositions(t, ctx, mc, &truth);
        const ShotOutcome& out =
            sim.Run(setup, SampleExecution(*shot, ctx.noise, mc), truth, ShotSimulator::Mode::kFull, {});
        dropped += out.first_hit == 1 && out.object_pocket == static_cast<int>(c.pocket);
      }
      std::printf("%s{\"cut_deg\": %.3f, \"cue_distance\": %.4f, \"object_distance\": %.4f, "
                  "\"pocket\": \"%s\", \"estimate\": %.5f, \"monte_carlo\": %.5f, \"nominal\": %s}",
                  first ? "" : ",\n", physics::RadToDeg(c.estimate.aim.cut),
                  (c.estimate.aim.ghost - t.balls[0].position).norm(), c.estimate.distance,
                  physics::ToString(c.pocket), c.estimate.probability,
                  static_cast<double>(dropped) / kSamples, nominal ? "true" : "false");
      first = false;
      ++count;
    }
  }
  std::printf("\n]}\n");
  return 0;
}

// A planner-like spread of shots: for seeded frames, every candidate's rolling pot
// with its speed and spins varied as the search varies them.
struct TestShot {
  TableState table;
  ShotSetup setup;
  physics::Shot shot;
};

std::vector<TestShot> SearchLikeShots(int frames) {
  std::vector<TestShot> shots;
  const Planner& planner = Planner::Default();
  for (int f = 0; f < frames; ++f) {
    Rng rng(DeriveSeed(31, static_cast<std::uint64_t>(f)));
    TableState t = RandomFrame(rng, 8, physics::DefaultTable());
    PlanRequest req;
    req.table = t;
    const PotContext ctx = planner.ContextFor(req);
    const int cue = t.cue_index();
    for (const Candidate& c : EnumerateCandidates(t, BallOn::kRed, ctx).candidates) {
      const auto base = RollingPotShot(t.balls[static_cast<size_t>(cue)].position,
                                       t.balls[static_cast<size_t>(c.object)].position, c.estimate,
                                       planner.config().full);
      if (!base) continue;
      for (int v = 0; v < 4; ++v) {
        TestShot s;
        s.table = t;
        s.shot = *base;
        s.shot.speed *= rng.Uniform(0.8, 2.5);
        s.shot.topspin = rng.Uniform(-1, 1) * s.shot.speed / 0.02625;
        s.shot.sidespin = rng.Uniform(-0.5, 0.5) * s.shot.speed / 0.02625;
        s.setup = {nullptr, cue, c.object, c.pocket, BallOn::kRed};
        shots.push_back(std::move(s));
      }
    }
  }
  for (TestShot& s : shots) s.setup.table = &s.table;
  return shots;
}

// One simulator setting of the fidelity comparison.
struct FidelitySetting {
  const char* name;
  double tolerance;  // the impact solvers' (kSearch: its own kSearchTolerance)
  physics::SimParams params;
};

std::vector<FidelitySetting> FidelitySettings() {
  using physics::Fidelity;
  using physics::FidelityParams;
  std::vector<FidelitySetting> out;
  out.push_back({"the search's tier", physics::kSearchTolerance, FidelityParams(Fidelity::kSearch)});
  out.push_back({"the default tier", physics::SimParams::kShotTolerance, FidelityParams(Fidelity::kDefault)});
  // The adaptive solvers alone (no impact tables) at a sweep of tolerances.
  for (const double tol : {1e-10, 1e-8, 1e-7, 1e-6, 1e-4, 1e-3}) {
    physics::SimParams p;
    p.impact_tables = false;
    p.ball_ball_solver.tolerance = p.cushion_solver.tolerance = tol;
    out.push_back({"solvers only", tol, p});
  }
  return out;
}

int Fidelity() {
  std::vector<TestShot> shots = SearchLikeShots(40);
  const physics::TableModel& table = physics::DefaultTable();
  // Reference: the converged tier (DOP853 at 1e-12, every impact solved), run to the end.
  ShotSimulator full(table, physics::FidelityParams(physics::Fidelity::kReference));
  struct Ref {
    bool success;
    double offset;
    bool line;
    Vec2 cue_end;
  };
  std::vector<Ref> ref;
  for (const TestShot& s : shots) {
    const ShotOutcome& o = full.Run(s.setup, s.shot, {}, ShotSimulator::Mode::kFull, {});
    ref.push_back({o.success, o.line.offset, o.line.valid,
                   full.final_balls()[static_cast<size_t>(s.setup.cue)].r});
  }
  // A change of the object ball's line that matters: a tenth of a millimetre, far
  // inside a pocket's tolerance.
  constexpr double kLineChange = 1e-4;
  std::printf("{\"shots\": %zu, \"reference\": \"DOP853 at 1e-12, no impact tables\", \"settings\": [\n",
              shots.size());
  bool first = true;
  for (const FidelitySetting& setting : FidelitySettings()) {
    for (const bool early : {false, true}) {
      ShotSimulator sim(table, setting.params);
      const auto mode = early ? ShotSimulator::Mode::kDecide : ShotSimulator::Mode::kFull;
      // CPU time: the fastest of 5 passes over all shots (interference only adds).
      double best = 1e9;
      long events = 0;
      for (int pass = 0; pass < 5; ++pass) {
        events = 0;
        const double t0 = ThreadCpuSeconds();
        for (const TestShot& s : shots) events += sim.Run(s.setup, s.shot, {}, mode, {}).events;
        best = std::min(best, ThreadCpuSeconds() - t0);
      }
      int disagree = 0, lines = 0, lines_changed = 0;
      double max_offset = 0;
      std::vector<double> ends;  // the cue ball's end change of each shot that pots in both runs
      for (size_t i = 0; i < shots.size(); ++i) {
        const ShotOutcome& o = sim.Run(shots[i].setup, shots[i].shot, {}, mode, {});
        disagree += o.success != ref[i].success;
        if (o.line.valid && ref[i].line) {
          const double change = std::abs(o.line.offset - ref[i].offset);
          max_offset = std::max(max_offset, change);
          ++lines;
          lines_changed += change > kLineChange;
        }
        if (o.success && ref[i].success) {
          ends.push_back((sim.final_balls()[static_cast<size_t>(shots[i].setup.cue)].r - ref[i].cue_end).norm());
        }
      }
      std::sort(ends.begin(), ends.end());
      double sum_end = 0;
      for (const double d : ends) sum_end += d;
      const double mean_end = ends.empty() ? 0.0 : sum_end / static_cast<double>(ends.size());
      const double median_end = ends.empty() ? 0.0 : ends[ends.size() / 2];
      const double max_end = ends.empty() ? 0.0 : ends.back();
      std::printf("%s{\"setting\": \"%s\", \"tolerance\": %g, \"impact_tables\": %s, \"early_stop\": %s, "
                  "\"cpu_us_per_shot\": %.3f, \"events_per_shot\": %.2f, \"verdicts_changed\": %d, "
                  "\"lines_compared\": %d, \"lines_changed_over_0_1_mm\": %d, \"max_line_offset_change_mm\": %.6f, "
                  "\"mean_cue_end_change_mm\": %.6f, \"median_cue_end_change_mm\": %.6f, "
                  "\"max_cue_end_change_mm\": %.6f}",
                  first ? "" : ",\n", setting.name, setting.tolerance,
                  setting.params.impact_tables ? "true" : "false", early ? "true" : "false",
                  best / static_cast<double>(shots.size()) * 1e6,
                  static_cast<double>(events) / static_cast<double>(shots.size()), disagree, lines, lines_changed,
                  max_offset * 1e3, mean_end * 1e3, median_end * 1e3, max_end * 1e3);
      first = false;
    }
  }
  std::printf("\n]}\n");
  return 0;
}

int Search() {
  struct Variant {
    const char* name;
    LocalAlgorithm local;
    double global_share;  // of each candidate's evaluations
    bool predict_throw;
  };
  const Variant variants[] = {
      {"DIRECT-L + BOBYQA (default)", LocalAlgorithm::kBobyqa, 0.5, true},
      {"DIRECT-L + SBPLX", LocalAlgorithm::kSubplex, 0.5, true},
      {"DIRECT-L + COBYLA", LocalAlgorithm::kCobyla, 0.5, true},
      {"DIRECT-L only", LocalAlgorithm::kNone, 1.0, true},
      {"BOBYQA only", LocalAlgorithm::kBobyqa, 0.0, true},
      {"DIRECT-L + BOBYQA, geometric aim (no throw prediction)", LocalAlgorithm::kBobyqa, 0.5, false},
  };
  constexpr int kTables = 40, kSims = 500, kJudgeSamples = 200;
  std::vector<TableState> tables;
  for (int k = 0; k < kTables; ++k) {
    Rng rng(DeriveSeed(555, static_cast<std::uint64_t>(k)));
    tables.push_back(RandomFrame(rng, 6 + k % 5, physics::DefaultTable()));
  }
  const Planner& reference = Planner::Default();
  ShotSimulator judge(physics::DefaultTable(), reference.config().full);
  std::printf("{\"tables\": %d, \"simulations_per_plan\": %d, \"judge_samples\": %d, \"variants\": [\n",
              kTables, kSims, kJudgeSamples);
  bool first = true;
  for (const Variant& v : variants) {
    PlannerConfig config;
    config.search_settings.local = v.local;
    config.search_settings.predict_throw = v.predict_throw;
    config.global_share = v.global_share;
    const Planner planner(config);
    double score = 0, pot = 0, found = 0, evaluations = 0;
    for (size_t k = 0; k < tables.size(); ++k) {
      PlanRequest r;
      r.table = tables[k];
      r.time_budget = 60;
      r.max_simulations = kSims;
      r.seed = k;
      const PlanAnswer a = planner.Plan(r);
      evaluations += static_cast<double>(a.evaluations);
      if (a.shots.empty()) continue;
      ++found;
      const PlannedShot& s = a.shots.front();
      // An independent judge: the same Monte Carlo objective, its own seed.
      const ShotSetup setup{&r.table, r.table.cue_index(), s.object_ball, s.pocket, BallOn::kRed};
      MonteCarloTally t = RunSamples(setup, s.cue, reference.ContextFor(r), reference.config().search_settings,
                                     judge, StopControl{}, DeriveSeed(9, k), kJudgeSamples);
      score += t.mean_score();
      pot += t.success_rate();
    }
    std::printf("%s{\"variant\": \"%s\", \"mean_score\": %.4f, \"mean_pot\": %.4f, \"found\": %.0f, "
                "\"evaluations_per_plan\": %.1f}",
                first ? "" : ",\n", v.name, score / kTables, pot / std::max(1.0, found), found,
                evaluations / kTables);
    first = false;
  }
  std::printf("\n]}\n");
  return 0;
}

}  // namespace
}  // namespace snooker::planner

int main(int argc, char** argv) {
  const std::string what = argc > 1 ? argv[1] : "";
  if (what == "estimate") return snooker::planner::Estimate(argc > 2 ? std::atof(argv[2]) : 0.2);
  if (what == "fidelity") return snooker::planner::Fidelity();
  if (what == "search") return snooker::planner::Search();
  std::fprintf(stderr, "usage: planner_report estimate [POSITION_MM] | fidelity | search\n");
  return 2;
}
