// The fixed shot sets of the impact benchmarks and reports (docs/speed-vs-error.md,
// docs/impact-speed.md):
//  * kReportShots, ball-ball: the paper's five, glancing cuts, heavy side, heavy draw
//    and stun shots;
//  * CushionShots(), ball-cushion: what a ball brings to a cushion on the table -
//    mostly rolling (a ball has usually finished its slip before it gets there), at
//    any angle, with and without sidespin, and a few stun and screw arrivals; near
//    square-on arrivals of a rolling ball, the costly case, are a third of the set.
//    Seeded, so every run and every build solves the same impacts.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "physics/impact/ball_ball.h"
#include "physics/impact/ball_cushion.h"
#include "tests/physics/impact/paper_shots.h"

namespace snooker::physics {

struct NamedShot {
  const char* name;
  double speed, topspin_per_rolling, sidespin_per_rolling, cut_deg;  // spins in units of V0/R
};

inline constexpr std::array<NamedShot, 15> kReportShots = {{
    {"paper 1", 1.539, 1, 0, 33.83},
    {"paper 2", 1.032, 1, 0, 26.36},
    {"paper 3", 1.364, 1, 0, 40.52},
    {"paper 4", 1.731, 1, 0, 46.5},
    {"paper 5", 0.942, 1, 0, 18.05},
    {"glancing 80", 1.5, 1, 0, 80.0},
    {"glancing 88", 1.5, 1, 0, 88.0},
    {"glancing 89.9", 1.5, 1, 0, 89.9},
    {"heavy side +", 1.5, 1, 2, 25.0},
    {"heavy side -", 1.5, 0.5, -2, 25.0},
    {"heavy draw", 2.0, -2, 0, 20.0},
    {"draw and side", 1.2, -0.109, 0.437, 8.6},
    {"stun 5", 1.5, 0, 0, 5.0},
    {"stun 15", 1.5, 0, 0, 15.0},
    {"stun 30 side", 2.0, 0, 0.4, 30.0},
}};

inline ImpactState ReportShotState(const NamedShot& s) {
  const double r = BallParams{}.radius;
  return PaperIncidentState(s.speed, s.topspin_per_rolling * s.speed / r,
                            s.sidespin_per_rolling * s.speed / r, DegToRad(s.cut_deg));
}

/// Number of impacts in CushionShots().
inline constexpr int kCushionShotCount = 96;

/// The cushion shot set, in the cushion frame (CushionIncidentState): speed 0.2-3
/// m/s; angle to the cushion 5-90 deg (a third of them 80-90 deg); rolling in three
/// of four (topspin V/R), otherwise topspin in +-1 V/R; sidespin in +-1 V/R for half
/// of them. A fixed 64-bit LCG, so the set is the same on every platform.
inline std::vector<BallMotion> CushionShots() {
  std::uint64_t state = 20250101;
  auto uniform = [&state](double lo, double hi) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  const double r = BallParams{}.radius;
  std::vector<BallMotion> shots;
  for (int i = 0; i < kCushionShotCount; ++i) {
    const double v = uniform(0.2, 3.0);
    const double angle_deg = i % 3 == 0 ? uniform(80.0, 90.0) : uniform(5.0, 90.0);
    const double top = i % 4 != 3 ? 1.0 : uniform(-1.0, 1.0);
    const double side = i % 2 == 0 ? uniform(-1.0, 1.0) : 0.0;
    shots.push_back(CushionIncidentState(v, DegToRad(angle_deg), top * v / r, side * v / r));
  }
  return shots;
}

/// The cushion parameters of the table simulation (physics/sim/simulate.h, SimParams):
/// the paper's model with the measured restitution curve and the default table's
/// nose height, 36 mm (physics/table/table.h, TableSpec::cushion_height).
inline CushionParams TableCushionParams() {
  CushionParams p;
  p.restitution_curve = MeasuredReboundCurve();
  p.contact_height = 0.036;
  return p;
}

}  // namespace snooker::physics
