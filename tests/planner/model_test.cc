// The planner with a physical model other than the default (a model file, a
// calibration): it plans with that model, and its shots change the way the model
// says they should.
#include <gtest/gtest.h>

#include <cmath>

#include "physics/model/model.h"
#include "planner/planner.h"
#include "planner/selfplay.h"
#include "planner/shot_sim.h"

namespace snooker::planner {
namespace {

using physics::PocketId;
using physics::Vec2;

const physics::TableModel& Table() { return physics::DefaultTable(); }

// A model that throws much more than the default at every speed: ball-ball friction
// 0.12 at low slip, falling to 0.07.
physics::Model HighThrow() {
  physics::Model m;
  m.ball_ball = physics::WithFrictionCurve(m.ball_ball, {0.07, 0.05, 1.0});
  return m;
}

// A red 50 cm from the top-right pocket on its axis, the cue ball set for a cut of
// about 30 degrees, nothing else near.
TableState CutPot() {
  const physics::Pocket& p = Table().pocket(PocketId::kTopRight);
  const Vec2 red = p.mouth_centre - 0.5 * p.axis;
  const Vec2 ghost = red - 2 * 0.02625 * p.axis;
  const double a = 30.0 * M_PI / 180;
  const Vec2 back(-(std::cos(a) * p.axis.x() - std::sin(a) * p.axis.y()),
                  -(std::sin(a) * p.axis.x() + std::cos(a) * p.axis.y()));
  TableState t;
  t.balls = {{BallKind::kCue, ghost + 0.6 * back}, {BallKind::kRed, red}};
  return t;
}

PlanRequest Request(const TableState& t) {
  PlanRequest r;
  r.table = t;
  r.time_budget = 30;
  r.max_simulations = 600;
  r.monte_carlo_samples = 8;
  r.position_play = false;
  r.kinds = ShotKinds::Of(ShotKind::kPot);
  r.limits.max_sidespin_fraction = 0;  // no side: throw from the cut alone
  return r;
}

TEST(ModelPlanningTest, WithMoreThrowThePlannerCutsThinnerAndItsShotPotsInItsModel) {
  const TableState t = CutPot();
  const Planner plain;
  const Planner thrown(PlannerConfig{}.WithModel(HighThrow()));
  const PlanAnswer a = plain.Plan(Request(t));
  const PlanAnswer b = thrown.Plan(Request(t));
  ASSERT_FALSE(a.shots.empty()) << a.reason;
  ASSERT_FALSE(b.shots.empty()) << b.reason;
  const PlannedShot& sa = a.shots.front();
  const PlannedShot& sb = b.shots.front();
  ASSERT_EQ(sa.pocket, PocketId::kTopRight);
  ASSERT_EQ(sb.pocket, PocketId::kTopRight);
  // Throw carries the object ball towards the cue ball's line: the cut made up for it
  // is thinner (larger) the more the model throws.
  EXPECT_GT(std::abs(sb.cut), std::abs(sa.cut) + 0.2 * M_PI / 180)
      << "default cut " << sa.cut * 180 / M_PI << " deg, high-throw cut " << sb.cut * 180 / M_PI << " deg";
  // Each shot pots in the world of its own model, and the high-throw plan's shot,
  // played on a default table, is thrown less and finds the pocket differently.
  auto replay = [&](const physics::SimParams& params, const PlannedShot& s) {
    ShotSimulator sim(Table(), params);
    const ShotSetup setup{&t, 0, s.object_ball, s.pocket, BallOn::kRed, s.kind, -1};
    ShotOutcome out = sim.Run(setup, s.shot, {}, ShotSimulator::Mode::kFull, {});
    return std::make_pair(out.success, sim.final_balls()[0].r);
  };
  EXPECT_TRUE(replay(plain.config().full, sa).first);
  EXPECT_TRUE(replay(thrown.config().full, sb).first);
  EXPECT_EQ(replay(thrown.config().full, sb).second, sb.cue_ball_end);
}

TEST(ModelPlanningTest, WithModelReplacesThePhysicsAndKeepsTheNumerics) {
  const PlannerConfig base;
  physics::Model m = HighThrow();
  m.cue.end_mass = 0.009;
  const PlannerConfig c = base.WithModel(m);
  EXPECT_TRUE(physics::SameModel(c.model(), m));
  EXPECT_EQ(c.full.max_events, base.full.max_events);
  EXPECT_EQ(c.search.max_events, base.search.max_events);
  EXPECT_EQ(c.search.ball_ball_solver.tolerance, base.search.ball_ball_solver.tolerance);
  EXPECT_TRUE(physics::SameModel(base.model(), physics::Model{}));  // the default stays the default
}

// Sim-to-real: the world given explicitly as the planner's own model plays exactly
// the frames of no world; a world unlike the model plays others.
TEST(ModelPlanningTest, SelfPlayInAWorldOtherThanTheModelPlaysDifferentFrames) {
  SelfPlayOptions o;
  o.frames = 1;
  o.seed = 3;
  o.time_budget = 30;
  o.max_simulations = 150;
  o.monte_carlo_samples = 8;
  o.max_shots_per_frame = 4;
  const Planner& planner = Planner::Default();
  const SelfPlayReport none = RunSelfPlay(planner, o, nullptr, nullptr);
  o.world = physics::Model{};
  const SelfPlayReport same = RunSelfPlay(planner, o, nullptr, nullptr);
  physics::Model other = HighThrow();
  other.cloth.mu_s *= 0.8;
  other.cloth.mu_r *= 0.8;
  o.world = other;
  const SelfPlayReport changed = RunSelfPlay(planner, o, nullptr, nullptr);
  ASSERT_EQ(none.records.size(), 1u);
  EXPECT_EQ(same.records[0].points, none.records[0].points);
  EXPECT_EQ(same.records[0].attempts, none.records[0].attempts);
  EXPECT_EQ(same.records[0].end, none.records[0].end);
  EXPECT_NE(std::make_tuple(changed.records[0].points, changed.records[0].attempts, changed.records[0].end),
            std::make_tuple(none.records[0].points, none.records[0].attempts, none.records[0].end));
}

}  // namespace
}  // namespace snooker::planner
