#include "physics/core/splitmix64.h"

#include <cstdint>

#include <gtest/gtest.h>

namespace snooker::physics {
namespace {

// The published sequences of the reference generator (Vigna's splitmix64.c): from
// the seed 0, and the five numbers from 1234567 that other ports test against. A
// changed constant or shift gives other numbers, and with them every seeded plan,
// calibration record and load test would change.
TEST(SplitMix64Test, GivesTheReferenceSequences) {
  std::uint64_t state = 0;
  EXPECT_EQ(SplitMix64(state), 0xE220A8397B1DCDAFull);
  EXPECT_EQ(SplitMix64(state), 0x6E789E6AA1B965F4ull);
  EXPECT_EQ(SplitMix64(state), 0x06C45D188009454Full);

  state = 1234567;
  const std::uint64_t expected[] = {6457827717110365317ull, 3203168211198807973ull,
                                    9817491932198370423ull, 4593380528125082431ull,
                                    16408922859458223821ull};
  for (const std::uint64_t e : expected) EXPECT_EQ(SplitMix64(state), e);
  EXPECT_EQ(state, 1234567 + 5 * 0x9E3779B97F4A7C15ull);
}

// [0, 1) with 53 bits: zero maps to 0, all ones to the largest double below 1, and
// the low 11 bits, which a double cannot hold, are dropped rather than rounded up.
TEST(SplitMix64Test, UnitIntervalKeepsTheTop53Bits) {
  EXPECT_EQ(UnitInterval(0), 0.0);
  EXPECT_EQ(UnitInterval(~0ull), 1.0 - 0x1.0p-53);
  EXPECT_LT(UnitInterval(~0ull), 1.0);
  EXPECT_EQ(UnitInterval(0x7FFull), 0.0);
  EXPECT_EQ(UnitInterval(1ull << 11), 0x1.0p-53);
  EXPECT_EQ(UnitInterval(1ull << 63), 0.5);
}

}  // namespace
}  // namespace snooker::physics
