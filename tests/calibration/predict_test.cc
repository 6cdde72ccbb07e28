// Tests of calibration/predict.h: each prediction agrees with the physics it is
// built on (the collision, the cushion, the table simulation).
#include "calibration/predict.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "physics/sim/simulate.h"

namespace snooker::calibration {
namespace {

using physics::Vec2;

constexpr double kR = 0.02625;

ThrowObservation Stun(double cut_deg, double cue_ball_speed) {
  ThrowObservation o;
  o.cut = physics::DegToRad(cut_deg);
  o.cue_ball_speed = cue_ball_speed;
  return o;
}

// Given the object ball's speed, the solved incident speed gives it, and the
// throw is the cue-ball-speed form's at that speed.
TEST(PredictThrowTest, ObjectBallSpeedIsSolvedFor) {
  physics::Model m;
  m.ball_ball.friction_law = physics::BallBallFrictionLaw::kMarlow;
  for (double cut : {10.0, 45.0, 70.0}) {
    ThrowObservation o;
    o.cut = physics::DegToRad(cut);
    o.object_ball_speed = 0.8;
    o.topspin = 20;
    const ThrowPrediction p = PredictThrow(o, m);
    ASSERT_EQ(p.error, "") << cut;
    EXPECT_NEAR(p.object_ball_speed, 0.8, 1e-9) << cut;
    ThrowObservation direct = o;
    direct.object_ball_speed.reset();
    direct.cue_ball_speed = p.cue_ball_speed;
    EXPECT_DOUBLE_EQ(PredictThrow(direct, m).throw_angle, p.throw_angle) << cut;
  }
}

// A stun cut throws towards the cue ball's tangential motion, never beyond the
// no-slip limit atan(2 tan(cut) / (7 (1 + e))); outside side (positive sidespin
// here) that turns the contact's slip round throws the other way.
TEST(PredictThrowTest, ThrowHasTheCutsSignAndStaysUnderTheNoSlipLimit) {
  const physics::Model m;
  for (double cut : {15.0, 30.0, 45.0, 60.0}) {
    const ThrowPrediction p = PredictThrow(Stun(cut, 1.5), m);
    ASSERT_EQ(p.error, "");
    const double limit = std::atan(2 * std::tan(physics::DegToRad(cut)) / (7 * (1 + m.ball_ball.e)));
    EXPECT_GT(p.throw_angle, 0) << cut;
    EXPECT_LE(p.throw_angle, limit + 1e-6) << cut;
    ThrowObservation outside = Stun(cut, 1.5);
    outside.sidespin = 2 * 1.5 * std::sin(outside.cut) / kR;
    EXPECT_LT(PredictThrow(outside, m).throw_angle, 0) << cut;
  }
}

TEST(PredictThrowTest, ImpossibleObjectBallSpeedIsAnError) {
  ThrowObservation o;
  o.cut = physics::DegToRad(85);
  o.object_ball_speed = 9.9;  // needs over 100 m/s of the cue ball at 85 deg
  EXPECT_NE(PredictThrow(o, physics::Model{}).error.find("no incident speed"), std::string::npos);
}

// Square on, rolling: straight back, at the measured rebound (Mathavan et al.
// 2009's fit, which the default curve follows within 0.05 m/s on the table).
TEST(PredictReboundTest, SquareOnRollingFollowsTheMeasuredFit) {
  const physics::Model m;
  for (double v : {0.5, 1.0, 2.0, 3.0}) {
    const ReboundPrediction p = PredictRebound({v, physics::kPi / 2, v / kR, 0, 0, {}}, m);
    ASSERT_EQ(p.error, "");
    EXPECT_NEAR(p.angle, physics::kPi / 2, 1e-9) << v;
    EXPECT_NEAR(p.speed, -0.0877 * v * v + 1.131 * v - 0.0953, 0.05) << v;
  }
  // An approach along +X at 45 deg leaves on along +X (angle below pi/2).
  const ReboundPrediction oblique = PredictRebound({1.0, physics::kPi / 4, 1.0 / kR, 0, 0, {}}, m);
  EXPECT_GT(oblique.angle, 0);
  EXPECT_LT(oblique.angle, physics::kPi / 2);
}

TrackedShot TwoBallShot() {
  TrackedShot s;
  s.balls = {Vec2(0.9, 1.0), Vec2(0.92, 1.6)};
  s.strike = physics::CueStrike{2.5, physics::kPi / 2, 0.2, 0.1, 0.03};
  for (int k = 1; k <= 100; ++k) s.sightings.push_back({0.1 * k, {}});
  return s;
}

// The cue form goes through the model's cue: the same positions as the ball form
// with the shot physics::Strike gives; the first sighting is where the
// simulator puts the cue ball then; every ball rests at its final position after
// the run's end.
TEST(PredictShotTest, CueFormIsTheStrikesShotAndPositionsAreTheSimulators) {
  const physics::Model m;
  const TrackedShot cue = TwoBallShot();
  TrackedShot ball = cue;
  const physics::StrikeResult k =
      physics::Strike(std::get<physics::CueStrike>(cue.strike), m.cue, m.ball, m.cloth.g);
  ball.strike = k.shot;
  const ShotPrediction a = PredictShot(cue, m), b = PredictShot(ball, m);
  ASSERT_EQ(a.error, "");
  ASSERT_EQ(a.positions.size(), cue.sightings.size());
  for (std::size_t j = 0; j < a.positions.size(); ++j) {
    for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(a.positions[j][i], b.positions[j][i]);
  }
  physics::Simulator sim(physics::DefaultTable(), m.Apply(CalibrationNumerics()));
  std::string error;
  ASSERT_EQ(sim.Run(StartOfShot(cue, m, &error)), physics::SimStatus::kAtRest);
  EXPECT_EQ(a.end_time, sim.end_time());
  EXPECT_LT((a.positions[0][0] - sim.PositionAt(0, 0.1)).norm(), 1e-12);
  ASSERT_LT(a.end_time, 10.0);
  EXPECT_EQ(a.positions.back()[1], sim.final_balls()[1].r);
  // The object ball was struck: it moved.
  EXPECT_GT((a.positions.back()[1] - cue.balls[1]).norm(), 0.05);
}

TEST(PredictShotTest, APocketedBallStaysWhereItDropped) {
  const physics::TableModel& table = physics::DefaultTable();
  const physics::Pocket& p = table.pocket(physics::PocketId::kTopLeft);
  TrackedShot s;
  s.balls = {Vec2(p.mouth_centre - 0.5 * p.axis)};
  s.strike = physics::Shot{2.0, std::atan2(p.axis.y(), p.axis.x()), 2.0 / kR, 0, 0};
  for (int k = 1; k <= 20; ++k) s.sightings.push_back({0.1 * k, {}});
  const ShotPrediction pr = PredictShot(s, physics::Model{});
  ASSERT_EQ(pr.error, "");
  ASSERT_TRUE(std::isfinite(pr.pocketed_at[0]));
  EXPECT_LT(pr.pocketed_at[0], 0.5);
  EXPECT_EQ(pr.positions[10][0], pr.positions[19][0]);
}

TEST(PredictShotTest, ARefusedStrikeIsAnError) {
  TrackedShot s = TwoBallShot();
  std::get<physics::CueStrike>(s.strike).side = 0.7;  // beyond the miscue limit 0.51
  std::get<physics::CueStrike>(s.strike).height = 0;
  const std::string error = PredictShot(s, physics::Model{}).error;
  // It names the tip's offset and the limit it is beyond.
  std::ostringstream limit;
  limit << "beyond the cue's limit of " << physics::MiscueLimit(physics::Model{}.cue) << " R";
  EXPECT_NE(error.find("strike refused: miscue (the tip 0.7 R from"), std::string::npos) << error;
  EXPECT_NE(error.find(limit.str()), std::string::npos) << error;
  EXPECT_LT(physics::MiscueLimit(physics::Model{}.cue), 0.7);
}

}  // namespace
}  // namespace snooker::calibration
