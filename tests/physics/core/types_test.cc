#include "physics/core/types.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

namespace snooker::physics {
namespace {

// The fast path must give the library's remainder to the bit, or plans that wrap
// angles would change with it: at +-pi (ties round to the even quotient, 0), on
// either side of them, at multiples of 2 pi, far out, and at the non-finite values.
TEST(TypesTest, RemainderTwoPiIsTheLibrarysToTheBit) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> xs = {0.0, -0.0, inf, -inf, std::numeric_limits<double>::quiet_NaN(),
                            1e10, -1e10, 1e300, std::numeric_limits<double>::denorm_min()};
  for (int k = -5; k <= 5; ++k) {
    const double centre = k * kPi;
    double below = centre, above = centre;
    for (int s = 0; s < 4; ++s) {
      xs.push_back(below);
      xs.push_back(above);
      below = std::nextafter(below, -inf);
      above = std::nextafter(above, inf);
    }
  }
  for (int k = 0; k <= 10000; ++k) xs.push_back(-25.0 + 0.005 * k + 1e-7);  // off the grid of pi
  int inside = 0;
  for (const double x : xs) {
    const double want = std::remainder(x, 2 * kPi);
    const double got = RemainderTwoPi(x);
    if (std::isnan(want)) {
      EXPECT_TRUE(std::isnan(got)) << x;
      continue;
    }
    EXPECT_EQ(std::bit_cast<std::uint64_t>(got), std::bit_cast<std::uint64_t>(want)) << x;
    EXPECT_LE(std::abs(got), kPi) << x;
    if (std::abs(x) <= kPi) ++inside;
  }
  EXPECT_GT(inside, 1000);  // the fast path was taken, and not only at its ends
}

}  // namespace
}  // namespace snooker::physics
