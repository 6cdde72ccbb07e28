#include "planner/random.h"

#include <cmath>

#include "physics/core/splitmix64.h"

namespace snooker::planner {
namespace {

using physics::SplitMix64;

std::uint64_t Rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

std::uint64_t DeriveSeed(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
  std::uint64_t x = seed;
  std::uint64_t h = SplitMix64(x);
  x = h ^ (a * 0xD1B54A32D192ED03ull);
  h = SplitMix64(x);
  x = h ^ (b * 0xABC98388FB8FAC03ull);
  return SplitMix64(x);
}

Rng::Rng(std::uint64_t seed) {
  std::uint64_t x = seed;
  for (std::uint64_t& s : s_) s = SplitMix64(x);
}

std::uint64_t Rng::Next() {
  const std::uint64_t result = Rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = Rotl(s_[3], 45);
  return result;
}

double Rng::Uniform() { return physics::UnitInterval(Next()); }

double Rng::Gaussian() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  // Accepts with probability pi/4 per try: 64 failures in a row have probability
  // below 1e-42; the cap only guards the loop.
  for (int tries = 0; tries < 64; ++tries) {
    const double u = 2 * Uniform() - 1, v = 2 * Uniform() - 1;
    const double s = u * u + v * v;
    if (s >= 1 || s == 0) continue;
    const double f = std::sqrt(-2 * std::log(s) / s);
    spare_ = v * f;
    has_spare_ = true;
    return u * f;
  }
  return 0;
}

}  // namespace snooker::planner
