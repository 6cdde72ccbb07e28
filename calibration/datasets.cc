#include "calibration/datasets.h"

#include <array>
#include <span>

namespace snooker::calibration {
namespace {

// Stun shots at `cut_deg`, from (object ball speed m/s, throw deg) pairs.
std::vector<ThrowObservation> StunThrows(double cut_deg, std::span<const std::array<double, 2>> points) {
  std::vector<ThrowObservation> out;
  for (const auto& p : points) {
    ThrowObservation o;
    o.cut = physics::DegToRad(cut_deg);
    o.object_ball_speed = p[0];
    o.measured_throw = physics::DegToRad(p[1]);
    out.push_back(o);
  }
  return out;
}

}  // namespace

std::vector<ThrowObservation> AlciatoreStunThrow45() {
  // Read from the article's stun-shot curve.
  constexpr std::array<std::array<double, 2>, 8> kPoints = {{{0.35, 6.57}, {0.50, 6.78}, {0.65, 6.65}, {0.75, 6.03},
                                                             {1.00, 5.23}, {1.16, 4.15}, {1.44, 4.02}, {1.75, 3.02}}};
  return StunThrows(45.0, kPoints);
}

std::vector<ThrowObservation> AlciatoreStunThrow30Ends() {
  constexpr std::array<std::array<double, 2>, 2> kPoints = {{{0.35, 6.0}, {1.75, 3.5}}};
  return StunThrows(30.0, kPoints);
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
