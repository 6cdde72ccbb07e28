#include "physics/model/model.h"

#include <gtest/gtest.h>

namespace snooker::physics {
namespace {

TEST(ModelTest, DefaultIsTheSimulatorsAndTheCuesDefaults) {
  const Model m;
  EXPECT_TRUE(SameModel(m, ModelOf(SimParams{}, CueParams{})));
  EXPECT_EQ(ValidateModel(m), "");
}

TEST(ModelTest, ApplyReplacesThePhysicsAndKeepsTheNumericalSettings) {
  Model m;
  m.cloth.mu_s = 0.17;
  m.ball_ball.friction_law = BallBallFrictionLaw::kExponential;
  m.ball_ball.slip_gain = 0.1;
  m.cushion.mu_w = 0.2;
  SimParams base;
  base.max_events = 123;
  base.ball_ball_solver.tolerance = 1e-9;
  const SimParams p = m.Apply(base);
  EXPECT_EQ(p.cloth.mu_s, 0.17);
  EXPECT_EQ(p.ball_ball.slip_gain, 0.1);
  EXPECT_EQ(p.cushion.mu_w, 0.2);
  EXPECT_EQ(p.max_events, 123);
  EXPECT_EQ(p.ball_ball_solver.tolerance, 1e-9);
  EXPECT_TRUE(SameModel(ModelOf(p, m.cue), m));
  EXPECT_FALSE(SameModel(ModelOf(p, m.cue), Model{}));
}

TEST(ModelTest, EachPhysicalValueCountsInSameModel) {
  const Model base;
  auto differs = [&](auto change) {
    Model m = base;
    change(m);
    return !SameModel(m, base);
  };
  EXPECT_TRUE(differs([](Model& m) { m.ball.mass *= 1.01; }));
  EXPECT_TRUE(differs([](Model& m) { m.cloth.mu_r *= 1.01; }));
  EXPECT_TRUE(differs([](Model& m) { m.cloth.spin_decel *= 1.01; }));
  EXPECT_TRUE(differs([](Model& m) { m.ball_ball.e = 0.9; }));
  EXPECT_TRUE(differs([](Model& m) { m.ball_ball.slip_decay = 1; }));
  EXPECT_TRUE(differs([](Model& m) { m.cushion.restitution_curve.e[2] = 0.99; }));
  EXPECT_TRUE(differs([](Model& m) { m.cue.end_mass = 0.01; }));
  EXPECT_TRUE(differs([](Model& m) { m.cue.tip_restitution = 0.7; }));
}

TEST(ModelTest, ValidationNamesEachBadValueWithItsGroup) {
  Model m;
  m.cloth.mu_s = -1;
  m.cue.end_mass = 0;
  m.ball_ball.friction_law = BallBallFrictionLaw::kExponential;
  m.ball_ball.slip_decay = 500;
  const std::string e = ValidateModel(m);
  EXPECT_NE(e.find("cloth.mu_s = -1"), std::string::npos) << e;
  EXPECT_NE(e.find("cue.end_mass = 0"), std::string::npos) << e;
  EXPECT_NE(e.find("ball_ball.slip_decay = 500"), std::string::npos) << e;
}

}  // namespace
}  // namespace snooker::physics
