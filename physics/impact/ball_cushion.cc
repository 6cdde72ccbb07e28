#include "physics/impact/ball_cushion.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "physics/core/limits.h"
#include "physics/impact/ball_cushion_impulse.h"

namespace snooker::physics {
namespace {

void Add(std::ostringstream& out, const std::string& msg) {
  if (msg.empty()) return;
  if (out.tellp() > 0) out << "; ";
  out << msg;
}

bool Coefficient(double x) { return std::isfinite(x) && x >= 0 && x <= 1; }

void CheckCoefficient(std::ostringstream& out, const char* name, double value) {
  if (Coefficient(value)) return;
  std::ostringstream m;
  m << name << " = " << value << " (must be in [0, 1])";
  Add(out, m.str());
}

void CheckVec(std::ostringstream& out, const char* name, const Vec3& v) {
  if (v.allFinite()) return;
  std::ostringstream m;
  m << name << " = (" << v.x() << ", " << v.y() << ", " << v.z()
    << ") (every component must be a finite number)";
  Add(out, m.str());
}

// The checks, without building messages (ResolveCushionImpact must not allocate).
struct OptionChecks {
  bool fidelity, method, max_steps, steps, tolerance;
  bool Ok() const { return fidelity && method && max_steps && steps && tolerance; }
};

OptionChecks CheckOptions(const ImpulseSolverOptions& given) {
  const ImpulseSolverOptions o = EffectiveOptions(given);  // what the solver runs with
  OptionChecks k;
  k.fidelity = FidelityValid(given.fidelity);
  k.method = MethodValid(given.method);
  k.max_steps = o.max_steps > 0;
  k.steps = o.integrator != ImpulseIntegrator::kFixedStep || o.steps > 0;
  k.tolerance = o.integrator != ImpulseIntegrator::kAdaptive ||
                (limits::kTolerance.Contains(o.tolerance));
  return k;
}

struct ParamChecks {
  bool ball = false, e_e = false, mu_w = false, mu_s = false;
  bool points = false;  // the restitution curve's point count in [0, kMaxPoints]
  int bad_knot = -1;    // its first invalid knot
  bool height = false;  // R < h < 2R
  bool lift = false;    // mu_w cos th < sin th: the cloth reaction stays positive
  bool fall = false;    // the normal speed falls for every friction the cones allow
  double s = 0, c = 0, fall_rate = 0;
  bool Ok() const { return ball && e_e && mu_w && mu_s && height && lift && fall && points && bad_knot < 0; }
};

ParamChecks CheckParams(const BallParams& ball, const CushionParams& p) {
  ParamChecks k;
  k.ball = BallParamsValid(ball);
  k.e_e = Coefficient(p.e_e);
  k.mu_w = Coefficient(p.mu_w);
  k.mu_s = Coefficient(p.mu_s);
  const RestitutionCurve& curve = p.restitution_curve;
  k.points = curve.points >= 0 && curve.points <= RestitutionCurve::kMaxPoints;
  if (k.points) {
    for (int i = 0; i < curve.points && k.bad_knot < 0; ++i) {
      const bool ok = std::isfinite(curve.speed[i]) && curve.speed[i] >= 0 &&
                      Coefficient(curve.e[i]) && (i == 0 || curve.speed[i] > curve.speed[i - 1]);
      if (!ok) k.bad_knot = i;
    }
  }
  if (!(k.ball && k.e_e && k.mu_w && k.mu_s)) return k;  // the rest needs valid numbers
  const double R = ball.radius, h = p.contact_height;
  k.height = std::isfinite(h) && h > R && h < 2 * R;
  if (!k.height) return k;
  k.s = CushionSinTheta(ball, p);
  k.c = std::sqrt(1 - k.s * k.s);
  // Cloth reaction n_c = s - c fy with |fy| <= mu_w (eq. 8).
  k.lift = p.mu_w * k.c < k.s;
  // d ydot / dP_I = (-c - s fy + gy) / M with |fy| <= mu_w, |gy| <= mu_s n_c must stay
  // negative, or the impulse is unbounded.
  k.fall_rate = k.c - k.s * p.mu_w - p.mu_s * (k.s + k.c * p.mu_w);
  k.fall = k.fall_rate > 0;
  return k;
}

}  // namespace

CushionParams MathavanCushionParams(const BallParams& ball) {
  CushionParams p;
  p.contact_height = 7.0 / 5.0 * ball.radius;
  return p;
}

BallMotion CushionIncidentState(double speed, double alpha, double topspin, double sidespin) {
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  BallMotion m;
  m.v = Vec3(speed * ca, speed * sa, 0.0);
  m.w = Vec3(-topspin * sa, topspin * ca, sidespin);
  return m;
}

double CushionSinTheta(const BallParams& ball, const CushionParams& cushion) {
  return (cushion.contact_height - ball.radius) / ball.radius;
}

std::string ValidateCushionParams(const BallParams& ball, const CushionParams& cushion) {
  const ParamChecks k = CheckParams(ball, cushion);
  std::ostringstream out;
  if (!k.ball) Add(out, ValidateBallParams(ball));
  if (!k.e_e) CheckCoefficient(out, "e_e", cushion.e_e);
  if (!k.points || k.bad_knot >= 0) {
    const RestitutionCurve& c = cushion.restitution_curve;
    std::ostringstream m;
    if (!k.points) {
      m << "restitution_curve.points = " << c.points << " (must be in [0, "
        << RestitutionCurve::kMaxPoints << "])";
    } else {
      m << "restitution_curve knot " << k.bad_knot << " = (" << c.speed[k.bad_knot] << " m/s, "
        << c.e[k.bad_knot] << ") (speeds finite, >= 0 and increasing; e in [0, 1])";
    }
    Add(out, m.str());
  }
  if (!k.mu_w) CheckCoefficient(out, "mu_w", cushion.mu_w);
  if (!k.mu_s) CheckCoefficient(out, "mu_s", cushion.mu_s);
  if (out.tellp() > 0) return out.str();
  const double R = ball.radius, h = cushion.contact_height;
  if (!k.height) {
    std::ostringstream m;
    m << "contact_height = " << h << " m (must lie strictly between R = " << R
      << " m and 2R = " << 2 * R << " m)";
    Add(out, m.str());
    return out.str();
  }
  if (!k.lift) {
    std::ostringstream m;
    m << "mu_w = " << cushion.mu_w << " (must be below tan(theta) = " << k.s / k.c
      << " for contact_height = " << h << " m, or friction at the cushion lifts the ball"
      << " off the cloth)";
    Add(out, m.str());
  }
  if (!k.fall) {
    std::ostringstream m;
    m << "mu_w = " << cushion.mu_w << ", mu_s = " << cushion.mu_s << " with contact_height = "
      << h << " m (friction can stop the normal speed from falling: need cos th - mu_w sin th"
      << " - mu_s (sin th + mu_w cos th) > 0, have " << k.fall_rate << ")";
    Add(out, m.str());
  }
  return out.str();
}

std::string ValidateCushionImpact(const BallMotion& in, const BallParams& ball,
                                  const CushionParams& cushion,
                                  const ImpulseSolverOptions& options) {
  std::ostringstream out;
  Add(out, ValidateCushionParams(ball, cushion));
  CheckVec(out, "velocity", in.v);
  CheckVec(out, "angular velocity", in.w);
  if (in.v.allFinite() && in.w.allFinite() && BallParamsValid(ball)) {
    Add(out, ValidateSpeedScale(CushionSpeedScale(in, ball.radius), "the horizontal speed and R |w|"));
  }
  const OptionChecks k = CheckOptions(options);
  const ImpulseSolverOptions o = EffectiveOptions(options);
  Add(out, ValidateFidelity(options.fidelity));
  Add(out, ValidateMethod(options.method));
  if (!k.max_steps) Add(out, "max_steps = " + std::to_string(o.max_steps) + " (must be > 0)");
  if (!k.steps) Add(out, "steps = " + std::to_string(o.steps) + " (must be > 0)");
  if (!k.tolerance) {
    std::ostringstream m;
    m << "tolerance = " << o.tolerance << " (must be in [" << limits::kTolerance.lo << ", "
      << limits::kTolerance.hi << "])";
    Add(out, m.str());
  }
  return out.str();
}

double CushionSpeedScale(const BallMotion& in, double radius) {
  return std::max(Vec2(in.v.x(), in.v.y()).norm(), radius * in.w.norm());
}

RestitutionCurve MeasuredReboundCurve() {
  // e required at each speed (bisection on this model with the default friction
  // and a 36.75 mm nose; tools: docs/cushion-model.md), rounded to 3 decimals.
  RestitutionCurve c;
  const double speed[] = {0.3, 0.5, 0.62, 1.65, 2.5, 3.0, 3.5};
  const double e[] = {0.839, 0.964, 1.0, 1.0, 0.938, 0.895, 0.850};
  c.points = 7;
  for (int i = 0; i < c.points; ++i) c.speed[i] = speed[i], c.e[i] = e[i];
  return c;
}

double CushionRestitution(const CushionParams& cushion, double approach_speed) {
  const RestitutionCurve& c = cushion.restitution_curve;
  if (c.points <= 0) return cushion.e_e;
  if (approach_speed <= c.speed[0]) return c.e[0];
  for (int i = 1; i < c.points; ++i) {
    if (approach_speed <= c.speed[i]) {
      const double w = (approach_speed - c.speed[i - 1]) / (c.speed[i] - c.speed[i - 1]);
      return c.e[i - 1] + w * (c.e[i] - c.e[i - 1]);
    }
  }
  return c.e[c.points - 1];
}

CushionImpactResult ResolveCushionImpact(const BallMotion& in, const BallParams& ball,
                                         const CushionParams& cushion,
                                         const ImpulseSolverOptions& options) {
  CushionImpactResult r;
  r.out = in;
  if (!in.v.allFinite() || !in.w.allFinite() || !CheckOptions(options).Ok() ||
      !CheckParams(ball, cushion).Ok() ||
      !SpeedScaleValid(CushionSpeedScale(in, ball.radius))) {
    r.status = ImpactStatus::kInvalidInput;
    return r;
  }
  cushion::Model model(ball, cushion);
  model.e = CushionRestitution(cushion, in.v.y());  // Y points into the cushion
  const cushion::State x = cushion::Pack(in);
  if (!(cushion::NormalSpeed(x, model) > 0)) {
    r.status = ImpactStatus::kNotApproaching;
    return r;
  }
  const ImpulseSolverOptions o = EffectiveOptions(options);
  return o.integrator == ImpulseIntegrator::kFixedStep ? cushion::SolveFixedStep(in, model, o)
                                                      : cushion::SolveAdaptive(in, model, o);
}

}  // namespace snooker::physics
