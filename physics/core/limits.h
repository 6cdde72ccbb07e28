// Validation ranges, defined once: the library's own checks, the API (server/) and
// the command line (cli/) all use these, and their messages print them.
//
// Each bound keeps one request's work and output finite and small: a shot faster
// than any cue can play, a spin no tip can give, a step count or event cap that
// would run for minutes, an id that would be repeated in every event.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace snooker::physics {

/// A closed interval of finite numbers.
struct Range {
  double lo = 0;
  double hi = 0;
  /// True for a finite x in [lo, hi] (NaN and infinities are outside every range).
  constexpr bool Contains(double x) const { return std::isfinite(x) && x >= lo && x <= hi; }
};

namespace limits {

/// Relative local error tolerance of the adaptive impact integrators.
inline constexpr Range kTolerance{1e-15, 0.1};
/// Steps N of the paper's fixed-step scheme (eq. 14). 1e7 steps cost about 0.3 s;
/// the paper's own runs and our reports use at most 1e6.
inline constexpr std::int32_t kMaxFixedSteps = 10'000'000;
/// Cue-ball speed of a shot on the table, m/s (a hard break is about 10 m/s).
inline constexpr Range kShotSpeed{0, 20};
/// Incident speed of one collision (Collide), m/s: above 0 (no approach is no
/// collision) and below anything a snooker ball meets.
inline constexpr Range kImpactSpeed{1e-6, 100};
/// |topspin| and |sidespin| of a shot, rad/s (a cue gives at most about 300).
inline constexpr double kMaxSpin = 1000;
/// Simulation caps a request may ask for.
inline constexpr std::int32_t kMaxEvents = 1'000'000;
inline constexpr Range kMaxSimulatedTime{1e-3, 3600};  // s
/// Sampling interval of returned paths, s.
inline constexpr Range kPathSample{1e-4, 1};
/// Balls on one table (snooker has 22).
inline constexpr int kMaxBalls = 32;
/// Bytes in a ball id.
inline constexpr std::size_t kMaxIdBytes = 64;

}  // namespace limits
}  // namespace snooker::physics
