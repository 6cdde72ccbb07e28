// Tests of the judged shot simulation (planner/shot_sim.h): stopping early never
// changes the verdict, a reused simulator gives what a fresh one gives, a capped
// run is a failure, and the object ball's measured line is where it goes.
#include "planner/shot_sim.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "planner/geometry.h"
#include "planner/random.h"
#include "planner/selfplay.h"
#include "planner/throw_model.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

struct Case {
  TableState table;
  ShotSetup setup;
  physics::Shot shot;
};

// Random shots at random red-pocket pairs on random 8-red frames: mostly misses,
// some pots, some fouls.
std::vector<Case> RandomCases(int n) {
  std::vector<Case> cases;
  Rng rng(21);
  for (int k = 0; k < n; ++k) {
    Case c;
    c.table = RandomFrame(rng, 8, physics::DefaultTable());
    const int cue = c.table.cue_index();
    int object = -1;
    while (object < 0) {
      const int i = static_cast<int>(rng.Uniform() * static_cast<double>(c.table.balls.size()));
      if (c.table.balls[static_cast<size_t>(i)].kind == BallKind::kRed) object = i;
    }
    const Vec2 d = c.table.balls[static_cast<size_t>(object)].position - c.table.balls[static_cast<size_t>(cue)].position;
    c.shot.speed = rng.Uniform(0.5, 4.0);
    c.shot.heading = Direction(d) + rng.Uniform(-0.03, 0.03);
    c.shot.topspin = rng.Uniform(-1, 1) * c.shot.speed / 0.02625;
    c.shot.sidespin = rng.Uniform(-0.5, 0.5) * c.shot.speed / 0.02625;
    c.setup = {nullptr, cue, object, static_cast<physics::PocketId>(static_cast<int>(rng.Uniform() * 6)), BallOn::kRed};
    cases.push_back(std::move(c));
  }
  return cases;
}

// A straight pot into `p`: a red `red_back` (m) in front of the mouth on the pocket's
// axis, the cue ball `cue_back` (m) behind it on the same line.
TableState StraightPot(const physics::Pocket& p, double red_back, double cue_back) {
  TableState t;
  const Vec2 red = p.mouth_centre - red_back * p.axis;
  t.balls = {{BallKind::kCue, red - cue_back * p.axis}, {BallKind::kRed, red}};
  return t;
}

TEST(ShotSimTest, StoppingEarlyNeverChangesTheVerdict) {
  ShotSimulator decide(physics::DefaultTable(), physics::SimParams{});
  ShotSimulator full(physics::DefaultTable(), physics::SimParams{});
  int stopped = 0, successes = 0;
  for (Case& c : RandomCases(150)) {
    c.setup.table = &c.table;
    const ShotOutcome a = decide.Run(c.setup, c.shot, {}, ShotSimulator::Mode::kDecide, {});
    const ShotOutcome b = full.Run(c.setup, c.shot, {}, ShotSimulator::Mode::kFull, {});
    EXPECT_EQ(a.success, b.success);
    EXPECT_EQ(a.first_hit, b.first_hit);
    if (a.success) {
      ++successes;
      EXPECT_EQ(a.potted, b.potted);
      for (size_t i = 0; i < c.table.balls.size(); ++i) {
        EXPECT_EQ(decide.final_balls()[i].r, full.final_balls()[i].r);
      }
    }
    if (a.stopped_early) {
      ++stopped;
      EXPECT_LE(a.events, b.events);
    }
  }
  EXPECT_GT(stopped, 50);  // the rule is exercised
  EXPECT_GT(successes, 0);
}

TEST(ShotSimTest, AReusedSimulatorGivesWhatAFreshOneGives) {
  ShotSimulator reused(physics::DefaultTable(), physics::SimParams{});
  for (Case& c : RandomCases(40)) {
    c.setup.table = &c.table;
    const ShotOutcome a = reused.Run(c.setup, c.shot, {}, ShotSimulator::Mode::kDecide, {});
    ShotSimulator fresh(physics::DefaultTable(), physics::SimParams{});
    const ShotOutcome b = fresh.Run(c.setup, c.shot, {}, ShotSimulator::Mode::kDecide, {});
    EXPECT_EQ(a.success, b.success);
    EXPECT_EQ(a.events, b.events);
    EXPECT_EQ(a.foul, b.foul);
    EXPECT_EQ(a.line.offset, b.line.offset);
    for (size_t i = 0; i < c.table.balls.size(); ++i) {
      EXPECT_EQ(reused.final_balls()[i].r, fresh.final_balls()[i].r);
    }
  }
}

// A reused simulator keeps its buffers: every run, potting or not, writes into the
// potted list reserved for every ball (a run allocates nothing once they have grown).
TEST(ShotSimTest, AReusedSimulatorKeepsItsPottedList) {
  const physics::Pocket& p = physics::DefaultTable().pocket(physics::PocketId::kBaulkLeft);
  TableState t = StraightPot(p, 0.5, 0.6);
  const ShotSetup setup{&t, 0, 1, p.id, BallOn::kRed};
  ShotSimulator sim(physics::DefaultTable(), physics::SimParams{});
  for (int k = 0; k < 3; ++k) {
    const ShotOutcome& out = sim.Run(setup, {1.2 + 0.1 * k, Direction(p.axis), 0, 0}, {}, ShotSimulator::Mode::kFull, {});
    ASSERT_EQ(out.object_pocket, static_cast<int>(p.id));
    EXPECT_GE(out.potted.capacity(), static_cast<size_t>(physics::Simulator::kMaxBalls)) << "run " << k;
  }
}

TEST(ShotSimTest, AnEventCapIsAFailureNeverASuccess) {
  const physics::Pocket& p = physics::DefaultTable().pocket(physics::PocketId::kTopRight);
  TableState t = StraightPot(p, 0.4, 0.5);
  const ShotSetup setup{&t, 0, 1, p.id, BallOn::kRed};
  const physics::Shot shot{1.5, Direction(p.axis), -1.5 / 0.02625, 0};  // screw back: no in-off
  ShotSimulator normal(physics::DefaultTable(), physics::SimParams{});
  ASSERT_TRUE(normal.Run(setup, shot, {}, ShotSimulator::Mode::kFull, {}).success);
  physics::SimParams capped;
  capped.max_events = 3;
  ShotSimulator sim(physics::DefaultTable(), capped);
  for (const auto mode : {ShotSimulator::Mode::kDecide, ShotSimulator::Mode::kFull}) {
    const ShotOutcome& out = sim.Run(setup, shot, {}, mode, {});
    EXPECT_EQ(out.status, physics::SimStatus::kEventLimit);
    EXPECT_FALSE(out.success);
    EXPECT_EQ(out.foul, Foul::kSimulationFailed);
  }
}

TEST(ShotSimTest, TheMeasuredLineIsWhereTheObjectBallGoes) {
  // A straight pot: the object ball's line passes the mouth centre.
  const physics::Pocket& p = physics::DefaultTable().pocket(physics::PocketId::kBaulkLeft);
  TableState t = StraightPot(p, 0.5, 0.6);
  const ShotSetup setup{&t, 0, 1, p.id, BallOn::kRed};
  ShotSimulator sim(physics::DefaultTable(), physics::SimParams{});
  const ShotOutcome& out = sim.Run(setup, {1.2, Direction(p.axis), 0, 0}, {}, ShotSimulator::Mode::kFull, {});
  ASSERT_TRUE(out.line.valid);
  EXPECT_NEAR(out.line.offset, 0, 1e-9);
  EXPECT_NEAR(WrapAngle(out.line.direction - Direction(p.axis)), 0, 1e-9);
  EXPECT_GT(out.line.arrival_speed, 0.1);
  EXPECT_TRUE(out.success);
  // Offset by 5 mm sideways: the line is 5 mm off (the cue ball and object ball both).
  const Vec2 side(-p.axis.y(), p.axis.x());
  for (Ball& b : t.balls) b.position += 0.005 * side;
  const ShotOutcome& off = sim.Run(setup, {1.2, Direction(p.axis), 0, 0}, {}, ShotSimulator::Mode::kFull, {});
  EXPECT_NEAR(off.line.offset, 0.005, 1e-9);
}

// The throw measured on the line is the collision model's: a cue ball rolling into
// a cut (and one with side that adds to the throw) turns the object ball off the
// line of centres by what ThrowModel::Throw, the same impact solve from the same
// state, gives.
TEST(ShotSimTest, TheMeasuredThrowIsTheCollisionModelsThrow) {
  const physics::SimParams params;
  const double r = params.ball.radius;
  const ThrowModel throws(params, ThrowModel::Options{});
  struct Cut { double cut_deg, side; };
  for (const Cut& c : {Cut{30, 0}, Cut{-45, 0}, Cut{20, -20}}) {
    const double cut = physics::DegToRad(c.cut_deg), speed = 1.5, run = 0.1;
    // The cue ball rolls +y from `cue`, meets the red after `run`, centres along n.
    const Vec2 cue(0.9, 1.0), n(-std::sin(cut), std::cos(cut));
    TableState t;
    t.balls = {{BallKind::kCue, cue}, {BallKind::kRed, cue + Vec2(0, run) + 2 * r * n}};
    const ShotSetup setup{&t, 0, 1, physics::PocketId::kTopLeft, BallOn::kRed};
    ShotSimulator sim(physics::DefaultTable(), params);
    const ShotOutcome& out =
        sim.Run(setup, {speed, physics::kPi / 2, speed / r, c.side}, {}, ShotSimulator::Mode::kFull, {});
    ASSERT_EQ(out.first_hit, 1);
    ASSERT_TRUE(out.first_line.valid);
    // Rolling, it loses mu_r g run of its squared speed before the contact; the
    // side decays a little on the way (tolerance).
    const double contact = std::sqrt(speed * speed - 2 * params.cloth.mu_r * params.cloth.g * run);
    const double expected = throws.Throw(cut, contact, contact / r, c.side);
    EXPECT_GT(std::abs(expected), physics::DegToRad(0.3)) << c.cut_deg;
    EXPECT_NEAR(out.first_line.throw_angle, expected, 0.05 * std::abs(expected)) << c.cut_deg;
  }
}

// The cue ball's path after its first contact (ShotOutcome::cue_travel and
// cue_last_direction): a full-ball contact down the table's long axis, played with
// follow, with screw, and as a miss. On a straight path the chords add up to the
// distance from the contact to the end.
TEST(ShotSimTest, TheCueBallsPathAfterContactIsMeasured) {
  const physics::TableModel& model = physics::DefaultTable();
  const double radius = physics::BallParams{}.radius;
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(0.889, 1.0)}, {BallKind::kRed, Vec2(0.889, 1.5)}};
  const ShotSetup setup{&t, 0, 1, physics::PocketId::kTopLeft, BallOn::kRed};
  ShotSimulator sim(model, physics::SimParams{});
  const Vec2 contact = t.balls[1].position - Vec2(0, 2 * radius);
  const double up = physics::kPi / 2;
  // Follow: the cue ball rolls on after the red, straight.
  const ShotOutcome follow = sim.Run(setup, {1.5, up, 1.5 / radius, 0}, {}, ShotSimulator::Mode::kToRest, {});
  ASSERT_EQ(follow.first_hit, 1);
  const Vec2 end = sim.final_balls()[0].r;
  EXPECT_GT(end.y(), contact.y() + 0.1);
  EXPECT_NEAR(follow.cue_travel, (end - contact).norm(), 1e-6);
  EXPECT_NEAR(follow.cue_last_direction.y(), 1.0, 1e-6);
  // Screw: it comes back, its last move down the table.
  const ShotOutcome screw = sim.Run(setup, {2.0, up, -3.0 / radius, 0}, {}, ShotSimulator::Mode::kToRest, {});
  ASSERT_EQ(screw.first_hit, 1);
  const Vec2 back = sim.final_balls()[0].r;
  EXPECT_LT(back.y(), contact.y() - 0.1);
  EXPECT_NEAR(screw.cue_travel, (back - contact).norm(), 1e-6);
  EXPECT_NEAR(screw.cue_last_direction.y(), -1.0, 1e-6);
  // A stroke that meets no ball has no path after a contact.
  const ShotOutcome miss = sim.Run(setup, {1.0, 0.0, 0, 0}, {}, ShotSimulator::Mode::kToRest, {});
  EXPECT_EQ(miss.first_hit, -1);
  EXPECT_EQ(miss.cue_travel, 0.0);
  EXPECT_EQ(miss.cue_last_direction, Vec2::Zero());
}

}  // namespace
}  // namespace snooker::planner
