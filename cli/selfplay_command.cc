// snooker selfplay: the planner plays breaks alone (planner/selfplay.h) and reports
// mean and largest break, the share of attempted pots that dropped, and planning
// time per shot. The measure of docs/planner.md.
#include <iomanip>
#include <set>
#include <iostream>
#include <map>
#include <sstream>

#include "cli/args.h"
#include "cli/play_flags.h"
#include "cli/commands.h"
#include "cli/write_file.h"
#include "planner/selfplay.h"

namespace snooker::cli {
namespace {

constexpr const char* kSelfplayHelpHead = R"(usage: snooker selfplay --frames N --seed S [--budget-ms N] [--json]
                        [--noise-heading-deg X] [--noise-speed X] [--noise-spin X]
                        [--noise-position-mm X] [--cue-clearance-m X] [--pot-only] [--one-ply] [--max-simulations N]
                        [--uncertain-world] [--samples N] [--threads N] [--break-value P] [--position-spread K]
                        [--progress] [--records out.jsonl]

The planner plays snooker alone. Each frame starts from a seeded random mid-frame
table (6 to 10 reds scattered where they touch nothing, the colours on their spots,
the cue ball anywhere free) with a red on. The planner sees the table as vision
would (every ball moved by the position noise); its best shot is played on the true
table with the execution noise added, simulated at full fidelity and judged by the
rules. The break goes on until a miss, a foul or a cleared table; potted colours are
re-spotted while reds remain.

  --frames N       frames to play (1 to 100000)
  --seed S         seed of the frames, the noise and the planner (0 to 2^64 - 1)
  --budget-ms N    planning budget per shot, ms (default 80)
  --json           print one JSON object: {"meanBreak", "maxBreak", "potRate",
                   "planMsP50", "planMsP99", "frames", "shots", "plansCutShort"}
                   (points, points, share of attempted pots that dropped, ms, ms,
                   count, count, plans the clock cut short: 0 with a
                   --max-simulations cap the budget covers, when the run is a
                   function of its seed)
Noise (standard deviations; the same options as snooker plan):
)";
constexpr const char* kSelfplayHelpTail = R"(Planner:
  --pot-only             ignore the position left
  --one-ply              estimate the next shot only (no lookahead search)
  --uncertain-world      play in a world whose squirt and throw differ from the
                         model's on every stroke by the squirt and throw uncertainty
                         (a real table's; give them with it, e.g. 0.15 and 0.10)
  --max-simulations N    per-plan cap on simulations (default: from the budget)
  --samples N            Monte Carlo samples per ranked shot (default 48)
  --threads N            planner threads (default 2)
  --break-value P        what keeping the table is worth beyond the potted ball's
                         value, points (0 to 147; default 30, the planner's own: alone
                         at the table only the break's own points are to come)
  --position-spread K    value a pot's position over the cue ball's end spread, K
                         standard deviations of what the speed's noise gives it (0
                         to 4; default 0: at the nominal end)
  --progress             print each frame's break on stderr as it ends
  --records out.jsonl    write one JSON line per frame: {"frame", "reds", "points",
                         "attempts", "pots", "end"} (end: "miss", "foul: ...",
                         "no pot", "cleared" or "shot cap")
  --help                 this text
)";

}  // namespace

int RunSelfPlay(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  std::set<std::string> valued = {"frames", "seed", "records"};
  valued.insert(std::begin(kPlayFlagNames), std::end(kPlayFlagNames));
  Args args(argv, valued, {"json", "help", "pot-only", "one-ply", "progress", "uncertain-world"});
  if (args.error().empty() && args.Switch("help")) {
    out << kSelfplayHelpHead << kPlayFlagsHelp << kSelfplayHelpTail;
    return kExitOk;
  }
  planner::SelfPlayOptions o;
  const auto frames = args.Integer("frames", std::nullopt, 1, 100'000);
  const auto seed = args.Unsigned64("seed", std::nullopt);
  PlayFlags defaults, play;
  defaults.noise = o.noise;
  defaults.limits = o.limits;
  defaults.monte_carlo_samples = o.monte_carlo_samples;
  defaults.threads = o.threads;
  std::string error = args.error();
  if (error.empty()) error = ReadPlayFlags(args, defaults, &play);
  if (!error.empty()) {
    err << "snooker selfplay: " << error << "\n(see snooker selfplay --help)\n";
    return kExitUsage;
  }
  o.frames = static_cast<int>(*frames);
  o.seed = *seed;
  o.time_budget = play.budget_ms * 1e-3;
  o.noise = play.noise;
  o.limits = play.limits;
  o.position_play = !args.Switch("pot-only");
  o.lookahead = !args.Switch("one-ply");
  o.uncertain_world = args.Switch("uncertain-world");
  o.max_simulations = play.max_simulations;
  o.monte_carlo_samples = play.monte_carlo_samples;
  o.threads = play.threads;
  o.break_value = play.break_value;
  o.position_spread = play.position_spread;
  o.world = play.world;
  std::optional<planner::Planner> own;
  if (play.model) own.emplace(planner::PlannerConfig{}.WithModel(*play.model));
  struct Progress {
    std::ostream* err;
  } progress{&err};
  const planner::SelfPlayReport r = planner::RunSelfPlay(
      own ? *own : planner::Planner::Default(), o,
      args.Switch("progress")
          ? +[](int f, const planner::FrameRecord& rec, void* ctx) {
              *static_cast<Progress*>(ctx)->err << "frame " << f + 1 << ": " << rec.reds
                                                << " reds, break " << rec.points << " (" << rec.pots
                                                << "/" << rec.attempts << " pots), " << rec.end << "\n";
            }
          : nullptr,
      &progress);
  if (const auto records = args.Text("records", ""); !records->empty()) {
    std::ostringstream f;
    for (size_t i = 0; i < r.records.size(); ++i) {
      const planner::FrameRecord& rec = r.records[i];
      f << "{\"frame\": " << i << ", \"reds\": " << rec.reds << ", \"points\": " << rec.points
        << ", \"attempts\": " << rec.attempts << ", \"pots\": " << rec.pots << ", \"end\": \""
        << rec.end << "\"}\n";
    }
    if (!WriteOutputFile(*records, f.str(), "snooker selfplay", err)) return kExitFailure;
  }
  if (args.Switch("json")) {
    std::ostringstream j;
    j.precision(10);
    j << "{\"meanBreak\": " << r.mean_break << ", \"maxBreak\": " << r.max_break
      << ", \"potRate\": " << r.pot_rate << ", \"planMsP50\": " << r.plan_ms_p50
      << ", \"planMsP99\": " << r.plan_ms_p99 << ", \"frames\": " << r.frames
      << ", \"shots\": " << r.shots << ", \"plansCutShort\": " << r.plans_cut_short << "}\n";
    out << j.str();
    return kExitOk;
  }
  std::map<std::string, int> ends;
  for (const planner::FrameRecord& f : r.records) ++ends[f.end];
  out << std::fixed << std::setprecision(1) << r.frames << " frames, " << r.shots << " shots\n"
      << "mean break " << r.mean_break << ", largest " << r.max_break << "\n"
      << "pots dropped " << std::setprecision(3) << r.pot_rate << " (" << r.pots << " of " << r.shots
      << ")\n"
      << std::setprecision(1) << "planning time per shot: median " << r.plan_ms_p50 << " ms, 99th percentile "
      << r.plan_ms_p99 << " ms, " << r.plans_cut_short << " of " << r.plan_ms.size()
      << " plans cut short by the clock\nbreaks ended by:";
  for (const auto& [why, n] : ends) out << " " << why << " " << n << ";";
  out << "\n";
  return kExitOk;
}

}  // namespace snooker::cli
