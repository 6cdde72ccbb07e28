// Repairing vision's small placement errors (physics/table/placement_repair.h).
#include "physics/table/placement_repair.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace snooker::physics {
namespace {

constexpr double kTolerance = 1e-3;  // m, the service's default vision tolerance
constexpr double kPosTol = 1e-9;     // m, distances after a repair

class RepairTest : public testing::Test {
 protected:
  const TableModel& table_ = DefaultTable();
  const double r_ = table_.ball_radius();
  const double c_ = table_.cushion_contact_distance();
};

// Two balls overlapping by 0.5 mm move apart along their line of centres, each by
// half the overlap: the least displacement that separates them.
TEST_F(RepairTest, OverlappingPairMovesApartByHalfTheOverlapEach) {
  std::vector<BallPlacement> balls = {{"red-1", {0.9, 1.0}}, {"red-2", {0.9 + 2 * r_ - 5e-4, 1.0}}};
  const PlacementRepair fix = RepairPlacement(table_, balls, kTolerance);
  ASSERT_TRUE(fix.error.empty()) << fix.error;
  ASSERT_EQ(fix.moved.size(), 2u);
  EXPECT_NEAR(fix.moved[0].distance, 2.5e-4, kPosTol);
  EXPECT_NEAR(fix.moved[1].distance, 2.5e-4, kPosTol);
  EXPECT_NEAR(balls[0].r.y(), 1.0, 1e-15);  // along the line of centres only
  EXPECT_NEAR((balls[1].r - balls[0].r).norm(), 2 * r_, kPosTol);
  EXPECT_TRUE(table_.ValidatePlacement(balls).empty()) << table_.ValidatePlacement(balls);
}

// A centre 0.3 mm past the left cushion's contact distance moves straight back.
TEST_F(RepairTest, BallPastTheCushionMovesBackOntoTheBed) {
  std::vector<BallPlacement> balls = {{"cue", {c_ - 3e-4, 2.0}}};
  const PlacementRepair fix = RepairPlacement(table_, balls, kTolerance);
  ASSERT_TRUE(fix.error.empty()) << fix.error;
  ASSERT_EQ(fix.moved.size(), 1u);
  EXPECT_NEAR(fix.moved[0].distance, 3e-4, kPosTol);
  EXPECT_DOUBLE_EQ(balls[0].r.x(), c_);
  EXPECT_DOUBLE_EQ(balls[0].r.y(), 2.0);
}

// The tolerance bounds each overlap and overshoot, not each move: in a row of touching
// balls pressed against a cushion the moves add up along the row. Five balls from the
// left cushion, each overlapping the next by 0.9 mm: the row must grow by 3.6 mm, and
// the cushion holds its first ball, so the far ball moves at least that far, more
// than the 1 mm tolerance, and its move is reported.
TEST_F(RepairTest, MovesAddUpAlongARowPressedAgainstACushion) {
  constexpr double kOverlap = 9e-4;
  std::vector<BallPlacement> balls;
  for (int k = 0; k < 5; ++k) balls.push_back({"red-" + std::to_string(k + 1), {c_ + k * (2 * r_ - kOverlap), 1.5}});
  const PlacementRepair fix = RepairPlacement(table_, balls, kTolerance);
  ASSERT_TRUE(fix.error.empty()) << fix.error;
  EXPECT_TRUE(table_.ValidatePlacement(balls).empty()) << table_.ValidatePlacement(balls);
  double farthest = 0;
  for (const RepairedBall& m : fix.moved) farthest = std::max(farthest, m.distance);
  EXPECT_GE(farthest, 4 * kOverlap - 1e-6);
  EXPECT_GT(farthest, kTolerance);
  EXPECT_GE(balls.back().r.x() - balls.front().r.x(), 8 * r_ - 4 * kPosTol);  // four gaps
}

// A valid placement is left exactly as it is.
TEST_F(RepairTest, ValidPlacementIsUntouched) {
  std::vector<BallPlacement> balls = {{"cue", {0.5, 0.5}}, {"red", {0.5 + 2 * r_, 0.5}}, {"black", {c_, 3.0}}};
  const std::vector<BallPlacement> before = balls;
  const PlacementRepair fix = RepairPlacement(table_, balls, kTolerance);
  EXPECT_TRUE(fix.error.empty());
  EXPECT_TRUE(fix.moved.empty());
  for (size_t i = 0; i < balls.size(); ++i) EXPECT_EQ(balls[i].r, before[i].r);
}

// Beyond the tolerance: an error naming the balls and the size, and nothing moves.
TEST_F(RepairTest, BeyondTheToleranceIsAnErrorAndNothingMoves) {
  std::vector<BallPlacement> balls = {{"red-1", {0.9, 1.0}}, {"red-2", {0.9 + 2 * r_ - 2e-3, 1.0}},
                                      {"cue", {c_ - 5e-4, 2.0}}};
  const std::vector<BallPlacement> before = balls;
  const PlacementRepair fix = RepairPlacement(table_, balls, kTolerance);
  EXPECT_NE(fix.error.find("red-1 and red-2 overlap by 0.002"), std::string::npos) << fix.error;
  EXPECT_TRUE(fix.moved.empty());
  for (size_t i = 0; i < balls.size(); ++i) EXPECT_EQ(balls[i].r, before[i].r);
  // The cue ball alone would have been within the tolerance: not named.
  EXPECT_EQ(fix.error.find("cue"), std::string::npos) << fix.error;
}

// Many problems: the message lists the first few and counts the rest.
TEST_F(RepairTest, LongErrorsAreBounded) {
  std::vector<BallPlacement> balls(20, BallPlacement{"", {0.9, 1.0}});
  const PlacementRepair fix = RepairPlacement(table_, balls, kTolerance);
  EXPECT_NE(fix.error.find("and 185 more"), std::string::npos) << fix.error;  // 190 pairs
  EXPECT_LT(fix.error.size(), 600u);
}

// The opening rack as vision sees it: every ball jittered by up to 0.3 mm, so
// touching reds overlap a little. After the repair the placement is valid and no
// ball moved more than the tolerance.
TEST_F(RepairTest, JitteredRackIsRepaired) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-3e-4, 3e-4);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<BallPlacement> balls;
    for (const Vec2& red : table_.reds()) balls.push_back({"", red + Vec2(u(rng), u(rng))});
    for (int k = 0; k < kColourCount; ++k) balls.push_back({"", table_.spot(Colour(k)) + Vec2(u(rng), u(rng))});
    const PlacementRepair fix = RepairPlacement(table_, balls, kTolerance);
    ASSERT_TRUE(fix.error.empty()) << fix.error;
    EXPECT_TRUE(table_.ValidatePlacement(balls).empty()) << "trial " << trial;
    for (const RepairedBall& m : fix.moved) EXPECT_LE(m.distance, kTolerance) << "trial " << trial;
  }
}

}  // namespace
}  // namespace snooker::physics
