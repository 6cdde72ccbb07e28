// The fixed set of shots of the speed-against-error report (docs/speed-vs-error.md):
// the paper's five, glancing cuts, heavy side, heavy draw and stun shots.
#pragma once

#include <array>
#include <cmath>

#include "physics/impact/ball_ball.h"
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

}  // namespace snooker::physics
