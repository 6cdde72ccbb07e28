#include "physics/cue/strike.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "physics/motion/motion.h"

namespace snooker::physics {
namespace {

constexpr double kG = 9.81;

CueStrike Level(double speed, double side, double height, double heading = 0.3) {
  return CueStrike{speed, heading, side, height, 0.0};
}

// A cue without end mass: no lateral impulse (a shaft that does not resist).
CueParams NoSquirt() {
  CueParams c;
  c.end_mass = 1e-30;
  return c;
}

std::string OffsetName(const ::testing::TestParamInfo<double>& info) {
  const int milli = static_cast<int>(std::lround(info.param * 1000));
  return (milli < 0 ? "Minus" : "Plus") + std::to_string(std::abs(milli)) + "PermilleR";
}

class StrikeProofTest : public ::testing::TestWithParam<double> {};

// TP A.30: an elastic tip (e = 1) at height b gives v = 2 V / (1 + m/M + 5/2 (b/R)^2)
// and w = 5 v b / (2 R^2); with the tip's restitution, 2 becomes 1 + e.
TEST_P(StrikeProofTest, SpeedAndSpinFromTheTipHeightAreTpA30) {
  const double b = GetParam();
  BallParams ball;
  for (double e : {1.0, 0.73}) {
    CueParams cue;
    cue.tip_restitution = e;
    const double V = 2.0;
    const StrikeResult res = Strike(Level(V, 0.0, b), cue, ball, kG);
    const double v = (1 + e) * V / (1 + ball.mass / cue.mass + 2.5 * b * b);
    EXPECT_NEAR(res.shot.speed, v, 1e-9 * v);
    EXPECT_NEAR(res.shot.topspin, 5 * v * (b * ball.radius) / (2 * ball.radius * ball.radius), 1e-9 * v / ball.radius);
    EXPECT_NEAR(res.shot.sidespin, 0, 1e-12);
    EXPECT_NEAR(res.squirt, 0, 1e-12);
  }
}

// TP A.31: a level strike at side b squirts by atan(5/2 (b/R) sqrt(1 - (b/R)^2) /
// (1 + m / m_e + 5/2 (1 - (b/R)^2))), away from the side struck.
TEST_P(StrikeProofTest, SquirtFromTheSideOffsetIsTpA31) {
  const double b = GetParam();
  BallParams ball;
  for (double end_mass : {0.004, 0.006, 0.009}) {
    CueParams cue;
    cue.end_mass = end_mass;
    const StrikeResult res = Strike(Level(1.7, b, 0.0), cue, ball, kG);
    const double alpha =
        std::atan(2.5 * std::abs(b) * std::sqrt(1 - b * b) / (1 + ball.mass / end_mass + 2.5 * (1 - b * b)));
    EXPECT_NEAR(std::abs(res.squirt), alpha, 1e-9);
    EXPECT_NEAR(std::atan(std::abs(res.lateral_impulse) / res.axial_impulse), alpha, 1e-9);
    EXPECT_NEAR(SquirtAngle(b, cue, ball), alpha, 1e-12);
    if (b != 0) {
      EXPECT_EQ(res.squirt > 0, b > 0) << "right side squirts to the left (counter-clockwise)";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Offsets, StrikeProofTest, ::testing::Values(-0.5, -0.3, 0.0, 0.1, 0.25, 0.45, 0.5),
                         OffsetName);

TEST(StrikeTest, DefaultShaftSquirtsWithinTheMeasuredRangeAtSideOf045R) {
  const double deg = RadToDeg(SquirtAngle(0.45, CueParams{}, BallParams{}));
  EXPECT_GE(deg, 1.8);
  EXPECT_LE(deg, 2.5);
  // Low-deflection shafts have less end mass and squirt less.
  CueParams light;
  light.end_mass = 0.6 * CueParams{}.end_mass;
  EXPECT_LT(SquirtAngle(0.45, light, BallParams{}), SquirtAngle(0.45, CueParams{}, BallParams{}));
}

TEST(StrikeTest, SquirtIsIndependentOfSpeedAndNearlyLinearInSide) {
  const CueParams cue;
  const BallParams ball;
  const double slow = Strike(Level(0.5, 0.3, 0.1), cue, ball, kG).squirt;
  const double fast = Strike(Level(5.0, 0.3, 0.1), cue, ball, kG).squirt;
  EXPECT_NEAR(slow, fast, 1e-12);
  const double s1 = SquirtAngle(0.1, cue, ball), s4 = SquirtAngle(0.4, cue, ball);
  EXPECT_NEAR(s4 / s1, 4.0, 0.4);  // within 10 % of linear up to 0.4 R
}

TEST(StrikeTest, LevelCentreStrikeLeavesAtTheRestitutionRatio) {
  const CueParams cue;
  const BallParams ball;
  const StrikeResult res = Strike(Level(1.0, 0, 0), cue, ball, kG);
  EXPECT_NEAR(res.shot.speed, (1 + cue.tip_restitution) / (1 + ball.mass / cue.mass), 1e-12);
  EXPECT_GT(res.shot.speed, 1.3);
  EXPECT_LT(res.shot.speed, 1.4);
  EXPECT_NEAR(res.w.norm(), 0, 1e-12);
}

// Momentum: the ball takes exactly the impulses the cue gives (J along the cue, F_s
// across); angular momentum about the contact point is conserved (I w = r x F).
// Energy: an elastic tip without lateral impulse conserves it; a real tip loses
// (1 - e^2) / 2 of the relative motion's energy along the cue, mu V^2 / 2 with
// mu = 1 / (1/M + (1 + 5/2 offset^2) / m).
TEST(StrikeTest, MomentumAndEnergyBalance) {
  const BallParams ball;
  for (double e : {1.0, 0.73}) {
    for (double elevation_deg : {0.0, 5.0, 15.0}) {
      CueParams cue = NoSquirt();
      cue.tip_restitution = e;
      const CueStrike k{2.2, 1.1, 0.3, -0.35, DegToRad(elevation_deg)};
      const StrikeResult res = Strike(k, cue, ball, kG);
      const double off2 = k.side * k.side + k.height * k.height;
      EXPECT_NEAR(ball.mass * res.v.norm(), res.axial_impulse, 1e-12);
      const double V1 = k.speed - res.axial_impulse / cue.mass;
      const double before = 0.5 * cue.mass * k.speed * k.speed;
      const double after = 0.5 * cue.mass * V1 * V1 + 0.5 * ball.mass * res.v.squaredNorm() +
                           0.5 * ball.Inertia() * res.w.squaredNorm();
      const double mu = 1 / (1 / cue.mass + (1 + 2.5 * off2) / ball.mass);
      EXPECT_NEAR(before - after, 0.5 * mu * (1 - e * e) * k.speed * k.speed, 1e-12)
          << "e " << e << " elevation " << elevation_deg;
    }
  }
  // With the end mass: the lateral impulse is the shaft's momentum, and the
  // sticking contact across the cue can only lose energy.
  const CueParams cue;
  const CueStrike k{2.0, 0.0, 0.4, 0.2, 0.0};
  const StrikeResult res = Strike(k, cue, ball, kG);
  const double tip_lateral = -res.lateral_impulse / cue.end_mass;
  const double V1 = k.speed - res.axial_impulse / cue.mass;
  const double after = 0.5 * cue.mass * V1 * V1 + 0.5 * cue.end_mass * tip_lateral * tip_lateral +
                       0.5 * ball.mass * res.v.squaredNorm() + 0.5 * ball.Inertia() * res.w.squaredNorm();
  EXPECT_LT(after, 0.5 * cue.mass * k.speed * k.speed);
  // ... and the tip and the contact point leave with one velocity across the cue.
  const Vec3 s(std::sin(k.heading), -std::cos(k.heading), 0);
  const Vec3 d(std::cos(k.heading), std::sin(k.heading), 0);
  const Vec3 u = s.cross(d);
  const double c = std::sqrt(1 - k.side * k.side - k.height * k.height);
  const Vec3 r = ball.radius * (k.side * s + k.height * u - c * d);
  EXPECT_NEAR((res.v + res.w.cross(r)).dot(s), tip_lateral, 1e-12);
}

TEST(StrikeTest, MiscueBoundaryIsTheTipsFrictionAngle) {
  CueParams cue;
  const BallParams ball;
  EXPECT_NEAR(MiscueLimit(cue), std::sin(std::atan(cue.tip_friction)), 1e-15);
  EXPECT_NEAR(MiscueLimit(cue), 0.5145, 1e-3);  // "about half the radius"
  const double lim = MiscueLimit(cue);
  for (double angle : {0.0, 0.7, 2.0, 4.0}) {  // any direction on the ball's face
    const double a = std::cos(angle), b = std::sin(angle);
    EXPECT_EQ(Strike(Level(1, a * (lim - 1e-6), b * (lim - 1e-6)), cue, ball, kG).status, StrikeStatus::kOk);
    EXPECT_EQ(Strike(Level(1, a * (lim + 1e-6), b * (lim + 1e-6)), cue, ball, kG).status,
              StrikeStatus::kMiscue);
  }
  cue.tip_friction = 0.4;  // a poorly chalked tip miscues sooner
  EXPECT_LT(MiscueLimit(cue), lim);
}

TEST(StrikeTest, ElevatedStrikeLosesItsDownwardPartToTheBedAndHopsAboveTheLimit) {
  const CueParams cue;
  const BallParams ball;
  const CueStrike k{1.5, 0.0, 0.0, 0.2, DegToRad(12)};
  const StrikeResult res = Strike(k, cue, ball, kG);
  EXPECT_LT(res.v.z(), 0);
  EXPECT_NEAR(res.shot.speed, std::hypot(res.v.x(), res.v.y()), 1e-12);
  const double rise = cue.bed_restitution * -res.v.z();
  EXPECT_NEAR(res.hop, rise * rise / (2 * kG), 1e-15);
  // The same cue twice as fast hops four times as high.
  CueStrike fast = k;
  fast.speed *= 2;
  EXPECT_NEAR(Strike(fast, cue, ball, kG).hop, 4 * res.hop, 1e-12);
  // Steep and fast: a jump, refused.
  CueStrike jump{4.0, 0.0, 0.0, 0.0, DegToRad(30)};
  EXPECT_EQ(Strike(jump, cue, ball, kG).status, StrikeStatus::kHop);
  EXPECT_EQ(Strike(Level(4.0, 0, 0), cue, ball, kG).status, StrikeStatus::kOk);
}

TEST(StrikeTest, NonsenseIsRefusedNotPropagated) {
  const CueParams cue;
  const BallParams ball;
  for (const CueStrike& k : {CueStrike{-1, 0, 0, 0, 0}, CueStrike{NAN, 0, 0, 0, 0}, CueStrike{1, INFINITY, 0, 0, 0},
                             CueStrike{1, 0, 0.8, 0.8, 0}, CueStrike{1, 0, 0, 0, -0.1},
                             CueStrike{1, 0, 0, 0, kPi / 2}, CueStrike{1, 0, NAN, 0, 0}}) {
    const StrikeResult res = Strike(k, cue, ball, kG);
    EXPECT_EQ(res.status, StrikeStatus::kInvalid);
    EXPECT_TRUE(std::isfinite(res.shot.speed) && std::isfinite(res.shot.topspin));
  }
}

// Swerve: an elevated cue with right side tilts the spin axis forwards (w along
// the heading); sliding, the cloth's friction then pushes the ball to the right, so
// that after squirting left it curves back right. A level cue's path is straight.
TEST(StrikeTest, ElevatedRightSideSwervesRight) {
  const CueParams cue;
  const BallParams ball;
  const ClothParams cloth;
  auto lateral_after = [&](double elevation_deg, double side) {
    const StrikeResult res = Strike(CueStrike{1.0, 0.0, side, 0.0, DegToRad(elevation_deg)}, cue, ball, kG);
    EXPECT_EQ(res.status, StrikeStatus::kOk);
    BallState s = StruckBall(res.shot, Vec2(0, 0));
    s.s = ClassifyMotion(s, ball);
    const double t = TransitionTime(s, ball, cloth);
    const BallState end = Evolve(s, t, ball, cloth);
    // Lateral offset (to the right of the ball's own initial heading) at the end of
    // the sliding phase, and the swerve spin.
    const Vec2 h(std::cos(res.shot.heading), std::sin(res.shot.heading));
    const Vec2 right(h.y(), -h.x());
    return std::pair{end.r.dot(right), res.shot.swerve_spin};
  };
  const auto [level_offset, level_swerve] = lateral_after(0, 0.4);
  EXPECT_NEAR(level_swerve, 0, 1e-12);
  EXPECT_NEAR(level_offset, 0, 1e-9);
  double last = 0;
  for (double e : {5.0, 10.0, 20.0}) {
    const auto [offset, swerve] = lateral_after(e, 0.4);
    EXPECT_GT(swerve, 0);
    EXPECT_GT(offset, last) << "more elevation, more swerve";
    last = offset;
    const auto [left_offset, left_swerve] = lateral_after(e, -0.4);
    EXPECT_NEAR(left_offset, -offset, 1e-12);
    EXPECT_NEAR(left_swerve, -swerve, 1e-12);
  }
}

// The inverse: the strike that realises a shot, for level and elevated cues.
TEST(StrikeTest, StrikeForRealisesTheShot) {
  const CueParams cue;
  const BallParams ball;
  const double R = ball.radius;
  int tried = 0;
  for (double elevation_deg : {0.0, 8.0}) {
    for (double top : {-1.0, -0.3, 0.0, 0.5, 1.0}) {
      for (double side : {-0.5, 0.0, 0.25}) {
        Shot shot;
        shot.speed = 1.8;
        shot.heading = 2.5;
        shot.topspin = top * shot.speed / R;
        shot.sidespin = side * shot.speed / R;
        const auto k = StrikeFor(shot, DegToRad(elevation_deg), cue, ball, kG);
        ASSERT_TRUE(k.has_value()) << top << " " << side;
        const StrikeResult res = Strike(*k, cue, ball, kG);
        EXPECT_NEAR(res.shot.speed, shot.speed, 1e-9);
        EXPECT_NEAR(std::remainder(res.shot.heading - shot.heading, 2 * kPi), 0, 1e-9);
        EXPECT_NEAR(res.shot.topspin, shot.topspin, 1e-7);
        EXPECT_NEAR(res.shot.sidespin, shot.sidespin, 1e-7);
        EXPECT_NEAR(k->elevation, DegToRad(elevation_deg), 0);
        ++tried;
      }
    }
  }
  EXPECT_EQ(tried, 30);
  // Spin beyond the miscue limit has no strike.
  Shot wild;
  wild.speed = 1;
  wild.topspin = 1.6 / R;
  EXPECT_FALSE(StrikeFor(wild, 0, cue, ball, kG).has_value());
}

}  // namespace
}  // namespace snooker::physics
