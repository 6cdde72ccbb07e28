// The flags `snooker selfplay` and `snooker match` share: the planning budget, the
// execution and vision noise, the robot's cue room and the planner's work. Their
// ranges are planner/limits.h's, quoted in the flags' own units.
#pragma once

#include <cstdint>
#include <string>

#include "cli/args.h"
#include "planner/planner.h"

namespace snooker::cli {

struct PlayFlags {
  double budget_ms = planner::limits::kDefaultTimeBudget * 1e3;
  planner::NoiseModel noise;
  planner::RobotLimits limits;
  std::int64_t max_simulations = 0;
  int monte_carlo_samples = 48;
  int threads = 2;
};

/// The flags' names, for Args.
inline constexpr const char* kPlayFlagNames[] = {
    "budget-ms",     "noise-heading-deg", "noise-speed",     "noise-spin",         "noise-position-mm",
    "noise-aim-deg", "noise-cue-speed",   "noise-tip-mm",    "noise-elevation-deg", "squirt-uncertainty",
    "throw-uncertainty", "cue-clearance-m", "max-elevation-deg", "max-simulations", "samples", "threads"};

/// Reads the flags (each absent one keeps `defaults`' value) into `out`; empty, or
/// the first error naming the flag and its value.
std::string ReadPlayFlags(Args& args, const PlayFlags& defaults, PlayFlags* out);

}  // namespace snooker::cli
