// The ranges of a plan request, named once. The planner checks its requests against
// them (validate.h); the API (server/) converts their units and quotes them, the
// command line passes its values through, and proto/snooker/v1/plan.proto's comments
// state the same values. SI units here (m, s, rad, m/s, rad/s).
//
// Why each bound: a value outside it is a client's mistake rather than a robot's
// setting (a cue needing 2 m of room, a heading error of 10 deg), or a request whose
// work would not be bounded (a minute of planning, a hundred million simulations).
#pragma once

#include <cstdint>

#include "physics/core/limits.h"
#include "physics/core/types.h"

namespace snooker::planner::limits {

using physics::Range;

/// An inclusive range of integers.
struct IntRange {
  std::int64_t lo = 0;
  std::int64_t hi = 0;
  constexpr bool Contains(std::int64_t x) const { return x >= lo && x <= hi; }
};

// --- The robot ------------------------------------------------------------------
/// Slowest cue-ball speed the robot plays, m/s (up to the simulator's fastest shot).
inline constexpr Range kMinSpeed{0, physics::limits::kShotSpeed.hi};
/// Fastest cue-ball speed the robot plays, m/s; it must also exceed the slowest. A
/// robot that cannot play 5 cm/s cannot reach any pocket.
inline constexpr Range kMaxSpeed{0.05, physics::limits::kShotSpeed.hi};
/// Largest |topspin| and |sidespin| as a fraction of the rolling spin v/R. A tip
/// offset of half the radius gives about 1.25; 3 is beyond any cue.
inline constexpr Range kSpinFraction{0, 3};
/// Room the cue needs behind the cue ball along the shot, m, and the stick's radius
/// there, m.
inline constexpr Range kCueClearance{0, 2};
inline constexpr Range kCueRadius{0, 0.05};
/// The cue's speed at impact, m/s (10 m/s: beyond any break-off).
inline constexpr Range kCueSpeed{0, 10};
/// The steepest cue the robot may raise, rad (above 60 deg a cue strikes down into
/// the bed: masse, which the strike model does not play).
inline constexpr Range kMaxElevation{0, 60 * physics::kPi / 180};

// --- Noise ------------------------------------------------------------------------
/// Standard deviation of the heading, rad (10 deg: a robot worse than that cannot pot).
inline constexpr Range kHeadingSigma{0, 10 * physics::kPi / 180};
/// Standard deviation of the speed, as a fraction of the speed.
inline constexpr Range kSpeedSigmaFraction{0, 0.5};
/// Standard deviation of topspin and sidespin, rad/s.
inline constexpr Range kSpinSigma{0, 100};
/// Standard deviation of the tip's placement on the ball, per axis, m (5 mm: a
/// fifth of the radius).
inline constexpr Range kTipOffsetSigma{0, 0.005};
/// Standard deviation of the cue's elevation, rad.
inline constexpr Range kElevationSigma{0, 10 * physics::kPi / 180};
/// The model's uncertainty in squirt and throw, a fraction of the model's.
inline constexpr Range kModelUncertainty{0, 1};
/// Vision's standard deviation of a ball centre, per axis, m (5 cm: a different
/// table, not vision's error).
inline constexpr Range kPositionSigma{0, 0.05};

// --- The work ---------------------------------------------------------------------
/// Time budget of one plan, s, and a request's default: 80 ms is what the robot can
/// wait between shots and buys a few thousand simulations on two cores.
inline constexpr Range kTimeBudget{1e-3, 60};
inline constexpr double kDefaultTimeBudget = 0.08;
/// Shots returned, best first.
inline constexpr IntRange kMaxShots{1, 20};
/// Worker threads of one plan (the caller's included).
inline constexpr IntRange kThreads{1, 64};
/// Cap on the simulations of one plan (0: derived from the budget).
inline constexpr IntRange kMaxSimulations{0, 100'000'000};
/// Monte Carlo samples per ranked shot (0: rank by the search's estimate).
inline constexpr IntRange kMonteCarloSamples{0, 100'000};

// --- The objective ----------------------------------------------------------------
/// The break value: what keeping the table is worth beyond the potted ball's own
/// value, points (PositionOptions::continuation). 147, a maximum break, is more
/// than any table can still give.
inline constexpr Range kBreakValue{0, 147};
/// The position's spread in the search, standard deviations of the cue ball's end
/// from the speed's noise (SearchSettings::position_spread). Beyond a few the
/// quadrature's points leave the cue ball's reach.
inline constexpr Range kPositionSpread{0, 4};

}  // namespace snooker::planner::limits
