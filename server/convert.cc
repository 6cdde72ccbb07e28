#include "server/convert.h"

#include <cmath>
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
  if (o.has_steps()) s.steps = o.steps();
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
