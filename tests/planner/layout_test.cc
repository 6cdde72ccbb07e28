// Tests of the layout change (planner/layout.h): constructed tables whose answer
// the geometry fixes, and the open pots it finds played in the simulator.
#include "planner/layout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "planner/geometry.h"
#include "planner/planner.h"
#include "planner/pot_estimate.h"
#include "planner/selfplay.h"
#include "planner/shot_sim.h"

namespace snooker::planner {
namespace {

using physics::PocketId;
using physics::Vec2;

const physics::TableModel& Model() { return physics::DefaultTable(); }
double R() { return Model().ball_radius(); }

LayoutOptions Options() {
  LayoutOptions o;
  o.pockets = &Planner::Default().pockets();
  return o;
}

TableState Spotted() {
  TableState t;
  t.balls.push_back({BallKind::kCue, Vec2(0.5, 0.4)});
  for (int c = 0; c < physics::kColourCount; ++c) {
    t.balls.push_back({KindOf(static_cast<physics::Colour>(c)), Model().spot(static_cast<physics::Colour>(c))});
  }
  return t;
}

int IndexOf(const TableState& t, BallKind kind) {
  for (size_t i = 0; i < t.balls.size(); ++i) {
    if (t.balls[i].kind == kind) return static_cast<int>(i);
  }
  return -1;
}

TEST(LayoutTest, UnchangedTableIsZero) {
  Rng rng(3);
  for (int k = 0; k < 5; ++k) {
    const TableState t = RandomFrame(rng, 10, Model());
    EXPECT_EQ(LayoutChange(t, t, Model(), Options()), 0);
    // Only the cue ball moved: it takes no part.
    TableState moved = t;
    moved.balls[static_cast<size_t>(moved.cue_index())].position = Vec2(0.3, 0.3);
    EXPECT_EQ(LayoutChange(t, moved, Model(), Options()), 0);
  }
}

TEST(LayoutTest, PinkFromItsSpotToACushionCosts) {
  const LayoutOptions o = Options();
  const TableState before = Spotted();
  TableState after = before;
  const int pink = IndexOf(after, BallKind::kPink);
  after.balls[static_cast<size_t>(pink)].position = Vec2(Model().cushion_contact_distance(), 2.3);
  const LayoutSummary a = SummarizeLayout(before, Model(), o);
  const LayoutSummary b = SummarizeLayout(after, Model(), o);
  const auto k = static_cast<size_t>(physics::Colour::kPink);
  const double change = LayoutChange(before, after, Model(), o);
  EXPECT_NEAR(change, 6 * o.colour_weight * (b.colour_pottability[k] - a.colour_pottability[k]), 1e-12);
  EXPECT_LT(change, -1.0);
  // On its spot both top corners take it straight, and nearly surely (1.25 m, the
  // corner's widest window): pottability near 1 + 0.33.
  EXPECT_GT(a.colour_pottability[k], 1.2);
  // The other colours did not move and nothing of theirs changed.
  for (int c = 0; c < physics::kColourCount; ++c) {
    if (c != static_cast<int>(physics::Colour::kPink)) {
      EXPECT_EQ(a.colour_pottability[static_cast<size_t>(c)], b.colour_pottability[static_cast<size_t>(c)]);
    }
  }
  // Back to its spot (re-spotted, say): the same gain.
  EXPECT_NEAR(LayoutChange(after, before, Model(), o), -change, 1e-12);
}

TEST(LayoutTest, AColourPottedForGoodIsLeftOut) {
  const TableState before = Spotted();
  TableState after = before;
  after.balls.erase(after.balls.begin() + IndexOf(after, BallKind::kYellow));
  EXPECT_EQ(LayoutChange(before, after, Model(), Options()), 0);
}

// Three reds touching in a triangle and no colours: every red is tied up.
TableState Cluster() {
  TableState t;
  const Vec2 a(0.9, 1.2);
  t.balls = {{BallKind::kCue, Vec2(0.5, 0.4)},
             {BallKind::kRed, a},
             {BallKind::kRed, a + Vec2(2 * R(), 0)},
             {BallKind::kRed, a + Vec2(R(), std::sqrt(3.0) * R())}};
  return t;
}

TEST(LayoutTest, ARedFreedFromAClusterGains) {
  const LayoutOptions o = Options();
  const TableState before = Cluster();
  EXPECT_EQ(SummarizeLayout(before, Model(), o).tied_reds, 3);
  TableState after = before;
  after.balls[3].position = Vec2(0.5, 2.6);
  const LayoutSummary s = SummarizeLayout(after, Model(), o);
  EXPECT_EQ(s.reds, 3);
  EXPECT_EQ(s.tied_reds, 2);  // the two left still touch
  EXPECT_DOUBLE_EQ(LayoutChange(before, after, Model(), o), o.tied_red_cost);
  EXPECT_DOUBLE_EQ(LayoutChange(after, before, Model(), o), -o.tied_red_cost);
  // Potted instead of freed: one tied red fewer too.
  TableState potted = before;
  potted.balls.pop_back();
  EXPECT_DOUBLE_EQ(LayoutChange(before, potted, Model(), o), o.tied_red_cost);
}

TEST(LayoutTest, TiedUpMeansTouchingOrClosedToEveryPocket) {
  const LayoutOptions o = Options();
  // Alone in the open: free.
  TableState t;
  t.balls = {{BallKind::kRed, Vec2(0.7, 1.3)}};
  EXPECT_FALSE(TiedUp(t, 0, Model(), o));
  // Frozen to a cushion (its centre at the contact distance): tied.
  t.balls[0].position.x() = Model().cushion_contact_distance() + 0.5e-3;
  EXPECT_TRUE(TiedUp(t, 0, Model(), o));
  // 2 mm off the cushion: free again (over touch_gap).
  t.balls[0].position.x() = Model().cushion_contact_distance() + 2e-3;
  EXPECT_FALSE(TiedUp(t, 0, Model(), o));
  // Ringed by six colours 2 mm off it (not touching, 2 mm apart from each other):
  // no line leaves the ring, since passing between two of them takes 4R + 1 mm.
  TableState ring;
  const Vec2 c(0.9, 1.4);
  ring.balls = {{BallKind::kRed, c}};
  for (int k = 0; k < 6; ++k) {
    const double a = k * physics::kPi / 3;
    ring.balls.push_back({BallKind::kYellow, c + (2 * R() + 2e-3) * Vec2(std::cos(a), std::sin(a))});
  }
  EXPECT_TRUE(TiedUp(ring, 0, Model(), o));
  for (int k = 0; k < physics::kPocketCount; ++k) {
    EXPECT_FALSE(OpenPot(ring, 0, static_cast<PocketId>(k), Model(), o).has_value());
  }
}

TEST(LayoutTest, PotsCloseWhenTheLineOrTheGhostBallIsTaken) {
  const LayoutOptions o = Options();
  const physics::Pocket& p = Model().pocket(PocketId::kTopRight);
  const Vec2 ball = p.mouth_centre - 0.6 * p.axis;
  TableState t;
  t.balls = {{BallKind::kBlack, ball}};
  const auto open = OpenPot(t, 0, PocketId::kTopRight, Model(), o);
  ASSERT_TRUE(open.has_value());
  EXPECT_EQ(open->cut, 0);
  EXPECT_GT(open->chance, 0.9);
  // A ball on the line to the mouth.
  TableState line = t;
  line.balls.push_back({BallKind::kRed, ball + 0.3 * p.axis});
  EXPECT_FALSE(OpenPot(line, 0, PocketId::kTopRight, Model(), o).has_value());
  // A ball where the cue ball must be at contact.
  TableState ghost = t;
  ghost.balls.push_back({BallKind::kRed, ball - 2 * R() * p.axis});
  EXPECT_FALSE(OpenPot(ghost, 0, PocketId::kTopRight, Model(), o).has_value());
  // A ball straight behind the ghost ball, 97.5 mm from it: the 10 cm run behind
  // the ghost ball passes it at 0.0975 sin(cut) (its foot on the run), under 2R +
  // 0.5 mm at 15 and 30 deg (25 and 49 mm), clear at 45 deg (69 mm). A cut is less
  // likely to pot.
  TableState behind = t;
  behind.balls.push_back({BallKind::kRed, ball - (0.0975 + 2 * R()) * p.axis});
  const auto cut = OpenPot(behind, 0, PocketId::kTopRight, Model(), o);
  ASSERT_TRUE(cut.has_value());
  EXPECT_NEAR(std::abs(cut->cut), 3 * o.cut_step, 1e-12);
  EXPECT_LT(cut->chance, open->chance);
  // The cue ball is no obstacle.
  TableState cue = t;
  cue.balls.push_back({BallKind::kCue, ball + 0.3 * p.axis});
  EXPECT_TRUE(OpenPot(cue, 0, PocketId::kTopRight, Model(), o).has_value());
  // Frozen to the top cushion, a ball cannot go away from it: its ghost ball
  // would be behind the cushion.
  TableState top;
  top.balls = {{BallKind::kBlack, Vec2(0.9, Model().spec().length - Model().cushion_contact_distance())}};
  EXPECT_FALSE(OpenPot(top, 0, PocketId::kBaulkLeft, Model(), o).has_value());
  EXPECT_FALSE(OpenPot(top, 0, PocketId::kMiddleLeft, Model(), o).has_value());
}

TEST(LayoutTest, OpenStraightPotsDropInTheSimulator) {
  // Each colour on its spot, each pocket the test finds open straight: the cue ball
  // where the test put it, struck along its heading, pots the colour there.
  const LayoutOptions o = Options();
  ShotSimulator sim(Model(), physics::SimParams{});
  int played = 0;
  for (int c = 0; c < physics::kColourCount; ++c) {
    TableState t = Spotted();
    t.balls.erase(t.balls.begin());  // the cue ball goes where each pot needs it
    const int colour = IndexOf(t, KindOf(static_cast<physics::Colour>(c)));
    for (int k = 0; k < physics::kPocketCount; ++k) {
      const auto pot = OpenPot(t, colour, static_cast<PocketId>(k), Model(), o);
      if (!pot || pot->cut != 0) continue;
      // The start may lie on a cushion, up to touch_gap past its contact line:
      // 2 mm further along the stroke it is on the bed, on the same line.
      TableState with_cue = t;
      with_cue.balls.push_back({BallKind::kCue, pot->cue + 2e-3 * physics::HeadingVector(pot->heading)});
      const int cue = static_cast<int>(with_cue.balls.size()) - 1;
      physics::Shot shot;
      shot.heading = pot->heading;
      const double distance = (Model().pocket(static_cast<PocketId>(k)).mouth_centre - t.balls[static_cast<size_t>(colour)].position).norm();
      shot.speed = TypicalContactSpeed(distance, 0) + 0.2;
      shot.topspin = shot.speed / R();
      const ShotSetup setup{&with_cue, cue, colour, static_cast<PocketId>(k), BallOnFor(KindOf(static_cast<physics::Colour>(c)))};
      const ShotOutcome& out = sim.Run(setup, shot, {}, ShotSimulator::Mode::kFull, {});
      EXPECT_EQ(out.first_hit, colour) << c << " " << k;
      EXPECT_EQ(out.object_pocket, k) << c << " " << k;
      ++played;
    }
  }
  EXPECT_GE(played, 12);
}


TEST(LayoutTest, KeepingUntouchedBallsChangesNothing) {
  // Random strokes at a red on random 10-red tables, simulated, the rules applied:
  // the change computed keeping the untouched balls' results is the change from
  // both tables judged afresh, to the bit.
  const LayoutOptions o = Options();
  ShotSimulator sim(Model(), physics::SimParams{});
  Rng rng(17);
  std::vector<Vec2> ends;
  int moved_far = 0;
  for (int k = 0; k < 60; ++k) {
    const TableState before = RandomFrame(rng, 10, Model());
    const int cue = before.cue_index();
    int red = cue;
    while (before.balls[static_cast<size_t>(red)].kind != BallKind::kRed) {
      red = static_cast<int>(rng.Uniform() * static_cast<double>(before.balls.size()));
    }
    physics::Shot shot;
    shot.speed = rng.Uniform(1.0, 5.0);
    shot.heading = Direction(before.balls[static_cast<size_t>(red)].position - before.balls[static_cast<size_t>(cue)].position) +
                   rng.Uniform(-0.05, 0.05);
    const ShotSetup setup{&before, cue, red, PocketId::kTopLeft, BallOn::kRed};
    const ShotOutcome& out = sim.Run(setup, shot, {}, ShotSimulator::Mode::kFull, {});
    ends.clear();
    for (const physics::BallState& b : sim.final_balls()) ends.push_back(b.r);
    const TableState after = ApplyShot(before, BallOn::kRed, ends, out.potted, out.foul != Foul::kNone, Model());
    const LayoutSummary a = SummarizeLayout(before, Model(), o);
    const LayoutSummary b = SummarizeLayout(after, Model(), o);
    double fresh = -o.tied_red_cost * (b.tied_reds - a.tied_reds);
    for (int c = 0; c < physics::kColourCount; ++c) {
      const auto i = static_cast<size_t>(c);
      fresh += Value(KindOf(static_cast<physics::Colour>(c))) * (b.colour_pottability[i] - a.colour_pottability[i]);
    }
    EXPECT_EQ(LayoutChange(before, a, after, Model(), o), fresh) << k;
    EXPECT_EQ(LayoutChange(before, after, Model(), o), fresh) << k;
    if (fresh != 0) ++moved_far;
  }
  EXPECT_GT(moved_far, 10);  // shots that changed the layout
}

}  // namespace
}  // namespace snooker::planner
