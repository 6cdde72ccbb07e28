// Ball states and table scenes shared by the tests, benchmarks and report tools
// (one source, so a benchmark measures exactly what a test checks).
#pragma once

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "physics/core/shot.h"
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

/// The 15 reds in their triangle with `gap` (m) between neighbours (0: touching),
/// the apex where the table puts it; then the six colours on their spots.
inline std::vector<BallState> RackWithGap(double gap, const TableModel& table = DefaultTable()) {
  std::vector<BallState> balls;
  const Vec2 apex = table.reds()[0];
  const double across = 2 * kR + gap, along = std::sqrt(3.0) * (kR + gap / 2);
  for (int row = 0; row < 5; ++row) {
    for (int k = 0; k <= row; ++k) {
      balls.push_back(AtRest(apex + Vec2((2 * k - row) * across / 2, row * along)));
    }
  }
  for (int c = 0; c < kColourCount; ++c) balls.push_back(AtRest(table.spot(Colour(c))));
  return balls;
}

/// The cue ball at `position` struck with speed (m/s), heading (rad), topspin and
/// sidespin (rad/s), as the robot plays it (physics/core/shot.h).
inline BallState Struck(const Vec2& position, double speed, double heading, double topspin,
                        double sidespin) {
  return StruckBall({speed, heading, topspin, sidespin}, position);
}

/// A random break-off into RackWithGap(gap): the cue ball from the baulk line area
/// at 5-9 m/s towards the apex red (within 3 cm either side), any top and side spin
/// up to a rolling ball's. Cue ball first. Deterministic in `rng`.
template <typename Rng>
std::vector<BallState> RandomBreakOff(double gap, Rng& rng, const TableModel& table = DefaultTable()) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<BallState> balls = {AtRest(Vec2::Zero())};
  for (const BallState& b : RackWithGap(gap, table)) balls.push_back(b);
  const Vec2 cue(table.spec().width / 2 - 0.15 + 0.3 * u(rng), table.spec().baulk_line - 0.09);
  const Vec2 target = balls[1].r + Vec2((u(rng) - 0.5) * 0.06, 0);
  const Vec2 d = target - cue;
  const double speed = 5 + 4 * u(rng);
  const double top = (2 * u(rng) - 1) * speed / kR, side = (2 * u(rng) - 1) * speed / kR;
  balls[0] = Struck(cue, speed, std::atan2(d.y(), d.x()), top, side);
  return balls;
}

/// A mid-frame table: `reds` reds scattered where they do not touch anything (at
/// least 1 mm clear of every ball and cushion), the six colours on their spots and
/// the cue ball anywhere free. Cue ball first, then the reds, then the colours.
template <typename Rng>
std::vector<BallState> MidFrameTable(int reds, Rng& rng, const TableModel& table = DefaultTable()) {
  std::uniform_real_distribution<double> u(0, 1);
  const double margin = table.cushion_contact_distance() + 1e-3;
  const double w = table.spec().width, l = table.spec().length;
  std::vector<BallState> balls;
  for (int c = 0; c < kColourCount; ++c) balls.push_back(AtRest(table.spot(Colour(c))));
  auto place = [&] {
    for (int tries = 0; tries < 10000; ++tries) {
      const Vec2 r(margin + u(rng) * (w - 2 * margin), margin + u(rng) * (l - 2 * margin));
      bool clear = true;
      for (const BallState& b : balls) clear &= (b.r - r).norm() >= 2 * kR + 1e-3;
      if (clear) return r;
    }
    return Vec2(w / 2, l / 4);  // not reached with at most 15 reds
  };
  std::vector<BallState> out = {AtRest(place())};
  balls.push_back(out[0]);
  for (int i = 0; i < reds; ++i) {
    out.push_back(AtRest(place()));
    balls.push_back(out.back());
  }
  for (int c = 0; c < kColourCount; ++c) out.push_back(AtRest(table.spot(Colour(c))));
  return out;
}

/// The planner workload: MidFrameTable with 8 reds and a shot of 0.5-4
/// m/s aimed at a random object ball's centre (or up to one ball radius either side
/// of it) with top and side spin up to a rolling ball's either way.
template <typename Rng>
std::vector<BallState> PlannerWorkloadShot(Rng& rng, const TableModel& table = DefaultTable()) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<BallState> balls = MidFrameTable(8, rng, table);
  const size_t target = 1 + static_cast<size_t>(u(rng) * static_cast<double>(balls.size() - 1));
  const Vec2 to = balls[std::min(target, balls.size() - 1)].r - balls[0].r;
  const double heading = std::atan2(to.y(), to.x()) + (2 * u(rng) - 1) * std::asin(std::min(1.0, kR / to.norm()));
  const double speed = 0.5 + 3.5 * u(rng);
  balls[0] = Struck(balls[0].r, speed, heading, (2 * u(rng) - 1) * speed / kR, (2 * u(rng) - 1) * speed / kR);
  return balls;
}

/// A positional shot with several cushions: the cue ball alone with the colours on
/// their spots, struck at 2-4 m/s in any direction with any spin, so it travels
/// 3-10 m and meets several cushions.
template <typename Rng>
std::vector<BallState> CushionsShot(Rng& rng, const TableModel& table = DefaultTable()) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<BallState> balls = MidFrameTable(0, rng, table);
  const double speed = 2 + 2 * u(rng);
  balls[0] = Struck(balls[0].r, speed, 2 * kPi * u(rng), (2 * u(rng) - 1) * speed / kR,
                    (2 * u(rng) - 1) * speed / kR);
  return balls;
}

/// The seeded shot sets of the whole-shot benchmarks (bench/shot_count,
/// tools/shot_speed_error, tools/impact_methods): `n` shots of "planner"
/// (PlannerWorkloadShot), "cushions" (CushionsShot) or "break-off" (RandomBreakOff with
/// the reds 1e-4 m apart), from one generator seeded 2026; empty for an unknown name.
inline std::vector<std::vector<BallState>> WorkloadShots(const std::string& workload, int n) {
  std::mt19937_64 rng(2026);
  std::vector<std::vector<BallState>> shots;
  if (workload != "planner" && workload != "cushions" && workload != "break-off") return shots;
  for (int i = 0; i < n; ++i) {
    if (workload == "planner") shots.push_back(PlannerWorkloadShot(rng));
    if (workload == "cushions") shots.push_back(CushionsShot(rng));
    if (workload == "break-off") shots.push_back(RandomBreakOff(1e-4, rng));
  }
  return shots;
}

/// "pot-empty", "pot-full", "break-off"; empty for an unknown name.
inline std::vector<BallState> Scenario(const std::string& name) {
  if (name == "pot-empty") return TwoBallPot(false);
  if (name == "pot-full") return TwoBallPot(true);
  if (name == "break-off") return BreakOff();
  return {};
}

}  // namespace snooker::physics::scenarios
