// The model's prediction of each observation (calibration/observations.h): what a
// fit compares with the measurements.
//
//  * Throw: the paper's collision (physics/impact/ball_ball.h, ResolveImpact) from
//    its incident state (PaperIncidentState): the object ball's direction right
//    after the impact against the line of centres. Given the object ball's speed
//    instead of the cue ball's, the incident speed that gives it is solved for by
//    secant steps on a bracket (bisection where a secant step leaves it), capped.
//  * Rebound: the cushion model (physics/impact/ball_cushion.h, ResolveCushionImpact
//    from CushionIncidentState), as docs/cushion-model.md compares it with measured
//    rebounds: the speed and angle right after the impact. The cushion's contact
//    height is the default table's (TableSpec::cushion_height), as the table
//    simulation sets it, so rebounds and tracked shots see one cushion.
//  * Tracked shot: the shot simulated on the default table (physics::DefaultTable())
//    with the model, the balls' positions at the sighting times. A strike in the
//    cue's terms becomes the cue ball's motion through the model's cue
//    (physics::Strike), squirt and all. A pocketed ball stays where it dropped.
//
// A model whose ball-ball friction law is not the constant one answers every
// ball-ball impact with the solver: the precomputed impact table is keyed to the
// constant law (physics/impact/impact_table.h), which is right.
//
// Pure functions of their arguments; each allocates (a simulator's buffers) and is
// safe to call from several threads at once.
#pragma once

#include <string>
#include <vector>

#include "calibration/observations.h"
#include "physics/core/ball_state.h"
#include "physics/model/model.h"
#include "physics/sim/sim_params.h"

namespace snooker::calibration {

/// The numerical settings predictions run with by default: physics::Fidelity::
/// kDefault's solvers (tolerance SimParams::kShotTolerance) with every impact
/// solved, not looked up. The impact tables are built for the default parameters
/// and a fit moves away from them: answering the start model from the tables and
/// every other from the solvers would put a step of up to the tables' error into
/// the residuals right at the start.
physics::SimParams CalibrationNumerics();

struct ThrowPrediction {
  /// Empty when the prediction holds; otherwise what failed (an impact solver's
  /// status, an object ball speed no incident speed up to 3 kMaxSpeed gives).
  std::string error;
  /// rad, the sign convention of ThrowObservation::measured_throw.
  double throw_angle = 0;
  /// The incident speed (given or solved for) and the object ball's speed after
  /// the impact. m/s.
  double cue_ball_speed = 0;
  double object_ball_speed = 0;
};

/// The model's throw for one collision. `numerics` gives the ball-ball solver's
/// options (ball_ball_solver); the physics is the model's.
ThrowPrediction PredictThrow(const ThrowObservation& o, const physics::Model& model,
                             const physics::SimParams& numerics = CalibrationNumerics());

struct ReboundPrediction {
  std::string error;  ///< empty, or the cushion solver's failure
  double speed = 0;   ///< m/s, right after the impact
  double angle = 0;   ///< rad to the cushion line, (0, pi); CushionObservation's convention
};

/// The model's rebound for one approach (numerics.cushion_solver's options).
ReboundPrediction PredictRebound(const CushionObservation& o, const physics::Model& model,
                                 const physics::SimParams& numerics = CalibrationNumerics());

/// The balls at the start of a tracked shot, the cue ball struck: the shot's
/// strike in the cue's terms goes through the model's cue. Empty with *error set
/// when the strike is refused (a miscue, a hop, a bad value).
std::vector<physics::BallState> StartOfShot(const TrackedShot& shot, const physics::Model& model,
                                            std::string* error);

struct ShotPrediction {
  /// Empty, or why the shot could not be simulated (the strike refused, the
  /// simulator's status when it stopped on anything but every ball at rest, its
  /// event or time cap included).
  std::string error;
  /// [sighting][ball]: every ball's position at each sighting's time, m, table
  /// frame; a pocketed ball where it dropped.
  std::vector<std::vector<physics::Vec2>> positions;
  /// When each ball dropped into a pocket, s after the strike; +inf for a ball
  /// that did not.
  std::vector<double> pocketed_at;
  /// When the run ended (every ball at rest, or a cap), s.
  double end_time = 0;
};

/// The model's positions at the shot's sighting times (at least one simulator run;
/// after the run's end every ball stays where it rests).
ShotPrediction PredictShot(const TrackedShot& shot, const physics::Model& model,
                           const physics::SimParams& numerics = CalibrationNumerics());

}  // namespace snooker::calibration
