#include "calibration/datasets.h"

#include <iterator>

namespace snooker::calibration {

std::vector<ThrowObservation> AlciatoreStunThrow45() {
  // (object ball speed m/s, throw deg), read from the article's stun-shot curve.
  constexpr double kPoints[][2] = {{0.35, 6.57}, {0.50, 6.78}, {0.65, 6.65}, {0.75, 6.03},
                                   {1.00, 5.23}, {1.16, 4.15}, {1.44, 4.02}, {1.75, 3.02}};
  std::vector<ThrowObservation> out;
  for (const auto& p : kPoints) {
    ThrowObservation o;
    o.cut = physics::DegToRad(45.0);
    o.object_ball_speed = p[0];
    o.measured_throw = physics::DegToRad(p[1]);
    out.push_back(o);
  }
  return out;
}

std::vector<ThrowObservation> AlciatoreStunThrow30Ends() {
  constexpr double kPoints[][2] = {{0.35, 6.0}, {1.75, 3.5}};
  std::vector<ThrowObservation> out;
  for (const auto& p : kPoints) {
    ThrowObservation o;
    o.cut = physics::DegToRad(30.0);
    o.object_ball_speed = p[0];
    o.measured_throw = physics::DegToRad(p[1]);
    out.push_back(o);
  }
  return out;
}

physics::Model SimToRealWorld() {
  physics::Model m;
  m.ball_ball = physics::WithFrictionCurve(m.ball_ball, kSimToRealThrowLaw);
  m.cloth.mu_s *= 1.2;
  m.cloth.mu_r *= 1.2;
  m.cue.end_mass = 0.009;
  return m;
}

}  // namespace snooker::calibration
