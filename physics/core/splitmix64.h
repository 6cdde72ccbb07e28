// SplitMix64 (Steele, Lea & Flood 2014), the one 64-bit mixing step of the seeded
// numbers above physics: the planner seeds its generator and derives its tasks'
// streams with it, calibration draws its simulated observations with it and the load
// test its tables. It lives in physics/core because that is the one layer they all
// include; physics itself draws no random numbers. Plain integer arithmetic, so a
// seed gives the same numbers on every platform and standard library.
#pragma once

#include <cstdint>

namespace snooker::physics {

/// Advances `state` by the golden-ratio increment and returns the mix of its new
/// value: successive calls are SplitMix64's sequence from the seed `state` held.
inline std::uint64_t SplitMix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// The top 53 bits of `bits` as a double in [0, 1), every value a multiple of 2^-53.
inline double UnitInterval(std::uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

}  // namespace snooker::physics
