// snooker match: two players, each a way of asking the planner, play whole frames
// of snooker by the rules (planner/match.h), and the frames, points, breaks, fouls,
// safeties, stalls and planning times of each are reported.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string_view>

#include "cli/args.h"
#include "cli/play_flags.h"
#include "cli/commands.h"
#include "planner/match.h"
#include "planner/outlook.h"

namespace snooker::cli {
namespace {

constexpr const char* kMatchHelpHead = R"(usage: snooker match --frames N --seed S [--player-a NAME] [--player-b NAME]
                     [--budget-ms MS] [--noise-heading-deg X] [--noise-speed X]
                     [--noise-spin X] [--noise-position-mm X] [--cue-clearance-m X]
                     [--max-simulations N] [--samples N] [--threads N]
                     [--max-shots N] [--progress] [--strokes out.jsonl [--stroke-tables]]
                     [--thin-break-off] [--break-value P] [--position-spread K] [--json]

Two players play whole frames of snooker by the rules: the standard start (15 reds,
the colours on their spots, the cue ball in hand for the break-off; player A breaks
off in the first, third, ... frame), scores and penalties (4 to 7), the touching-ball
rule, ball in hand after an in-off, re-spotting, the colours in order once the reds
are gone, and a re-spotted black when a frame ends level. Each turn the striker's
planner sees the table as vision would (every ball moved by the position noise); its
first shot is played on the true table with the execution noise added and simulated
at full fidelity. A turn with no shot is a stall: the player then plays a firm
straight shot at the nearest ball on, one with a clear path if there is one. Not
applied: the free ball and the miss rule; a ball cannot leave the simulated table.

Players:
  default       the planner with every shot kind, pot route and the lookahead
  direct-pots   direct pots only, no lookahead (no pot: the straight shot above)
  one-ply       the default without the lookahead

  --frames N       frames to play (1 to 100000)
  --seed S         seed of the frames, the noise and the planners (0 to 2^64 - 1)
  --player-a NAME  player A (default: default)
  --player-b NAME  player B (default: direct-pots)
  --budget-ms MS   planning budget per shot for both players, ms (default 80)
  --json           print one JSON object: {"frames", "framesWonA", "framesWonB",
                   "pointsA", "pointsB", "meanBreakA", "meanBreakB", "highestBreak",
                   "centuries", "foulsA", "foulsB", "safetiesA", "safetiesB", "stalls",
                   "shots", "planMsP50", "planMsP99"} and more: the players and
                   settings ("seedText": the seed as a string, exact where a JSON
                   double would round it), "framesCapped" (frames stopped at the
                   shot cap), "framesUndecided" (of those, level), "blackRespots",
                   "simulationFailures", "thinBreakOff" (--thin-break-off),
                   "plansCutShort" (plans the clock cut short: 0 with a
                   --max-simulations that binds, the match then a function of
                   the seed), and per
                   player (suffix A or B) highestBreak, centuries, penaltyPoints
                   (from the opponent's fouls), shots, stalls, planMsP50,
                   planMsP99, safetyOutlook and safetyOutlookP50 (the opponent's
                   best pot probability after each safety of the player's, mean
                   and median; null: none played), breakOffOutlook and
                   breakOffOutlookP50 (the same after each of its break-offs)
Noise (standard deviations; the same options as snooker selfplay):
)";
constexpr const char* kMatchHelpTail = R"(Planner:
  --max-simulations N    per-plan cap on simulations (default: from the budget); set,
                         the whole match is a function of the seed
  --samples N            Monte Carlo samples per ranked shot (default 48)
  --threads N            planner threads (default 2)
  --break-value P        what keeping the table is worth beyond the potted ball's
                         value, points, for default and one-ply (0 to 147; default
                         100: a miss also hands the opponent the table); direct-pots
                         keeps the planner's own 30
  --position-spread K    default and one-ply value a pot's position over the cue
                         ball's end spread, K standard deviations of what the
                         speed's noise gives it (0 to 4; default 0: at the nominal
                         end); direct-pots keeps the nominal end
Match:
  --max-shots N          strokes after which a frame is stopped (1 to 200, default 200)
  --progress             print each frame's score on stderr as it ends
  --thin-break-off       the players' break-offs also search the thin break on an
                         end red beside the soft break into the pack (the request's
                         thin_break_off; off by default: docs/whole-frame-planner.md)
  --strokes out.jsonl    write one JSON line per stroke, as it is played: {"frame",
                         "stroke", "striker" ("A" or "B"), "turn" ("on table", "in
                         hand", "break-off"), "kind" (the plan's, null for a
                         stall), "route" (a pot's, else null), "stall",
                         "potProbability" (the plan's Monte Carlo, pots only, else
                         null), "planScore" (its ranking score, points), "potted",
                         "foul" ("none" or the foul), "points", "penalty", "scoreA",
                         "scoreB", "planMs", "handoverPot" (when the stroke handed
                         the table over and the frame goes on, the incoming
                         player's best pot probability by the planner's fast
                         estimate, as safetyOutlook measures it; else null),
                         "planHandovers" (what the plan's Monte Carlo predicted:
                         {"samples", "runs" that handed the table over,
                         "snookeredRuns", "meanPotProbability" the opponent's best
                         pot over those runs}; null for a stall)}; a
                         stall adds "stallReason" (why the plan gave no stroke),
                         "stallOn", "stallInHand" and "stallTable" (the table as
                         the striker saw it, in --table's format: `snooker plan
                         --table T.json --on ON` plans the turn again); frames
                         count from 0, strokes from 1; "planSeed" is the seed of
                         the turn's plan (a string of digits)
  --stroke-tables        with --strokes, every line adds the turn's "on",
                         "inHand" and "table" (as for a stall): with the match's
                         flags, any turn plays again to the same shot when
                         --max-simulations is set: `snooker plan --table T.json
                         --on ON [--cue-in-hand] --seed planSeed --shots 1
                         --squirt-uncertainty 0 --throw-uncertainty 0` and the
                         player's flags: default `--break-value B`, one-ply
                         `--break-value B --no-lookahead` (B the match's break
                         value), direct-pots `--kinds POT --routes DIRECT
                         --no-lookahead`, and `--thin-break-off` if the match had
                         it, `--position-spread K` for default and one-ply if it
                         had one (docs/operations.md)
  --help                 this text
)";

struct Parsed {
  planner::MatchOptions options;
  double budget_ms = 80;
  std::optional<physics::Model> model;  // the planners' (--model)
};

// The options from the flags; an error message naming the flag and value otherwise.
std::string Parse(Args& args, Parsed* p) {
  planner::MatchOptions& o = p->options;
  const auto frames = args.Integer("frames", std::nullopt, 1, 100'000);
  const auto seed = args.Unsigned64("seed", std::nullopt);
  const auto player_a = args.Text("player-a", "default");
  const auto player_b = args.Text("player-b", "direct-pots");
  const auto shots = args.Integer("max-shots", planner::kFrameShotCap, 1, planner::kFrameShotCap);
  if (!args.error().empty()) return args.error();
  PlayFlags defaults, play;
  defaults.noise = o.noise;
  defaults.limits = o.limits;
  defaults.monte_carlo_samples = o.monte_carlo_samples;
  defaults.threads = o.threads;
  if (const std::string e = ReadPlayFlags(args, defaults, &play); !e.empty()) return e;
  const auto a = planner::ParsePlayerKind(*player_a);
  const auto b = planner::ParsePlayerKind(*player_b);
  const char* players = "(one of default, direct-pots, one-ply)";
  if (!a) return "--player-a '" + *player_a + "' is not a player " + players;
  if (!b) return "--player-b '" + *player_b + "' is not a player " + players;
  o.frames = static_cast<int>(*frames);
  o.seed = *seed;
  o.players = {*a, *b};
  p->budget_ms = play.budget_ms;
  o.time_budget = play.budget_ms * 1e-3;
  o.noise = play.noise;
  o.limits = play.limits;
  o.max_simulations = play.max_simulations;
  o.monte_carlo_samples = play.monte_carlo_samples;
  o.threads = play.threads;
  o.break_value = play.break_value.value_or(planner::kFrameBreakValue);
  o.position_spread = play.position_spread.value_or(0.0);
  o.max_shots_per_frame = static_cast<int>(*shots);
  o.thin_break_off = args.Switch("thin-break-off");
  if (args.Switch("stroke-tables") && !args.Has("strokes")) return "--stroke-tables needs --strokes out.jsonl";
  o.world = play.world;
  p->model = play.model;
  return planner::MatchOptionsError(o);
}

// A JSON number, or null when it is not finite.
std::string Number(double x) {
  if (!std::isfinite(x)) return "null";
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

void PrintJson(const Parsed& p, const planner::MatchReport& r, std::ostream& out) {
  const planner::MatchOptions& o = p.options;
  const planner::PlayerStats& a = r.players[0];
  const planner::PlayerStats& b = r.players[1];
  std::ostringstream j;
  j << "{\"frames\": " << r.frames << ", \"framesWonA\": " << a.frames_won << ", \"framesWonB\": " << b.frames_won
    << ", \"pointsA\": " << a.points << ", \"pointsB\": " << b.points << ", \"meanBreakA\": " << Number(a.mean_break)
    << ", \"meanBreakB\": " << Number(b.mean_break) << ", \"highestBreak\": " << r.highest_break
    << ", \"centuries\": " << r.centuries << ", \"foulsA\": " << a.fouls << ", \"foulsB\": " << b.fouls
    << ", \"safetiesA\": " << a.safeties << ", \"safetiesB\": " << b.safeties << ", \"stalls\": " << r.stalls
    << ", \"shots\": " << r.shots << ", \"planMsP50\": " << Number(r.plan_ms_p50)
    << ", \"planMsP99\": " << Number(r.plan_ms_p99) << ", \"plansCutShort\": " << r.plans_cut_short;
  j << ", \"playerA\": \"" << planner::ToString(a.kind) << "\", \"playerB\": \"" << planner::ToString(b.kind)
    << "\", \"seed\": " << o.seed << ", \"seedText\": \"" << o.seed << "\", \"budgetMs\": " << Number(p.budget_ms)
    << ", \"maxSimulations\": " << o.max_simulations << ", \"samples\": " << o.monte_carlo_samples
    << ", \"threads\": " << o.threads << ", \"breakValue\": " << Number(o.break_value)
    << ", \"positionSpread\": " << Number(o.position_spread)
    << ", \"thinBreakOff\": " << (o.thin_break_off ? "true" : "false")
    << ", \"noiseHeadingDeg\": " << Number(physics::RadToDeg(o.noise.heading))
    << ", \"noiseSpeed\": " << Number(o.noise.speed_fraction) << ", \"noiseSpin\": " << Number(o.noise.topspin)
    << ", \"noiseAimDeg\": " << Number(physics::RadToDeg(o.noise.aim))
    << ", \"noiseCueSpeed\": " << Number(o.noise.cue_speed_fraction)
    << ", \"noiseTipMm\": " << Number(o.noise.tip_offset * 1e3)
    << ", \"noiseElevationDeg\": " << Number(physics::RadToDeg(o.noise.elevation))
    << ", \"noisePositionMm\": " << Number(o.noise.position * 1e3) << ", \"maxShots\": " << o.max_shots_per_frame
    << ", \"framesCapped\": " << r.frames_capped << ", \"framesUndecided\": " << r.frames_undecided
    << ", \"blackRespots\": " << r.black_respots << ", \"simulationFailures\": " << r.simulation_failures;
  for (size_t i = 0; i < 2; ++i) {
    const planner::PlayerStats& s = r.players[i];
    const char* x = i == 0 ? "A" : "B";
    j << ", \"highestBreak" << x << "\": " << s.highest_break << ", \"centuries" << x << "\": " << s.centuries
      << ", \"penaltyPoints" << x << "\": " << s.penalty_points << ", \"shots" << x << "\": " << s.shots
      << ", \"stalls" << x << "\": " << s.stalls << ", \"planMsP50" << x << "\": " << Number(s.plan_ms_p50)
      << ", \"planMsP99" << x << "\": " << Number(s.plan_ms_p99) << ", \"safetyOutlook" << x
      << "\": " << Number(s.mean_safety_outlook) << ", \"safetyOutlookP50" << x
      << "\": " << Number(s.median_safety_outlook) << ", \"breakOffOutlook" << x << "\": "
      << Number(s.mean_break_off_outlook) << ", \"breakOffOutlookP50" << x << "\": "
      << Number(s.median_break_off_outlook);
    j << ", \"kinds" << x << "\": {";
    for (int k = 0; k < planner::kShotKindCount; ++k) {
      j << (k ? ", " : "") << "\"" << planner::ToString(static_cast<planner::ShotKind>(k)) << "\": " << s.kinds[static_cast<size_t>(k)];
    }
    j << "}, \"routes" << x << "\": {";
    for (int k = 0; k < planner::kPotRouteCount; ++k) {
      j << (k ? ", " : "") << "\"" << planner::ToString(static_cast<planner::PotRoute>(k)) << "\": " << s.routes[static_cast<size_t>(k)];
    }
    j << "}";
  }
  j << ", \"planMsByTurn\": {";
  for (size_t t = 0; t < r.plan_ms_p50_by_turn.size(); ++t) {
    j << (t ? ", " : "") << "\"" << planner::ToString(static_cast<planner::TurnType>(t)) << "\": {\"p50\": "
      << Number(r.plan_ms_p50_by_turn[t]) << ", \"p99\": " << Number(r.plan_ms_p99_by_turn[t]) << "}";
  }
  j << "}}\n";
  out << j.str();
}

// A JSON string: quotes, backslashes and control characters escaped.
std::string JsonString(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// `text` in capitals: a ball kind or ball on in the spelling --table and --on read.
std::string Upper(std::string_view text) {
  std::string out;
  for (const char c : text) out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// A table in snooker plan's --table format (balls "b<index>" but the cue ball), the
// positions to the last bit (17 digits), so that it is read back to the same doubles.
std::string TableJson(const planner::TableState& table) {
  std::ostringstream j;
  j.precision(std::numeric_limits<double>::max_digits10);
  j << "{\"balls\": [";
  int n = 0;
  for (const planner::Ball& b : table.balls) {
    const std::string kind = Upper(planner::ToString(b.kind));
    j << (n ? ", " : "") << "{\"id\": \"" << (b.kind == planner::BallKind::kCue ? std::string("cue") : "b" + std::to_string(n))
      << "\", \"kind\": \"" << kind << "\", \"position\": {\"x\": " << b.position.x()
      << ", \"y\": " << b.position.y() << "}}";
    ++n;
  }
  j << "]}";
  return j.str();
}

// A name as a JSON string, or null.
std::string Quoted(const char* name) { return name == nullptr ? "null" : "\"" + std::string(name) + "\""; }

// One stroke as a JSON line (--strokes); with `tables`, the turn's table too
// (--stroke-tables).
void PrintStroke(const planner::StrokeRecord& s, bool tables, std::ostream& out) {
  const std::string on = Upper(planner::ToString(s.ball_on));
  const char* in_hand = s.turn == planner::TurnType::kOnTable ? "false" : "true";
  std::ostringstream j;
  j << "{\"frame\": " << s.frame << ", \"stroke\": " << s.stroke << ", \"striker\": \"" << (s.striker == 0 ? "A" : "B")
    << "\", \"turn\": \"" << planner::ToString(s.turn) << "\", \"kind\": " << Quoted(s.stall ? nullptr : planner::ToString(s.kind))
    << ", \"route\": " << Quoted(!s.stall && s.kind == planner::ShotKind::kPot ? planner::ToString(s.route) : nullptr)
    << ", \"stall\": " << (s.stall ? "true" : "false")
    << ", \"potProbability\": " << Number(s.pot_probability) << ", \"planScore\": " << Number(s.plan_score)
    << ", \"potted\": " << s.potted << ", \"foul\": \"" << planner::ToString(s.foul) << "\", \"points\": " << s.points
    << ", \"penalty\": " << s.penalty << ", \"scoreA\": " << s.score[0] << ", \"scoreB\": " << s.score[1]
    << ", \"planMs\": " << Number(s.plan_ms) << ", \"handoverPot\": " << Number(s.handover_outlook)
    // A string: 64 bits do not fit a JSON reader's double.
    << ", \"planSeed\": \"" << s.plan_seed << "\"";
  j << ", \"planHandovers\": ";
  if (s.stall || s.plan_samples == 0) {
    j << "null";
  } else {
    const planner::Handovers& h = s.plan_handovers;
    j << "{\"samples\": " << s.plan_samples << ", \"runs\": " << h.runs << ", \"snookeredRuns\": " << h.snookered_runs
      << ", \"meanPotProbability\": " << Number(h.mean_pot_probability) << "}";
  }
  if (tables) j << ", \"on\": \"" << on << "\", \"inHand\": " << in_hand << ", \"table\": " << TableJson(s.table);
  if (s.stall) {
    // Why the plan gave no stroke, and its table in snooker plan's --table format
    // with the ball on in --on's spelling: `snooker plan` plays the turn again.
    j << ", \"stallReason\": " << JsonString(s.stall_reason) << ", \"stallOn\": \"" << on
      << "\", \"stallInHand\": " << in_hand << ", \"stallTable\": " << TableJson(s.table);
  }
  j << "}\n";
  out << j.str();
}

void PrintText(const planner::MatchReport& r, std::ostream& out) {
  const planner::PlayerStats& a = r.players[0];
  const planner::PlayerStats& b = r.players[1];
  auto row = [&](const char* what, const auto& x, const auto& y) {
    out << "  " << std::left << std::setw(26) << what << std::right << std::setw(10) << x << std::setw(10) << y
        << "\n";
  };
  out << std::fixed << std::setprecision(1) << r.frames << " frames, " << r.shots << " strokes: A "
      << planner::ToString(a.kind) << " against B " << planner::ToString(b.kind) << "\n";
  row("", "A", "B");
  row("frames won", a.frames_won, b.frames_won);
  row("points", a.points, b.points);
  row("  of them from penalties", a.penalty_points, b.penalty_points);
  row("mean break", a.mean_break, b.mean_break);
  row("highest break", a.highest_break, b.highest_break);
  row("centuries", a.centuries, b.centuries);
  row("fouls", a.fouls, b.fouls);
  row("safeties", a.safeties, b.safeties);
  row("strokes", a.shots, b.shots);
  row("stalls", a.stalls, b.stalls);
  row("planning ms, median", a.plan_ms_p50, b.plan_ms_p50);
  row("planning ms, 99th pct", a.plan_ms_p99, b.plan_ms_p99);
  // A probability to two places, or "-" for a player who played no such stroke.
  auto probability = [](double p) {
    if (!std::isfinite(p)) return std::string("-");
    std::ostringstream s;
    s << std::fixed << std::setprecision(2) << p;
    return s.str();
  };
  if (std::isfinite(a.mean_safety_outlook) || std::isfinite(b.mean_safety_outlook)) {
    row("opponent's pot after safety", probability(a.mean_safety_outlook), probability(b.mean_safety_outlook));
  }
  if (std::isfinite(a.mean_break_off_outlook) || std::isfinite(b.mean_break_off_outlook)) {
    row("opponent's pot after break-off", probability(a.mean_break_off_outlook),
        probability(b.mean_break_off_outlook));
  }
  out << "frames stopped at the shot cap: " << r.frames_capped << " (" << r.frames_undecided
      << " level); re-spotted blacks: " << r.black_respots << "; strokes not simulated to rest: "
      << r.simulation_failures << "\n";
  std::map<std::string, int> ends;
  for (const planner::FrameSummary& f : r.records) ++ends[planner::ToString(f.end)];
  out << "frames ended by:";
  for (const auto& [why, n] : ends) out << " " << why << " " << n << ";";
  out << "\n";
}

}  // namespace

int RunMatch(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  std::set<std::string> valued = {"frames", "seed", "player-a", "player-b", "max-shots", "strokes"};
  valued.insert(std::begin(kPlayFlagNames), std::end(kPlayFlagNames));
  Args args(argv, valued, {"json", "help", "progress", "thin-break-off", "stroke-tables"});
  if (args.error().empty() && args.Switch("help")) {
    out << kMatchHelpHead << kPlayFlagsHelp << kMatchHelpTail;
    return kExitOk;
  }
  Parsed p;
  if (const std::string e = Parse(args, &p); !e.empty()) {
    err << "snooker match: " << e << "\n(see snooker match --help)\n";
    return kExitUsage;
  }
  std::function<void(int, const planner::FrameSummary&)> progress;
  if (args.Switch("progress")) {
    progress = [&err](int f, const planner::FrameSummary& s) {
      err << "frame " << f + 1 << ": " << s.score[0] << "-" << s.score[1] << " ("
          << (s.winner < 0 ? "level" : (s.winner == 0 ? "A" : "B")) << "), " << s.shots << " strokes, "
          << s.stalls << " stalls, " << s.fouls << " fouls, " << planner::ToString(s.end) << "\n";
    };
  }
  // After each safety: the opponent's best pot probability, by the planner's own
  // fast estimate (outlook.h; from the D when the cue ball is in hand).
  std::optional<planner::Planner> own;
  if (p.model) own.emplace(planner::PlannerConfig{}.WithModel(*p.model));
  const planner::Planner& planner = own ? *own : planner::Planner::Default();
  planner::PlanRequest seen;
  seen.noise = p.options.noise;
  seen.limits = p.options.limits;
  const planner::PotContext ctx = planner.ContextFor(seen);
  p.options.outlook = [&ctx](const planner::TableState& table, bool /*cue_in_hand*/, planner::BallOn on) {
    return planner::EvaluateOutlook(table, on, ctx, planner::OutlookOptions{}).pot_probability;
  };
  // The stroke log is opened before the first frame: a path that cannot be written
  // fails now, not after the match.
  std::ofstream strokes;
  const std::string strokes_path = args.Text("strokes", "").value_or("");
  if (!strokes_path.empty()) {
    strokes.open(strokes_path);
    if (!strokes) {
      err << "snooker match: cannot write --strokes '" << strokes_path << "'\n";
      return kExitFailure;
    }
    const bool tables = args.Switch("stroke-tables");
    p.options.on_stroke = [&strokes, tables](const planner::StrokeRecord& s) { PrintStroke(s, tables, strokes); };
  }
  const planner::MatchReport r = planner::RunMatch(planner, p.options, progress);
  if (strokes.is_open() && !strokes.flush()) {
    err << "snooker match: cannot write --strokes '" << strokes_path << "'\n";
    return kExitFailure;
  }
  if (args.Switch("json")) {
    PrintJson(p, r, out);
  } else {
    PrintText(r, out);
  }
  return kExitOk;
}

}  // namespace snooker::cli
