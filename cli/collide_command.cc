// snooker collide: one ball-ball collision (Mathavan et al. 2014) from the command
// line. Builds the same CollideRequest the gRPC service takes and calls the same
// operation (server/api.h), so both paths are one.
#include <algorithm>
#include <iomanip>
#include <map>

#include "cli/args.h"
#include "cli/model_file.h"
#include "cli/commands.h"
#include "cli/json.h"
#include "server/api.h"
#include "server/convert.h"
#include "server/limits.h"

namespace snooker::cli {
namespace {

constexpr const char* kCollideHelp = R"(usage: snooker collide --speed V0 [--topspin wT] [--sidespin wS] [--cut-deg THETA]
                       [--steps N | --tolerance X] [--mu-bb X] [--restitution E]
                       [--mu-s X] [--friction-law LAW] [--json]

Resolves one ball-ball collision with the model of Mathavan, Jackson & Parkin (2014),
then each ball's slip on the cloth until it rolls (paper section 2.5).

Frame (the paper's): the line of centres is +Y, the cue ball sits at -Y and the object
ball at +Y, Z points up. The cue ball arrives with velocity (V0 sin th, V0 cos th, 0)
and spin (-wT cos th, wT sin th, wS); the object ball is at rest.

  --speed V0         incident speed of the cue ball, m/s (> 0; required)
  --topspin wT       topspin, rad/s; positive = follow, negative = draw;
                     a rolling cue ball has wT = V0 / R = V0 / 0.02625 (default 0)
  --sidespin wS      sidespin, rad/s: the Z component of the cue ball's spin,
                     right-hand rule with Z up (positive = counter-clockwise seen
                     from above) (default 0)
  --cut-deg THETA    cut angle between V0 and the line of centres, degrees,
                     -90 < THETA < 90 (default 0: full ball)
  --steps N          use the paper's fixed-step scheme (eq. 14) with N steps
  --tolerance X      adaptive integrator: local error per step relative to the
                     incident speed, 1e-15 to 0.1 (default 1e-10; the default
                     integrator)
  --mu-bb X          ball-ball friction coefficient, 0 to 1 (default 0.05)
  --restitution E    energetic coefficient of restitution, 0 to 1 (default 0.89)
  --mu-s X           ball-cloth sliding friction coefficient, 0.01 to 1 (default 0.21)
  --friction-law L   constant (mu_bb), marlow (slip-speed dependent, Marlow 1994)
                     exponential (mu_bb + b exp(-c s), s the slip speed in m/s)
                     or exponential-impact-speed (the same, s the normal approach
                     speed at first contact, held through the impact)
  --slip-gain B      the exponential law's b, >= 0 with mu_bb + b <= 1
  --slip-decay C     the exponential law's c, 0 to 100 s/m
  --model FILE       take the parameters not given here from this model file
                     (JSON of snooker.v1.PhysicsModel; default: the paper's)
  --json             print one JSON object instead of a table:
                     {"cue": {"velocity": {x,y,z} m/s, "angularVelocity": {x,y,z} rad/s,
                     "slipEnd": {"velocity": {x,y} m/s, "speed" m/s, "exitAngleDeg" deg,
                     "time" s, "sidespin" rad/s}}, "object": {...}, "impulseSteps",
                     "rhsEvaluations", "rejectedSteps", "events", "impulseCompression" N s,
                     "impulseFinal" N s}
                     velocities are right after the impact, in the collision frame
  --help             this text
)";

// API field name -> the flag that sets it, for error messages.
const std::map<std::string, std::string>& FlagOfField() {
  static const std::map<std::string, std::string> m = {
      {"speed", "--speed"},
      {"topspin", "--topspin"},
      {"sidespin", "--sidespin"},
      {"cut_angle_deg", "--cut-deg"},
      {"parameters.mu_bb", "--mu-bb"},
      {"parameters.restitution", "--restitution"},
      {"parameters.mu_s", "--mu-s"},
      {"parameters.slip_gain", "--slip-gain"},
      {"parameters.slip_decay", "--slip-decay"},
      {"solver.steps", "--steps"},
      {"solver.tolerance", "--tolerance"},
  };
  return m;
}

std::string FlagErrors(const std::vector<server::FieldError>& errors) {
  std::string out;
  const std::size_t shown =
      std::min<std::size_t>(errors.size(), server::limits::kMaxReportedProblems);
  for (std::size_t i = 0; i < shown; ++i) {
    const server::FieldError& e = errors[i];
    const auto it = FlagOfField().find(e.field);
    if (!out.empty()) out += "; ";
    out += (it != FlagOfField().end() ? it->second : e.field) + " " + e.value + ": " + e.rule;
  }
  if (errors.size() > shown) out += "; and " + std::to_string(errors.size() - shown) + " more";
  return server::BoundMessage(std::move(out));
}

void PrintTable(const v1::CollideRequest& req, const v1::CollideResponse& r, std::ostream& out) {
  auto vec3 = [](const v1::Vec3& v) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(5) << "(" << v.x() << ", " << v.y() << ", " << v.z()
      << ")";
    return s.str();
  };
  const bool fixed = req.solver().integrator() == v1::IMPULSE_INTEGRATOR_FIXED_STEP;
  out << "Ball-ball collision, Mathavan et al. (2014), collision frame (+Y line of centres)\n"
      << "  incident: V0 " << req.speed() << " m/s, topspin " << req.topspin()
      << " rad/s, sidespin " << req.sidespin() << " rad/s, cut " << req.cut_angle_deg()
      << " deg\n"
      << "  integrator: " << (fixed ? "fixed-step (paper eq. 14)" : "adaptive") << ", "
      << r.impulse_steps() << " steps, " << r.rhs_evaluations() << " RHS evaluations, "
      << r.events() << " events\n\n";
  out << std::left << std::setw(30) << "" << std::setw(32) << "cue ball" << "object ball\n";
  auto row = [&](const char* name, const std::string& c, const std::string& o) {
    out << std::left << std::setw(30) << name << std::setw(32) << c << o << "\n";
  };
  auto num = [](double x, int digits) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << x;
    return s.str();
  };
  row("velocity after impact (m/s)", vec3(r.cue().velocity()), vec3(r.object().velocity()));
  row("spin after impact (rad/s)", vec3(r.cue().angular_velocity()),
      vec3(r.object().angular_velocity()));
  row("speed at end of slip (m/s)", num(r.cue().slip_end().speed(), 4),
      num(r.object().slip_end().speed(), 4));
  row("exit angle (deg)", num(r.cue().slip_end().exit_angle_deg(), 3),
      num(r.object().slip_end().exit_angle_deg(), 3));
  row("slip time (s)", num(r.cue().slip_end().time(), 4), num(r.object().slip_end().time(), 4));
  row("sidespin at end of slip (rad/s)", num(r.cue().slip_end().sidespin(), 3),
      num(r.object().slip_end().sidespin(), 3));
}

}  // namespace

int RunCollide(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args(argv,
            {"speed", "topspin", "sidespin", "cut-deg", "steps", "tolerance", "mu-bb",
             "restitution", "mu-s", "friction-law", "slip-gain", "slip-decay", "model"},
            {"json", "help"});
  if (args.error().empty() && args.Switch("help")) {
    out << kCollideHelp;
    return kExitOk;
  }
  v1::CollideRequest req;
  const auto speed = args.Number("speed", std::nullopt);
  const auto topspin = args.Number("topspin", 0.0);
  const auto sidespin = args.Number("sidespin", 0.0);
  const auto cut = args.Number("cut-deg", 0.0);
  if (args.error().empty() && args.Has("steps") && args.Has("tolerance")) {
    err << "snooker collide: --steps selects the fixed-step scheme and --tolerance the "
           "adaptive one; give one of them\n";
    return kExitUsage;
  }
  if (args.Has("steps")) {
    const auto steps = args.Integer("steps", std::nullopt, 1, physics::limits::kMaxFixedSteps);
    if (steps) {
      req.mutable_solver()->set_integrator(v1::IMPULSE_INTEGRATOR_FIXED_STEP);
      req.mutable_solver()->set_steps(static_cast<int>(*steps));
    }
  }
  if (args.Has("tolerance")) {
    if (const auto t = args.Number("tolerance", std::nullopt)) {
      req.mutable_solver()->set_tolerance(*t);
    }
  }
  v1::CollisionParameters* p = req.mutable_parameters();
  if (args.Has("mu-bb")) {
    if (const auto x = args.Number("mu-bb", std::nullopt)) p->set_mu_bb(*x);
  }
  if (args.Has("restitution")) {
    if (const auto x = args.Number("restitution", std::nullopt)) p->set_restitution(*x);
  }
  if (args.Has("mu-s")) {
    if (const auto x = args.Number("mu-s", std::nullopt)) p->set_mu_s(*x);
  }
  if (args.Has("slip-gain")) {
    if (const auto x = args.Number("slip-gain", std::nullopt)) p->set_slip_gain(*x);
  }
  if (args.Has("slip-decay")) {
    if (const auto x = args.Number("slip-decay", std::nullopt)) p->set_slip_decay(*x);
  }
  if (args.Has("friction-law")) {
    const auto law = args.Text("friction-law", std::nullopt);
    if (law && *law == "marlow") {
      p->set_friction_law(v1::BALL_BALL_FRICTION_LAW_MARLOW);
    } else if (law && *law == "exponential") {
      p->set_friction_law(v1::BALL_BALL_FRICTION_LAW_EXPONENTIAL);
    } else if (law && *law == "exponential-impact-speed") {
      p->set_friction_law(v1::BALL_BALL_FRICTION_LAW_EXPONENTIAL_IMPACT_SPEED);
    } else if (law && *law == "constant") {
      p->set_friction_law(v1::BALL_BALL_FRICTION_LAW_CONSTANT);
    } else if (law) {
      err << "snooker collide: --friction-law '" << *law << "' is not constant, marlow, exponential or exponential-impact-speed\n";
      return kExitUsage;
    }
  }
  bool model_ok = true;
  const std::optional<physics::Model> model = ModelFlag(args, "snooker collide", err, &model_ok);
  if (!model_ok) return kExitUsage;
  if (!args.error().empty()) {
    err << "snooker collide: " << args.error() << "\n(see snooker collide --help)\n";
    return kExitUsage;
  }
  req.set_speed(*speed);
  req.set_topspin(*topspin);
  req.set_sidespin(*sidespin);
  req.set_cut_angle_deg(*cut);

  const auto errors = server::ValidateCollideRequest(req);
  if (!errors.empty()) {
    err << "snooker collide: " << FlagErrors(errors) << "\n";
    return kExitUsage;
  }
  v1::CollideResponse resp;
  server::CallLimits limits;
  if (model) limits.model = &*model;
  const server::ApiStatus status = server::Collide(req, &resp, limits);
  if (!status.ok()) {
    err << "snooker collide: " << status.message << "\n";
    return status.code == server::ApiStatus::Code::kInvalidArgument ? kExitUsage : kExitFailure;
  }
  if (args.Switch("json")) {
    if (!PrintJson(resp, "snooker collide", out, err)) return kExitFailure;
  } else {
    PrintTable(req, resp, out);
  }
  return kExitOk;
}

}  // namespace snooker::cli
