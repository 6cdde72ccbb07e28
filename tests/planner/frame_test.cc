// Tests of a frame by the rules (planner/frame.h): the standard start, each foul and
// what it gives the opponent, the touching ball, ball in hand after an in-off,
// re-spotting while reds remain and not in the final sequence, visits and breaks, the
// end of the frame, a tie going to the re-spotted black, and the shot cap.
#include "planner/frame.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace snooker::planner {
namespace {

using physics::Vec2;

const physics::TableModel& Table() { return physics::DefaultTable(); }
Vec2 Spot(BallKind k) { return Table().spot(ColourOf(k)); }
double R() { return Table().ball_radius(); }

// A frame in play on `balls` (the cue ball on the table), player 0 at the table.
FrameState Frame(std::vector<Ball> balls, BallOn on, std::array<int, 2> score = {0, 0}) {
  FrameState f;
  f.table.balls = std::move(balls);
  f.ball_on = on;
  f.cue_in_hand = false;
  f.score = score;
  return f;
}

// A stroke on the frame's stroke table in which nothing moves but what drops.
Stroke Played(const FrameState& f, int first_hit, std::vector<int> potted,
              std::optional<Vec2> cue_start = std::nullopt) {
  Stroke s;
  s.cue_start = cue_start;
  s.first_hit = first_hit;
  s.potted = std::move(potted);
  for (const Ball& b : StrokeTable(f, cue_start).balls) s.ends.push_back(b.position);
  return s;
}

// The cue ball, two reds, the yellow, the blue and the black (indices 0 to 5).
std::vector<Ball> MidFrame() {
  return {{BallKind::kCue, Vec2(0.6, 1.2)},         {BallKind::kRed, Vec2(0.5, 2.2)},
          {BallKind::kRed, Vec2(1.2, 2.6)},         {BallKind::kYellow, Spot(BallKind::kYellow)},
          {BallKind::kBlue, Spot(BallKind::kBlue)}, {BallKind::kBlack, Spot(BallKind::kBlack)}};
}

TEST(FrameTest, TheStandardStart) {
  const FrameState f = StartFrame(5, 1);
  EXPECT_EQ(f.table.reds(), 15);
  EXPECT_EQ(f.table.Count(BallKind::kCue), 0);
  for (int c = 0; c < physics::kColourCount; ++c) {
    const BallKind k = KindOf(static_cast<physics::Colour>(c));
    ASSERT_EQ(f.table.Count(k), 1);
    for (const Ball& b : f.table.balls) {
      if (b.kind == k) {
        EXPECT_EQ(b.position, Spot(k));
      }
    }
  }
  std::vector<physics::BallPlacement> placed;
  for (const Ball& b : f.table.balls) placed.push_back({"", b.position});
  EXPECT_EQ(Table().ValidatePlacement(placed), "");
  EXPECT_TRUE(f.cue_in_hand);
  EXPECT_EQ(f.ball_on, BallOn::kRed);
  EXPECT_EQ(f.striker, 1);
  EXPECT_EQ(f.score, (std::array<int, 2>{0, 0}));
  EXPECT_FALSE(f.over);
  EXPECT_EQ(f.max_shots, kFrameShotCap);
  EXPECT_THROW(StartFrame(5, 2), std::invalid_argument);
}

TEST(FrameTest, TheDIsTheHalfCircleOnTheBaulkLine) {
  const physics::TableSpec& s = Table().spec();
  const Vec2 centre(s.width / 2, s.baulk_line);
  EXPECT_TRUE(InTheD(centre, Table()));
  EXPECT_TRUE(InTheD(centre + Vec2(0, -s.d_radius), Table()));
  EXPECT_TRUE(InTheD(centre + Vec2(s.d_radius, 0), Table()));
  EXPECT_FALSE(InTheD(centre + Vec2(0, 0.01), Table()));                 // beyond the baulk line
  EXPECT_FALSE(InTheD(centre + Vec2(0, -s.d_radius - 0.001), Table()));  // outside the circle
  const FrameState f = StartFrame(1, 0);
  EXPECT_EQ(CuePlacementError(f.table, centre + Vec2(0, -0.1), Table()), "");
  // The brown sits on its spot, the D's centre.
  EXPECT_NE(CuePlacementError(f.table, centre, Table()).find("overlaps the brown"), std::string::npos);
  EXPECT_NE(CuePlacementError(f.table, Vec2(0.9, 1.5), Table()).find("not in the D"), std::string::npos);
}

TEST(FrameTest, PottingABallOnScoresAndTheVisitGoesOn) {
  FrameState f = Frame(MidFrame(), BallOn::kRed);
  StrokeResult r = ApplyStroke(f, Played(f, 1, {1}));
  EXPECT_EQ(r.judgement.foul, Foul::kNone);
  EXPECT_FALSE(r.visit_over);
  EXPECT_EQ(f.score, (std::array<int, 2>{1, 0}));
  EXPECT_EQ(f.striker, 0);
  EXPECT_EQ(f.ball_on, BallOn::kAnyColour);
  EXPECT_EQ(f.table.reds(), 1);  // reds stay down
  EXPECT_EQ(f.visit_points, 1);
  // The black after it: 7 more, re-spotted (reds remain), a red on again.
  const int black = 4;  // the red has gone: cue, red, yellow, blue, black
  ASSERT_EQ(f.table.balls[black].kind, BallKind::kBlack);
  Stroke s = Played(f, black, {black});
  s.nominated = BallKind::kBlack;
  s.ends[black] = Vec2(1.7, 3.5);  // where it dropped
  r = ApplyStroke(f, s);
  EXPECT_EQ(f.score, (std::array<int, 2>{8, 0}));
  EXPECT_EQ(f.ball_on, BallOn::kRed);
  EXPECT_EQ(f.table.Count(BallKind::kBlack), 1);
  for (const Ball& b : f.table.balls) {
    if (b.kind == BallKind::kBlack) {
      EXPECT_EQ(b.position, Spot(BallKind::kBlack));
    }
  }
  // A miss ends the visit: the break was 8, and the opponent plays a red.
  r = ApplyStroke(f, Played(f, 1, {}));
  EXPECT_TRUE(r.visit_over);
  EXPECT_EQ(r.break_points, 8);
  EXPECT_EQ(r.striker, 0);
  EXPECT_EQ(f.striker, 1);
  EXPECT_EQ(f.ball_on, BallOn::kRed);
  EXPECT_EQ(f.visit_points, 0);
  EXPECT_EQ(f.shots, 3);
}

// Each foul: the opponent scores the penalty and plays next, the striker nothing.
struct FoulCase {
  const char* name;
  BallOn on;
  int first_hit;  // MidFrame's indices
  std::vector<int> potted;
  Foul foul;
  int penalty;
};

// gtest prints a parameter with this (not as bytes).
void PrintTo(const FoulCase& c, std::ostream* os) { *os << c.name; }

class FrameFoulTest : public testing::TestWithParam<FoulCase> {};

TEST_P(FrameFoulTest, TheOpponentScoresThePenaltyAndPlays) {
  const FoulCase& c = GetParam();
  FrameState f = Frame(MidFrame(), c.on, {10, 20});
  const StrokeResult r = ApplyStroke(f, Played(f, c.first_hit, c.potted));
  EXPECT_EQ(r.judgement.foul, c.foul);
  EXPECT_EQ(r.judgement.penalty, c.penalty);
  EXPECT_TRUE(r.visit_over);
  EXPECT_EQ(f.score, (std::array<int, 2>{10, 20 + c.penalty}));
  EXPECT_EQ(f.striker, 1);
  EXPECT_FALSE(f.over);
  // Colours potted in a foul come back; reds do not.
  EXPECT_EQ(f.table.Count(BallKind::kBlack), 1);
  EXPECT_EQ(f.table.Count(BallKind::kBlue), 1);
}

INSTANTIATE_TEST_SUITE_P(
    Fouls, FrameFoulTest,
    testing::Values(FoulCase{"NoBallHit", BallOn::kRed, -1, {}, Foul::kNoBallHit, 4},
                    FoulCase{"WrongBallFirstYellow", BallOn::kRed, 3, {}, Foul::kWrongBallFirst, 4},
                    FoulCase{"WrongBallFirstBlue", BallOn::kRed, 4, {}, Foul::kWrongBallFirst, 5},
                    FoulCase{"WrongBallFirstBlack", BallOn::kRed, 5, {}, Foul::kWrongBallFirst, 7},
                    FoulCase{"InOff", BallOn::kRed, 1, {0}, Foul::kCuePotted, 4},
                    FoulCase{"RedAndInOff", BallOn::kRed, 1, {1, 0}, Foul::kCuePotted, 4},
                    FoulCase{"BallNotOnPottedBlue", BallOn::kRed, 1, {4}, Foul::kWrongBallPotted, 5},
                    FoulCase{"BallNotOnPottedBlack", BallOn::kRed, 1, {5}, Foul::kWrongBallPotted, 7},
                    FoulCase{"RedPottedOnAColour", BallOn::kAnyColour, 4, {1}, Foul::kWrongBallPotted, 5}),
    [](const testing::TestParamInfo<FoulCase>& param) { return std::string(param.param.name); });

TEST(FrameTest, AfterAnInOffTheOpponentHasTheBallInHand) {
  FrameState f = Frame(MidFrame(), BallOn::kRed);
  ApplyStroke(f, Played(f, 1, {0}));
  EXPECT_TRUE(f.cue_in_hand);
  EXPECT_EQ(f.table.Count(BallKind::kCue), 0);
  EXPECT_EQ(f.striker, 1);
  EXPECT_EQ(f.score, (std::array<int, 2>{0, 4}));
  // The next stroke must place the cue ball, in the D and on no ball.
  Stroke no_place = Played(f, 1, {});
  EXPECT_NE(StrokeError(f, no_place, Table()).find("needs its cue_start"), std::string::npos);
  EXPECT_THROW(ApplyStroke(f, no_place), std::invalid_argument);
  const Stroke outside = Played(f, 1, {}, Vec2(0.9, 1.5));
  EXPECT_NE(StrokeError(f, outside, Table()).find("not in the D"), std::string::npos);
  // Placed in the D (appended last: index 5), it hits a red and pots it.
  const Vec2 start(0.7, 0.6);
  const StrokeResult r = ApplyStroke(f, Played(f, 0, {0}, start));
  EXPECT_EQ(r.judgement.foul, Foul::kNone);
  EXPECT_EQ(f.score, (std::array<int, 2>{0, 5}));
  EXPECT_FALSE(f.cue_in_hand);
  ASSERT_EQ(f.table.cue_index(), 4);
  EXPECT_EQ(f.table.balls[4].position, start);
}

TEST(FrameTest, PlayingAwayFromATouchingRedIsNoFoul) {
  std::vector<Ball> balls = MidFrame();
  balls[1].position = balls[0].position + Vec2(0, 2 * R());
  FrameState f = Frame(balls, BallOn::kRed, {3, 3});
  Stroke s = Played(f, -1, {});
  s.touching = TouchingCueBall(StrokeTable(f, std::nullopt), Table());
  ASSERT_EQ(s.touching, (std::vector<int>{1}));
  const StrokeResult r = ApplyStroke(f, s);
  EXPECT_EQ(r.judgement.foul, Foul::kNone);
  EXPECT_EQ(f.score, (std::array<int, 2>{3, 3}));
  EXPECT_EQ(f.striker, 1);
  // The same stroke with the touching ball not declared is a foul.
  FrameState g = Frame(balls, BallOn::kRed, {3, 3});
  EXPECT_EQ(ApplyStroke(g, Played(g, -1, {})).judgement.foul, Foul::kNoBallHit);
  EXPECT_EQ(g.score, (std::array<int, 2>{3, 7}));
}

TEST(FrameTest, TheColourAfterTheLastRedComesBackThenTheColoursGoInOrder) {
  // The last red potted; the blue after it comes back and the yellow is on.
  std::vector<Ball> balls = MidFrame();
  balls.erase(balls.begin() + 2);  // cue, red, yellow, blue, black
  FrameState f = Frame(balls, BallOn::kRed);
  ApplyStroke(f, Played(f, 1, {1}));
  ASSERT_EQ(f.ball_on, BallOn::kAnyColour);
  Stroke blue = Played(f, 2, {2});  // cue, yellow, blue, black
  blue.nominated = BallKind::kBlue;
  ApplyStroke(f, blue);
  EXPECT_EQ(f.score[0], 6);
  EXPECT_EQ(f.table.Count(BallKind::kBlue), 1);
  EXPECT_EQ(f.ball_on, BallOn::kYellow);
  // In the sequence a fairly potted colour stays down and the next one is on.
  const StrokeResult r = ApplyStroke(f, Played(f, 1, {1}));
  EXPECT_EQ(r.judgement.points, 2);
  EXPECT_EQ(f.table.Count(BallKind::kYellow), 0);
  EXPECT_EQ(f.ball_on, BallOn::kBlue);
  EXPECT_EQ(f.score[0], 8);
  // The blue potted on a foul (the cue ball follows it in) comes back.
  const int blue_index = 2;  // cue, black, blue (re-spotted balls come last)
  ASSERT_EQ(f.table.balls[blue_index].kind, BallKind::kBlue);
  ApplyStroke(f, Played(f, blue_index, {blue_index, 0}));
  EXPECT_EQ(f.table.Count(BallKind::kBlue), 1);
  EXPECT_EQ(f.score, (std::array<int, 2>{8, 5}));
  EXPECT_TRUE(f.cue_in_hand);
}

TEST(FrameTest, WithoutANominationTheFirstColourHitIsTheBallOn) {
  FrameState f = Frame(MidFrame(), BallOn::kAnyColour);
  // Yellow first, the black potted: the yellow was on, so a foul worth 7.
  const StrokeResult r = ApplyStroke(f, Played(f, 3, {5}));
  EXPECT_EQ(r.judgement.foul, Foul::kWrongBallPotted);
  EXPECT_EQ(r.judgement.penalty, 7);
  EXPECT_EQ(f.score, (std::array<int, 2>{0, 7}));
}

// The black alone, the cue ball on the table.
std::vector<Ball> LastBlack() {
  return {{BallKind::kCue, Vec2(0.9, 2.5)}, {BallKind::kBlack, Spot(BallKind::kBlack)}};
}

TEST(FrameTest, PottingTheLastBlackEndsTheFrame) {
  FrameState f = Frame(LastBlack(), BallOn::kBlack, {40, 45});
  const StrokeResult r = ApplyStroke(f, Played(f, 1, {1}));
  EXPECT_TRUE(f.over);
  EXPECT_EQ(f.end, FrameEnd::kBlackPotted);
  EXPECT_EQ(f.score, (std::array<int, 2>{47, 45}));
  EXPECT_EQ(f.winner, 0);
  EXPECT_TRUE(r.visit_over);
  EXPECT_EQ(r.break_points, 7);
  EXPECT_FALSE(f.black_respotted);
  EXPECT_NE(StrokeError(f, Played(f, 1, {}), Table()).find("the frame is over"), std::string::npos);
}

TEST(FrameTest, AFoulOnTheLastBlackEndsTheFrame) {
  FrameState f = Frame(LastBlack(), BallOn::kBlack, {40, 45});
  ApplyStroke(f, Played(f, -1, {}));
  EXPECT_TRUE(f.over);
  EXPECT_EQ(f.end, FrameEnd::kBlackFouled);
  EXPECT_EQ(f.score, (std::array<int, 2>{40, 52}));
  EXPECT_EQ(f.winner, 1);
}

TEST(FrameTest, MissingTheLastBlackDoesNotEndTheFrame) {
  FrameState f = Frame(LastBlack(), BallOn::kBlack, {40, 45});
  ApplyStroke(f, Played(f, 1, {}));
  EXPECT_FALSE(f.over);
  EXPECT_EQ(f.striker, 1);
  EXPECT_EQ(f.ball_on, BallOn::kBlack);
}

TEST(FrameTest, ATieReSpotsTheBlackForThePlayerTheSeedChooses) {
  std::set<int> strikers;
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    FrameState f = Frame(LastBlack(), BallOn::kBlack, {40, 47});
    f.seed = seed;
    f.table.balls[1].position = Vec2(0.4, 3.0);  // the black elsewhere than its spot
    ApplyStroke(f, Played(f, 1, {1}));
    ASSERT_FALSE(f.over);
    EXPECT_EQ(f.end, FrameEnd::kPlaying);
    EXPECT_TRUE(f.black_respotted);
    EXPECT_EQ(f.score, (std::array<int, 2>{47, 47}));
    ASSERT_EQ(f.table.balls.size(), 1u);
    EXPECT_EQ(f.table.balls[0].kind, BallKind::kBlack);
    EXPECT_EQ(f.table.balls[0].position, Spot(BallKind::kBlack));
    EXPECT_TRUE(f.cue_in_hand);
    EXPECT_EQ(f.ball_on, BallOn::kBlack);
    strikers.insert(f.striker);
    // The same seed chooses the same player.
    FrameState again = Frame(LastBlack(), BallOn::kBlack, {40, 47});
    again.seed = seed;
    ApplyStroke(again, Played(again, 1, {1}));
    EXPECT_EQ(again.striker, f.striker);
    // The next score decides: the striker pots the black from the D.
    const int striker = f.striker;
    ApplyStroke(f, Played(f, 0, {0}, Vec2(0.9, 0.6)));
    EXPECT_TRUE(f.over);
    EXPECT_EQ(f.winner, striker);
    EXPECT_EQ(f.score[static_cast<size_t>(striker)], 54);
  }
  EXPECT_EQ(strikers, (std::set<int>{0, 1}));  // both players get it for some seed
}

TEST(FrameTest, AFoulLeavingTheScoresLevelAlsoGoesToTheReSpottedBlack) {
  FrameState f = Frame(LastBlack(), BallOn::kBlack, {47, 40});
  ApplyStroke(f, Played(f, -1, {}));  // 7 to player 1: 47-47
  EXPECT_FALSE(f.over);
  EXPECT_TRUE(f.black_respotted);
  EXPECT_TRUE(f.cue_in_hand);
  EXPECT_EQ(f.table.balls.size(), 1u);
}

TEST(FrameTest, TheShotCapStopsTheFrame) {
  FrameState f = Frame(MidFrame(), BallOn::kRed, {12, 5});
  f.max_shots = 3;
  for (int k = 0; k < 3; ++k) {
    ASSERT_FALSE(f.over);
    ApplyStroke(f, Played(f, 1, {}));
  }
  EXPECT_TRUE(f.over);
  EXPECT_EQ(f.end, FrameEnd::kShotCap);
  EXPECT_EQ(f.winner, 0);
  FrameState level = Frame(MidFrame(), BallOn::kRed, {5, 5});
  level.max_shots = 1;
  ApplyStroke(level, Played(level, 1, {}));
  EXPECT_TRUE(level.over);
  EXPECT_EQ(level.winner, -1);
}

TEST(FrameTest, AStrokeTheSimulatorCouldNotFinishIsAFoulThatMovesNothing) {
  FrameState f = Frame(MidFrame(), BallOn::kAnyColour);
  Stroke s;
  s.simulation_failed = true;
  s.nominated = BallKind::kBlue;
  const StrokeResult r = ApplyStroke(f, s);
  EXPECT_EQ(r.judgement.foul, Foul::kSimulationFailed);
  EXPECT_EQ(r.judgement.penalty, 5);
  EXPECT_EQ(f.score, (std::array<int, 2>{0, 5}));
  ASSERT_EQ(f.table.balls.size(), MidFrame().size());
  for (size_t i = 0; i < f.table.balls.size(); ++i) EXPECT_EQ(f.table.balls[i].position, MidFrame()[i].position);
}

TEST(FrameTest, BadStrokesAreNamed) {
  const FrameState f = Frame(MidFrame(), BallOn::kRed);
  Stroke s = Played(f, 9, {});
  EXPECT_NE(StrokeError(f, s, Table()).find("first_hit 9"), std::string::npos);
  s = Played(f, 1, {7});
  EXPECT_NE(StrokeError(f, s, Table()).find("potted ball 7"), std::string::npos);
  s = Played(f, 1, {});
  s.ends.pop_back();
  EXPECT_NE(StrokeError(f, s, Table()).find("ends has 5 positions for 6 balls"), std::string::npos);
  s = Played(f, 1, {});
  s.nominated = BallKind::kRed;
  EXPECT_NE(StrokeError(f, s, Table()).find("nominated ball red"), std::string::npos);
}

}  // namespace
}  // namespace snooker::planner
