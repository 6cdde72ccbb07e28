// The physical model of one table, in one place: the balls, the cloth, the ball-ball
// contact (its friction law and restitution), the cushions and the robot's cue. What
// a calibration fits and a model file sets (every other SimParams field is a
// numerical setting: tolerances, caps, thresholds, which stay the caller's).
//
// The default is the model every figure of docs/ was made with; a Model read from a
// file replaces only the values the file gives.
#pragma once

#include <string>

#include "physics/core/params.h"
#include "physics/cue/strike.h"
#include "physics/impact/ball_cushion.h"
#include "physics/sim/sim_params.h"

namespace snooker::physics {

struct Model {
  BallParams ball;
  ClothParams cloth;
  BallBallParams ball_ball;
  /// SimParams' default cushion (the measured rebound curve).
  CushionParams cushion = SimParams{}.cushion;
  CueParams cue;

  /// `base` with its physical parameters replaced by this model's (its numerical
  /// settings kept).
  SimParams Apply(SimParams base) const;
};

/// The physical parameters of `sim` and `cue` as a Model.
Model ModelOf(const SimParams& sim, const CueParams& cue);

/// True when every physical parameter of `a` equals `b`'s (bit for bit).
bool SameModel(const Model& a, const Model& b);

/// Empty when every value is valid; otherwise one message naming each bad value
/// ("cloth.mu_s = -1 (must be in [0, 1])").
std::string ValidateModel(const Model& m);

}  // namespace snooker::physics
