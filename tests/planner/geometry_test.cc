// Tests of the pot geometry (planner/geometry.h): cut and heading are inverses, the
// ghost-ball construction is what the simulator does when there is no friction at
// the contact (no throw), path clearance and the cue's room.
#include "planner/geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "physics/core/shot.h"
#include "physics/sim/simulate.h"
#include "planner/random.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

constexpr double kR = 0.02625;
// Angles equal up to the rounding of an asin/atan2 round trip at thin cuts. rad.
constexpr double kAngleTolerance = 1e-9;

TEST(GeometryTest, WrapAngleStaysInHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(WrapAngle(3 * physics::kPi), physics::kPi);
  EXPECT_DOUBLE_EQ(WrapAngle(-physics::kPi), physics::kPi);
  EXPECT_NEAR(WrapAngle(2 * physics::kPi + 0.1), 0.1, 1e-15);
  EXPECT_NEAR(WrapAngle(-0.1), -0.1, 1e-15);
}

TEST(GeometryTest, HeadingForCutAndAimAlongAreInverses) {
  Rng rng(11);
  for (int k = 0; k < 500; ++k) {
    const Vec2 cue(rng.Uniform(0.1, 1.7), rng.Uniform(0.1, 3.4));
    const double a = rng.Uniform(0, 2 * physics::kPi);
    const Vec2 object = cue + rng.Uniform(0.06, 2.0) * Vec2(std::cos(a), std::sin(a));
    const double cut = rng.Uniform(-1.5, 1.5);
    const auto h = HeadingForCut(cue, object, cut, kR);
    ASSERT_TRUE(h);
    const auto aim = AimAlong(cue, object, *h + cut, kR);
    ASSERT_TRUE(aim) << k;
    EXPECT_NEAR(aim->cut, cut, kAngleTolerance) << k;
    EXPECT_NEAR(WrapAngle(aim->heading - *h), 0, kAngleTolerance) << k;
    // The ghost ball is on the heading's line, 2R from the object ball.
    EXPECT_NEAR((aim->ghost - object).norm(), 2 * kR, 1e-12);
    EXPECT_NEAR(Cross(Vec2(std::cos(*h), std::sin(*h)), aim->ghost - cue), 0, 1e-9);
  }
}

TEST(GeometryTest, NoCutAtNinetyDegreesOrWithTouchingBalls) {
  EXPECT_FALSE(HeadingForCut(Vec2(0, 0), Vec2(0, 1), physics::kPi / 2, kR));
  EXPECT_FALSE(HeadingForCut(Vec2(0, 0), Vec2(0, kR), 0.1, kR));
  EXPECT_FALSE(AimAlong(Vec2(0, 0), Vec2(0, 1), -physics::kPi / 2, kR));  // behind
}

// Without friction at the contact the object ball leaves along the line of centres:
// the simulator must send it along heading + cut.
TEST(GeometryTest, FrictionlessContactSendsTheObjectBallAlongTheCut) {
  physics::SimParams params;
  params.ball_ball.mu_bb = 0;
  physics::Simulator sim(physics::DefaultTable(), params);
  const Vec2 cue(0.6, 0.8), object(0.9, 1.6);
  for (const double cut_deg : {-60.0, -30.0, -5.0, 0.0, 12.0, 45.0, 70.0}) {
    const double cut = physics::DegToRad(cut_deg);
    const auto h = HeadingForCut(cue, object, cut, kR);
    ASSERT_TRUE(h);
    physics::Shot shot{1.0, *h, 1.0 / kR, 0};
    const std::vector<physics::BallState> balls = {physics::StruckBall(shot, cue),
                                                   physics::BallState{object}};
    physics::RunOptions run;
    run.record_events = true;
    ASSERT_EQ(sim.Start(balls, run), physics::SimStatus::kRunning);
    physics::SimStatus status = physics::SimStatus::kRunning;
    while (status == physics::SimStatus::kRunning && sim.last_event().kind != physics::EventKind::kBallBall) {
      status = sim.Step();
    }
    ASSERT_EQ(sim.last_event().kind, physics::EventKind::kBallBall) << cut_deg;
    const physics::BallState o = sim.path(1).back().state;
    const double dir = Direction(Vec2(o.v.x(), o.v.y()));
    EXPECT_NEAR(WrapAngle(dir - (*h + cut)), 0, 1e-6) << cut_deg;
  }
}

TEST(GeometryTest, PathMarginSeesBallsNearTheSegment) {
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(0.5, 0.5)}, {BallKind::kRed, Vec2(0.5, 1.5)},
             {BallKind::kRed, Vec2(0.5 + 2 * kR + 0.001, 1.0)}};
  // From the cue ball to the object ball, the third ball's centre is 2R + 1 mm off.
  EXPECT_NEAR(PathMargin(Vec2(0.5, 0.5), Vec2(0.5, 1.5), 2 * kR, t, 0, 1), 0.001, 1e-12);
  t.balls[2].position.x() = 0.5 + 2 * kR - 0.001;
  EXPECT_LT(PathMargin(Vec2(0.5, 0.5), Vec2(0.5, 1.5), 2 * kR, t, 0, 1), 0);
  // Beyond the segment's end the distance is to the end point.
  EXPECT_NEAR(PathMargin(Vec2(0.5, 0.5), Vec2(0.5, 0.9), 0, t, 0, 1), (t.balls[2].position - Vec2(0.5, 0.9)).norm(), 1e-12);
}

TEST(GeometryTest, TheCueNeedsRoomBehindTheCueBall) {
  const physics::TableModel& table = physics::DefaultTable();
  const double c = table.cushion_contact_distance();
  CueClearance level;
  level.max_elevation = 0;
  TableState t;
  // Frozen to the left cushion: along the cushion is fine, away from it is not.
  t.balls = {{BallKind::kCue, Vec2(c, 1.0)}};
  EXPECT_GT(CueMargin(t, 0, physics::kPi / 2, level, table), 0);
  EXPECT_LT(CueMargin(t, 0, 0.0, level, table), 0);
  // A ball right behind the cue ball blocks the stroke; one beside it does not.
  t.balls = {{BallKind::kCue, Vec2(0.8, 1.0)}, {BallKind::kRed, Vec2(0.8, 1.0 - 2 * kR - 0.01)}};
  EXPECT_LT(CueMargin(t, 0, physics::kPi / 2, level, table), 0);
  EXPECT_GT(CueMargin(t, 0, 0.0, level, table), 0);
}

// A raised cue passes over a cushion or a ball behind the cue ball: the lowest
// elevation that clears is found, a lower one does not clear, and a level stroke
// keeps its level margin.
TEST(GeometryTest, ARaisedCuePassesOverWhatBlocksALevelOne) {
  const physics::TableModel& table = physics::DefaultTable();
  const double c = table.cushion_contact_distance();
  const CueClearance cue;
  struct Case {
    const char* what;
    std::vector<Ball> balls;
    double heading;
  };
  const std::vector<Case> cases = {
      {"frozen to the left cushion, away from it", {{BallKind::kCue, Vec2(c, 1.0)}}, 0.0},
      {"2 cm off the baulk cushion, away from it", {{BallKind::kCue, Vec2(0.9, c + 0.02)}}, physics::kPi / 2},
      {"a red 1 cm behind", {{BallKind::kCue, Vec2(0.8, 1.0)}, {BallKind::kRed, Vec2(0.8, 1.0 - 2 * kR - 0.01)}},
       physics::kPi / 2},
  };
  for (const Case& k : cases) {
    TableState t;
    t.balls = k.balls;
    EXPECT_LT(CueMarginAt(t, 0, k.heading, 0.0, 0.0, cue, table), 0) << k.what;
    const auto e = CueElevation(t, 0, k.heading, kMaxTipOffset, cue, table);
    ASSERT_TRUE(e.has_value()) << k.what;
    EXPECT_GT(*e, 0) << k.what;
    EXPECT_LE(*e, cue.max_elevation) << k.what;
    EXPECT_GE(CueMarginAt(t, 0, k.heading, *e, kMaxTipOffset, cue, table), 0) << k.what;
    EXPECT_LT(CueMarginAt(t, 0, k.heading, *e - physics::DegToRad(1), kMaxTipOffset, cue, table), 0) << k.what;
    EXPECT_GE(CueMargin(t, 0, k.heading, cue, table), 0) << k.what;
  }
  // A higher cushion top needs a steeper cue.
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(c, 1.0)}};
  CueClearance high = cue;
  high.cushion_top += 0.004;
  EXPECT_GT(CueElevation(t, 0, 0.0, kMaxTipOffset, high, table).value_or(10),
            *CueElevation(t, 0, 0.0, kMaxTipOffset, cue, table));
  // Level where level clears: the margin is the level one.
  EXPECT_EQ(CueMargin(t, 0, physics::kPi / 2, cue, table), CueMarginAt(t, 0, physics::kPi / 2, 0, 0, cue, table));
}

}  // namespace
}  // namespace snooker::planner
