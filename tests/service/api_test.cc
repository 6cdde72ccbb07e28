// Tests of server/api.h and server/convert.h: validation names bad fields; the
// operation returns the library's answer.
#include "server/api.h"

#include <gtest/gtest.h>

#include <cmath>

#include "server/convert.h"
#include "tests/physics/paper_shots.h"

namespace snooker::server {
namespace {

v1::CollideRequest PaperShotRequest(const physics::PaperShot& s) {
  v1::CollideRequest r;
  r.set_speed(s.speed);
  r.set_topspin(s.speed / physics::BallParams{}.radius);
  r.set_cut_angle_deg(s.cut_deg);
  return r;
}

TEST(ValidateCollideRequestTest, AcceptsThePapersShots) {
  for (const auto& s : physics::kPaperShots) {
    EXPECT_TRUE(ValidateCollideRequest(PaperShotRequest(s)).empty());
  }
}

TEST(ValidateCollideRequestTest, NamesEveryBadField) {
  v1::CollideRequest r;
  r.set_speed(-1);
  r.set_topspin(NAN);
  r.set_cut_angle_deg(90);
  r.mutable_parameters()->set_mu_bb(1.5);
  r.mutable_parameters()->set_restitution(-0.1);
  r.mutable_solver()->set_steps(0);
  r.mutable_solver()->set_tolerance(1.0);
  const auto errors = ValidateCollideRequest(r);
  std::vector<std::string> fields;
  for (const auto& e : errors) fields.push_back(e.field);
  EXPECT_EQ(fields, (std::vector<std::string>{"speed", "topspin", "cut_angle_deg",
                                              "parameters.mu_bb", "parameters.restitution",
                                              "solver.steps", "solver.tolerance"}));
  EXPECT_EQ(errors[0].value, "-1");
  EXPECT_NE(Describe(errors).find("cut_angle_deg = 90"), std::string::npos);
}

TEST(CollideTest, ReturnsThePapersFirstShot) {
  v1::CollideResponse resp;
  const ApiStatus st = Collide(PaperShotRequest(physics::kPaperShots[0]), &resp);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_NEAR(resp.cue().slip_end().speed(), 0.914, 0.005);
  EXPECT_NEAR(resp.object().slip_end().exit_angle_deg(), 32.20, 0.05);
  EXPECT_GT(resp.rhs_evaluations(), 0);
  EXPECT_GT(resp.impulse_final(), resp.impulse_compression());
}

TEST(CollideTest, FixedStepSchemeIsSelectable) {
  v1::CollideRequest req = PaperShotRequest(physics::kPaperShots[0]);
  req.mutable_solver()->set_integrator(v1::IMPULSE_INTEGRATOR_FIXED_STEP);
  req.mutable_solver()->set_steps(100);
  v1::CollideResponse resp;
  ASSERT_TRUE(Collide(req, &resp).ok());
  // eq. 14: about N/2 steps for two free balls (the step assumes a wall).
  EXPECT_NEAR(resp.impulse_steps(), 50, 3);
  EXPECT_EQ(resp.rhs_evaluations(), resp.impulse_steps());
}

TEST(CollideTest, BadRequestIsInvalidArgumentNamingTheField) {
  v1::CollideRequest req;
  req.set_speed(1.0);
  req.set_cut_angle_deg(95);
  v1::CollideResponse resp;
  const ApiStatus st = Collide(req, &resp);
  EXPECT_EQ(st.code, ApiStatus::Code::kInvalidArgument);
  EXPECT_NE(st.message.find("cut_angle_deg = 95"), std::string::npos);
}

TEST(ConvertTest, UnsetParametersTakeThePapersValues) {
  const v1::CollisionParameters p;
  EXPECT_EQ(BallBallParamsFrom(p).mu_bb, 0.05);
  EXPECT_EQ(BallBallParamsFrom(p).e, 0.89);
  EXPECT_EQ(ClothParamsFrom(p).mu_s, 0.21);
  EXPECT_EQ(BallParamsFrom(p).mass, 0.1406);
  EXPECT_EQ(BallParamsFrom(p).radius, 0.02625);
}

}  // namespace
}  // namespace snooker::server
