#include "physics/impact/ball_ball.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "physics/core/limits.h"
#include "physics/impact/ball_ball_detail.h"
#include "physics/impact/ball_ball_impulse.h"

namespace snooker::physics {
namespace {

bool AllFinite(const ImpactState& s) {
  return s.c.v.allFinite() && s.c.w.allFinite() && s.o.v.allFinite() && s.o.w.allFinite();
}

bool OptionsValid(const ImpulseSolverOptions& o) {
  if (o.max_steps <= 0 || !FidelityValid(o.fidelity) || !MethodValid(o.method)) return false;
  if (o.integrator == ImpulseIntegrator::kFixedStep) return o.steps > 0;
  return limits::kTolerance.Contains(o.tolerance);
}

// The same rules as ValidateBallParams / ValidateBallBallParams, without building
// messages: this runs on every call.
bool InUnit(double x) { return std::isfinite(x) && x >= 0 && x <= 1; }
bool ParamsValid(const BallParams& ball, const BallBallParams& contact, double mu_s) {
  if (IsExponentialLaw(contact.friction_law) &&
      !ExponentialLawInRange(contact.mu_bb, contact.slip_gain, contact.slip_decay)) {
    return false;
  }
  return BallParamsValid(ball) && InUnit(contact.mu_bb) && InUnit(contact.e) && InUnit(mu_s) &&
         static_cast<unsigned>(contact.friction_law) <=
             static_cast<unsigned>(BallBallFrictionLaw::kExponentialImpactSpeed);
}

void PutVec(std::ostringstream& out, const char* name, const Vec3& v) {
  if (v.allFinite()) return;
  if (out.tellp() > 0) out << "; ";
  out << name << " = (" << v.x() << ", " << v.y() << ", " << v.z()
      << ") (every component must be a finite number)";
}

}  // namespace

double SpeedScale(const ImpactState& s, double radius) {
  return std::max({s.c.v.norm(), s.o.v.norm(), radius * s.c.w.norm(), radius * s.o.w.norm()});
}

ImpactState PaperIncidentState(double speed, double topspin, double sidespin, double cut) {
  const double s = std::sin(cut);
  const double c = std::cos(cut);
  ImpactState st;
  st.c.v = Vec3(speed * s, speed * c, 0.0);           // eq. 13a
  st.c.w = Vec3(-topspin * c, topspin * s, sidespin);  // eq. 13b
  return st;                                           // O at rest, eq. 13c
}

double KineticEnergy(const ImpactState& s, const BallParams& ball) {
  const double m = ball.mass;
  const double i = ball.Inertia();
  return 0.5 * m * (s.c.v.squaredNorm() + s.o.v.squaredNorm()) +
         0.5 * i * (s.c.w.squaredNorm() + s.o.w.squaredNorm());
}

std::string ValidateImpact(const ImpactState& in, const BallParams& ball,
                           const BallBallParams& contact, double mu_s,
                           const ImpulseSolverOptions& options) {
  std::ostringstream out;
  auto add = [&out](const std::string& msg) {
    if (msg.empty()) return;
    if (out.tellp() > 0) out << "; ";
    out << msg;
  };
  add(ValidateBallParams(ball));
  add(ValidateBallBallParams(contact));
  if (!(std::isfinite(mu_s) && mu_s >= 0 && mu_s <= 1)) {
    std::ostringstream m;
    m << "mu_s = " << mu_s << " (must be in [0, 1])";
    add(m.str());
  }
  PutVec(out, "C velocity", in.c.v);
  PutVec(out, "C angular velocity", in.c.w);
  PutVec(out, "O velocity", in.o.v);
  PutVec(out, "O angular velocity", in.o.w);
  if (AllFinite(in) && BallParamsValid(ball)) {
    add(ValidateSpeedScale(SpeedScale(in, ball.radius), "|v| and R |w| of each ball"));
  }
  add(ValidateFidelity(options.fidelity));
  add(ValidateMethod(options.method));
  const ImpulseSolverOptions o = EffectiveOptions(options);  // what the solver runs with
  if (o.max_steps <= 0) add("max_steps = " + std::to_string(o.max_steps) + " (must be > 0)");
  if (o.integrator == ImpulseIntegrator::kFixedStep && o.steps <= 0) {
    add("steps = " + std::to_string(o.steps) + " (must be > 0)");
  }
  if (o.integrator == ImpulseIntegrator::kAdaptive && !limits::kTolerance.Contains(o.tolerance)) {
    std::ostringstream m;
    m << "tolerance = " << o.tolerance << " (must be in [" << limits::kTolerance.lo << ", "
      << limits::kTolerance.hi << "])";
    add(m.str());
  }
  return out.str();
}

ImpactResult ResolveImpact(const ImpactState& in, const BallParams& ball,
                           const BallBallParams& contact, double mu_s,
                           const ImpulseSolverOptions& options) {
  ImpactResult r;
  r.out = in;
  const ImpulseSolverOptions o = EffectiveOptions(options);
  if (!AllFinite(in) || !OptionsValid(o) || !ParamsValid(ball, contact, mu_s) ||
      !SpeedScaleValid(SpeedScale(in, ball.radius))) {
    r.status = ImpactStatus::kInvalidInput;
    return r;
  }
  const double approach = in.c.v.y() - in.o.v.y();
  if (!(approach > kMinApproach * SpeedScale(in, ball.radius))) {  // eq. 5c
    r.status = ImpactStatus::kNotApproaching;
    return r;
  }
  const impulse::Model model(ball, AtImpactSpeed(contact, approach), mu_s);
  return o.integrator == ImpulseIntegrator::kFixedStep ? detail::SolveFixedStep(in, model, o)
                                                      : detail::SolveAdaptive(in, model, o);
}

}  // namespace snooker::physics
