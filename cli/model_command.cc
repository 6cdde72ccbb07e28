// `snooker model`: the effective physical model (the default, or a model file's
// values over it), as a model file or as a readable list.
#include <iomanip>
#include <iostream>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/json.h"
#include "cli/model_file.h"
#include "server/model_convert.h"
#include "snooker/v1/physics_model.pb.h"

namespace snooker::cli {
namespace {

constexpr const char* kModelHelp = R"(usage: snooker model [--model FILE] [--json]

Prints the physical model the other commands use: the balls, the cloth, the
ball-ball contact (friction law and restitution), the cushions and the robot's cue.

options:
)";

constexpr const char* kModelHelpTail = R"(  --json             print it as a model file (JSON of snooker.v1.PhysicsModel,
                     every field set): what --model FILE reads
  --help             this text
)";

void PrintText(const physics::Model& m, std::ostream& out) {
  const physics::BallBallParams& bb = m.ball_ball;
  const physics::FrictionCurve f = physics::FrictionCurveOf(bb);
  out << std::setprecision(6);
  out << "ball       mass " << m.ball.mass << " kg, radius " << m.ball.radius << " m\n"
      << "cloth      mu_s " << m.cloth.mu_s << ", mu_r " << m.cloth.mu_r << ", spin deceleration "
      << m.cloth.spin_decel << " rad/s^2, g " << m.cloth.g << " m/s^2\n"
      << "ball-ball  friction " << server::FrictionLawName(bb.friction_law) << ": mu(s) = " << f.a << " + " << f.b
      << " exp(-" << f.c << " s), s the "
      << (bb.friction_law == physics::BallBallFrictionLaw::kExponentialImpactSpeed
              ? "normal approach speed at first contact"
              : "slip speed")
      << " in m/s; restitution " << bb.e << "\n"
      << "cushion    mu_w " << m.cushion.mu_w << ", mu_s " << m.cushion.mu_s << ", restitution ";
  const physics::RestitutionCurve& c = m.cushion.restitution_curve;
  if (c.points <= 0) {
    out << m.cushion.e_e << " at every speed\n";
  } else {
    out << "curve";
    for (int i = 0; i < c.points; ++i) {
      out << (i ? ", " : " ") << c.e[static_cast<std::size_t>(i)] << " at " << c.speed[static_cast<std::size_t>(i)]
          << " m/s";
    }
    out << "\n";
  }
  out << "cue        mass " << m.cue.mass << " kg, tip radius " << m.cue.tip_radius << " m, tip restitution "
      << m.cue.tip_restitution << ", tip friction " << m.cue.tip_friction << ", end mass " << m.cue.end_mass
      << " kg, bed restitution " << m.cue.bed_restitution << ", max hop " << m.cue.max_hop << " m\n";
}

}  // namespace

int RunModel(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args(argv, {"model"}, {"json", "help"});
  if (args.error().empty() && args.Switch("help")) {
    out << kModelHelp << kModelFlagHelp << kModelHelpTail;
    return kExitOk;
  }
  bool ok = true;
  const std::optional<physics::Model> file = ModelFlag(args, "snooker model", err, &ok);
  if (!ok) return kExitUsage;
  if (!args.error().empty()) {
    err << "snooker model: " << args.error() << "\n(see snooker model --help)\n";
    return kExitUsage;
  }
  const physics::Model model = file.value_or(physics::Model{});
  if (args.Switch("json")) {
    v1::PhysicsModel proto;
    server::ModelToProto(model, &proto);
    return PrintJson(proto, "snooker model", out, err) ? kExitOk : kExitFailure;
  }
  PrintText(model, out);
  return kExitOk;
}

}  // namespace snooker::cli
