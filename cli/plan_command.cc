// snooker plan: the shot planner from the command line. Reads a table file (the
// TableState of proto/snooker/v1/table.proto in Protobuf's JSON form) or takes a
// built-in table, builds the PlanRequest the service takes and calls the same
// operation (server/plan_api.h), here or on a server (--server: Plan, or PlanStream
// with --stream), and prints the same answer either way.

#include <google/protobuf/descriptor.h>

#include <algorithm>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <optional>
#include <memory>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

#include "cli/args.h"
#include "cli/model_file.h"
#include "cli/client.h"
#include "cli/commands.h"
#include "cli/json.h"
#include "cli/json_input.h"
#include "cli/load_tables.h"
#include "cli/svg.h"
#include "cli/write_file.h"
#include "server/api.h"
#include "server/convert.h"
#include "server/limits.h"
#include "server/read_file.h"
#include "snooker/v1/service.grpc.pb.h"

namespace snooker::cli {
namespace {

constexpr const char* kPlanHelp = R"(usage: snooker plan --table T.json|builtin:NAME [--on RED|YELLOW|GREEN|BROWN|BLUE|PINK|BLACK|COLOUR]
                    [--budget-ms N] [--shots K] [--seed S] [--json] [--svg out.svg] [--stream]
                    [--vision-tolerance-mm MM]
                    [--noise-aim-deg X] [--noise-cue-speed X] [--noise-tip-mm X]
                    [--noise-elevation-deg X] [--squirt-uncertainty X] [--throw-uncertainty X]
                    [--max-elevation-deg X] [--noise-heading-deg X] [--noise-speed X] [--noise-spin X]
                    [--noise-position-mm X] [--min-speed X] [--max-speed X]
                    [--max-topspin X] [--max-sidespin X] [--cue-clearance-m X] [--pot-only]
                    [--max-simulations N] [--samples N] [--cue-in-hand] [--break-value P]
                    [--kinds K,...] [--routes R,...] [--no-lookahead]
                    [--thin-break-off] [--position-spread K]
                    [--server HOST:PORT [--tls-ca CA.pem] [--tls-cert C --tls-key K]
                    [--tls-server-name N] [--deadline-ms MS]]

Plans the shots that pot a ball on and leave the cue ball in a good position for the
next one: every shot is searched with NLopt over speed, topspin, sidespin and cut
angle, checked with the full simulator, and ranked by its probability of success
under the robot's execution noise and the vision system's position noise (seeded
Monte Carlo). Each shot is listed with its kind (pot, safety, escape, break-off;
foul, naming the colour it nominates, only when no legal stroke was found), a pot
with its route (direct, plant, double, kick).

  --table T.json   the balls, as for snooker simulate: {"balls": [{"id": "cue",
                   "kind": "CUE", "position": {"x": 0.9, "y": 0.6}}, ...]}; positions
                   in metres, x across from the left cushion, y from the baulk cushion;
                   or builtin:NAME, a built-in table: black (the black on its spot, three
                   reds near it), red (a red by the top-right pocket, the black, a red
                   in baulk), colours (the reds gone, the colours on their spots),
                   break-off (the 15 reds racked, the colours on their spots, the cue
                   ball in hand: --cue-in-hand is implied)
  --on BALL        the ball on, in any case: RED, a colour, or COLOUR (any colour,
                   the planner choosing); default: a red while reds remain, else the
                   lowest colour
  --budget-ms N    planning time budget, ms (default 80; 1 to 60000; with --server,
                   the server's --default-budget-ms and at most its --max-budget-ms)
  --shots K        how many shots to list, best first (default 3; 1 to 20)
  --seed S         seed of the Monte Carlo (default 1; 0 to 2^64 - 1): same table
                   and seed, same answer when the budget does not cut the work short
  --cue-in-hand    the cue ball is in hand (the break-off, or after an in-off): the
                   table has no CUE ball, and each shot says where in the D to place
                   it (the placed cue ball is named "cue", so no ball may be)
  --break-value P  what keeping the table is worth beyond the potted ball's value,
                   points (0 to 147; default 30, best for a break alone; about 100
                   wins more frames against an opponent)
  --json           print the answer as JSON: {"shots": [{"speed", "headingDeg",
                   "topspin", "sidespin", "cutDeg", "objectBall", "pocket",
                   "potProbability", "pocketProbability", "positionValue", "nextBall",
                   "cueBallEnd": {"x", "y"}, "events": [...], "kind", "route",
                   "firstBall", "foulProbability", "cueBallStart": {"x", "y"},
                   "ballsEnd": [{"ball", "position", "pocket"}], "expectedPoints",
                   "monteCarloSamples", "opponent": {"potProbability",
                   "expectedPoints", "snookered", "foulProbability",
                   "penaltyPoints"}, "handovers": {"runs", "snookeredRuns",
                   "meanPotProbability", "meanExpectedPoints"}}], "reason",
                   "simulations", "evaluations", "elapsedMs", "final", "warnings",
                   "simulationCap", "cutShort"}; a shot's first four fields are a
                   simulate shot file; an answer not cut short (by the clock) comes
                   again from --max-simulations simulationCap
  --svg out.svg    draw the plan (docs/plan-pictures.md): every ball's path of the
                   best shot (simulated again with the model in use), its ghost
                   ball, aim point, target pocket with P(pot) and next ball; each
                   alternative's object-ball path, dashed; the shots numbered on the
                   table and listed beside it; with no shot, the table and why
  --stream         print the best shot so far each time the search improves on it
                   ("progress" lines, or one JSON object per line with --json: final
                   false, potProbability the fast estimate), then the answer; with
                   --server through PlanStream
  --vision-tolerance-mm MM
                   balls overlapping, or past a cushion, by at most MM are moved apart
                   or back first, each with a warning; more is an error (default 1
                   here, the server's own with --server; 0: no repair)
Noise (standard deviations; the same options as snooker selfplay):
  --noise-aim-deg X       the cue's aim, degrees (default 0.02)
  --noise-cue-speed X     the cue's speed, fraction of the speed (default 0.01)
  --noise-tip-mm X        where the tip meets the ball, per axis, mm (default 0.1)
  --noise-elevation-deg X the cue's elevation, degrees (default 0.1)
  --squirt-uncertainty X  the model's squirt, give or take this fraction (default 0.15)
  --throw-uncertainty X   the model's throw, give or take this fraction (default 0.10)
  --noise-heading-deg X   more noise on the cue ball's heading after the strike,
                          degrees (default 0)
  --noise-speed X         more on its speed, fraction of the speed (default 0)
  --noise-spin X          more on its topspin and sidespin, rad/s (default 0)
  --noise-position-mm X   vision, each ball centre per axis, mm (default 0.2)
Robot limits:
  --min-speed X, --max-speed X     cue-ball speed range, m/s (default 0.3 to 6)
  --max-topspin X                  largest |topspin|, fraction of the rolling spin (1.25)
  --max-sidespin X                 largest |sidespin|, fraction of the rolling spin (0.5)
  --cue-clearance-m X              clear bed the cue needs behind the cue ball, m (0.10)
  --max-elevation-deg X            the steepest the cue may be raised, degrees (25; 0:
                                   always level)
Planner:
  --pot-only             ignore the position left (the comparison of docs/planner.md)
  --kinds K,...          the kinds of shot it may offer, of POT, SAFETY, ESCAPE,
                         BREAK_OFF, FOUL (default all)
  --routes R,...         the routes its pots may take, of DIRECT, PLANT, DOUBLE, KICK
                         (default all)
  --no-lookahead         estimate the position each shot leaves, without searching
                         the next shot (one-ply); --kinds POT --routes DIRECT
                         --no-lookahead plays as snooker match's direct-pots
  --thin-break-off       on the break-off's table, also search the thin break on an
                         end red beside the soft break into the pack
  --position-spread K    value a pot's position over the cue ball's end spread, K
                         standard deviations of what the speed's noise gives it (0
                         to 4; default 0: at the nominal end)
  --max-simulations N    cap on simulations (default: from the budget)
  --samples N            Monte Carlo samples per ranked shot (default 48)
  --help                 this text
)";

// The table of --table into the request's; a built-in table without a cue ball (the
// break-off's) has it in hand, and sets cue_in_hand too.
bool ReadTable(const std::string& path, v1::PlanRequest* request, std::ostream& err) {
  v1::TableState* table = request->mutable_table();
  constexpr std::string_view kBuiltin = "builtin:";
  if (path.compare(0, kBuiltin.size(), kBuiltin) == 0) {
    const std::string name = path.substr(kBuiltin.size());
    if (BuiltinTable(name, table)) {
      if (server::CueIndex(*table) < 0) request->set_cue_in_hand(true);
      return true;
    }
    err << "snooker plan: --table '" << path << "': no built-in table '" << name
        << "' (there are: " << BuiltinTableNames() << ")\n";
    return false;
  }
  std::string text, why;
  if (!server::ReadInputFile(path, &text, &why)) {
    err << "snooker plan: cannot read '" << path << "': " << why << "\n";
    return false;
  }
  if (!ReadJsonMessage(text, table, &why)) {
    err << "snooker plan: '" << path << "' is not a valid TableState JSON: " << server::BoundMessage(why)
        << "\n";
    return false;
  }
  return true;
}

void PrintReadable(const v1::PlanResponse& r, const v1::TableState& table, std::ostream& out) {
  for (const v1::Warning& w : r.warnings()) out << "warning: " << w.message() << "\n";
  if (r.warnings_size() > 0) out << "\n";
  if (r.shots_size() == 0) {
    out << "no shot: " << r.reason() << "\n";
  } else if (!r.reason().empty()) {
    out << "note: " << r.reason() << "\n";  // a foul as the last resort, a stroke past the budget
  }
  int rank = 0;
  for (const v1::PlannedShot& s : r.shots()) {
    out << std::fixed << "#" << ++rank << "  " << ShotLabel(s, table) << std::setprecision(3) << "   ";
    if (s.kind() == v1::POT) out << "P(pot) " << s.pot_probability() << ", ";
    const std::string leave = LeaveLabel(s, 3);
    out << "P(foul) " << s.foul_probability() << (leave.empty() ? "" : ", " + leave) << "; worth "
        << std::setprecision(2) << s.expected_points() << " points";
    if (s.monte_carlo_samples() > 0) out << " over " << s.monte_carlo_samples() << " runs";
    out << "\n";
    if (s.has_cue_ball_start()) {
      out << "    cue ball in hand: place it at (" << s.cue_ball_start().x() << ", " << s.cue_ball_start().y()
          << ") m, in the D\n";
    }
    if (s.handovers().runs() > 0) {
      const v1::Handovers& h = s.handovers();
      out << "    handed over in " << h.runs() << " of " << s.monte_carlo_samples() << " runs: their best pot "
          << std::setprecision(3) << h.mean_pot_probability() << " and " << std::setprecision(2)
          << h.mean_expected_points() << " points on average, snookered in " << h.snookered_runs() << "\n";
    }
    out << "    shot: speed " << std::setprecision(4) << s.speed() << " m/s, heading "
        << s.heading_deg() << " deg, topspin " << std::setprecision(2) << s.topspin()
        << " rad/s, sidespin " << s.sidespin() << " rad/s; cut " << std::setprecision(3)
        << s.cut_deg() << " deg\n    cue: speed " << std::setprecision(4) << s.cue().speed() << " m/s, heading "
        << s.cue().heading_deg() << " deg, tip " << std::setprecision(2) << s.cue().tip_side() << " R right, "
        << s.cue().tip_height() << " R up, elevation " << std::setprecision(1) << s.cue().elevation_deg()
        << " deg\n    cue ball stops at (" << std::setprecision(3)
        << s.cue_ball_end().x() << ", " << s.cue_ball_end().y() << ") m; " << s.events_size()
        << " events\n";
  }
  out << std::setprecision(1) << r.simulations() << " simulations of " << r.simulation_cap() << ", "
      << r.evaluations() << " NLopt evaluations, " << r.elapsed_ms() << " ms; "
      << (r.cut_short() ? "cut short by the clock: another run may differ"
                        : "--max-simulations " + std::to_string(r.simulation_cap()) + " repeats it")
      << "\n";
}

// A progress message of --stream: the best verified shot so far.
void PrintProgress(const v1::PlanResponse& r, const v1::TableState& table, bool json, std::ostream& out,
                   std::ostream& err) {
  if (json) {
    PrintJson(r, "snooker plan", out, err);
    return;
  }
  for (const v1::PlannedShot& s : r.shots()) {
    out << std::fixed << std::setprecision(1) << "progress " << r.elapsed_ms() << " ms: " << ShotLabel(s, table)
        << std::setprecision(3);
    if (s.kind() == v1::POT) out << ", P(pot) estimate " << s.pot_probability();
    const std::string leave = LeaveLabel(s, 3);
    out << (leave.empty() ? "" : ", " + leave) << std::setprecision(4) << "; speed " << s.speed()
        << " m/s, heading " << s.heading_deg() << " deg\n";
  }
  out << std::flush;
}

// What the flags ask for: the request (its table read later) and how to run it.
struct PlanSettings {
  v1::PlanRequest request;
  std::string table_path;  // a file, or builtin:NAME
  ClientOptions client;    // target empty: plan here
  double vision_tolerance_mm = server::limits::kDefaultVisionToleranceMm;
  bool vision_tolerance_given = false;
  bool json = false;
  bool stream = false;
  std::string svg_path;  // empty: no drawing
  std::optional<physics::Model> model;  // --model: plan with it (here only)
};

// --on into the request's ball_on. False after saying why on `err`.
bool SetBallOn(Args& args, v1::PlanRequest* req, std::ostream& err) {
  const std::string on = *args.Text("on", "");
  const google::protobuf::EnumValueDescriptor* value = FindInAnyCase(v1::BallOn_descriptor(), on);
  if (value == nullptr || value->number() == v1::BALL_ON_UNSPECIFIED) {
    err << "snooker plan: --on '" << on << "' is not one of " << ValueList(v1::BallOn_descriptor())
        << " (in any case)\n";
    return false;
  }
  req->set_ball_on(static_cast<v1::BallOn>(value->number()));
  return true;
}

// A flag's comma-separated names of an API enum's values (*_UNSPECIFIED, the value
// 0, is none) into their numbers. False after saying why on `err`.
bool EnumList(Args& args, const char* flag, const google::protobuf::EnumDescriptor* type, std::vector<int>* out,
              std::ostream& err) {
  if (!args.Has(flag)) return true;
  const std::string list = *args.Text(flag, "");
  size_t begin = 0;
  while (true) {
    const size_t end = std::min(list.find(',', begin), list.size());
    const std::string item = list.substr(begin, end - begin);
    const google::protobuf::EnumValueDescriptor* value = type->FindValueByName(item);
    if (value == nullptr || value->number() == 0) {
      std::string names;
      for (int k = 0; k < type->value_count(); ++k) {
        if (type->value(k)->number() != 0) names += (names.empty() ? "" : ", ") + std::string(type->value(k)->name());
      }
      err << "snooker plan: --" << flag << " '" << list << "': '" << item << "' is not one of " << names
          << " (a comma-separated list)\n";
      return false;
    }
    out->push_back(value->number());
    if (end == list.size()) return true;
    begin = end + 1;
  }
}

// --kinds and --routes into the request's kinds and routes. False after saying why
// on `err`.
bool SetKindsAndRoutes(Args& args, v1::PlanRequest* req, std::ostream& err) {
  std::vector<int> kinds, routes;
  if (!EnumList(args, "kinds", v1::ShotKind_descriptor(), &kinds, err) ||
      !EnumList(args, "routes", v1::PotRoute_descriptor(), &routes, err)) {
    return false;
  }
  for (const int k : kinds) req->add_kinds(static_cast<v1::ShotKind>(k));
  for (const int r : routes) req->add_routes(static_cast<v1::PotRoute>(r));
  return true;
}

// The request's fields from the flags given. Each option sets its API field only
// when given: unset fields keep the planner's defaults. A flag's value must parse as
// the field's type (a finite number; a whole number that fits the field): anything
// else is an error in `args`; the API validates the value's range and names the
// field (max_shots, monte_carlo_samples, ...).
void SetRequestFields(Args& args, v1::PlanRequest* req) {
  auto number = [&](const char* flag, auto set) {
    if (args.Has(flag)) {
      if (const auto x = args.Number(flag, std::nullopt)) set(*x);
    }
  };
  auto int32 = [&](const char* flag, auto set) {
    using Limits = std::numeric_limits<std::int32_t>;
    if (args.Has(flag)) {
      if (const auto n = args.Integer(flag, std::nullopt, Limits::min(), Limits::max())) {
        set(static_cast<std::int32_t>(*n));
      }
    }
  };
  number("budget-ms", [&](double x) { req->set_time_budget_ms(x); });
  int32("shots", [&](std::int32_t n) { req->set_max_shots(n); });
  if (args.Has("seed")) {
    if (const auto n = args.Unsigned64("seed", std::nullopt)) req->set_seed(*n);
  }
  int32("max-simulations", [&](std::int32_t n) { req->set_max_simulations(n); });
  int32("samples", [&](std::int32_t n) { req->set_monte_carlo_samples(n); });
  number("break-value", [&](double x) { req->set_break_value(x); });
  number("position-spread", [&](double x) { req->set_position_spread(x); });
  v1::NoiseModel* noise = req->mutable_noise();
  number("noise-heading-deg", [&](double x) { noise->set_heading_sigma_deg(x); });
  number("noise-speed", [&](double x) { noise->set_speed_sigma_fraction(x); });
  number("noise-spin", [&](double x) {
    noise->set_topspin_sigma(x);
    noise->set_sidespin_sigma(x);
  });
  number("noise-position-mm", [&](double x) { noise->set_position_sigma_mm(x); });
  number("noise-aim-deg", [&](double x) { noise->set_aim_sigma_deg(x); });
  number("noise-cue-speed", [&](double x) { noise->set_cue_speed_sigma_fraction(x); });
  number("noise-tip-mm", [&](double x) { noise->set_tip_offset_sigma_mm(x); });
  number("noise-elevation-deg", [&](double x) { noise->set_elevation_sigma_deg(x); });
  number("squirt-uncertainty", [&](double x) { noise->set_squirt_sigma_fraction(x); });
  number("throw-uncertainty", [&](double x) { noise->set_throw_sigma_fraction(x); });
  v1::RobotLimits* limits = req->mutable_limits();
  number("min-speed", [&](double x) { limits->set_min_speed(x); });
  number("max-speed", [&](double x) { limits->set_max_speed(x); });
  number("max-topspin", [&](double x) { limits->set_max_topspin_fraction(x); });
  number("max-sidespin", [&](double x) { limits->set_max_sidespin_fraction(x); });
  number("cue-clearance-m", [&](double x) { limits->set_cue_clearance_m(x); });
  number("max-elevation-deg", [&](double x) { limits->set_max_elevation_deg(x); });
  if (args.Switch("pot-only")) req->set_position_play(false);
  if (args.Switch("cue-in-hand")) req->set_cue_in_hand(true);
  if (args.Switch("no-lookahead")) req->set_lookahead(false);
  if (args.Switch("thin-break-off")) req->set_thin_break_off(true);
}

// Reads and checks the flags, and the table, into `s`. An exit code when the command
// ends here (after --help, or a usage error said on `err`); nothing to go ahead.
std::optional<int> ParsePlanFlags(const std::vector<std::string>& argv, std::ostream& out,
                                  std::ostream& err, PlanSettings* s) {
  std::set<std::string> valued = {"table", "on", "budget-ms", "shots", "seed", "svg",
                                  "noise-heading-deg", "noise-speed", "noise-spin", "noise-aim-deg",
                                  "noise-cue-speed", "noise-tip-mm", "noise-elevation-deg", "squirt-uncertainty",
                                  "throw-uncertainty", "max-elevation-deg",
                                  "noise-position-mm", "min-speed", "max-speed", "max-topspin",
                                  "max-sidespin", "cue-clearance-m", "max-simulations", "samples",
                                  "vision-tolerance-mm", "model", "break-value", "kinds", "routes",
                                  "position-spread"};
  for (const std::string& flag : ClientFlags()) valued.insert(flag);
  Args args(argv, valued,
            {"json", "help", "pot-only", "stream", "cue-in-hand", "no-lookahead", "thin-break-off"});
  if (args.error().empty() && args.Switch("help")) {
    out << kPlanHelp << kModelFlagHelp << "\n" << ClientFlagsHelp();
    return kExitOk;
  }
  bool model_ok = true;
  s->model = ModelFlag(args, "snooker plan", err, &model_ok);
  if (!model_ok) return kExitUsage;
  if (s->model && args.Has("server")) {
    err << "snooker plan: --model is for a local plan; a server plans with its own model (serve --model)\n";
    return kExitUsage;
  }
  const auto table_path = args.Text("table", std::nullopt);
  if (args.Has("on") && !SetBallOn(args, &s->request, err)) return kExitUsage;
  if (!SetKindsAndRoutes(args, &s->request, err)) return kExitUsage;
  SetRequestFields(args, &s->request);
  const auto vision = args.Number("vision-tolerance-mm", server::limits::kDefaultVisionToleranceMm);
  if (!ClientOptionsFrom(args, "snooker plan", "server", 60'000, &s->client, err)) return kExitUsage;
  // Here, the flag is the tolerance of the local "server" (PlanControl), which the
  // API takes as given: checked against what `snooker serve --vision-tolerance-mm`
  // accepts. With --server it is the request's vision_tolerance_mm, which the server
  // checks.
  const physics::Range& tolerances = server::limits::kVisionToleranceMm;
  if (args.error().empty() && s->client.target.empty() && !tolerances.Contains(*vision)) {
    err << "snooker plan: --vision-tolerance-mm " << server::FormatNumber(*vision) << " is outside ["
        << server::FormatNumber(tolerances.lo) << ", " << server::FormatNumber(tolerances.hi) << "]\n";
    return kExitUsage;
  }
  if (!args.error().empty()) {
    err << "snooker plan: " << args.error() << "\n(see snooker plan --help)\n";
    return kExitUsage;
  }
  if (!ReadTable(*table_path, &s->request, err)) return kExitUsage;
  s->table_path = *table_path;
  s->vision_tolerance_mm = *vision;
  s->vision_tolerance_given = args.Has("vision-tolerance-mm");
  s->json = args.Switch("json");
  s->stream = args.Switch("stream");
  s->svg_path = *args.Text("svg", "");
  return std::nullopt;
}

// The plan from the server of --server (Plan, or PlanStream with --stream, printing
// the progress): kExitOk with the answer in `resp`, or the exit code after saying why.
int PlanOnServer(const PlanSettings& s, v1::PlanResponse* resp, std::ostream& out, std::ostream& err) {
  // The same request to a server: its vision tolerance unless one is asked for here.
  v1::PlanRequest req = s.request;
  if (s.vision_tolerance_given) req.set_vision_tolerance_mm(s.vision_tolerance_mm);
  auto stub = v1::ShotPlanner::NewStub(MakeChannel(s.client));
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + s.client.deadline);
  const std::string request_id = NameCall(&context);
  if (!s.stream) {
    const grpc::Status st = stub->Plan(&context, req, resp);
    return st.ok() ? kExitOk : ReportCallError("snooker plan", s.client.target, st, request_id, err);
  }
  auto reader = stub->PlanStream(&context, req);
  v1::PlanResponse message;
  bool final_seen = false;
  // A stream sends one message per improvement (at most one per candidate) and
  // the final one; the count is bounded here too.
  for (int i = 0; i < 100'000 && reader->Read(&message); ++i) {
    if (message.final()) {
      *resp = message;
      final_seen = true;
    } else {
      PrintProgress(message, s.request.table(), s.json, out, err);
    }
  }
  const grpc::Status st = reader->Finish();
  if (!st.ok()) return ReportCallError("snooker plan", s.client.target, st, request_id, err);
  if (!final_seen) {
    err << "snooker plan: " << s.client.target << " ended the stream without a final answer\n";
    return kExitFailure;
  }
  return kExitOk;
}

// The plan computed here, with the flags' vision tolerance (printing the progress
// with --stream): kExitOk with the answer in `resp`, or the exit code after saying why.
int PlanHere(const PlanSettings& s, v1::PlanResponse* resp, std::ostream& out, std::ostream& err) {
  server::PlanControl control;
  control.vision_tolerance_mm = s.vision_tolerance_mm;
  std::optional<planner::Planner> own;
  if (s.model) {
    own.emplace(planner::PlannerConfig{}.WithModel(*s.model));
    control.planner = &*own;
  }
  if (s.stream) {
    control.on_progress = [&](const v1::PlanResponse& best) { PrintProgress(best, s.request.table(), s.json, out, err); };
  }
  const server::ApiStatus status = server::Plan(s.request, resp, control);
  if (!status.ok()) {
    err << "snooker plan: " << status.message << "\n";
    return status.code == server::ApiStatus::Code::kInvalidArgument ? kExitUsage : kExitFailure;
  }
  return kExitOk;
}

// How the drawing simulates each shot again: as `snooker simulate` would, with the
// model the plan used (the server's Simulate with --server, server::Simulate with
// --model's or the default model here).
SimulateFn DrawingSimulator(const PlanSettings& s) {
  if (!s.client.target.empty()) {
    std::shared_ptr<v1::ShotPlanner::Stub> stub = v1::ShotPlanner::NewStub(MakeChannel(s.client));
    const std::chrono::milliseconds deadline = s.client.deadline;
    return [stub, deadline](const v1::SimulateRequest& request, v1::SimulateResponse* response) {
      grpc::ClientContext context;
      context.set_deadline(std::chrono::system_clock::now() + deadline);
      const grpc::Status st = stub->Simulate(&context, request, response);
      if (st.ok()) return server::ApiStatus::Ok();
      return server::ApiStatus{server::ApiStatus::Code::kInternal,
                               std::string(StatusCodeName(st.error_code())) + ": " + st.error_message()};
    };
  }
  const std::optional<physics::Model> model = s.model;
  return [model](const v1::SimulateRequest& request, v1::SimulateResponse* response) {
    server::CallLimits limits;
    if (model) limits.model = &*model;
    return server::Simulate(request, response, limits);
  };
}

double DrawnBallRadius(const PlanSettings& s) {
  return s.model ? s.model->ball.radius : physics::BallParams{}.radius;
}

// The answer: drawn with --svg, and printed (JSON with --json).
int WriteAnswer(const PlanSettings& s, const v1::PlanResponse& resp, std::ostream& out, std::ostream& err) {
  if (!s.svg_path.empty()) {
    // Drawn from the table the plan started from (after any vision repair).
    v1::TableState drawn = s.request.table();
    for (const v1::Warning& w : resp.warnings()) {
      for (v1::Ball& b : *drawn.mutable_balls()) {
        if (b.id() == w.ball_id()) *b.mutable_position() = w.to();
      }
    }
    std::string why;
    const std::string doc = PlanSvg(drawn, resp, DrawingSimulator(s), DrawnBallRadius(s), &why);
    if (doc.empty()) {
      err << "snooker plan: " << why << "\n";
      return kExitFailure;
    }
    if (!WriteOutputFile(s.svg_path, doc, "snooker plan", err)) return kExitFailure;
  }
  if (s.json) {
    if (!PrintJson(resp, "snooker plan", out, err)) return kExitFailure;
  } else {
    PrintReadable(resp, s.request.table(), out);
  }
  return kExitOk;
}

// A plan that failed (`said`: what the command said on stderr) drawn as the table,
// its balls and why, with --svg; the exit code stays the failure's.
void DrawFailure(const PlanSettings& s, const std::string& said, std::ostream& err) {
  if (s.svg_path.empty()) return;
  std::string why = said;
  constexpr std::string_view kPrefix = "snooker plan: ";
  if (why.compare(0, kPrefix.size(), kPrefix) == 0) why.erase(0, kPrefix.size());
  while (!why.empty() && why.back() == '\n') why.pop_back();
  WriteOutputFile(s.svg_path,
                  TableSvg(physics::DefaultTable(), s.request.table(), DrawnBallRadius(s), "no shot: " + why),
                  "snooker plan", err);
}

}  // namespace

int RunPlan(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  PlanSettings s;
  if (const std::optional<int> stop = ParsePlanFlags(argv, out, err, &s)) return *stop;
  v1::PlanResponse resp;
  // What the plan says on stderr, kept to draw a failure with.
  std::ostringstream said;
  const int rc = s.client.target.empty() ? PlanHere(s, &resp, out, said) : PlanOnServer(s, &resp, out, said);
  err << said.str();
  if (rc != kExitOk) {
    DrawFailure(s, said.str(), err);
    return rc;
  }
  return WriteAnswer(s, resp, out, err);
}

}  // namespace snooker::cli
