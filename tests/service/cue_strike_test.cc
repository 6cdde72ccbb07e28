// The plan's cue block is the shot in the robot's terms: struck through Simulate's
// cue it does what the ball-velocity shot does; a cue ball against a cushion is
// played with a raised cue.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "physics/table/table.h"
#include "server/api.h"
#include "server/plan_api.h"
#include "tests/service/requests.h"

namespace snooker::server {
namespace {

const physics::TableModel& Table() { return physics::DefaultTable(); }

v1::PlanRequest PlanOn(const std::vector<std::tuple<const char*, v1::BallKind, double, double>>& balls) {
  v1::PlanRequest r;
  for (const auto& [id, kind, x, y] : balls) {
    v1::Ball* b = r.mutable_table()->add_balls();
    b->set_id(id);
    b->set_kind(kind);
    b->mutable_position()->set_x(x);
    b->mutable_position()->set_y(y);
  }
  r.set_time_budget_ms(2000);
  r.set_max_simulations(3000);
  r.set_max_shots(5);
  r.set_seed(3);
  return r;
}

struct Ends {
  std::vector<std::string> pocketed;
  physics::Vec2 cue = physics::Vec2::Zero();
};

Ends SimulateWith(const v1::PlanRequest& plan, const v1::PlannedShot& s, bool by_cue) {
  v1::SimulateRequest r;
  *r.mutable_table() = plan.table();
  if (by_cue) {
    *r.mutable_cue() = s.cue();
  } else {
    r.mutable_shot()->set_speed(s.speed());
    r.mutable_shot()->set_heading_deg(s.heading_deg());
    r.mutable_shot()->set_topspin(s.topspin());
    r.mutable_shot()->set_sidespin(s.sidespin());
    r.mutable_shot()->set_swerve_spin(s.swerve_spin());
  }
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(r, &resp);
  EXPECT_TRUE(st.ok()) << st.message;
  Ends e;
  for (const v1::FinalBall& b : resp.final_balls()) {
    if (b.pocketed()) e.pocketed.push_back(b.id() + "@" + b.pocket());
    if (b.kind() == v1::CUE) e.cue = physics::Vec2(b.position().x(), b.position().y());
  }
  return e;
}

// Every shot of a plan, simulated from its cue block, pots what its ball-velocity
// fields pot, and its cue ball ends within 1 mm of theirs.
void ExpectCueBlocksReproduce(const v1::PlanRequest& req, int* checked) {
  v1::PlanResponse resp;
  const ApiStatus st = Plan(req, &resp);
  ASSERT_TRUE(st.ok()) << st.message;
  ASSERT_GT(resp.shots_size(), 0) << resp.reason();
  for (const v1::PlannedShot& s : resp.shots()) {
    const Ends by_ball = SimulateWith(req, s, false), by_cue = SimulateWith(req, s, true);
    EXPECT_EQ(by_cue.pocketed, by_ball.pocketed);
    EXPECT_LT((by_cue.cue - by_ball.cue).norm(), 1e-3) << "cue " << s.cue().ShortDebugString();
    EXPECT_LT((by_ball.cue - physics::Vec2(s.cue_ball_end().x(), s.cue_ball_end().y())).norm(), 1e-6);
    ++*checked;
  }
}

TEST(CueStrikeApiTest, EveryPlannedShotStruckByItsCueDoesWhatItsShotDoes) {
  const double w = Table().spec().width;
  int checked = 0;
  ExpectCueBlocksReproduce(PlanOn({{"cue", v1::CUE, 0.7, 1.2},
                                   {"red-1", v1::RED, 0.95, 2.2},
                                   {"red-2", v1::RED, 0.4, 2.9},
                                   {"black", v1::BLACK, 0.889, 3.24}}),
                           &checked);
  ExpectCueBlocksReproduce(PlanOn({{"cue", v1::CUE, 1.3, 2.6},
                                   {"red-1", v1::RED, w - 0.2, 3.3},
                                   {"blue", v1::BLUE, 0.889, 1.7845},
                                   {"pink", v1::PINK, 0.889, 2.677}}),
                           &checked);
  EXPECT_GE(checked, 4);
}

// A cue ball frozen to the left cushion, or 2 cm off it, with a straight pot across
// the table into the right middle pocket: only a raised cue reaches it. With the
// robot's cue kept level there is no direct pot of it.
TEST(CueStrikeApiTest, ACueBallAgainstACushionIsPlayedWithARaisedCue) {
  const double c = Table().cushion_contact_distance();
  const double y = Table().pocket(physics::PocketId::kMiddleRight).mouth_centre.y();
  for (const double gap : {0.0, 0.02}) {
    v1::PlanRequest req = PlanOn({{"cue", v1::CUE, c + gap, y}, {"red-1", v1::RED, 0.9, y}});
    req.set_max_simulations(20000);  // the search's budget, not the clock, ends it
    v1::PlanResponse resp;
    ASSERT_TRUE(Plan(req, &resp).ok());
    ASSERT_GT(resp.shots_size(), 0) << "gap " << gap << ": " << resp.reason();
    const v1::PlannedShot& best = resp.shots(0);
    EXPECT_EQ(best.kind(), v1::POT) << "gap " << gap << " x " << c + gap << " " << best.ShortDebugString().substr(0, 300);
    EXPECT_EQ(best.pocket(), "middle-right") << "gap " << gap;
    EXPECT_GT(best.cue().elevation_deg(), 0) << "gap " << gap;
    EXPECT_LE(best.cue().elevation_deg(), 25) << "gap " << gap;
    const Ends by_cue = SimulateWith(req, best, true);
    EXPECT_EQ(by_cue.pocketed, std::vector<std::string>{"red-1@middle-right"}) << "gap " << gap;

    req.mutable_limits()->set_max_elevation_deg(0);
    v1::PlanResponse level;
    ASSERT_TRUE(Plan(req, &level).ok() || level.shots_size() == 0);
    for (const v1::PlannedShot& s : level.shots()) {
      EXPECT_FALSE(s.kind() == v1::POT && s.route() == v1::DIRECT && s.pocket() == "middle-right")
          << "a level cue through the cushion, gap " << gap;
      EXPECT_EQ(s.cue().elevation_deg(), 0);
    }
  }
}

// A ball 1 cm behind the cue ball, on the line of a straight pot into the right
// middle pocket: the cue is raised over it.
TEST(CueStrikeApiTest, ABallCloseBehindIsClearedWithARaisedCue) {
  const double y = Table().pocket(physics::PocketId::kMiddleRight).mouth_centre.y();
  const double r = physics::BallParams{}.radius;
  v1::PlanRequest req = PlanOn({{"cue", v1::CUE, 0.5, y}, {"red-1", v1::RED, 1.2, y},
                                {"yellow", v1::YELLOW, 0.5 - 2 * r - 0.01, y}});
  req.set_max_simulations(20000);
  req.set_ball_on(v1::BALL_ON_RED);
  v1::PlanResponse resp;
  ASSERT_TRUE(Plan(req, &resp).ok());
  ASSERT_GT(resp.shots_size(), 0) << resp.reason();
  bool raised_pot = false;
  for (const v1::PlannedShot& s : resp.shots()) {
    if (s.kind() != v1::POT || s.pocket() != "middle-right" || s.route() != v1::DIRECT) continue;
    EXPECT_GT(s.cue().elevation_deg(), 0);
    EXPECT_EQ(SimulateWith(req, s, true).pocketed, std::vector<std::string>{"red-1@middle-right"});
    raised_pot = true;
  }
  EXPECT_TRUE(raised_pot) << resp.shots(0).ShortDebugString().substr(0, 300);
}

TEST(CueStrikeApiTest, GetModelReportsTheCueWithItsSources) {
  v1::GetModelResponse m;
  ASSERT_TRUE(GetModel(v1::GetModelRequest{}, &m, CallLimits{}).ok());
  EXPECT_NEAR(m.cue().squirt_at_045_deg(), 2.18, 0.01);
  EXPECT_GE(m.cue().squirt_at_045_deg(), 1.8);
  EXPECT_LE(m.cue().squirt_at_045_deg(), 2.5);
  EXPECT_NEAR(m.cue().miscue_limit(), 0.514, 1e-3);
  EXPECT_NEAR(m.cue().centre_speed_ratio(), (1 + m.cue().tip_restitution()) / (1 + m.ball().mass_kg() / m.cue().mass_kg()),
              1e-12);
  for (const char* field : {"mass_kg", "tip_radius_m", "tip_restitution", "tip_friction", "end_mass_kg",
                            "bed_restitution", "max_hop_m", "miscue_limit", "squirt_at_045_deg", "centre_speed_ratio"}) {
    EXPECT_FALSE(m.cue().sources().at(field).empty()) << field;
  }
}

TEST(CueStrikeApiTest, AMiscueOrAHopIsRefusedNamingIt) {
  v1::SimulateRequest r;
  testing_requests::AddBall(&r, "cue", v1::CUE, 0.9, 1.0);
  r.mutable_cue()->set_speed(1.0);
  r.mutable_cue()->set_tip_side(0.6);
  v1::SimulateResponse resp;
  ApiStatus st = Simulate(r, &resp);
  EXPECT_FALSE(st.ok());
  EXPECT_NE(st.message.find("miscue"), std::string::npos) << st.message;
  r.mutable_cue()->set_tip_side(0.8);
  r.mutable_cue()->set_tip_height(0.8);  // off the ball altogether
  st = Simulate(r, &resp);
  EXPECT_FALSE(st.ok());
  EXPECT_NE(st.message.find("miscue"), std::string::npos) << st.message;
  r.mutable_cue()->set_tip_side(0);
  r.mutable_cue()->set_tip_height(0);
  r.mutable_cue()->set_speed(4.0);
  r.mutable_cue()->set_elevation_deg(30);
  st = Simulate(r, &resp);
  EXPECT_FALSE(st.ok());
  EXPECT_NE(st.message.find("hop"), std::string::npos) << st.message;
  r.mutable_cue()->set_elevation_deg(0);
  r.mutable_shot()->set_speed(1);
  st = Simulate(r, &resp);
  EXPECT_FALSE(st.ok());
  EXPECT_NE(st.message.find("not both"), std::string::npos) << st.message;
  // Neither: the balls are at rest and nothing would move. A shot of speed 0 is still
  // a stroke, and answers the table as it is.
  r.clear_cue();
  r.clear_shot();
  st = Simulate(r, &resp);
  EXPECT_EQ(st.code, ApiStatus::Code::kInvalidArgument);
  EXPECT_NE(st.message.find("shot = unset (give the stroke: shot, or cue in the robot's terms)"), std::string::npos) << st.message;
  r.mutable_shot()->set_speed(0);
  st = Simulate(r, &resp);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_EQ(resp.final_balls_size(), r.table().balls_size());
}

}  // namespace
}  // namespace snooker::server
