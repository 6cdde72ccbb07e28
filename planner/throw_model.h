// How much the robot's spin and speed noise turns the object ball: sensitivities of
// the object ball's rolling direction, tabulated by the collision model.
//
// The object ball leaves along the line of centres plus the throw that friction at
// the contact gives it (Mathavan et al. 2014). Throw depends on the slip at the
// contact, so a sidespin or topspin error turns the object ball, most of all at slow
// speeds and near-full hits, where the contact can stick. For each cut angle and
// contact speed of a rolling cue ball the table holds d(direction)/d(sidespin),
// d(direction)/d(topspin) and d(direction)/d(ln speed), by central differences of
// the full impact solve (ResolveBallBallOnTable) and the object ball's slip phase,
// over a step equal to the default noise. A few hundred impact solves, once.
#pragma once

#include <vector>

#include "physics/sim/simulate.h"

namespace snooker::planner {

struct ThrowSensitivity {
  double per_sidespin = 0;   ///< rad of object direction per rad/s of sidespin
  double per_topspin = 0;    ///< rad per rad/s of topspin
  double per_log_speed = 0;  ///< rad per unit relative change of speed
};

class ThrowModel {
 public:
  struct Options {
    double cut_step = 5.0 * physics::kPi / 180;  ///< rad, grid from 0 to max_cut
    double max_cut = 85.0 * physics::kPi / 180;
    std::vector<double> contact_speeds = {0.3, 0.6, 1.2, 2.5, 5.0};  ///< m/s, ascending
    double spin_step = 2.0;     ///< rad/s, the difference step
    double speed_step = 0.01;   ///< relative
  };
  ThrowModel(const physics::SimParams& params, const Options& options);
  /// Built on first use from default SimParams (thread-safe).
  static const ThrowModel& Default();

  /// Sensitivities for a cue ball rolling into the contact at `contact_speed` (m/s)
  /// with cut `cut` (rad; the sign does not matter), interpolated.
  ThrowSensitivity At(double cut, double contact_speed) const;
  /// The object ball's rolling direction relative to the line of centres (the
  /// throw, rad, positive counter-clockwise) for a cue ball arriving along +y with
  /// the given state: the primitive the table is built from.
  double Throw(double cut, double speed, double topspin, double sidespin) const;

 private:
  physics::SimParams params_;
  Options options_;
  int cuts_ = 0;
  std::vector<ThrowSensitivity> cells_;  // [speed][cut]
};

}  // namespace snooker::planner
