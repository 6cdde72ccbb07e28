// The flags `snooker selfplay` and `snooker match` share: the planning budget, the
// execution and vision noise, the robot's cue room and the planner's work. Their
// ranges are planner/limits.h's, quoted in the flags' own units.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "cli/args.h"
#include "physics/model/model.h"
#include "planner/planner.h"

namespace snooker::cli {

struct PlayFlags {
  double budget_ms = planner::limits::kDefaultTimeBudget * 1e3;
  planner::NoiseModel noise;
  planner::RobotLimits limits;
  std::int64_t max_simulations = 0;
  int monte_carlo_samples = 48;
  int threads = 2;
  /// --break-value P: the planner's break value, points (none: the command's own).
  std::optional<double> break_value;
  /// --position-spread K: the search's position spread (none: the planner's own, 0).
  std::optional<double> position_spread;
  /// --model FILE: the planner's physical model (none: the default).
  std::optional<physics::Model> model;
  /// --world FILE: the table the shots are played on (none: the planner's model).
  std::optional<physics::Model> world;
};

/// The flags' names, for Args.
inline constexpr const char* kPlayFlagNames[] = {
    "budget-ms",     "noise-heading-deg", "noise-speed",     "noise-spin",         "noise-position-mm",
    "noise-aim-deg", "noise-cue-speed",   "noise-tip-mm",    "noise-elevation-deg", "squirt-uncertainty",
    "throw-uncertainty", "cue-clearance-m", "max-elevation-deg", "max-simulations", "samples", "threads",
    "model",         "world",             "break-value",     "position-spread"};

/// The help lines of the noise and robot flags, after each command's "Noise" line.
inline constexpr const char* kPlayFlagsHelp = R"(  --noise-aim-deg X       the cue's aim, degrees (default 0.02)
  --noise-cue-speed X     the cue's speed, fraction of the speed (default 0.01)
  --noise-tip-mm X        where the tip meets the ball, per axis, mm (default 0.1)
  --noise-elevation-deg X the cue's elevation, degrees (default 0.1)
  --squirt-uncertainty X  the model's squirt, give or take this fraction, as the
  --throw-uncertainty X   planner believes it (default 0 each here: the world played
                          is the model itself; snooker plan's 0.15 and 0.10 model a
                          real table)
  --noise-heading-deg X   more noise on the cue ball's heading after the strike,
                          degrees (default 0)
  --noise-speed X         more on its speed, fraction of the speed (default 0)
  --noise-spin X          more on its topspin and sidespin, rad/s (default 0)
  --noise-position-mm X   vision, each ball centre per axis, mm (default 0.2)
Robot:
  --cue-clearance-m X     clear bed the cue needs behind the cue ball, m (0.10)
  --max-elevation-deg X   the steepest the cue may be raised, degrees (default 25;
                          0: always level)
Models:
  --model FILE            the planner's physical model: a model file (JSON of
                          snooker.v1.PhysicsModel; fields left out keep the default)
  --world FILE            the table the shots are played on, a model file: the
                          planner plans with its model and the world answers
                          (sim-to-real; default: the planner's model)
)";

/// Reads the flags (each absent one keeps `defaults`' value) into `out`; empty, or
/// the first error naming the flag and its value.
std::string ReadPlayFlags(Args& args, const PlayFlags& defaults, PlayFlags* out);

}  // namespace snooker::cli
