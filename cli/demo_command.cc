// snooker demo: the main job on an embedded default. It runs the service as a robot
// would meet it: starts the gRPC server on a free loopback port, then, through a
// real client stub, (1) resolves the first collision of Mathavan et al. (2014)
// Tables 1-2 and (2) simulates a built-in shot on a built-in table (a pot of the
// black with reds around it), and prints both. --svg draws the shot.
#include <grpcpp/grpcpp.h>

#include <cmath>
#include <iomanip>

#include "cli/args.h"
#include "cli/client.h"
#include "cli/commands.h"
#include "cli/load_tables.h"
#include "cli/svg.h"
#include "cli/write_file.h"
#include "server/api.h"
#include "server/server.h"
#include "snooker/v1/service.grpc.pb.h"

namespace snooker::cli {
namespace {

v1::SimulateRequest DemoShot() {
  v1::SimulateRequest r;
  BuiltinTable("black", r.mutable_table());  // the cue ball, the black, three reds
  const physics::TableModel& table = physics::DefaultTable();
  const physics::Vec2 black = table.spot(physics::Colour::kBlack);
  // Cut the black (about 13 deg) into the top-left pocket: the ghost-ball line to the
  // mouth, turned 0.22 deg to allow for the throw that ball-ball friction gives the
  // black (found by simulating: the pot drops for turns of -0.32 to -0.12 deg).
  const physics::Pocket& pocket = table.pocket(physics::PocketId::kTopLeft);
  const physics::Vec2 to_pocket = (pocket.mouth_centre - black).normalized();
  const physics::Vec2 ghost = black - 2 * physics::BallParams{}.radius * to_pocket;
  const physics::Vec2 cue(r.table().balls(0).position().x(), r.table().balls(0).position().y());
  const physics::Vec2 aim = ghost - cue;
  constexpr double kThrowAllowanceDeg = -0.22;
  r.mutable_shot()->set_speed(2.2);
  r.mutable_shot()->set_heading_deg(physics::RadToDeg(std::atan2(aim.y(), aim.x())) +
                                    kThrowAllowanceDeg);
  r.mutable_shot()->set_topspin(-30);  // a touch of draw
  r.mutable_options()->set_include_paths(true);
  return r;
}

}  // namespace

int RunDemo(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args(argv, {"svg"}, {"help"});
  if (args.error().empty() && args.Switch("help")) {
    out << "usage: snooker demo [--svg out.svg]\n\nStarts the service on a free loopback "
           "port and, as a client, resolves the paper's first collision and simulates a "
           "built-in shot.\n";
    return kExitOk;
  }
  const auto svg_path = args.Text("svg", "");
  if (!args.error().empty()) {
    err << "snooker demo: " << args.error() << "\n";
    return kExitUsage;
  }
  std::string error;
  auto server = server::Server::Start("127.0.0.1:0", &error);
  if (!server) {
    err << "snooker demo: " << error << "\n";
    return kExitFailure;
  }
  out << "Service snooker.v1.ShotPlanner started on 127.0.0.1:" << server->port() << "\n\n";
  ClientOptions client;  // plaintext to loopback; MakeChannel's set-up before connecting
  client.target = "127.0.0.1:" + std::to_string(server->port());
  auto stub = v1::ShotPlanner::NewStub(MakeChannel(client));

  // (1) The paper's first shot.
  v1::CollideRequest collide;
  collide.set_speed(1.539);
  collide.set_topspin(1.539 / physics::BallParams{}.radius);  // rolling
  collide.set_cut_angle_deg(33.83);
  v1::CollideResponse c;
  grpc::ClientContext ctx1;
  if (const grpc::Status st = stub->Collide(&ctx1, collide, &c); !st.ok()) {
    err << "snooker demo: Collide failed: " << st.error_message() << "\n";
    return kExitFailure;
  }
  out << std::fixed << std::setprecision(3)
      << "Collide: Mathavan et al. (2014) shot 1, rolling cue ball 1.539 m/s, cut 33.83 deg\n"
      << "  cue ball   " << c.cue().slip_end().speed() << " m/s at "
      << c.cue().slip_end().exit_angle_deg() << " deg   (paper: 0.914 m/s, 31.93 deg)\n"
      << "  object     " << c.object().slip_end().speed() << " m/s at "
      << c.object().slip_end().exit_angle_deg() << " deg   (paper: 0.831 m/s, 32.20 deg)\n"
      << "  " << c.impulse_steps() << " integration steps, " << c.rhs_evaluations()
      << " right-hand-side evaluations\n\n";

  // (2) A shot on a table.
  const v1::SimulateRequest sim = DemoShot();
  v1::SimulateResponse s;
  grpc::ClientContext ctx2;
  if (const grpc::Status st = stub->Simulate(&ctx2, sim, &s); !st.ok()) {
    err << "snooker demo: Simulate failed: " << st.error_message() << "\n";
    return kExitFailure;
  }
  out << "Simulate: cut the black into the top-left pocket with a touch of draw\n"
      << "  " << s.status() << " after " << s.duration_s() << " s, " << s.events_size()
      << " events\n";
  for (const v1::FinalBall& b : s.final_balls()) {
    out << "  " << std::left << std::setw(8) << b.id() << std::right;
    if (b.pocketed()) {
      out << "pocketed (" << b.pocket() << ")\n";
    } else {
      out << "(" << b.position().x() << ", " << b.position().y() << ") m\n";
    }
  }
  if (!svg_path->empty()) {
    if (!WriteOutputFile(*svg_path, ShotSvg(physics::DefaultTable(), sim.table(), s, physics::BallParams{}.radius),
                         "snooker demo", err)) {
      server->Shutdown();
      return kExitFailure;
    }
    out << "  drawn in " << *svg_path << "\n";
  }
  server->Shutdown();
  return kExitOk;
}

}  // namespace snooker::cli
