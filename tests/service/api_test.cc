// Tests of server/api.h and server/convert.h: validation names bad fields; the
// operation returns the library's answer.
#include "server/api.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "physics/motion/motion.h"
#include "server/convert.h"
#include "tests/physics/impact/paper_shots.h"
#include "tests/service/requests.h"
#include "tests/support/text.h"

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

// A cloth too slippery to end the slip: mu_s = 0 answered a slip of 0 s, and a
// denormal one a slip of infinite time.
TEST(ValidateCollideRequestTest, TheClothMustEndTheSlip) {
  for (const double mu_s : {0.0, 1e-320, 0.009}) {
    v1::CollideRequest r = PaperShotRequest(physics::kPaperShots[0]);
    r.mutable_parameters()->set_mu_s(mu_s);
    const auto errors = ValidateCollideRequest(r);
    ASSERT_EQ(errors.size(), 1u) << mu_s;
    EXPECT_EQ(errors[0].field, "parameters.mu_s");
    EXPECT_TRUE(Mentions(Describe(errors), "must be in [0.01, 1]")) << Describe(errors);
  }
  v1::CollideRequest r = PaperShotRequest(physics::kPaperShots[0]);
  v1::CollideResponse usual, slippery;
  ASSERT_TRUE(Collide(r, &usual).ok());
  r.mutable_parameters()->set_mu_s(0.01);
  ASSERT_TRUE(Collide(r, &slippery).ok());
  // T_s = 2|u| / (7 mu_s g): about 21 times the paper's cloth's (0.21; the impact
  // itself changes a little with mu_s).
  const double ratio = slippery.cue().slip_end().time() / usual.cue().slip_end().time();
  EXPECT_GT(ratio, 15);
  EXPECT_LT(ratio, 30);
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

// The API's impact-speed law answers as the constant law at its coefficient for the
// shot's normal speed (a cue ball on a ball at rest: speed cos(cut)).
TEST(CollideTest, ImpactSpeedLawIsTheConstantLawAtTheShotsNormalSpeed) {
  const physics::PaperShot& s = physics::kPaperShots[1];
  v1::CollideRequest law = PaperShotRequest(s);
  law.mutable_parameters()->set_friction_law(v1::BALL_BALL_FRICTION_LAW_EXPONENTIAL_IMPACT_SPEED);
  law.mutable_parameters()->set_mu_bb(0.01);
  law.mutable_parameters()->set_slip_gain(0.14);
  law.mutable_parameters()->set_slip_decay(0.6);
  v1::CollideRequest constant = PaperShotRequest(s);
  constant.mutable_parameters()->set_mu_bb(0.01 + 0.14 * std::exp(-0.6 * s.speed * std::cos(s.cut_deg * M_PI / 180)));
  v1::CollideResponse a, b;
  ASSERT_TRUE(Collide(law, &a).ok());
  ASSERT_TRUE(Collide(constant, &b).ok());
  EXPECT_NEAR(a.cue().slip_end().exit_angle_deg(), b.cue().slip_end().exit_angle_deg(), 1e-9);
  EXPECT_NEAR(a.object().slip_end().speed(), b.object().slip_end().speed(), 1e-12);
  v1::CollideResponse d;
  ASSERT_TRUE(Collide(PaperShotRequest(s), &d).ok());
  EXPECT_GT(std::abs(a.cue().slip_end().exit_angle_deg() - d.cue().slip_end().exit_angle_deg()), 0.1);
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

// The default step cap (1e5) must not stop a fine fixed-step run (about N/2 steps).
TEST(CollideTest, FineFixedStepRunIsNotCapped) {
  v1::CollideRequest req = PaperShotRequest(physics::kPaperShots[0]);
  req.mutable_solver()->set_integrator(v1::IMPULSE_INTEGRATOR_FIXED_STEP);
  req.mutable_solver()->set_steps(1'000'000);
  v1::CollideResponse resp;
  const ApiStatus st = Collide(req, &resp);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_GT(resp.impulse_steps(), 400'000);
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

v1::SimulateRequest PotRequest() {
  // The black 0.35 m out of the top-right pocket on its axis, the cue ball behind.
  v1::SimulateRequest r;
  auto add = [&](const char* id, v1::BallKind kind, double x, double y) {
    testing_requests::AddBall(&r, id, kind, x, y);
  };
  const physics::Pocket& p = physics::DefaultTable().pocket(physics::PocketId::kTopRight);
  const physics::Vec2 black = p.mouth_centre - 0.35 * p.axis, cue = black - 0.4 * p.axis;
  add("cue", v1::CUE, cue.x(), cue.y());
  add("black", v1::BLACK, black.x(), black.y());
  r.mutable_shot()->set_speed(1.5);
  r.mutable_shot()->set_heading_deg(physics::RadToDeg(std::atan2(p.axis.y(), p.axis.x())));
  r.mutable_shot()->set_topspin(1.5 / 0.02625);
  return r;
}

TEST(SimulateApiTest, PotsTheBlackAndReportsEventsAndFinalBalls) {
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(PotRequest(), &resp);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_EQ(resp.status(), "at rest");
  ASSERT_EQ(resp.final_balls_size(), 2);
  EXPECT_EQ(resp.final_balls(1).id(), "black");
  EXPECT_TRUE(resp.final_balls(1).pocketed());
  EXPECT_EQ(resp.final_balls(1).pocket(), "top-right");
  bool pot_event = false;
  for (const v1::Event& e : resp.events()) {
    pot_event |= e.kind() == v1::POCKET && e.balls(0) == "black" && e.pocket() == "top-right";
  }
  EXPECT_TRUE(pot_event);
  EXPECT_EQ(resp.paths_size(), 0);  // only on request
}

// options.impact_tables reaches the simulator: the pot's impact of the rolling cue
// ball on the black is answered from the table by default (a different rounding of
// the same answer) and by the integrator when told, within 0.1 mm of each other.
TEST(SimulateApiTest, ImpactTablesOptionSwitchesTheTablesOff) {
  EXPECT_TRUE(SimParamsFrom({}).impact_tables);
  v1::SimulationOptions off;
  off.set_impact_tables(false);
  EXPECT_FALSE(SimParamsFrom(off).impact_tables);
  v1::SimulateRequest req = PotRequest();
  v1::SimulateResponse with, without;
  ASSERT_TRUE(Simulate(req, &with).ok());
  *req.mutable_options() = off;
  ASSERT_TRUE(Simulate(req, &without).ok());
  ASSERT_EQ(with.final_balls_size(), 2);
  ASSERT_EQ(without.final_balls_size(), 2);
  EXPECT_TRUE(without.final_balls(1).pocketed());
  const v1::Vec2& a = with.final_balls(0).position();
  const v1::Vec2& b = without.final_balls(0).position();
  EXPECT_NE(std::make_pair(a.x(), a.y()), std::make_pair(b.x(), b.y()));
  EXPECT_LE(std::hypot(a.x() - b.x(), a.y() - b.y()), 1e-4);
}

TEST(SimulateApiTest, PathsOnRequestStartAtTheBallsAndEndAtTheirFinalPositions) {
  v1::SimulateRequest req = PotRequest();
  req.mutable_options()->set_include_paths(true);
  v1::SimulateResponse resp;
  ASSERT_TRUE(Simulate(req, &resp).ok());
  ASSERT_EQ(resp.paths_size(), 2);
  const v1::BallPath& cue = resp.paths(0);
  ASSERT_GT(cue.points_size(), 10);
  EXPECT_NEAR(cue.points(0).x(), req.table().balls(0).position().x(), 1e-12);
  EXPECT_NEAR(cue.points(cue.points_size() - 1).y(), resp.final_balls(0).position().y(), 1e-9);
  for (int i = 1; i < cue.t_size(); ++i) EXPECT_GE(cue.t(i), cue.t(i - 1));
}

TEST(SimulateApiTest, BadTablesAreRejectedNamingTheBall) {
  struct Case {
    std::function<void(v1::SimulateRequest*)> spoil;
    const char* must_mention;
  };
  const std::vector<Case> cases = {
      {[](v1::SimulateRequest* r) { r->mutable_table()->mutable_balls(1)->set_id("cue"); },
       "table.balls[1].id = \"cue\""},
      {[](v1::SimulateRequest* r) { r->mutable_table()->mutable_balls(1)->set_kind(v1::CUE); },
       "table.balls = 2 CUE balls (\"cue\", \"black\") (must have exactly one)"},
      {[](v1::SimulateRequest* r) { r->mutable_table()->mutable_balls(0)->set_kind(v1::RED); },
       "table.balls = 0 CUE balls (must have exactly one)"},  // no cue ball in hand here
      {[](v1::SimulateRequest* r) {
         r->mutable_table()->mutable_balls(1)->clear_kind();
       },
       "table.balls[1].kind"},
      {[](v1::SimulateRequest* r) {
         *r->mutable_table()->mutable_balls(1)->mutable_position() =
             r->table().balls(0).position();
       },
       "beyond the vision tolerance of 1 mm, which repairs smaller errors only: cue and black "
       "overlap by 0.0525 m"},
      {[](v1::SimulateRequest* r) {
         r->mutable_table()->mutable_balls(1)->mutable_position()->set_x(-0.5);
       },
       "(ball \"black\") (is off the table: the centre must lie on the bed, x in [0, 1.778] m"},
      {[](v1::SimulateRequest* r) { r->mutable_table()->mutable_balls(1)->mutable_position()->clear_y(); },
       "table.balls[1].position.y = missing (ball \"black\") (must be given"},
      {[](v1::SimulateRequest* r) { r->mutable_table()->mutable_balls(1)->clear_position(); },
       "table.balls[1].position = missing (ball \"black\")"},
      {[](v1::SimulateRequest* r) { r->mutable_table()->mutable_balls(1)->set_kind(static_cast<v1::BallKind>(42)); },
       "table.balls[1].kind = 42 (ball \"black\") (must be one of CUE, RED, YELLOW, GREEN, BROWN, BLUE, PINK, "
       "BLACK)"},
      {[](v1::SimulateRequest* r) {
         r->mutable_table()->mutable_balls(1)->mutable_position()->set_y(NAN);
       },
       "table.balls[1].position"},
      {[](v1::SimulateRequest* r) { r->mutable_shot()->set_speed(-1); }, "shot.speed = -1"},
      {[](v1::SimulateRequest* r) { r->mutable_shot()->set_topspin(5000); }, "shot.topspin = 5000"},
      {[](v1::SimulateRequest* r) { r->mutable_table()->clear_balls(); }, "table.balls"},
      {[](v1::SimulateRequest* r) { r->mutable_options()->set_max_events(0); },
       "options.max_events = 0"},
  };
  for (const Case& c : cases) {
    v1::SimulateRequest req = PotRequest();
    c.spoil(&req);
    v1::SimulateResponse resp;
    const ApiStatus st = Simulate(req, &resp);
    EXPECT_EQ(st.code, ApiStatus::Code::kInvalidArgument) << c.must_mention;
    EXPECT_NE(st.message.find(c.must_mention), std::string::npos)
        << "'" << st.message << "' should mention '" << c.must_mention << "'";
  }
}

TEST(ConvertTest, ShotGivesTheCueBallItsVelocityAndSpin) {
  v1::Shot shot;
  shot.set_speed(2.0);
  shot.set_heading_deg(90);
  shot.set_topspin(2.0 / 0.02625);  // rolling
  shot.set_sidespin(7.0);
  const physics::BallState s = physics::StruckBall(ShotFrom(shot), physics::Vec2(0.5, 0.5));
  EXPECT_NEAR(s.v.x(), 0.0, 1e-12);
  EXPECT_NEAR(s.v.y(), 2.0, 1e-12);
  EXPECT_NEAR(physics::ClothSlip(s, physics::BallParams{}).norm(), 0.0, 1e-12);  // rolls
  EXPECT_EQ(s.w.z(), 7.0);
}

}  // namespace
}  // namespace snooker::server
