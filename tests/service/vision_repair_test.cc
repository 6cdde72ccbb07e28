// The vision repair: balls that overlap, or a centre a hair past a
// cushion, by at most the vision tolerance are moved apart or back by the least
// distance, with a warning naming each ball and how far it moved; beyond the
// tolerance the request is INVALID_ARGUMENT naming the balls. Through the library
// operation, a real server and stub, and the command line.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "physics/table/table.h"
#include "server/api.h"
#include "server/plan_convert.h"
#include "tests/support/cli_support.h"
#include "tests/service/requests.h"
#include "tests/service/server_support.h"
#include "tests/support/text.h"

namespace snooker::server {
namespace {

using server_support::TestServer;

const double kR = physics::DefaultTable().ball_radius();
const double kContact = physics::DefaultTable().cushion_contact_distance();

// The cue ball, red-1 and red-2 side by side in x, red-1 and red-2 `gap` m apart
// (negative: overlapping), and a shot that misses them both.
v1::SimulateRequest Table(double gap) {
  v1::SimulateRequest r;
  auto add = [&](const char* id, v1::BallKind kind, double x, double y) {
    testing_requests::AddBall(&r, id, kind, x, y);
  };
  add("cue", v1::CUE, 0.9, 0.6);
  add("red-1", v1::RED, 0.8, 2.0);
  add("red-2", v1::RED, 0.8 + 2 * kR + gap, 2.0);
  r.mutable_shot()->set_speed(0.5);
  r.mutable_shot()->set_heading_deg(-90);  // into the baulk cushion, away from the reds
  return r;
}

TEST(VisionRepairTest, AnOverlapWithinTheToleranceIsMovedApartWithAWarning) {
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(Table(-0.0004), &resp);  // 0.4 mm overlap
  ASSERT_TRUE(st.ok()) << st.message;
  ASSERT_EQ(resp.warnings_size(), 2);
  // Each moves half the overlap along the line of centres: the least displacement.
  EXPECT_EQ(resp.warnings(0).ball_id(), "red-1");
  EXPECT_EQ(resp.warnings(1).ball_id(), "red-2");
  for (const v1::Warning& w : resp.warnings()) {
    EXPECT_NEAR(w.moved_mm(), 0.2, 1e-6);
    EXPECT_NEAR(w.to().y(), 2.0, 1e-12);
    EXPECT_NEAR(std::hypot(w.to().x() - w.from().x(), w.to().y() - w.from().y()) * 1e3, w.moved_mm(),
                1e-9);
  }
  EXPECT_NEAR(resp.warnings(1).to().x() - resp.warnings(0).to().x(), 2 * kR, 1e-9);
  EXPECT_TRUE(Mentions(resp.warnings(0).message(), "moved red-1 by 0.2 mm from (0.8, 2) to"))
      << resp.warnings(0).message();
  EXPECT_TRUE(Mentions(resp.warnings(0).message(), "it overlapped red-2 by 0.4 mm"))
      << resp.warnings(0).message();
  // The simulation starts from the moved positions: the reds did not move, and end
  // where the repair put them.
  EXPECT_NEAR(resp.final_balls(1).position().x(), resp.warnings(0).to().x(), 1e-12);
  EXPECT_NEAR(resp.final_balls(2).position().x(), resp.warnings(1).to().x(), 1e-12);
}

TEST(VisionRepairTest, ACentrePastACushionIsMovedBackOntoTheBed) {
  v1::SimulateRequest r = Table(0.01);
  r.mutable_table()->mutable_balls(1)->mutable_position()->set_x(kContact - 0.0003);
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(r, &resp);
  ASSERT_TRUE(st.ok()) << st.message;
  ASSERT_EQ(resp.warnings_size(), 1);
  EXPECT_EQ(resp.warnings(0).ball_id(), "red-1");
  EXPECT_NEAR(resp.warnings(0).moved_mm(), 0.3, 1e-6);
  EXPECT_NEAR(resp.warnings(0).to().x(), kContact, 1e-9);
  EXPECT_TRUE(Mentions(resp.warnings(0).message(), "0.3 mm past where a ball touches the left cushion"))
      << resp.warnings(0).message();
}

TEST(VisionRepairTest, AValidTableIsLeftExactlyAsItIs) {
  const v1::SimulateRequest r = Table(0);  // touching: valid
  v1::SimulateResponse resp;
  ASSERT_TRUE(Simulate(r, &resp).ok());
  EXPECT_EQ(resp.warnings_size(), 0);
  EXPECT_EQ(resp.final_balls(2).position().x(), r.table().balls(2).position().x());
}

// A plan with the cue ball in hand: its table (no CUE ball) is repaired as
// Simulate's is; Simulate itself still needs its cue ball.
TEST(VisionRepairTest, ATableWithTheCueBallInHandIsRepairedTheSame) {
  v1::PlanRequest plan;
  *plan.mutable_table() = Table(-0.0004).table();
  plan.mutable_table()->mutable_balls()->DeleteSubrange(0, 1);  // the cue ball
  plan.set_cue_in_hand(true);
  PlanBounds bounds;
  bounds.vision_tolerance_mm = 1;
  const PlanCheck check = CheckPlanRequest(plan, physics::DefaultTable(), bounds);
  EXPECT_TRUE(check.errors.empty()) << Describe(check.errors);
  ASSERT_EQ(check.warnings.size(), 2u);
  EXPECT_EQ(check.warnings[0].ball_id(), "red-1");
  EXPECT_EQ(check.warnings[1].ball_id(), "red-2");
  EXPECT_NEAR(check.warnings[0].moved_mm() + check.warnings[1].moved_mm(), 0.4, 1e-6);
  ASSERT_TRUE(check.repaired.has_value());
  EXPECT_EQ(check.repaired->balls_size(), 2);
  // The same table, checked as Simulate checks one, lacks its cue ball.
  const TableCheck simulate = CheckTable(plan.table(), physics::DefaultTable(), 1e-3);
  ASSERT_EQ(simulate.errors.size(), 1u) << Describe(simulate.errors);
  EXPECT_EQ(simulate.errors[0].value, "0 CUE balls");
  // Beyond the tolerance, the balls are named as ever.
  plan.mutable_table()->mutable_balls(1)->mutable_position()->set_x(0.8 + 2 * kR - 0.0015);
  const std::string refused = Describe(CheckPlanRequest(plan, physics::DefaultTable(), bounds).errors);
  EXPECT_TRUE(Mentions(refused, "red-1 and red-2 overlap by 0.0015 m")) << refused;
}

TEST(VisionRepairTest, BeyondTheToleranceIsInvalidArgumentNamingTheBalls) {
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(Table(-0.0015), &resp);  // 1.5 mm > 1 mm
  EXPECT_EQ(st.code, ApiStatus::Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "table.balls = positions (beyond the vision tolerance of 1 mm"))
      << st.message;
  EXPECT_TRUE(Mentions(st.message, "red-1 and red-2 overlap by 0.0015 m")) << st.message;
  EXPECT_EQ(resp.warnings_size(), 0);
}

TEST(VisionRepairTest, ARequestMayAskForLessButNotMore) {
  v1::SimulateRequest strict = Table(-0.0004);
  strict.set_vision_tolerance_mm(0);  // no repair: every overlap is an error
  v1::SimulateResponse resp;
  ApiStatus st = Simulate(strict, &resp);
  EXPECT_EQ(st.code, ApiStatus::Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "red-1 at (0.8, 2) m overlaps red-2")) << st.message;

  v1::SimulateRequest greedy = Table(-0.0004);
  greedy.set_vision_tolerance_mm(2);
  st = Simulate(greedy, &resp);
  EXPECT_EQ(st.code, ApiStatus::Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "vision_tolerance_mm = 2 (must be in [0, 1] mm")) << st.message;
  // Only the tolerance is reported: the table is fine at the server's tolerance.
  EXPECT_FALSE(Mentions(st.message, "table.balls")) << st.message;

  CallLimits generous;
  generous.vision_tolerance_mm = 3;
  v1::SimulateRequest wide = Table(-0.0015);
  wide.set_vision_tolerance_mm(2);
  st = Simulate(wide, &resp, generous);
  EXPECT_TRUE(st.ok()) << st.message;
  EXPECT_EQ(resp.warnings_size(), 2);
}

TEST(VisionRepairTest, ThroughTheServerWithItsOwnTolerance) {
  ServerOptions options;
  options.vision_tolerance_mm = 0.5;
  TestServer s(options);
  ASSERT_NE(s.stub, nullptr);
  {
    v1::SimulateResponse resp;
    grpc::ClientContext ctx;
    const grpc::Status st = s.stub->Simulate(&ctx, Table(-0.0004), &resp);
    ASSERT_TRUE(st.ok()) << st.error_message();
    ASSERT_EQ(resp.warnings_size(), 2);
    EXPECT_NEAR(resp.warnings(1).moved_mm(), 0.2, 1e-6);
  }
  {
    v1::SimulateResponse resp;
    grpc::ClientContext ctx;
    const grpc::Status st = s.stub->Simulate(&ctx, Table(-0.0008), &resp);
    EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_TRUE(Mentions(st.error_message(), "beyond the vision tolerance of 0.5 mm"))
        << st.error_message();
  }
}

TEST(VisionRepairTest, TheCommandLinePrintsTheWarningAndTakesTheFlag) {
  using cli_support::RunCli;
  using cli_support::TempFile;
  const std::string table = TempFile("repair_table.json", R"({"balls": [
      {"id": "cue", "kind": "CUE", "position": {"x": 0.9, "y": 0.6}},
      {"id": "red-1", "kind": "RED", "position": {"x": 0.8, "y": 2.0}},
      {"id": "red-2", "kind": "RED", "position": {"x": 0.8521, "y": 2.0}}]})");  // 0.4 mm
  const std::string shot = TempFile("repair_shot.json", R"({"speed": 0.5, "headingDeg": -90})");
  const cli_support::RunResult ok = RunCli("simulate --table " + table + " --shot " + shot);
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(Mentions(ok.out, "warning: moved red-1 by 0.2 mm")) << ok.out;
  EXPECT_TRUE(Mentions(ok.out, "warning: moved red-2 by 0.2 mm")) << ok.out;
  const cli_support::RunResult json = RunCli("simulate --json --table " + table + " --shot " + shot);
  EXPECT_TRUE(Mentions(json.out, "\"warnings\":[{\"message\":\"moved red-1 by 0.2 mm")) << json.out;
  EXPECT_TRUE(Mentions(json.out, "\"ballId\":\"red-1\"")) << json.out;
  EXPECT_TRUE(Mentions(json.out, "\"movedMm\":0.2")) << json.out;
  const cli_support::RunResult strict =
      RunCli("simulate --vision-tolerance-mm 0 --table " + table + " --shot " + shot);
  EXPECT_EQ(strict.exit_code, 2);
  EXPECT_TRUE(Mentions(strict.err, "red-1 at (0.8, 2) m overlaps red-2")) << strict.err;
  const cli_support::RunResult bad =
      RunCli("simulate --vision-tolerance-mm 11 --table " + table + " --shot " + shot);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(Mentions(bad.err, "--vision-tolerance-mm 11 is outside [0, 10]")) << bad.err;
}

}  // namespace
}  // namespace snooker::server
