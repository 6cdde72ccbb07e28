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

/// Friction coefficients mu_bb (ball-ball), mu_s (ball-cloth) and mu_r (rolling).
/// mu_bb <= 1 with mu_s <= 1 keeps the normal relative velocity strictly falling
/// during an impact, which bounds the impulse and the integrators' step count.
inline constexpr Range kFrictionCoefficient{0, 1};
/// The exponential friction laws' b (dimensionless) and c (s/m), mu = a + b exp(-c s)
/// (core/params.h); b also keeps mu at zero speed, a + b, a friction coefficient
/// (kFrictionCoefficient), so that the bound on the impulse above holds for it.
inline constexpr Range kSlipGain{0, 1};
inline constexpr Range kSlipDecay{0, 100};
/// The cloth's sliding friction mu_s and rolling resistance mu_r that a model or a
/// request may set: friction coefficients (kFrictionCoefficient) large enough to stop
/// a ball within a shot. With less a slip or a roll outlasts any shot (mu_s = 1e-300
/// made a collision's slip last 1e297 s) and simulations end at their caps. A real
/// cloth is near 0.2 and 0.01 (calibration fits them in [0.05, 0.6] and [0.002, 0.05]).
inline constexpr Range kClothSlideFriction{0.01, 1};
inline constexpr Range kRollingResistance{0.001, 1};
/// Energetic coefficient of restitution (Stronge).
inline constexpr Range kRestitution{0, 1};
/// Ball mass, kg, and radius, m, an API may ask for: from a marble to a bowling ball.
inline constexpr Range kBallMass{1e-3, 10};
inline constexpr Range kBallRadius{1e-3, 1};
/// Gravitational acceleration, m/s^2.
inline constexpr Range kGravity{0.1, 100};
/// Z-spin deceleration on the cloth, rad/s^2.
inline constexpr Range kSpinDecel{0, 1e4};
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
/// The speed scale of an impact solver's input (physics/impact/): the largest |v| and
/// R |w| of its balls, m/s. Ten thousand times the fastest impact the API takes
/// (kImpactSpeed), and far below where the solvers' arithmetic overflows (the squares
/// in their step control and energy do beyond about 1e150 m/s).
inline constexpr double kMaxImpactSpeedScale = 1e6;
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
