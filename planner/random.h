// Seeded random numbers for the planner: the same seed gives the same numbers on
// every platform and standard library (std::normal_distribution is implementation-
// defined, so the Gaussian is our own), and work split across threads stays
// deterministic by giving every task its own stream derived from the request seed.
#pragma once

#include <cstdint>

namespace snooker::planner {

/// A seed for one task: a hash of the request seed and the task's coordinates
/// (e.g. shot index, sample block). Different coordinates give independent streams.
std::uint64_t DeriveSeed(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0);

/// xoshiro256** (Blackman & Vigna), seeded through splitmix64.
class Rng {
 public:
  explicit Rng(std::uint64_t seed);

  std::uint64_t Next();
  /// Uniform in [0, 1).
  double Uniform();
  /// Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  /// Standard normal (Marsaglia's polar method; loop capped, expected 1.27 tries).
  double Gaussian();

 private:
  std::uint64_t s_[4];
  bool has_spare_ = false;
  double spare_ = 0;
};

}  // namespace snooker::planner
