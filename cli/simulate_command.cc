// snooker simulate: a shot on a table, from JSON files in Protobuf's JSON form (the
// table and shot messages of proto/snooker/v1/table.proto). Builds the same
// SimulateRequest the gRPC service takes and calls the same operation.

#include <iomanip>
#include <new>
#include <set>
#include <sstream>

#include "cli/args.h"
#include "cli/model_file.h"
#include "cli/client.h"
#include "cli/commands.h"
#include "cli/json.h"
#include "cli/json_input.h"
#include "cli/svg.h"
#include "cli/write_file.h"
#include "server/api.h"
#include "server/convert.h"
#include "server/limits.h"
#include "server/read_file.h"
#include "snooker/v1/service.grpc.pb.h"

namespace snooker::cli {
namespace {

constexpr const char* kSimulateHelp = R"(usage: snooker simulate --table T.json (--shot S.json | --cue C.json) [--json] [--svg out.svg]
                        [--tolerance X] [--no-impact-tables] [--max-events N]
                        [--vision-tolerance-mm MM] [--server HOST:PORT [--tls-ca CA.pem] [--tls-cert C --tls-key K]
                        [--tls-server-name N] [--deadline-ms MS]]

Simulates a shot on a full-size snooker table until every ball is at rest or
pocketed, and prints the events and where every ball ended.

Frame: x across the table from 0 (the left cushion nose, seen from the baulk end) to
1.778 m, y along it from 0 (the baulk cushion nose) to 3.569 m, z up; positions are
ball centres in metres.

  --table T.json   the balls: {"balls": [{"id": "cue", "kind": "CUE",
                   "position": {"x": 0.9, "y": 0.6}}, ...]}; kinds CUE, RED, YELLOW,
                   GREEN, BROWN, BLUE, PINK, BLACK; exactly one CUE
  --shot S.json    the cue ball right after the cue strikes it:
                   {"speed": 1.5, "headingDeg": 90, "topspin": 57.1, "sidespin": 0}
                   speed m/s; headingDeg degrees counter-clockwise from +x;
                   topspin rad/s about z x heading (positive follow, negative draw;
                   rolling = speed / 0.02625); sidespin rad/s, the z component of the
                   spin: positive is counter-clockwise seen from above, what a tip
                   striking right of centre imparts (as the robot looks along the shot)
  --cue C.json     instead of --shot, the stroke in the robot's terms, struck with the
                   model's cue (GetModel's CueModel; a plan's "cue" block is one):
                   {"speed": 1.1, "headingDeg": 90, "tipSide": 0, "tipHeight": 0.3,
                   "elevationDeg": 0}: the cue's speed m/s; its direction, degrees
                   counter-clockwise from +x; where the tip meets the ball, fractions
                   of the radius, right and up as the robot looks along the cue; the
                   cue's angle above the bed, degrees. A miscue (an offset beyond the
                   tip's limit, 0.51) or a strike that would make the ball hop is an error
  --json           print the result as JSON: {"status", "durationS", "events": [{"time"
                   s, "kind", "balls", "cushion", "pocket", "motion"}], "finalBalls":
                   [{"id", "kind", "position", "pocketed", "pocket"}]}
  --svg out.svg    also draw the table: each ball where it starts (with its id),
                   its path and where it stops, and beside the table the status
                   and the balls potted
  --tolerance X    impact integrators' local error tolerance, 1e-15 to 0.1
                   (default 1e-7; tighter also turns the impact tables off)
  --no-impact-tables
                   solve every impact with the integrators instead of answering
                   rolling balls' impacts from the precomputed tables
  --max-events N   cap on events (default 5000)
  --vision-tolerance-mm MM
                   balls overlapping, or past a cushion, by at most MM are moved
                   apart or back first, each with a warning; more is an error
                   (default 1 here, the server's own with --server; 0: no repair)
  --help           this text
)";

// Reads a JSON file into `msg`: kExitOk, kExitUsage (the file or its content is bad,
// said on `err`) or kExitFailure (out of memory).
int ReadJson(const std::string& path, google::protobuf::Message* msg, std::ostream& err) {
  std::string text, why;
  if (!server::ReadInputFile(path, &text, &why)) {
    err << "snooker simulate: cannot read '" << path << "': " << why << "\n";
    return why == server::kOutOfMemory ? kExitFailure : kExitUsage;
  }
  try {
    if (!ReadJsonMessage(text, msg, &why)) {
      err << "snooker simulate: '" << path << "' is not a valid " << msg->GetDescriptor()->name()
          << " JSON: " << server::BoundMessage(why) << "\n";
      return kExitUsage;
    }
  } catch (const std::bad_alloc&) {
    err << "snooker simulate: out of memory reading '" << path << "' (" << text.size()
        << " bytes)\n";
    return kExitFailure;
  }
  return kExitOk;
}

void PrintReadable(const v1::SimulateResponse& r, std::ostream& out) {
  for (const v1::Warning& w : r.warnings()) out << "warning: " << w.message() << "\n";
  if (r.warnings_size() > 0) out << "\n";
  out << "status: " << r.status() << ", " << std::fixed << std::setprecision(3) << r.duration_s()
      << " s, " << r.events_size() << " events\n\n";
  for (const v1::Event& e : r.events()) {
    out << std::setw(9) << std::setprecision(4) << e.time() << " s  " << std::left << std::setw(14)
        << v1::EventKind_Name(e.kind()) << std::right;
    for (int i = 0; i < e.balls_size(); ++i) out << (i ? " & " : "") << e.balls(i);
    if (!e.cushion().empty()) out << "  cushion " << e.cushion();
    if (!e.pocket().empty()) out << "  pocket " << e.pocket();
    out << "  -> " << e.motion() << "\n";
  }
  out << "\nfinal positions (m):\n";
  for (const v1::FinalBall& b : r.final_balls()) {
    out << "  " << std::left << std::setw(10) << b.id() << std::right;
    if (b.pocketed()) {
      out << "pocketed in " << b.pocket() << "\n";
    } else {
      out << std::setprecision(4) << "(" << b.position().x() << ", " << b.position().y() << ")\n";
    }
  }
}

}  // namespace

int RunSimulate(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  std::set<std::string> valued = {"table", "shot", "cue", "svg", "tolerance", "max-events",
                                  "vision-tolerance-mm", "model"};
  for (const std::string& flag : ClientFlags()) valued.insert(flag);
  Args args(argv, valued, {"json", "help", "no-impact-tables"});
  if (args.error().empty() && args.Switch("help")) {
    out << kSimulateHelp << kModelFlagHelp << "\n" << ClientFlagsHelp();
    return kExitOk;
  }
  bool model_ok = true;
  const std::optional<physics::Model> model = ModelFlag(args, "snooker simulate", err, &model_ok);
  if (!model_ok) return kExitUsage;
  const auto table_path = args.Text("table", std::nullopt);
  const bool by_cue = args.Has("cue") && !args.Has("shot");
  const auto shot_path = args.Text(by_cue ? "cue" : "shot", std::nullopt);
  v1::SimulateRequest req;
  if (args.Has("tolerance")) {
    if (const auto t = args.Number("tolerance", std::nullopt)) req.mutable_options()->set_tolerance(*t);
  }
  if (args.Has("max-events")) {
    if (const auto n = args.Integer("max-events", std::nullopt, 1, physics::limits::kMaxEvents)) {
      req.mutable_options()->set_max_events(static_cast<int>(*n));
    }
  }
  if (args.Switch("no-impact-tables")) req.mutable_options()->set_impact_tables(false);
  const auto vision = args.Number("vision-tolerance-mm", server::limits::kDefaultVisionToleranceMm);
  ClientOptions client;
  if (!ClientOptionsFrom(args, "snooker simulate", "server", 30'000, &client, err)) return kExitUsage;
  if (args.error().empty() && !server::limits::kVisionToleranceMm.Contains(*vision)) {
    err << "snooker simulate: --vision-tolerance-mm " << server::FormatNumber(*vision)
        << " is outside [0, " << server::FormatNumber(server::limits::kVisionToleranceMm.hi)
        << "]\n";
    return kExitUsage;
  }
  if (!args.error().empty()) {
    err << "snooker simulate: " << args.error() << "\n(see snooker simulate --help)\n";
    return kExitUsage;
  }
  if (model && args.Has("server")) {
    err << "snooker simulate: --model is for a local run; a server simulates with its own model (serve --model)\n";
    return kExitUsage;
  }
  if (const int rc = ReadJson(*table_path, req.mutable_table(), err); rc != kExitOk) return rc;
  if (args.Has("cue") && args.Has("shot")) {
    err << "snooker simulate: give --shot or --cue, not both\n";
    return kExitUsage;
  }
  if (const int rc = by_cue ? ReadJson(*shot_path, req.mutable_cue(), err) : ReadJson(*shot_path, req.mutable_shot(), err);
      rc != kExitOk) {
    return rc;
  }
  const auto svg_path = args.Text("svg", "");
  req.mutable_options()->set_include_paths(!svg_path->empty());
  v1::SimulateResponse resp;
  if (!client.target.empty()) {
    // The same request to a server: its vision tolerance unless one is asked for here.
    if (args.Has("vision-tolerance-mm")) req.set_vision_tolerance_mm(*vision);
    auto stub = v1::ShotPlanner::NewStub(MakeChannel(client));
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + client.deadline);
    const std::string request_id = NameCall(&context);
    const grpc::Status st = stub->Simulate(&context, req, &resp);
    if (!st.ok()) return ReportCallError("snooker simulate", client.target, st, request_id, err);
  } else {
    server::CallLimits limits;
    limits.vision_tolerance_mm = *vision;
    if (model) limits.model = &*model;
    const server::ApiStatus status = server::Simulate(req, &resp, limits);
    if (!status.ok()) {
      err << "snooker simulate: " << status.message << "\n";
      return status.code == server::ApiStatus::Code::kInvalidArgument ? kExitUsage : kExitFailure;
    }
  }
  if (!svg_path->empty()) {
    // Drawn from the table the simulation started from (after any vision repair).
    v1::TableState drawn = req.table();
    for (const v1::Warning& w : resp.warnings()) {
      for (v1::Ball& b : *drawn.mutable_balls()) {
        if (b.id() == w.ball_id()) *b.mutable_position() = w.to();
      }
    }
    if (!WriteOutputFile(*svg_path,
                         ShotSvg(physics::DefaultTable(), drawn, resp,
                                 model ? model->ball.radius : physics::BallParams{}.radius),
                         "snooker simulate", err)) {
      return kExitFailure;
    }
  }
  if (args.Switch("json")) {
    resp.clear_paths();  // the paths go into the SVG; JSON carries events and finals
    if (!PrintJson(resp, "snooker simulate", out, err)) return kExitFailure;
  } else {
    PrintReadable(resp, out);
  }
  return kExitOk;
}

}  // namespace snooker::cli
