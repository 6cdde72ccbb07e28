// Tests of physics/motion/slip_phase.h against the closed forms of paper section 2.5.
#include "physics/motion/slip_phase.h"

#include <gtest/gtest.h>

#include <cmath>

namespace snooker::physics {
namespace {

constexpr double kTol = 1e-12;  // closed forms evaluated in double precision

TEST(SlipPhaseTest, StunBallEndsAtFiveSeventhsOfItsSpeed) {
  const BallParams ball;
  const ClothParams cloth;
  BallMotion m;
  m.v = Vec3(0.0, 2.0, 0.0);  // no spin: slip = velocity
  const SlipEnd end = SlipPhaseEnd(m, ball, cloth);
  EXPECT_NEAR(end.speed, 5.0 / 7.0 * 2.0, kTol);
  EXPECT_NEAR(end.time, 2 * 2.0 / (7 * cloth.mu_s * cloth.g), kTol);
  // Slide distance 12 v^2 / (49 mu_s g).
  EXPECT_NEAR(end.displacement.y(), 12 * 4.0 / (49 * cloth.mu_s * cloth.g), kTol);
  EXPECT_NEAR(end.displacement.x(), 0.0, kTol);
}

TEST(SlipPhaseTest, RollingBallHasNoSlipPhase) {
  const BallParams ball;
  BallMotion m;
  m.v = Vec3(0.6, 0.8, 0.0);
  m.w = Vec3(-0.8 / ball.radius, 0.6 / ball.radius, 3.0);  // v = w x (R z)
  const SlipEnd end = SlipPhaseEnd(m, ball, {});
  EXPECT_NEAR(end.time, 0.0, kTol);
  EXPECT_NEAR(end.speed, 1.0, kTol);
  EXPECT_NEAR(end.sidespin, 3.0, kTol);
}

// The slip keeps its direction, so the end velocity is v - (2/7) u for any spin,
// and the ball rolls from there: the slip of the end state is zero.
TEST(SlipPhaseTest, EndVelocityIsVMinusTwoSeventhsOfSlip) {
  const BallParams ball;
  BallMotion m;
  m.v = Vec3(0.3, 1.1, 0.0);
  m.w = Vec3(20.0, -35.0, -4.0);
  const Vec2 u = ClothSlip(m, ball.radius);
  const SlipEnd end = SlipPhaseEnd(m, ball, {});
  EXPECT_NEAR((end.velocity - (Vec2(0.3, 1.1) - 2.0 / 7.0 * u)).norm(), 0.0, kTol);
  EXPECT_NEAR(end.time, 2 * u.norm() / (7 * 0.21 * 9.81), kTol);
}

TEST(SlipPhaseTest, SidespinDecaysToZeroAndStops) {  // eq. 21
  EXPECT_DOUBLE_EQ(SpinAfter(10.0, 22.0, 0.2), 10.0 - 4.4);
  EXPECT_DOUBLE_EQ(SpinAfter(-10.0, 22.0, 0.2), -10.0 + 4.4);
  EXPECT_DOUBLE_EQ(SpinAfter(10.0, 22.0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(SpinAfter(-10.0, 22.0, 1.0), 0.0);
}

TEST(SlipPhaseTest, AngleBetweenIsUnsignedAndExactAtExtremes) {
  EXPECT_NEAR(AngleBetween(Vec2(1, 0), Vec2(0, 1)), kPi / 2, kTol);
  EXPECT_NEAR(AngleBetween(Vec2(0, 1), Vec2(1, 0)), kPi / 2, kTol);
  EXPECT_NEAR(AngleBetween(Vec2(1, 0), Vec2(-1, 1e-300)), kPi, kTol);
  EXPECT_NEAR(AngleBetween(Vec2(1, 0), Vec2(1, 1e-9)), 1e-9, 1e-20);
  EXPECT_EQ(AngleBetween(Vec2(0, 0), Vec2(1, 0)), 0.0);
}

}  // namespace
}  // namespace snooker::physics
