// The five shots of Mathavan, Jackson & Parkin (2014), Tables 1 and 2: a rolling
// cue ball (topspin = V0 / R, no sidespin) at speed V0 and cut angle theta. Values as
// printed, with two misprints corrected:
//  * Table 1 row 4: predicted cue v_S 1.28, not 0.128 (docs/physics-notes.md section 3);
//  * Table 2 row 3: the cue-ball exit-angle error is -1.93 %, not -0.90 %: the paper's
//    own columns give (29.91 - 30.50) / 30.50 = -1.93 % (every other error in Table 2
//    is (predicted - measured) / measured; -0.90 is the speed error of the same row).
// Used by tests, benchmarks and the report tool.
#pragma once

#include <array>

namespace snooker::physics {

struct PaperShot {
  double speed;   // V0, m/s
  double cut_deg;
  double measured_cue_speed, measured_object_speed;        // v_S, m/s (Table 1)
  double predicted_cue_speed, predicted_object_speed;      // v_S, m/s (Table 1)
  double paper_cue_speed_err_pct, paper_object_speed_err_pct;
  double measured_cue_exit_deg, measured_object_exit_deg;  // Table 2
  double predicted_cue_exit_deg, predicted_object_exit_deg;
  double paper_cue_exit_err_pct, paper_object_exit_err_pct;
};

inline constexpr std::array<PaperShot, 5> kPaperShots = {{
    {1.539, 33.83, 0.816, 0.836, 0.914, 0.831, 10.70, -0.62, 35.96, 33.83, 31.93, 32.20, -11.21, -4.81},
    {1.032, 26.36, 0.52, 0.629, 0.520, 0.599, -0.03, -5.00, 33.20, 26.36, 32.45, 25.07, -2.27, -4.91},
    {1.364, 40.52, 0.925, 0.7, 0.917, 0.676, -0.90, -3.52, 30.50, 40.51, 29.91, 38.62, -1.93, -4.67},
    {1.731, 46.5, 1.275, 0.787, 1.28, 0.780, 0.18, -0.94, 27.97, 46.50, 27.32, 44.38, -2.34, -4.57},
    {0.942, 18.05, 0.365, 0.581, 0.383, 0.579, 4.81, -0.38, 29.86, 18.05, 29.47, 17.15, -1.31, -4.99},
}};

}  // namespace snooker::physics
