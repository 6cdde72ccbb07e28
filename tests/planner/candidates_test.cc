// Tests of candidate enumeration and pruning (planner/candidates.h): each reason to
// prune, and only balls on are candidates.
#include "planner/candidates.h"

#include <gtest/gtest.h>

#include "planner/planner.h"

namespace snooker::planner {
namespace {

using physics::PocketId;
using physics::Vec2;

constexpr double kR = 0.02625;

class CandidatesTest : public testing::Test {
 protected:
  PotContext Context() {
    PlanRequest req;
    return Planner::Default().ContextFor(req);
  }
  const physics::Pocket& TopRight() { return physics::DefaultTable().pocket(PocketId::kTopRight); }
};

TEST_F(CandidatesTest, OnlyBallsOnAreCandidates) {
  TableState t;
  const Vec2 red = TopRight().mouth_centre - 0.5 * TopRight().axis;
  t.balls = {{BallKind::kCue, red - 0.5 * TopRight().axis}, {BallKind::kRed, red},
             {BallKind::kBlack, physics::DefaultTable().spot(physics::Colour::kBlack)}};
  const CandidateSet reds = EnumerateCandidates(t, BallOn::kRed, Context());
  EXPECT_EQ(reds.pairs, physics::kPocketCount);
  ASSERT_FALSE(reds.candidates.empty());
  for (const Candidate& c : reds.candidates) EXPECT_EQ(c.object, 1);
  // The straight pot is the most likely.
  EXPECT_EQ(reds.candidates.front().pocket, PocketId::kTopRight);
  EXPECT_GT(reds.candidates.front().estimate.probability, 0.95);
  const CandidateSet colours = EnumerateCandidates(t, BallOn::kAnyColour, Context());
  for (const Candidate& c : colours.candidates) EXPECT_EQ(c.object, 2);
}

TEST_F(CandidatesTest, EachPruneReason) {
  const physics::Pocket& p = TopRight();
  const Vec2 red = p.mouth_centre - 0.6 * p.axis;
  const Vec2 cue = red - 0.6 * p.axis;
  TableState t;
  t.balls = {{BallKind::kCue, cue}, {BallKind::kRed, red}};
  PruneReason why;
  ASSERT_TRUE(AssessPot(t, 0, 1, PocketId::kTopRight, Context(), &why));
  EXPECT_EQ(why, PruneReason::kNone);
  // A ball between cue ball and object ball.
  t.balls.push_back({BallKind::kRed, 0.5 * (cue + red)});
  EXPECT_FALSE(AssessPot(t, 0, 1, PocketId::kTopRight, Context(), &why));
  EXPECT_EQ(why, PruneReason::kCueBallPath);
  // A ball between the object ball and the pocket.
  t.balls[2].position = red + 0.3 * p.axis;
  EXPECT_FALSE(AssessPot(t, 0, 1, PocketId::kTopRight, Context(), &why));
  EXPECT_EQ(why, PruneReason::kObjectBallPath);
  // A ball right behind the cue ball: no room for a level cue; a raised one clears it.
  t.balls[2].position = cue - (2 * kR + 0.01) * p.axis;
  PotContext level = Context();
  level.cue.max_elevation = 0;
  EXPECT_FALSE(AssessPot(t, 0, 1, PocketId::kTopRight, level, &why));
  EXPECT_EQ(why, PruneReason::kCueRoom);
  EXPECT_TRUE(AssessPot(t, 0, 1, PocketId::kTopRight, Context(), &why));
  t.balls.pop_back();
  // An 85 deg cut (the cue ball comes almost square across the pocket's line).
  const Vec2 side(-p.axis.y(), p.axis.x());
  const double a = physics::DegToRad(85);
  t.balls[0].position = red - 2 * kR * p.axis - 0.5 * (std::cos(a) * p.axis + std::sin(a) * side);
  EXPECT_FALSE(AssessPot(t, 0, 1, PocketId::kTopRight, Context(), &why));
  EXPECT_EQ(why, PruneReason::kCutTooThin);
}

TEST_F(CandidatesTest, MiddlePocketFromAlongItsCushionIsClosed) {
  const physics::TableModel& table = physics::DefaultTable();
  const double c = table.cushion_contact_distance();
  TableState t;  // a red on the left cushion, the cue ball behind it along the cushion
  t.balls = {{BallKind::kCue, Vec2(c + 0.01, 0.8)}, {BallKind::kRed, Vec2(c + 0.01, 1.2)}};
  PruneReason why;
  EXPECT_FALSE(AssessPot(t, 0, 1, PocketId::kMiddleLeft, Context(), &why));
  EXPECT_EQ(why, PruneReason::kPocketAngle);
}

}  // namespace
}  // namespace snooker::planner
