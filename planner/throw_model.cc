#include "planner/throw_model.h"

#include <algorithm>
#include <cmath>

#include "physics/motion/motion.h"
#include "physics/sim/resolve.h"

namespace snooker::planner {

using physics::Vec2;
using physics::Vec3;

ThrowModel::ThrowModel(const physics::SimParams& params, const Options& options)
    : params_(params), options_(options) {
  cuts_ = static_cast<int>(std::lround(options_.max_cut / options_.cut_step)) + 1;
  cells_.resize(static_cast<size_t>(cuts_) * options_.contact_speeds.size());
  const double r = params_.ball.radius;
  for (size_t s = 0; s < options_.contact_speeds.size(); ++s) {
    const double v = options_.contact_speeds[s];
    for (int c = 0; c < cuts_; ++c) {
      const double cut = c * options_.cut_step;
      const double top = v / r, h = options_.spin_step, dv = options_.speed_step;
      ThrowSensitivity& t = cells_[s * static_cast<size_t>(cuts_) + static_cast<size_t>(c)];
      t.per_sidespin = (Throw(cut, v, top, h) - Throw(cut, v, top, -h)) / (2 * h);
      t.per_topspin = (Throw(cut, v, top + h, 0) - Throw(cut, v, top - h, 0)) / (2 * h);
      t.per_log_speed = (Throw(cut, v * (1 + dv), top * (1 + dv), 0) -
                         Throw(cut, v * (1 - dv), top * (1 - dv), 0)) / (2 * dv);
    }
  }
}

const ThrowModel& ThrowModel::Default() {
  static const ThrowModel model(physics::SimParams{}, Options{});
  return model;
}

double ThrowModel::Throw(double cut, double speed, double topspin, double sidespin) const {
  const double r = params_.ball.radius;
  // Cue ball at the origin moving along +y; the object ball 2R away along the line
  // of centres, turned by `cut` counter-clockwise from +y.
  const Vec2 n(-std::sin(cut), std::cos(cut));
  physics::BallState cue;
  cue.v = Vec3(0, speed, 0);
  // Topspin is about z x heading = (-1, 0, 0) for a heading along +y.
  cue.w = Vec3(-topspin, 0, sidespin);
  cue = physics::Settle(cue, params_.ball);
  physics::BallState object;
  object.r = 2 * r * n;
  const physics::BallBallResolution res = physics::ResolveBallBallOnTable(
      cue, object, params_.ball, params_.ball_ball, params_.cloth, params_.ball_ball_solver);
  if (res.status != physics::ImpactStatus::kOk) return 0;
  physics::BallState o = res.b;
  if (o.s == physics::MotionState::kSliding) {
    o = physics::Evolve(o, physics::TransitionTime(o, params_.ball, params_.cloth), params_.ball,
                        params_.cloth);
  }
  const Vec2 v(o.v.x(), o.v.y());
  if (v.norm() <= 0) return 0;
  return physics::RemainderTwoPi(std::atan2(v.y(), v.x()) - std::atan2(n.y(), n.x()));
}

ThrowSensitivity ThrowModel::At(double cut, double contact_speed) const {
  const double fc = std::clamp(std::abs(cut) / options_.cut_step, 0.0, cuts_ - 1.0);
  const int c0 = std::min(static_cast<int>(fc), cuts_ - 2);
  const double tc = fc - c0;
  const std::vector<double>& v = options_.contact_speeds;
  const double speed = std::clamp(contact_speed, v.front(), v.back());
  int s0 = 0;
  while (s0 + 2 < static_cast<int>(v.size()) && speed > v[static_cast<size_t>(s0 + 1)]) ++s0;
  const double ts = (speed - v[static_cast<size_t>(s0)]) /
                    (v[static_cast<size_t>(s0 + 1)] - v[static_cast<size_t>(s0)]);
  auto cell = [&](int s, int c) -> const ThrowSensitivity& {
    return cells_[static_cast<size_t>(s) * static_cast<size_t>(cuts_) + static_cast<size_t>(c)];
  };
  ThrowSensitivity out;
  for (int ds = 0; ds < 2; ++ds) {
    for (int dc = 0; dc < 2; ++dc) {
      const double w = (ds ? ts : 1 - ts) * (dc ? tc : 1 - tc);
      const ThrowSensitivity& t = cell(s0 + ds, c0 + dc);
      out.per_sidespin += w * t.per_sidespin;
      out.per_topspin += w * t.per_topspin;
      out.per_log_speed += w * t.per_log_speed;
    }
  }
  return out;
}

}  // namespace snooker::planner
