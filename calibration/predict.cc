#include "calibration/predict.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "physics/impact/ball_ball.h"
#include "physics/impact/ball_cushion.h"
#include "physics/sim/fidelity.h"
#include "physics/sim/simulate.h"
#include "physics/table/table.h"

namespace snooker::calibration {
namespace {

using physics::Vec2;

struct Collision {
  physics::ImpactStatus status = physics::ImpactStatus::kOk;
  double throw_angle = 0, object_speed = 0;
};

// One collision at incident speed v; the cut's sign taken away (the tangential
// motion is then +X of the paper's frame).
Collision Collide(const ThrowObservation& o, double v, const physics::Model& model,
                  const physics::SimParams& numerics) {
  const physics::ImpactState in = physics::PaperIncidentState(v, o.topspin, o.sidespin, std::abs(o.cut));
  const physics::ImpactResult r =
      physics::ResolveImpact(in, model.ball, model.ball_ball, model.cloth.mu_s, numerics.ball_ball_solver);
  Collision c;
  c.status = r.status;
  const physics::Vec3& w = r.out.o.v;
  c.throw_angle = std::atan2(w.x(), w.y());
  c.object_speed = std::hypot(w.x(), w.y());
  return c;
}

// The incident speed whose collision sends the object ball off at `target` (m/s):
// secant steps from the frictionless estimate target / (cos cut (1 + e) / 2), kept
// inside a bracket once one is known (bisection when a step leaves it). The object
// ball's speed grows with the incident speed (near proportionally), so the root is
// single. At most kMaxSteps collisions.
ThrowPrediction SolveIncidentSpeed(const ThrowObservation& o, double target, const physics::Model& model,
                                   const physics::SimParams& numerics) {
  constexpr int kMaxSteps = 40;
  constexpr double kRelTol = 1e-10, kMaxIncident = 3 * kMaxSpeed;
  ThrowPrediction p;
  const double guess = target / (std::cos(std::abs(o.cut)) * (1 + model.ball_ball.e) / 2);
  double lo = 0, hi = kMaxIncident;                // bracket: f(lo) < 0 < f(hi)
  double v0 = std::min(guess, kMaxIncident), v1 = std::min(1.05 * v0, kMaxIncident);
  Collision c0 = Collide(o, v0, model, numerics);
  for (int step = 0; step < kMaxSteps; ++step) {
    if (c0.status != physics::ImpactStatus::kOk) break;
    const double f0 = c0.object_speed - target;
    if (f0 < 0) {
      lo = std::max(lo, v0);
    } else {
      hi = std::min(hi, v0);
    }
    if (std::abs(f0) <= kRelTol * target) {
      p.throw_angle = c0.throw_angle;
      p.cue_ball_speed = v0;
      p.object_ball_speed = c0.object_speed;
      return p;
    }
    const Collision c1 = Collide(o, v1, model, numerics);
    if (c1.status != physics::ImpactStatus::kOk) break;
    const double f1 = c1.object_speed - target;
    double next = f1 != f0 ? v1 - f1 * (v1 - v0) / (f1 - f0) : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    v0 = v1;
    c0 = c1;
    v1 = next;
  }
  std::ostringstream e;
  e << "no incident speed up to " << kMaxIncident << " m/s gives object_ball_speed = " << target << " m/s";
  if (c0.status != physics::ImpactStatus::kOk) e << " (impact: " << physics::ToString(c0.status) << ")";
  p.error = e.str();
  return p;
}

}  // namespace

physics::SimParams CalibrationNumerics() {
  physics::SimParams p = physics::FidelityParams(physics::Fidelity::kDefault);
  p.impact_tables = false;
  return p;
}

ThrowPrediction PredictThrow(const ThrowObservation& o, const physics::Model& model,
                             const physics::SimParams& numerics) {
  if (o.object_ball_speed && !o.cue_ball_speed) return SolveIncidentSpeed(o, *o.object_ball_speed, model, numerics);
  ThrowPrediction p;
  p.cue_ball_speed = o.cue_ball_speed.value_or(0);
  const Collision c = Collide(o, p.cue_ball_speed, model, numerics);
  if (c.status != physics::ImpactStatus::kOk) {
    p.error = std::string("impact: ") + physics::ToString(c.status);
    return p;
  }
  p.throw_angle = c.throw_angle;
  p.object_ball_speed = c.object_speed;
  return p;
}

ReboundPrediction PredictRebound(const CushionObservation& o, const physics::Model& model,
                                 const physics::SimParams& numerics) {
  physics::CushionParams cushion = model.cushion;
  cushion.contact_height = physics::DefaultTable().spec().cushion_height;
  const physics::BallMotion in = physics::CushionIncidentState(o.speed, o.angle, o.topspin, o.sidespin);
  const physics::CushionImpactResult r =
      physics::ResolveCushionImpact(in, model.ball, cushion, numerics.cushion_solver);
  ReboundPrediction p;
  if (r.status != physics::ImpactStatus::kOk) {
    p.error = std::string("cushion impact: ") + physics::ToString(r.status);
    return p;
  }
  // Cushion frame: X along the cushion, Y into it; the rebound has v.y < 0.
  p.speed = std::hypot(r.out.v.x(), r.out.v.y());
  p.angle = std::atan2(-r.out.v.y(), r.out.v.x());
  return p;
}

std::vector<physics::BallState> StartOfShot(const TrackedShot& shot, const physics::Model& model,
                                            std::string* error) {
  physics::Shot struck;
  if (const auto* k = std::get_if<physics::CueStrike>(&shot.strike)) {
    const physics::StrikeResult s = physics::Strike(*k, model.cue, model.ball, model.cloth.g);
    if (s.status != physics::StrikeStatus::kOk) {
      std::ostringstream why;
      why << "strike refused: " << physics::ToString(s.status);
      if (s.status == physics::StrikeStatus::kMiscue) {
        why << " (the tip " << std::hypot(k->side, k->height) << " R from the ball's centre line, beyond the cue's limit of "
            << physics::MiscueLimit(model.cue) << " R)";
      } else if (s.status == physics::StrikeStatus::kHop) {
        why << " (the ball would hop " << s.hop * 1e3 << " mm, more than the cue's " << model.cue.max_hop * 1e3 << " mm)";
      }
      *error = why.str();
      return {};
    }
    struck = s.shot;
  } else {
    struck = std::get<physics::Shot>(shot.strike);
  }
  std::vector<physics::BallState> balls(shot.balls.size());
  for (std::size_t i = 0; i < balls.size(); ++i) balls[i].r = shot.balls[i];
  const std::size_t cue = static_cast<std::size_t>(shot.cue_ball);
  if (cue >= balls.size()) {
    *error = "cue_ball is not one of the balls";
    return {};
  }
  balls[cue] = physics::Settle(physics::StruckBall(struck, shot.balls[cue]), model.ball);
  return balls;
}

ShotPrediction PredictShot(const TrackedShot& shot, const physics::Model& model,
                           const physics::SimParams& numerics) {
  ShotPrediction p;
  const std::vector<physics::BallState> start = StartOfShot(shot, model, &p.error);
  if (start.empty()) return p;
  physics::RunOptions run;
  run.record_events = false;
  physics::Simulator sim(physics::DefaultTable(), model.Apply(numerics));
  const physics::SimStatus status = sim.Run(start, run);
  if (status == physics::SimStatus::kInvalidInput) {
    p.error = "simulation: invalid input";
    return p;
  }
  if (status != physics::SimStatus::kAtRest) p.error = std::string("simulation: ") + physics::ToString(status);
  const int n = sim.ball_count();
  p.end_time = sim.end_time();
  p.pocketed_at.assign(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
  for (int i = 0; i < n; ++i) {
    const auto path = sim.path(i);
    if (sim.pocket_of(i) >= 0 && !path.empty()) p.pocketed_at[static_cast<std::size_t>(i)] = path.back().t;
  }
  p.positions.reserve(shot.sightings.size());
  for (const Sighting& g : shot.sightings) {
    std::vector<Vec2>& at = p.positions.emplace_back(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const auto path = sim.path(i);
      // A pocketed ball's path ends where it dropped; every ball rests after the end.
      const bool done = path.empty() || g.t >= sim.end_time() ||
                        (sim.pocket_of(i) >= 0 && g.t >= path.back().t);
      at[static_cast<std::size_t>(i)] = done ? sim.final_balls()[static_cast<std::size_t>(i)].r
                                             : sim.PositionAt(i, g.t);
    }
  }
  return p;
}

}  // namespace snooker::calibration
