// Ball states and table scenes shared by the tests, benchmarks and report tools
// (one source, so a benchmark measures exactly what a test checks).
#pragma once

#include <string>
#include <vector>

#include "physics/sim/simulate.h"
#include "physics/table/table.h"

namespace snooker::physics::scenarios {

/// Ball radius of the default BallParams. m.
inline constexpr double kR = 0.02625;

/// A ball rolling without slip at `speed` (m/s) along the unit vector `dir`.
inline BallState Rolling(const Vec2& r, const Vec2& dir, double speed) {
  BallState s;
  s.r = r;
  s.v = Vec3(speed * dir.x(), speed * dir.y(), 0);
  s.w = Vec3(-dir.y(), dir.x(), 0) * (speed / kR);  // v = w x (R z): no slip
  return s;
}

inline BallState AtRest(const Vec2& r) {
  BallState s;
  s.r = r;
  return s;
}

/// A straight pot of one ball into the baulk-left pocket (cue ball and object ball
/// moving). `full`: 20 more balls at rest far from the action (the reds' triangle,
/// the colours but the green): 22 in all.
inline std::vector<BallState> TwoBallPot(bool full, const TableModel& table = DefaultTable()) {
  const Pocket& p = table.pocket(PocketId::kBaulkLeft);
  const Vec2 red = p.mouth_centre - 0.35 * p.axis;
  std::vector<BallState> balls = {Rolling(red - 0.4 * p.axis, p.axis, 1.5), AtRest(red)};
  if (full) {
    for (const Vec2& r : table.reds()) balls.push_back(AtRest(r));
    for (int c = 0; c < kColourCount; ++c) {
      if (Colour(c) != Colour::kGreen) balls.push_back(AtRest(table.spot(Colour(c))));
    }
  }
  return balls;
}

/// The break-off: the cue ball from the D into the full pack of 22 balls at 7 m/s,
/// with half the rolling topspin.
inline std::vector<BallState> BreakOff(const TableModel& table = DefaultTable()) {
  std::vector<BallState> balls;
  const Vec2 cue(table.spot(Colour::kBrown).x() + 0.15, table.spot(Colour::kBrown).y() - 0.1);
  const Vec2 target = table.reds()[0] + Vec2(0.02, 0.0);
  balls.push_back(Rolling(cue, (target - cue).normalized(), 7.0));
  balls[0].w *= 0.5;
  for (const Vec2& r : table.reds()) balls.push_back(AtRest(r));
  for (int c = 0; c < kColourCount; ++c) balls.push_back(AtRest(table.spot(Colour(c))));
  return balls;
}

/// "pot-empty", "pot-full", "break-off"; empty for an unknown name.
inline std::vector<BallState> Scenario(const std::string& name) {
  if (name == "pot-empty") return TwoBallPot(false);
  if (name == "pot-full") return TwoBallPot(true);
  if (name == "break-off") return BreakOff();
  return {};
}

}  // namespace snooker::physics::scenarios
