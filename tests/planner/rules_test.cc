// Tests of snooker's rules (planner/rules.h): values, the ball on, fouls, their
// penalties and the score of a shot, the touching ball, and every re-spotting case
// of WPBSA rule 3.4.
#include "planner/rules.h"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

namespace snooker::planner {
namespace {

using physics::Colour;
using physics::Vec2;

const physics::TableModel& Table() { return physics::DefaultTable(); }
Vec2 Spot(BallKind k) { return Table().spot(ColourOf(k)); }
double R() { return Table().ball_radius(); }

TEST(RulesTest, ValuesFollowTheRules) {
  EXPECT_EQ(Value(BallKind::kRed), 1);
  EXPECT_EQ(Value(BallKind::kYellow), 2);
  EXPECT_EQ(Value(BallKind::kGreen), 3);
  EXPECT_EQ(Value(BallKind::kBrown), 4);
  EXPECT_EQ(Value(BallKind::kBlue), 5);
  EXPECT_EQ(Value(BallKind::kPink), 6);
  EXPECT_EQ(Value(BallKind::kBlack), 7);
  EXPECT_EQ(Value(BallKind::kCue), 0);
  for (int c = 0; c < physics::kColourCount; ++c) {
    EXPECT_EQ(ColourOf(KindOf(static_cast<Colour>(c))), static_cast<Colour>(c));
  }
}

TEST(RulesTest, LegalTargets) {
  EXPECT_TRUE(IsLegalTarget(BallOn::kRed, BallKind::kRed));
  EXPECT_FALSE(IsLegalTarget(BallOn::kRed, BallKind::kBlack));
  EXPECT_FALSE(IsLegalTarget(BallOn::kRed, BallKind::kCue));
  EXPECT_TRUE(IsLegalTarget(BallOn::kAnyColour, BallKind::kYellow));
  EXPECT_TRUE(IsLegalTarget(BallOn::kAnyColour, BallKind::kBlack));
  EXPECT_FALSE(IsLegalTarget(BallOn::kAnyColour, BallKind::kRed));
  EXPECT_TRUE(IsLegalTarget(BallOn::kGreen, BallKind::kGreen));
  EXPECT_FALSE(IsLegalTarget(BallOn::kGreen, BallKind::kBrown));
}

TEST(RulesTest, OpeningBallOnIsARedThenTheLowestColour) {
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(0.5, 0.5)}, {BallKind::kRed, Vec2(0.5, 2)},
             {BallKind::kBlue, Spot(BallKind::kBlue)}, {BallKind::kPink, Spot(BallKind::kPink)}};
  EXPECT_EQ(OpeningBallOn(t), BallOn::kRed);
  t.balls.erase(t.balls.begin() + 1);
  EXPECT_EQ(OpeningBallOn(t), BallOn::kBlue);
  t.balls.resize(1);
  EXPECT_EQ(OpeningBallOn(t), std::nullopt);
}

TEST(RulesTest, NextBallOnAlternatesRedsAndColoursThenTheSequence) {
  TableState reds_left;
  reds_left.balls = {{BallKind::kCue, Vec2(0.5, 0.5)}, {BallKind::kRed, Vec2(0.5, 2)},
                     {BallKind::kYellow, Spot(BallKind::kYellow)}};
  EXPECT_EQ(NextBallOn(BallOn::kRed, BallKind::kRed, reds_left), BallOn::kAnyColour);
  EXPECT_EQ(NextBallOn(BallOn::kAnyColour, BallKind::kYellow, reds_left), BallOn::kRed);
  TableState colours;  // the last red has gone; the colour after it was re-spotted
  colours.balls = {{BallKind::kCue, Vec2(0.5, 0.5)}, {BallKind::kYellow, Spot(BallKind::kYellow)},
                   {BallKind::kBlack, Spot(BallKind::kBlack)}};
  EXPECT_EQ(NextBallOn(BallOn::kAnyColour, BallKind::kBlack, colours), BallOn::kYellow);
  colours.balls.erase(colours.balls.begin() + 1);
  EXPECT_EQ(NextBallOn(BallOn::kYellow, BallKind::kYellow, colours), BallOn::kBlack);
  colours.balls.resize(1);
  EXPECT_EQ(NextBallOn(BallOn::kBlack, BallKind::kBlack, colours), std::nullopt);
}

class JudgeTest : public testing::Test {
 protected:
  // 0 cue, 1 red, 2 red, 3 yellow, 4 black.
  TableState t_{{{BallKind::kCue, Vec2(0.5, 0.5)},
                 {BallKind::kRed, Vec2(0.5, 2.0)},
                 {BallKind::kRed, Vec2(0.7, 2.0)},
                 {BallKind::kYellow, Spot(BallKind::kYellow)},
                 {BallKind::kBlack, Spot(BallKind::kBlack)}}};
};

TEST_F(JudgeTest, PottingTheBallOnScores) {
  const std::vector<int> potted = {1};
  const ShotJudgement j = JudgeShot(t_, BallOn::kRed, std::nullopt, 1, potted);
  EXPECT_EQ(j.foul, Foul::kNone);
  EXPECT_EQ(j.points, 1);
  EXPECT_EQ(j.legal_pots, 1);
  EXPECT_EQ(j.potted_kind, BallKind::kRed);
}

TEST_F(JudgeTest, TwoRedsInOneShotBothScore) {
  const std::vector<int> potted = {1, 2};
  const ShotJudgement j = JudgeShot(t_, BallOn::kRed, std::nullopt, 2, potted);
  EXPECT_EQ(j.foul, Foul::kNone);
  EXPECT_EQ(j.points, 2);
}

TEST_F(JudgeTest, NoPotIsNoFoulAndNoPoints) {
  const ShotJudgement j = JudgeShot(t_, BallOn::kRed, std::nullopt, 1, {});
  EXPECT_EQ(j.foul, Foul::kNone);
  EXPECT_EQ(j.legal_pots, 0);
  EXPECT_EQ(j.points, 0);
}

TEST_F(JudgeTest, EachFoul) {
  EXPECT_EQ(JudgeShot(t_, BallOn::kRed, std::nullopt, -1, {}).foul, Foul::kNoBallHit);
  EXPECT_EQ(JudgeShot(t_, BallOn::kRed, std::nullopt, 4, {}).foul, Foul::kWrongBallFirst);
  const std::vector<int> in_off = {1, 0};
  EXPECT_EQ(JudgeShot(t_, BallOn::kRed, std::nullopt, 1, in_off).foul, Foul::kCuePotted);
  const std::vector<int> black = {1, 4};
  const ShotJudgement j = JudgeShot(t_, BallOn::kRed, std::nullopt, 1, black);
  EXPECT_EQ(j.foul, Foul::kWrongBallPotted);
  EXPECT_EQ(j.points, 0);
}

TEST_F(JudgeTest, TheNominatedColourIsTheBallOn) {
  const std::vector<int> black = {4};
  EXPECT_EQ(JudgeShot(t_, BallOn::kAnyColour, BallKind::kBlack, 4, black).points, 7);
  // Nominating the yellow and hitting the black first is a foul...
  EXPECT_EQ(JudgeShot(t_, BallOn::kAnyColour, BallKind::kYellow, 4, black).foul,
            Foul::kWrongBallFirst);
  // ... and so is potting another colour than the nominated one.
  const std::vector<int> both = {3, 4};
  EXPECT_EQ(JudgeShot(t_, BallOn::kAnyColour, BallKind::kYellow, 3, both).foul,
            Foul::kWrongBallPotted);
  // A red is never on after a red.
  EXPECT_EQ(JudgeShot(t_, BallOn::kAnyColour, BallKind::kYellow, 1, {}).foul,
            Foul::kWrongBallFirst);
}

TEST_F(JudgeTest, AFairShotHasNoPenalty) {
  const std::vector<int> potted = {1};
  EXPECT_EQ(JudgeShot(t_, BallOn::kRed, std::nullopt, 1, potted).penalty, 0);
  EXPECT_EQ(JudgeShot(t_, BallOn::kRed, std::nullopt, 1, {}).penalty, 0);
}

// A foul's value: 4, or the ball on, the ball hit first or a ball potted, whichever
// is highest. One case per value from 4 to 7 and per source of the value.
struct PenaltyCase {
  const char* name;
  BallOn on;
  std::optional<BallKind> nominated;
  int first_hit;  // index into JudgeTest's table: 0 cue, 1-2 red, 3 yellow, 4 black
  std::vector<int> potted;
  Foul foul;
  int penalty;
};

// gtest prints a parameter with this (not as bytes).
void PrintTo(const PenaltyCase& c, std::ostream* os) { *os << c.name; }

class PenaltyTest : public JudgeTest, public testing::WithParamInterface<PenaltyCase> {};

TEST_P(PenaltyTest, TheFoulIsWorthTheHighestValueInvolved) {
  const PenaltyCase& c = GetParam();
  const ShotJudgement j = JudgeShot(t_, c.on, c.nominated, c.first_hit, c.potted);
  EXPECT_EQ(j.foul, c.foul);
  EXPECT_EQ(j.penalty, c.penalty);
  EXPECT_EQ(j.points, 0);
  EXPECT_EQ(FoulPenalty(t_, c.on, c.nominated, c.first_hit, c.potted), c.penalty);
}

INSTANTIATE_TEST_SUITE_P(
    Values, PenaltyTest,
    testing::Values(
        PenaltyCase{"NoBallHitOnARedIs4", BallOn::kRed, std::nullopt, -1, {}, Foul::kNoBallHit, 4},
        PenaltyCase{"YellowFirstOnARedIs4", BallOn::kRed, std::nullopt, 3, {}, Foul::kWrongBallFirst, 4},
        PenaltyCase{"InOffOffARedIs4", BallOn::kRed, std::nullopt, 1, {1, 0}, Foul::kCuePotted, 4},
        PenaltyCase{"BlackFirstOnARedIs7", BallOn::kRed, std::nullopt, 4, {}, Foul::kWrongBallFirst, 7},
        PenaltyCase{"BlackPottedOffARedIs7", BallOn::kRed, std::nullopt, 1, {4}, Foul::kWrongBallPotted, 7},
        PenaltyCase{"NominatedBlackMissedIs7", BallOn::kAnyColour, BallKind::kBlack, -1, {}, Foul::kNoBallHit, 7},
        PenaltyCase{"NominatedYellowHittingBlackIs7", BallOn::kAnyColour, BallKind::kYellow, 4, {},
                    Foul::kWrongBallFirst, 7},
        PenaltyCase{"BlackOnMissedIs7", BallOn::kBlack, std::nullopt, -1, {}, Foul::kNoBallHit, 7},
        PenaltyCase{"BlueOnMissedIs5", BallOn::kBlue, std::nullopt, -1, {}, Foul::kNoBallHit, 5},
        PenaltyCase{"PinkOnRedHitIs6", BallOn::kPink, std::nullopt, 1, {}, Foul::kWrongBallFirst, 6},
        PenaltyCase{"YellowOnInOffIs4", BallOn::kYellow, std::nullopt, 3, {3, 0}, Foul::kCuePotted, 4}),
    [](const testing::TestParamInfo<PenaltyCase>& param) { return std::string(param.param.name); });

TEST(TouchingTest, BallsWithinTheTouchingGapTouchTheCueBall) {
  // 0 cue; 1 red just touching; 2 red half kTouchingGap away (touching); 3 black
  // twice kTouchingGap away (not); 4 yellow far off.
  const Vec2 cue(0.8, 1.5);
  TableState t;
  t.balls = {{BallKind::kCue, cue},
             {BallKind::kRed, cue + Vec2(2 * R(), 0)},
             {BallKind::kRed, cue + Vec2(0, 2 * R() + 0.5 * kTouchingGap)},
             {BallKind::kBlack, cue + Vec2(0, -(2 * R() + 2 * kTouchingGap))},
             {BallKind::kYellow, Spot(BallKind::kYellow)}};
  EXPECT_EQ(TouchingCueBall(t, Table()), (std::vector<int>{1, 2}));
  t.balls.erase(t.balls.begin());
  EXPECT_TRUE(TouchingCueBall(t, Table()).empty());  // no cue ball
}

TEST_F(JudgeTest, PlayingAwayFromATouchingBallOnIsFair) {
  const std::vector<int> red = {1};
  // Touching a red with a red on: hitting nothing, or the black, is no foul.
  EXPECT_EQ(JudgeShot(t_, BallOn::kRed, std::nullopt, -1, {}, red).foul, Foul::kNone);
  const ShotJudgement black_first = JudgeShot(t_, BallOn::kRed, std::nullopt, 4, {}, red);
  EXPECT_EQ(black_first.foul, Foul::kNone);
  EXPECT_EQ(black_first.penalty, 0);
  // Without the touching ball the same strokes foul.
  EXPECT_EQ(JudgeShot(t_, BallOn::kRed, std::nullopt, -1, {}).foul, Foul::kNoBallHit);
  EXPECT_EQ(JudgeShot(t_, BallOn::kRed, std::nullopt, 4, {}).foul, Foul::kWrongBallFirst);
  // Potting a ball not on is still a foul, and so is an in-off.
  const std::vector<int> black = {4};
  const ShotJudgement potted_black = JudgeShot(t_, BallOn::kRed, std::nullopt, -1, black, red);
  EXPECT_EQ(potted_black.foul, Foul::kWrongBallPotted);
  EXPECT_EQ(potted_black.penalty, 7);
  const std::vector<int> in_off = {0};
  EXPECT_EQ(JudgeShot(t_, BallOn::kRed, std::nullopt, -1, in_off, red).foul, Foul::kCuePotted);
  // A red potted after playing away scores.
  const std::vector<int> other_red = {2};
  EXPECT_EQ(JudgeShot(t_, BallOn::kRed, std::nullopt, 2, other_red, red).points, 1);
}

TEST_F(JudgeTest, ATouchingBallNotOnChangesNothing) {
  const std::vector<int> black = {4};
  EXPECT_EQ(JudgeShot(t_, BallOn::kRed, std::nullopt, -1, {}, black).foul, Foul::kNoBallHit);
  EXPECT_EQ(JudgeShot(t_, BallOn::kRed, std::nullopt, 3, {}, black).foul, Foul::kWrongBallFirst);
  EXPECT_EQ(JudgeShot(t_, BallOn::kRed, std::nullopt, 1, {}, black).foul, Foul::kNone);
  // With a colour on, the touching colour counts only when it is the nominated one.
  const std::vector<int> yellow = {3};
  EXPECT_EQ(JudgeShot(t_, BallOn::kAnyColour, BallKind::kBlack, -1, {}, yellow).foul, Foul::kNoBallHit);
  EXPECT_EQ(JudgeShot(t_, BallOn::kAnyColour, BallKind::kYellow, -1, {}, yellow).foul, Foul::kNone);
}

// Re-spotting (WPBSA 3.4), one test per case.

TEST(RespotTest, OwnSpotWhenFree) {
  const std::vector<Vec2> others = {Vec2(0.3, 0.3)};
  const auto p = RespotPosition(BallKind::kPink, others, Table());
  ASSERT_TRUE(p);
  EXPECT_EQ(*p, Spot(BallKind::kPink));
}

TEST(RespotTest, OccupiedOwnSpotGoesToTheHighestFreeSpot) {
  // A ball touching the green's spot, and the black's spot taken: the green goes to
  // the pink's spot (the highest free).
  const std::vector<Vec2> others = {Spot(BallKind::kGreen) + Vec2(2 * R(), 0), Spot(BallKind::kBlack)};
  const auto p = RespotPosition(BallKind::kGreen, others, Table());
  ASSERT_TRUE(p);
  EXPECT_EQ(*p, Spot(BallKind::kPink));
}

TEST(RespotTest, ABallExactlyTouchingTheSpotOccupiesIt) {
  const std::vector<Vec2> others = {Spot(BallKind::kBlue) + Vec2(0, 2 * R())};
  const auto p = RespotPosition(BallKind::kBlue, others, Table());
  ASSERT_TRUE(p);
  EXPECT_EQ(*p, Spot(BallKind::kBlack));
}

// Every spot covered: as near the own spot as possible towards the top cushion.
std::vector<Vec2> AllSpotsCovered() {
  std::vector<Vec2> others;
  for (int c = 0; c < physics::kColourCount; ++c) others.push_back(Table().spot(static_cast<Colour>(c)));
  return others;
}

TEST(RespotTest, AllSpotsTakenGoesTowardsTheTopCushion) {
  const std::vector<Vec2> others = AllSpotsCovered();
  const auto p = RespotPosition(BallKind::kBrown, others, Table());
  ASSERT_TRUE(p);
  const Vec2 spot = Spot(BallKind::kBrown);
  EXPECT_DOUBLE_EQ(p->x(), spot.x());
  // Just clear of the ball on the brown spot, above it.
  EXPECT_NEAR(p->y() - spot.y(), 2 * R(), 1e-5);
  for (const Vec2& o : others) EXPECT_GE((*p - o).norm(), 2 * R());
}

TEST(RespotTest, PastABallInTheWayOnTheLine) {
  // The yellow's spot is covered and a red lies just above it, off the line by R:
  // the yellow goes above the red's interval.
  std::vector<Vec2> others = AllSpotsCovered();
  const Vec2 spot = Spot(BallKind::kYellow);
  const Vec2 red = spot + Vec2(R(), 2.5 * R());
  others.push_back(red);
  const auto p = RespotPosition(BallKind::kYellow, others, Table());
  ASSERT_TRUE(p);
  EXPECT_DOUBLE_EQ(p->x(), spot.x());
  EXPECT_NEAR(p->y(), red.y() + std::sqrt(4 * R() * R() - R() * R()), 1e-5);
  for (const Vec2& o : others) EXPECT_GE((*p - o).norm(), 2 * R());
}

TEST(RespotTest, BlackWithTheWayToTheTopBlockedGoesBelowItsSpot) {
  // The black's spot and the line above it up to the top cushion are covered.
  std::vector<Vec2> others = AllSpotsCovered();
  const Vec2 spot = Spot(BallKind::kBlack);
  const double top = Table().spec().length - Table().cushion_contact_distance();
  for (double y = spot.y() + 2 * R(); y < top + 2 * R(); y += 2 * R()) others.push_back(Vec2(spot.x(), y));
  const auto p = RespotPosition(BallKind::kBlack, others, Table());
  ASSERT_TRUE(p);
  EXPECT_DOUBLE_EQ(p->x(), spot.x());
  EXPECT_LT(p->y(), spot.y());
  EXPECT_NEAR(spot.y() - p->y(), 2 * R(), 1e-5);
}

TEST(ApplyShotTest, ColoursComeBackWhileRedsRemainHighestFirst) {
  // The black and the pink potted together (a foul) while reds remain; a red sits
  // on the black's spot, the blue and the brown on theirs. The black goes back
  // first (the higher value): its spot is taken, so the highest free spot, the
  // pink's. Then the pink: its own spot now holds the black, so the highest free
  // one: the black's, blue's and brown's are taken, the green's is free.
  TableState before;
  before.balls = {{BallKind::kCue, Vec2(0.5, 0.5)},
                  {BallKind::kRed, Spot(BallKind::kBlack)},
                  {BallKind::kPink, Vec2(0.2, 3.0)},
                  {BallKind::kBlack, Vec2(0.3, 3.3)},
                  {BallKind::kBlue, Spot(BallKind::kBlue)},
                  {BallKind::kBrown, Spot(BallKind::kBrown)}};
  std::vector<Vec2> finals;
  for (const Ball& b : before.balls) finals.push_back(b.position);
  const std::vector<int> potted = {2, 3};
  std::vector<int> origin;
  const TableState after = ApplyShot(before, BallOn::kRed, finals, potted, true, Table(), &origin);
  ASSERT_EQ(after.balls.size(), 6u);
  // Black first (higher value): its spot is taken by the red, the pink's is free.
  EXPECT_EQ(after.balls[4].kind, BallKind::kBlack);
  EXPECT_EQ(after.balls[4].position, Spot(BallKind::kPink));
  EXPECT_EQ(origin[4], 3);
  // Then the pink: its own spot now holds the black; black's has the red; blue's and
  // brown's are taken: the green's is the highest free.
  EXPECT_EQ(after.balls[5].kind, BallKind::kPink);
  EXPECT_EQ(after.balls[5].position, Spot(BallKind::kGreen));
  EXPECT_EQ(origin[5], 2);
}

TEST(ApplyShotTest, RedsStayDownAndTheColourAfterTheLastRedComesBack) {
  TableState before;
  before.balls = {{BallKind::kCue, Vec2(0.5, 0.5)}, {BallKind::kBlue, Vec2(0.4, 2.5)},
                  {BallKind::kYellow, Spot(BallKind::kYellow)}};
  std::vector<Vec2> finals = {Vec2(0.6, 0.6), Vec2(0.0, 0.0), Spot(BallKind::kYellow)};
  const std::vector<int> potted = {1};
  // No reds left, but the blue was the colour after the last red (any colour on).
  const TableState after = ApplyShot(before, BallOn::kAnyColour, finals, potted, false, Table());
  ASSERT_EQ(after.balls.size(), 3u);
  EXPECT_EQ(after.balls[2].kind, BallKind::kBlue);
  EXPECT_EQ(after.balls[2].position, Spot(BallKind::kBlue));
  EXPECT_EQ(after.balls[0].position, Vec2(0.6, 0.6));  // the cue ball where it stopped
}

TEST(ApplyShotTest, InTheFinalSequenceTheBallOnStaysDown) {
  TableState before;
  before.balls = {{BallKind::kCue, Vec2(0.5, 0.5)}, {BallKind::kYellow, Vec2(0.4, 1.5)},
                  {BallKind::kGreen, Spot(BallKind::kGreen)}};
  std::vector<Vec2> finals;
  for (const Ball& b : before.balls) finals.push_back(b.position);
  const std::vector<int> potted = {1};
  const TableState fair = ApplyShot(before, BallOn::kYellow, finals, potted, false, Table());
  EXPECT_EQ(fair.Count(BallKind::kYellow), 0);
  // The same pot on a foul (say an in-off too) comes back.
  const TableState foul = ApplyShot(before, BallOn::kYellow, finals, potted, true, Table());
  EXPECT_EQ(foul.Count(BallKind::kYellow), 1);
  // And a colour not on, potted in the sequence, comes back.
  const std::vector<int> green = {2};
  const TableState wrong = ApplyShot(before, BallOn::kYellow, finals, green, true, Table());
  EXPECT_EQ(wrong.Count(BallKind::kGreen), 1);
}

}  // namespace
}  // namespace snooker::planner
