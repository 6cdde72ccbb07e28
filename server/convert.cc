#include "server/convert.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace snooker::server {
namespace {

std::string Num(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

// Adds an error when an optional double field is set and outside [lo, hi].
template <typename Msg, typename Has, typename Get>
void CheckRange(std::vector<FieldError>* errors, const Msg& m, Has has, Get get,
                const char* field, double lo, double hi) {
  if (!(m.*has)()) return;
  const double x = (m.*get)();
  if (std::isfinite(x) && x >= lo && x <= hi) return;
  errors->push_back({field, Num(x), "must be a number in [" + Num(lo) + ", " + Num(hi) + "]"});
}

void CheckFinite(std::vector<FieldError>* errors, double x, const char* field) {
  if (!std::isfinite(x)) errors->push_back({field, Num(x), "must be a finite number"});
}

}  // namespace

std::string Describe(const std::vector<FieldError>& errors) {
  std::string out;
  for (const FieldError& e : errors) {
    if (!out.empty()) out += "; ";
    out += e.field + " = " + e.value + " (" + e.rule + ")";
  }
  return out;
}

std::vector<FieldError> ValidateCollideRequest(const v1::CollideRequest& r) {
  std::vector<FieldError> errors;
  if (!(std::isfinite(r.speed()) && r.speed() > 0)) {
    errors.push_back({"speed", Num(r.speed()), "must be a finite speed > 0 m/s"});
  }
  CheckFinite(&errors, r.topspin(), "topspin");
  CheckFinite(&errors, r.sidespin(), "sidespin");
  if (!(std::isfinite(r.cut_angle_deg()) && std::abs(r.cut_angle_deg()) < 90)) {
    errors.push_back({"cut_angle_deg", Num(r.cut_angle_deg()),
                      "must be in (-90, 90): at 90 deg or more the balls do not meet"});
  }
  using P = v1::CollisionParameters;
  const P& p = r.parameters();
  CheckRange(&errors, p, &P::has_mu_bb, &P::mu_bb, "parameters.mu_bb", 0, 1);
  CheckRange(&errors, p, &P::has_restitution, &P::restitution, "parameters.restitution", 0, 1);
  CheckRange(&errors, p, &P::has_mu_s, &P::mu_s, "parameters.mu_s", 0, 1);
  CheckRange(&errors, p, &P::has_mass_kg, &P::mass_kg, "parameters.mass_kg", 1e-3, 10);
  CheckRange(&errors, p, &P::has_radius_m, &P::radius_m, "parameters.radius_m", 1e-3, 1);
  CheckRange(&errors, p, &P::has_gravity, &P::gravity, "parameters.gravity", 0.1, 100);
  CheckRange(&errors, p, &P::has_spin_decel, &P::spin_decel, "parameters.spin_decel", 0, 1e4);
  using S = v1::ImpulseSolverOptions;
  const S& s = r.solver();
  if (s.has_steps() && s.steps() <= 0) {
    errors.push_back({"solver.steps", std::to_string(s.steps()), "must be an integer > 0"});
  }
  CheckRange(&errors, s, &S::has_tolerance, &S::tolerance, "solver.tolerance", 1e-15, 0.1);
  return errors;
}

std::vector<FieldError> ValidateSimulateRequest(const v1::SimulateRequest& r,
                                                const physics::TableModel& table) {
  std::vector<FieldError> errors;
  const v1::TableState& t = r.table();
  if (t.balls_size() == 0) errors.push_back({"table.balls", "[]", "must list at least the cue ball"});
  if (t.balls_size() > physics::Simulator::kMaxBalls) {
    errors.push_back({"table.balls", std::to_string(t.balls_size()) + " balls",
                      "at most " + std::to_string(physics::Simulator::kMaxBalls)});
  }
  std::set<std::string> ids;
  int cues = 0;
  bool positions_ok = true;
  for (int i = 0; i < t.balls_size(); ++i) {
    const v1::Ball& b = t.balls(i);
    const std::string where = "table.balls[" + std::to_string(i) + "]";
    if (b.id().empty()) errors.push_back({where + ".id", "\"\"", "must not be empty"});
    if (!ids.insert(b.id()).second) {
      errors.push_back({where + ".id", "\"" + b.id() + "\"", "is used by another ball"});
    }
    if (b.kind() == v1::BALL_KIND_UNSPECIFIED || !v1::BallKind_IsValid(b.kind())) {
      errors.push_back({where + ".kind", std::to_string(b.kind()) + " (ball \"" + b.id() + "\")",
                        "must be one of CUE, RED, YELLOW, GREEN, BROWN, BLUE, PINK, BLACK"});
    }
    if (b.kind() == v1::CUE) ++cues;
    if (!(std::isfinite(b.position().x()) && std::isfinite(b.position().y()))) {
      errors.push_back({where + ".position", "(" + Num(b.position().x()) + ", " +
                                                 Num(b.position().y()) + ") (ball \"" + b.id() + "\")",
                        "must be finite, in metres"});
      positions_ok = false;
    }
  }
  if (t.balls_size() > 0 && cues != 1) {
    errors.push_back({"table.balls", std::to_string(cues) + " CUE balls", "must have exactly one"});
  }
  if (positions_ok && t.balls_size() > 0) {
    std::vector<physics::BallPlacement> placed;
    for (const v1::Ball& b : t.balls()) {
      placed.push_back({b.id(), physics::Vec2(b.position().x(), b.position().y())});
    }
    const std::string msg = table.ValidatePlacement(placed);
    if (!msg.empty()) errors.push_back({"table.balls", "positions", msg});
  }
  const v1::Shot& shot = r.shot();
  if (!(std::isfinite(shot.speed()) && shot.speed() >= 0 && shot.speed() <= 20)) {
    errors.push_back({"shot.speed", Num(shot.speed()), "must be in [0, 20] m/s"});
  }
  CheckFinite(&errors, shot.heading_deg(), "shot.heading_deg");
  for (const auto& [x, name] : {std::pair{shot.topspin(), "shot.topspin"},
                                std::pair{shot.sidespin(), "shot.sidespin"}}) {
    if (!(std::isfinite(x) && std::abs(x) <= 1000)) {
      errors.push_back({name, Num(x), "must be in [-1000, 1000] rad/s"});
    }
  }
  using O = v1::SimulationOptions;
  const O& o = r.options();
  if (o.has_max_events() && (o.max_events() < 1 || o.max_events() > 1'000'000)) {
    errors.push_back({"options.max_events", std::to_string(o.max_events()), "must be in [1, 1000000]"});
  }
  CheckRange(&errors, o, &O::has_max_time_s, &O::max_time_s, "options.max_time_s", 1e-3, 3600);
  CheckRange(&errors, o, &O::has_tolerance, &O::tolerance, "options.tolerance", 1e-15, 0.1);
  CheckRange(&errors, o, &O::has_path_sample_s, &O::path_sample_s, "options.path_sample_s", 1e-4, 1);
  return errors;
}

int CueIndex(const v1::TableState& table) {
  for (int i = 0; i < table.balls_size(); ++i) {
    if (table.balls(i).kind() == v1::CUE) return i;
  }
  return -1;
}

physics::Shot ShotFrom(const v1::Shot& shot) {
  return {shot.speed(), physics::DegToRad(shot.heading_deg()), shot.topspin(), shot.sidespin()};
}

std::vector<physics::BallState> BallStatesFrom(const v1::TableState& table, const v1::Shot& shot) {
  std::vector<physics::BallState> balls;
  for (const v1::Ball& b : table.balls()) {
    const physics::Vec2 r(b.position().x(), b.position().y());
    if (b.kind() == v1::CUE) {
      balls.push_back(physics::StruckBall(ShotFrom(shot), r));
    } else {
      physics::BallState s;
      s.r = r;
      balls.push_back(s);
    }
  }
  return balls;
}

physics::SimParams SimParamsFrom(const v1::SimulationOptions& o) {
  physics::SimParams p;
  if (o.has_max_events()) p.max_events = o.max_events();
  if (o.has_max_time_s()) p.max_time = o.max_time_s();
  if (o.has_tolerance()) p.ball_ball_solver.tolerance = p.cushion_solver.tolerance = o.tolerance();
  return p;
}

physics::BallParams BallParamsFrom(const v1::CollisionParameters& p) {
  physics::BallParams b;
  if (p.has_mass_kg()) b.mass = p.mass_kg();
  if (p.has_radius_m()) b.radius = p.radius_m();
  return b;
}

physics::ClothParams ClothParamsFrom(const v1::CollisionParameters& p) {
  physics::ClothParams c;
  if (p.has_mu_s()) c.mu_s = p.mu_s();
  if (p.has_gravity()) c.g = p.gravity();
  if (p.has_spin_decel()) c.spin_decel = p.spin_decel();
  return c;
}

physics::BallBallParams BallBallParamsFrom(const v1::CollisionParameters& p) {
  physics::BallBallParams c;
  if (p.has_mu_bb()) c.mu_bb = p.mu_bb();
  if (p.has_restitution()) c.e = p.restitution();
  if (p.friction_law() == v1::BALL_BALL_FRICTION_LAW_MARLOW) {
    c.friction_law = physics::BallBallFrictionLaw::kMarlow;
  }
  return c;
}

physics::ImpulseSolverOptions SolverOptionsFrom(const v1::ImpulseSolverOptions& o) {
  physics::ImpulseSolverOptions s;
  if (o.integrator() == v1::IMPULSE_INTEGRATOR_FIXED_STEP) {
    s.integrator = physics::ImpulseIntegrator::kFixedStep;
  }
  if (o.has_steps()) {
    s.steps = o.steps();
    // The scheme takes about N/2 steps (N for a wall): keep the cap above that.
    s.max_steps = std::max(s.max_steps, 4 * s.steps);
  }
  if (o.has_tolerance()) s.tolerance = o.tolerance();
  return s;
}

void ToProto(const physics::Vec2& v, v1::Vec2* out) {
  out->set_x(v.x());
  out->set_y(v.y());
}

void ToProto(const physics::Vec3& v, v1::Vec3* out) {
  out->set_x(v.x());
  out->set_y(v.y());
  out->set_z(v.z());
}

}  // namespace snooker::server
