// Fitting a table's physical model (physics::Model) to its measurements
// (calibration/observations.h): bounded least squares over the parameters of the
// groups asked for, every other parameter held at the start model's value.
//
// Groups and their parameters (FittedParameters lists them with bounds and scales):
//  * ball-ball: the friction law mu(s) = a + b exp(-c s) (physics/core/params.h),
//    a = ball_ball.mu_bb, b = ball_ball.slip_gain, c = ball_ball.slip_decay; the
//    fitted model's law is BallBallFrictionLaw::kExponential, or
//    kExponentialImpactSpeed when the start's law is (s is then the impact's normal
//    speed: the form is the caller's choice, not fitted). A start whose law is
//    the constant one (b = 0, where c changes nothing and so cannot be found) starts
//    from Marlow's measured law instead, the family's one published member with a
//    slope. The restitution e stays: throw hardly depends on it.
//  * cushion: the nose friction cushion.mu_w and the restitution: the knots of the
//    start's restitution curve that the rebounds cover (a knot counts as covered
//    when at least 2 rebounds approach the cushion, normal speed v sin(angle), in
//    the speed range where it acts, between its neighbouring knots or beyond an end
//    knot), or the constant e_e when the start has no curve. Why knots and not one
//    scale of the whole curve: the measured curve's shape (e rising to 1 at
//    0.6-1.7 m/s, falling beyond) is what a table changes, and a scale cannot move a
//    knot at the cap e = 1; a knot without data would be a parameter without
//    information, so it keeps its value. Knots are bounded to [0.3, 1].
//  * cloth: cloth.mu_s (sliding), cloth.mu_r (rolling resistance), cloth.spin_decel
//    (the vertical spin's decay). Only tracked shots show them.
//  * cue: cue.end_mass (squirt) and cue.tip_restitution (the ball's speed for a cue
//    speed). Only tracked shots struck in the cue's terms show them, and the end
//    mass only those with side.
//
// Residuals, each divided by its sigma (FitOptions) so that the kinds combine into
// one sum of squares: throw (rad; reported in deg), rebound speed (m/s) and angle
// (rad; reported in deg), tracked positions (m, each coordinate of each seen ball
// at each sighting). A prediction that fails during the search (a strike the trial
// cue refuses, a solver's failure) counts as a residual of kFailedResidual sigmas.
//
// The search: NLopt's LN_BOBYQA (LN_COBYLA for a single parameter, which BOBYQA
// does not take) on the parameters scaled to [0, 1] within their bounds, capped in
// evaluations and in time.
//
// Tracked shots need two more things, both measured on recorded shots
// (calibration/record.h): a run whose model is 20 % off diverges from the
// sightings after its first collision (a ball-ball impact turns a millimetre of
// the ghost ball into 2 deg of the object ball; a ball drops or does not), so
// that a plain least-squares search from the start model stalls in a local
// minimum with residuals of 0.1-0.3 m. Hence:
//  * stages of growing horizon (FitOptions::horizons: 0.5, 1, 2, 4 s, then the
//    whole shot): each stage fits only the sightings up to its horizon, starting
//    from the stage before's best point, so that the early, smooth part of every
//    shot brings the model near before the chaotic part is looked at;
//  * a Cauchy loss on the position residuals (FitOptions::position_outlier_scale,
//    5 sigma): a residual r becomes c sqrt(log(1 + (r / c)^2)) with its sign, the
//    same below a few sigma and nearly flat for a ball whose path has gone
//    another way, so such a ball does not pull the fit.
// With both, 12 recorded shots with 1 mm of noise give every group back within
// its uncertainty (tests/calibration/fit_test.cc). Derivative-free on purpose: the tracked positions come
// out of an event-driven simulation whose outputs kink at every event (a contact
// that starts or ends, a ball that stops rolling before or after a sighting, a
// cushion reached or not), so a finite-difference gradient there is unreliable,
// while BOBYQA's quadratic models average over the kinks. Tracked shots are
// simulated on FitOptions::threads threads; each writes its own residuals, so the
// result does not depend on the thread count or timing (only the time cap can make
// it so).
//
// Uncertainties: at the optimum, the Jacobian J of the weighted residuals by
// central differences (one-sided at a bound), cov = s^2 (J^T J)^-1 with
// s^2 = RSS / (n - p), the standard uncertainty of each parameter the square root
// of its diagonal element. Linearised: a parameter at its bound, or a tracked shot
// whose events change within the step, make it an estimate only.
//
// Refusals (FitResult::error set, nothing fitted), each saying why: observations
// that Validate refuses; a group without data that depends on it (cloth from throws
// alone: "cloth: no tracked shots; throw observations do not depend on mu_s, mu_r
// or spin_decel"); fewer residuals than parameters; a start model that fails
// ValidateModel or whose predictions fail; and, from the Jacobian at the start, a
// J^T J whose smallest eigenvalue relative to its largest is below
// kIdentifiability (on the parameters in units of their scales), with the
// direction in parameter space that the data do not determine.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "calibration/observations.h"
#include "calibration/predict.h"
#include "physics/model/model.h"
#include "physics/sim/sim_params.h"
#include "physics/sim/simulate.h"

namespace snooker::calibration {

enum class Group : std::uint8_t { kBallBall, kCushion, kCloth, kCue };

/// "ball-ball", "cushion", "cloth", "cue".
const char* ToString(Group g);

struct ParsedGroups {
  std::vector<Group> groups;  ///< in the order given, each once
  std::string error;          ///< empty, or names the bad word
};

/// Comma-separated group names ("ball-ball,cloth"; spaces around names ignored).
/// An unknown or empty name is an error that names it and lists the known ones;
/// a repeated one is taken once.
ParsedGroups ParseGroups(std::string_view text);

/// One fitted parameter.
struct ParameterSpec {
  /// The model's field: "ball_ball.mu_bb", "cushion.restitution_curve.e[3]", ...
  std::string name;
  /// What it is, with its unit: "friction law a (mu at high slip)", "e at 1.65 m/s".
  std::string what;
  /// Bounds of the search, in the parameter's unit.
  double lo = 0, hi = 0;
  /// A typical size of its change, in its unit: the search's first step and the
  /// unit the identifiability check measures it in (the Jacobian's step is a
  /// hundredth of it).
  double scale = 0;
};

/// The parameters `groups` fit from `observations`, in group order, and the start
/// values of each in the model the fit starts from (`start` with the ball-ball
/// law turned exponential as above). `values` may be null.
std::vector<ParameterSpec> FittedParameters(std::span<const Group> groups, const Observations& observations,
                                            const physics::Model& start, std::vector<double>* values = nullptr);

struct FitOptions {
  /// Standard deviation of each measurement, in the residual's unit (see above).
  double throw_sigma = 0.25 * physics::kPi / 180;         ///< rad (0.25 deg)
  double rebound_speed_sigma = 0.02;                      ///< m/s
  double rebound_angle_sigma = 1.0 * physics::kPi / 180;  ///< rad (1 deg)
  double position_sigma = 1e-3;                           ///< m
  /// Caps of the search. The two Jacobians (at the start, for the
  /// identifiability check, and at the optimum; at most 2 p evaluations each for
  /// p parameters) and one evaluation per stage come on top of max_evaluations;
  /// max_seconds caps the search, not the final Jacobian.
  int max_evaluations = 4000;
  double max_seconds = 120;
  /// Stop when a step changes every scaled parameter by less than this (of its
  /// range).
  double x_tolerance = 1e-6;
  /// Threads that simulate tracked shots, >= 1.
  int threads = 2;
  /// The staged search's horizons, s (see above), increasing; a last stage
  /// without one is always added. Used only with tracked shots. The stages share
  /// max_evaluations evenly (what one leaves goes to the next).
  std::vector<double> horizons = {0.5, 1.0, 2.0, 4.0};
  /// The Cauchy loss's scale on the position residuals, in sigmas (see above); 0
  /// for plain least squares.
  double position_outlier_scale = 5.0;
  /// Numerical settings of every prediction (the physics is the model's).
  physics::SimParams numerics = CalibrationNumerics();
  /// The caller's deadline and cancellation, checked before every prediction (each
  /// throw, rebound and tracked shot of every evaluation, the Jacobians' included):
  /// once due, the fit ends with FitResult::interrupted, within one prediction.
  physics::Interrupt interrupt;
};

/// A failed prediction's residual, in sigmas.
inline constexpr double kFailedResidual = 1e3;
/// Smallest eigenvalue of the scaled J^T J relative to its largest that the fit
/// accepts.
inline constexpr double kIdentifiability = 1e-10;

struct ParameterEstimate {
  std::string name, what;  ///< as ParameterSpec
  double start = 0;        ///< the value the search started from
  double fitted = 0;
  /// Standard uncertainty, same unit; NaN when J^T J at the optimum is singular.
  double uncertainty = 0;
};

/// The residuals of one kind of observation, in its unit, before (start model) and
/// after (fitted model): root mean square over `count` values.
struct KindResiduals {
  int count = 0;
  double rms_before = 0, rms_after = 0;
};

struct FitResult {
  /// Empty when the fit ran; otherwise why it was refused or failed (no model).
  std::string error;
  /// How the search ended: "converged", "evaluation cap", "time cap" (then the
  /// best point found so far), "roundoff"; then the uncertainties' note if J^T J
  /// at the optimum was singular.
  std::string status;
  physics::Model model;  ///< the fitted model (the start's when refused)
  std::vector<ParameterEstimate> parameters;
  KindResiduals throw_deg;          ///< deg
  KindResiduals rebound_speed;      ///< m/s
  KindResiduals rebound_angle_deg;  ///< deg
  KindResiduals position;           ///< m
  /// s^2 = RSS / (n - p) of the weighted residuals at the optimum (about 1 when
  /// the sigmas are right and the model fits).
  double reduced_chi_square = 0;
  int evaluations = 0;  ///< prediction sets computed, the Jacobians' included
  double seconds = 0;
  /// The interrupt (FitOptions::interrupt) ended the fit; `error` says so and no
  /// model is fitted.
  bool interrupted = false;
};

/// Fits the parameters of `groups` to `observations` from `start` (see above).
FitResult Fit(const Observations& observations, std::span<const Group> groups, const physics::Model& start,
              const FitOptions& options = {});

}  // namespace snooker::calibration
