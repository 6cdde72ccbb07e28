// snooker plan: the shot planner from the command line. Reads a table file (the
// TableState of proto/snooker/v1/table.proto in Protobuf's JSON form), builds the
// PlanRequest the service takes and calls the same operation (server/plan_api.h).
#include <google/protobuf/util/json_util.h>

#include <cstdint>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/json.h"
#include "cli/svg.h"
#include "server/api.h"
#include "server/convert.h"

namespace snooker::cli {
namespace {

constexpr const char* kHelp = R"(usage: snooker plan --table T.json [--on RED|YELLOW|GREEN|BROWN|BLUE|PINK|BLACK|COLOUR]
                    [--budget-ms N] [--shots K] [--seed S] [--json] [--svg out.svg]
                    [--noise-heading-deg X] [--noise-speed X] [--noise-spin X]
                    [--noise-position-mm X] [--min-speed X] [--max-speed X]
                    [--max-topspin X] [--max-sidespin X] [--cue-clearance-m X] [--pot-only]
                    [--max-simulations N] [--samples N]

Plans the shots that pot a ball on and leave the cue ball in a good position for the
next one: every shot is searched with NLopt over speed, topspin, sidespin and cut
angle, checked with the full simulator, and ranked by its probability of success
under the robot's execution noise and the vision system's position noise (seeded
Monte Carlo).

  --table T.json   the balls, as for snooker simulate: {"balls": [{"id": "cue",
                   "kind": "CUE", "position": {"x": 0.9, "y": 0.6}}, ...]}; positions
                   in metres, x across from the left cushion, y from the baulk cushion
  --on BALL        the ball on: RED, a colour, or COLOUR (any colour, the planner
                   choosing); default: a red while reds remain, else the lowest colour
  --budget-ms N    planning time budget, ms (default 80; 1 to 60000)
  --shots K        how many shots to list, best first (default 3; 1 to 20)
  --seed S         seed of the Monte Carlo (default 1): same table and seed, same
                   answer when the budget does not cut the work short
  --json           print the answer as JSON: {"shots": [{"speed", "headingDeg",
                   "topspin", "sidespin", "cutDeg", "objectBall", "pocket",
                   "potProbability", "positionValue", "nextBall", "cueBallEnd": {"x",
                   "y"}, "events": [...]}], "reason", "simulations", "evaluations",
                   "elapsedMs"}; a shot's first four fields are a simulate shot file
  --svg out.svg    draw the best shot (both balls' paths, bold) and the cue ball's
                   path of each alternative (dashed) over the table
Noise (standard deviations; the same options as snooker selfplay):
  --noise-heading-deg X   cue heading, degrees (default 0.02)
  --noise-speed X         cue speed, fraction of the speed (default 0.01)
  --noise-spin X          topspin and sidespin, rad/s (default 2)
  --noise-position-mm X   vision, each ball centre per axis, mm (default 0.2)
Robot limits:
  --min-speed X, --max-speed X     cue-ball speed range, m/s (default 0.3 to 6)
  --max-topspin X                  largest |topspin|, fraction of the rolling spin (1)
  --max-sidespin X                 largest |sidespin|, fraction of the rolling spin (0.5)
  --cue-clearance-m X              clear bed the level cue needs behind the cue ball, m (0.10)
Planner:
  --pot-only             ignore the position left (the comparison of docs/planner.md)
  --max-simulations N    cap on simulations (default: from the budget)
  --samples N            Monte Carlo samples per ranked shot (default 48)
  --help                 this text
)";

bool ReadTable(const std::string& path, v1::TableState* table, std::ostream& err) {
  std::ifstream f(path);
  if (!f) {
    err << "snooker plan: cannot read '" << path << "'\n";
    return false;
  }
  std::stringstream ss;
  ss << f.rdbuf();
  const auto st = google::protobuf::util::JsonStringToMessage(ss.str(), table);
  if (!st.ok()) {
    err << "snooker plan: '" << path << "' is not a valid TableState JSON: " << st.message() << "\n";
    return false;
  }
  return true;
}

void PrintReadable(const v1::PlanResponse& r, std::ostream& out) {
  if (r.shots_size() == 0) out << "no shot: " << r.reason() << "\n";
  int rank = 0;
  for (const v1::PlannedShot& s : r.shots()) {
    out << std::fixed << "#" << ++rank << "  " << s.object_ball() << " into " << s.pocket()
        << std::setprecision(3) << "   P(pot) " << s.pot_probability() << ", position "
        << s.position_value() << (s.next_ball().empty() ? "" : " (next: " + s.next_ball() + ")")
        << "\n    shot: speed " << std::setprecision(4) << s.speed() << " m/s, heading "
        << s.heading_deg() << " deg, topspin " << std::setprecision(2) << s.topspin()
        << " rad/s, sidespin " << s.sidespin() << " rad/s; cut " << std::setprecision(3)
        << s.cut_deg() << " deg\n    cue ball stops at (" << std::setprecision(3)
        << s.cue_ball_end().x() << ", " << s.cue_ball_end().y() << ") m; " << s.events_size()
        << " events\n";
  }
  out << std::setprecision(1) << r.simulations() << " simulations, " << r.evaluations()
      << " NLopt evaluations, " << r.elapsed_ms() << " ms\n";
}

// The best shot's paths (ShotSvg) and each alternative's cue-ball path, dashed.
bool WriteSvg(const std::string& path, const v1::TableState& table, const v1::PlanResponse& plan,
              std::ostream& err) {
  const physics::TableModel& model = physics::DefaultTable();
  const double r = physics::BallParams{}.radius;
  std::string doc;
  std::ostringstream extra;
  extra.precision(5);
  extra << std::fixed;
  for (int k = 0; k < plan.shots_size(); ++k) {
    const v1::PlannedShot& s = plan.shots(k);
    v1::SimulateRequest sim;
    *sim.mutable_table() = table;
    sim.mutable_shot()->set_speed(s.speed());
    sim.mutable_shot()->set_heading_deg(s.heading_deg());
    sim.mutable_shot()->set_topspin(s.topspin());
    sim.mutable_shot()->set_sidespin(s.sidespin());
    sim.mutable_options()->set_include_paths(true);
    v1::SimulateResponse result;
    const server::ApiStatus st = server::Simulate(sim, &result);
    if (!st.ok()) {
      err << "snooker plan: cannot draw shot " << k + 1 << ": " << st.message << "\n";
      return false;
    }
    if (k == 0) {
      doc = ShotSvg(model, table, result, r);
      continue;
    }
    // Same mapping as ShotSvg: 250 px per metre, 30 px margin, y up the page.
    const double scale = 250, margin = 30, length = model.spec().length;
    for (const v1::BallPath& p : result.paths()) {
      if (p.id() != table.balls(server::CueIndex(table)).id() || p.points_size() < 2) continue;
      extra << "<polyline fill=\"none\" stroke=\"#ffffff\" stroke-opacity=\"0.6\" stroke-width=\"1\" "
               "stroke-dasharray=\"6 4\" points=\"";
      for (const v1::Vec2& q : p.points()) {
        extra << margin + q.x() * scale << "," << margin + (length - q.y()) * scale << " ";
      }
      extra << "\"><title>#" << k + 1 << ": " << s.object_ball() << " into " << s.pocket()
            << "</title></polyline>\n";
    }
  }
  const size_t end = doc.rfind("</svg>");
  if (end != std::string::npos) doc.insert(end, extra.str());
  std::ofstream f(path);
  f << doc;
  if (!f) {
    err << "snooker plan: cannot write '" << path << "'\n";
    return false;
  }
  return true;
}

}  // namespace

int RunPlan(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args(argv,
            {"table", "on", "budget-ms", "shots", "seed", "svg", "noise-heading-deg", "noise-speed",
             "noise-spin", "noise-position-mm", "min-speed", "max-speed", "max-topspin",
             "max-sidespin", "cue-clearance-m", "max-simulations", "samples"},
            {"json", "help", "pot-only"});
  if (args.error().empty() && args.Switch("help")) {
    out << kHelp;
    return kExitOk;
  }
  v1::PlanRequest req;
  const auto table_path = args.Text("table", std::nullopt);
  if (args.Has("on")) {
    static const std::map<std::string, v1::BallOn> kOn = {
        {"RED", v1::BALL_ON_RED},       {"COLOUR", v1::BALL_ON_COLOUR}, {"YELLOW", v1::BALL_ON_YELLOW},
        {"GREEN", v1::BALL_ON_GREEN},   {"BROWN", v1::BALL_ON_BROWN},   {"BLUE", v1::BALL_ON_BLUE},
        {"PINK", v1::BALL_ON_PINK},     {"BLACK", v1::BALL_ON_BLACK}};
    const std::string on = *args.Text("on", "");
    const auto it = kOn.find(on);
    if (it == kOn.end()) {
      err << "snooker plan: --on '" << on
          << "' is not one of RED, YELLOW, GREEN, BROWN, BLUE, PINK, BLACK, COLOUR\n";
      return kExitUsage;
    }
    req.set_ball_on(it->second);
  }
  // Each option sets its API field only when given: unset fields keep the
  // planner's defaults; the API validates the values and names the field.
  auto number = [&](const char* flag, auto set) {
    if (args.Has(flag)) {
      if (const auto x = args.Number(flag, std::nullopt)) set(*x);
    }
  };
  number("budget-ms", [&](double x) { req.set_time_budget_ms(x); });
  if (args.Has("shots")) {
    if (const auto n = args.Integer("shots", std::nullopt, 1, 20)) req.set_max_shots(static_cast<int>(*n));
  }
  if (args.Has("seed")) {
    if (const auto n = args.Integer("seed", std::nullopt, 0, std::numeric_limits<long>::max())) {
      req.set_seed(static_cast<std::uint64_t>(*n));
    }
  }
  if (args.Has("max-simulations")) {
    if (const auto n = args.Integer("max-simulations", std::nullopt, 0, 100'000'000)) {
      req.set_max_simulations(static_cast<int>(*n));
    }
  }
  if (args.Has("samples")) {
    if (const auto n = args.Integer("samples", std::nullopt, 0, 100'000)) {
      req.set_monte_carlo_samples(static_cast<int>(*n));
    }
  }
  v1::NoiseModel* noise = req.mutable_noise();
  number("noise-heading-deg", [&](double x) { noise->set_heading_sigma_deg(x); });
  number("noise-speed", [&](double x) { noise->set_speed_sigma_fraction(x); });
  number("noise-spin", [&](double x) {
    noise->set_topspin_sigma(x);
    noise->set_sidespin_sigma(x);
  });
  number("noise-position-mm", [&](double x) { noise->set_position_sigma_mm(x); });
  v1::RobotLimits* limits = req.mutable_limits();
  number("min-speed", [&](double x) { limits->set_min_speed(x); });
  number("max-speed", [&](double x) { limits->set_max_speed(x); });
  number("max-topspin", [&](double x) { limits->set_max_topspin_fraction(x); });
  number("max-sidespin", [&](double x) { limits->set_max_sidespin_fraction(x); });
  number("cue-clearance-m", [&](double x) { limits->set_cue_clearance_m(x); });
  if (args.Switch("pot-only")) req.set_position_play(false);
  if (!args.error().empty()) {
    err << "snooker plan: " << args.error() << "\n(see snooker plan --help)\n";
    return kExitUsage;
  }
  if (!ReadTable(*table_path, req.mutable_table(), err)) return kExitUsage;
  v1::PlanResponse resp;
  const server::ApiStatus status = server::Plan(req, &resp);
  if (!status.ok()) {
    err << "snooker plan: " << status.message << "\n";
    return status.code == server::ApiStatus::Code::kInvalidArgument ? kExitUsage : kExitFailure;
  }
  const auto svg_path = args.Text("svg", "");
  if (!svg_path->empty() && resp.shots_size() > 0 && !WriteSvg(*svg_path, req.table(), resp, err)) {
    return kExitFailure;
  }
  if (args.Switch("json")) {
    if (!PrintJson(resp, "snooker plan", out, err)) return kExitFailure;
  } else {
    PrintReadable(resp, out);
  }
  return kExitOk;
}

}  // namespace snooker::cli
