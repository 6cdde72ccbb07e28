// Tests of Plan at the API edge (server/plan_api.h, server/plan_convert.h):
// validation names each bad field and value, units are converted at the edge, and
// the answer carries the table's ids, every planner outcome has one API status,
// and the proto's comments quote the planner's ranges.
#include "server/plan_api.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "planner/limits.h"

#include "server/plan_convert.h"
#include "tests/service/requests.h"

namespace snooker::server {
namespace {

using testing_requests::AddBall;

// A red 40 cm before the top-right pocket on its axis, the cue ball 40 cm behind it.
v1::PlanRequest ObviousPot() {
  const physics::Pocket& p = physics::DefaultTable().pocket(physics::PocketId::kTopRight);
  const physics::Vec2 red = p.mouth_centre - 0.4 * p.axis;
  const physics::Vec2 cue = red - 0.4 * p.axis;
  v1::PlanRequest r;
  AddBall(&r, "white", v1::CUE, cue.x(), cue.y());
  AddBall(&r, "r7", v1::RED, red.x(), red.y());
  const physics::Vec2 black = physics::DefaultTable().spot(physics::Colour::kBlack);
  AddBall(&r, "the-black", v1::BLACK, black.x(), black.y());
  r.set_max_simulations(300);
  r.set_time_budget_ms(30000);
  r.set_monte_carlo_samples(16);
  return r;
}

// ObviousPot with the cue ball in hand: the table without its CUE ball.
v1::PlanRequest ObviousPotInHand() {
  v1::PlanRequest r = ObviousPot();
  r.mutable_table()->mutable_balls()->DeleteSubrange(0, 1);
  r.set_cue_in_hand(true);
  return r;
}

std::vector<std::string> Fields(const std::vector<FieldError>& errors) {
  std::vector<std::string> f;
  for (const FieldError& e : errors) f.push_back(e.field);
  return f;
}

TEST(ValidatePlanRequestTest, AcceptsAGoodRequest) {
  EXPECT_TRUE(ValidatePlanRequest(ObviousPot(), physics::DefaultTable()).empty());
}

TEST(ValidatePlanRequestTest, NamesEveryBadField) {
  v1::PlanRequest r = ObviousPot();
  r.set_ball_on(v1::BALL_ON_PINK);
  r.mutable_limits()->set_min_speed(3);
  r.mutable_limits()->set_max_speed(2);
  r.mutable_limits()->set_max_topspin_fraction(-1);
  r.mutable_noise()->set_heading_sigma_deg(NAN);
  r.mutable_noise()->set_position_sigma_mm(100);
  (*r.mutable_noise()->mutable_ball_position_sigma_mm())["nobody"] = 0.3;
  r.set_time_budget_ms(0);
  r.set_max_shots(0);
  r.set_monte_carlo_samples(-3);
  const std::vector<FieldError> errors = ValidatePlanRequest(r, physics::DefaultTable());
  std::vector<std::string> fields = Fields(errors);
  std::sort(fields.begin(), fields.end());
  EXPECT_EQ(fields, (std::vector<std::string>{"ball_on", "limits.max_speed", "limits.max_topspin_fraction",
                                              "max_shots", "monte_carlo_samples",
                                              "noise.ball_position_sigma_mm[\"nobody\"]",
                                              "noise.heading_sigma_deg", "noise.position_sigma_mm",
                                              "time_budget_ms"}));
  EXPECT_NE(Describe(errors).find("ball_on = BALL_ON_PINK (no such ball on the table)"), std::string::npos)
      << Describe(errors);
  // The message lists the first few problems and counts the rest; each error still
  // carries its value.
  EXPECT_NE(Describe(errors).find("and 4 more"), std::string::npos) << Describe(errors);
  for (const FieldError& e : errors) {
    if (e.field == "time_budget_ms") {
      EXPECT_EQ(e.value, "0");
    } else if (e.field == "noise.position_sigma_mm") {
      EXPECT_EQ(e.value, "100");
      EXPECT_EQ(e.rule, "must be in [0, 50] mm");  // planner/limits.h's 0.05 m, in the API's unit
    } else if (e.field == "noise.heading_sigma_deg") {
      EXPECT_EQ(e.rule, "must be in [0, 10] deg");
    }
  }
}

TEST(ValidatePlanRequestTest, MoreBallsOfAKindThanSnookerHas) {
  v1::PlanRequest r = ObviousPot();
  AddBall(&r, "black-2", v1::BLACK, 0.3, 0.3);
  for (int i = 0; i < 15; ++i) AddBall(&r, "x" + std::to_string(i), v1::RED, 0.2 + 0.1 * i, 1.0);
  const std::string d = Describe(ValidatePlanRequest(r, physics::DefaultTable()));
  EXPECT_NE(d.find("table.balls = 16 (reds: at most 15)"), std::string::npos) << d;
  EXPECT_NE(d.find("table.balls = 2 (black balls: at most one)"), std::string::npos) << d;
}

TEST(ValidatePlanRequestTest, TheTableIsCheckedAsSimulateChecksIt) {
  v1::PlanRequest r = ObviousPot();
  r.mutable_table()->mutable_balls(1)->mutable_position()->set_x(-1);  // off the table
  AddBall(&r, "white", v1::CUE, 0.5, 0.5);                              // a second cue, same id
  const std::string d = Describe(ValidatePlanRequest(r, physics::DefaultTable()));
  EXPECT_NE(d.find("table.balls[3].id = \"white\""), std::string::npos) << d;
  EXPECT_NE(d.find("2 CUE balls"), std::string::npos) << d;
  EXPECT_NE(d.find("r7"), std::string::npos) << d;
}

TEST(ValidatePlanRequestTest, WithTheCueBallInHandTheTableHasNone) {
  EXPECT_TRUE(ValidatePlanRequest(ObviousPotInHand(), physics::DefaultTable()).empty())
      << Describe(ValidatePlanRequest(ObviousPotInHand(), physics::DefaultTable()));
  // Without cue_in_hand the same table lacks its cue ball.
  v1::PlanRequest r = ObviousPotInHand();
  r.clear_cue_in_hand();
  std::string d = Describe(ValidatePlanRequest(r, physics::DefaultTable()));
  EXPECT_NE(d.find("table.balls = 0 CUE balls (must have exactly one)"), std::string::npos) << d;
  // With it, a CUE ball on the table is refused, naming the count and the ball.
  r = ObviousPot();
  r.set_cue_in_hand(true);
  const std::vector<FieldError> errors = ValidatePlanRequest(r, physics::DefaultTable());
  ASSERT_EQ(errors.size(), 1u) << Describe(errors);
  EXPECT_EQ(errors[0].field, "table.balls");
  EXPECT_EQ(errors[0].value, "1 CUE ball (\"white\")");
  EXPECT_NE(errors[0].rule.find("must have none"), std::string::npos) << errors[0].rule;
  EXPECT_NE(errors[0].rule.find("cue_in_hand"), std::string::npos) << errors[0].rule;
}

TEST(ValidatePlanRequestTest, WithTheCueBallInHandNoBallMayBeNamedCue) {
  v1::PlanRequest r = ObviousPotInHand();
  r.mutable_table()->mutable_balls(1)->set_id("cue");  // the black
  std::vector<FieldError> errors = ValidatePlanRequest(r, physics::DefaultTable());
  ASSERT_EQ(errors.size(), 1u) << Describe(errors);
  EXPECT_EQ(errors[0].field, "table.balls[1].id");
  EXPECT_EQ(errors[0].value, "\"cue\" (a BLACK ball)");
  EXPECT_NE(errors[0].rule.find("cue_in_hand"), std::string::npos) << errors[0].rule;
  // The id is free when the cue ball is on the table (ObviousPot's is "white").
  r.clear_cue_in_hand();
  AddBall(&r, "white", v1::CUE, 0.889, 0.6);
  errors = ValidatePlanRequest(r, physics::DefaultTable());
  EXPECT_TRUE(errors.empty()) << Describe(errors);
}

TEST(PlanRequestFromTest, ConvertsUnitsAtTheEdge) {
  v1::PlanRequest r = ObviousPot();
  r.mutable_noise()->set_heading_sigma_deg(0.05);
  r.mutable_noise()->set_position_sigma_mm(0.5);
  (*r.mutable_noise()->mutable_ball_position_sigma_mm())["r7"] = 1.5;
  r.set_time_budget_ms(250);
  r.set_ball_on(v1::BALL_ON_COLOUR);
  const planner::PlanRequest p = PlanRequestFrom(r);
  EXPECT_DOUBLE_EQ(p.noise.heading, physics::DegToRad(0.05));
  EXPECT_DOUBLE_EQ(p.noise.position, 0.5e-3);
  ASSERT_EQ(p.position_sigma.size(), 3u);
  EXPECT_DOUBLE_EQ(p.position_sigma[0], 0.5e-3);
  EXPECT_DOUBLE_EQ(p.position_sigma[1], 1.5e-3);
  EXPECT_DOUBLE_EQ(p.time_budget, 0.25);
  EXPECT_EQ(p.ball_on, planner::BallOn::kAnyColour);
  EXPECT_EQ(p.table.balls[2].kind, planner::BallKind::kBlack);
  // Unset fields keep the planner's defaults.
  const planner::PlanRequest d = PlanRequestFrom(v1::PlanRequest{});
  EXPECT_EQ(d.time_budget, planner::PlanRequest{}.time_budget);
  EXPECT_EQ(d.limits.max_speed, planner::RobotLimits{}.max_speed);
  EXPECT_FALSE(d.ball_on.has_value());
  EXPECT_FALSE(d.cue_in_hand);
  EXPECT_FALSE(p.cue_in_hand);
  const planner::PlanRequest in_hand = PlanRequestFrom(ObviousPotInHand());
  EXPECT_TRUE(in_hand.cue_in_hand);
  EXPECT_EQ(in_hand.table.balls.size(), 2u);
}

TEST(PlanTest, AnswersWithTheTablesIds) {
  v1::PlanResponse resp;
  int progress = 0;
  PlanControl control;
  control.on_progress = [&](const v1::PlanResponse& best) {
    ++progress;
    EXPECT_EQ(best.shots_size(), 1);
  };
  const ApiStatus st = Plan(ObviousPot(), &resp, control);
  ASSERT_TRUE(st.ok()) << st.message;
  ASSERT_GT(resp.shots_size(), 0) << resp.reason();
  const v1::PlannedShot& s = resp.shots(0);
  EXPECT_EQ(s.object_ball(), "r7");
  EXPECT_EQ(s.pocket(), "top-right");
  EXPECT_EQ(s.next_ball(), "the-black");
  EXPECT_GT(s.pot_probability(), 0.9);
  ASSERT_GT(s.events_size(), 0);
  EXPECT_EQ(s.events(0).kind(), v1::BALL_BALL);
  EXPECT_EQ(s.events(0).balls(0), "white");
  bool potted = false;
  for (const v1::Event& e : s.events()) potted = potted || (e.kind() == v1::POCKET && e.pocket() == "top-right");
  EXPECT_TRUE(potted);
  EXPECT_GT(resp.simulations(), 0);
  EXPECT_GT(resp.elapsed_ms(), 0);
  EXPECT_GT(progress, 0);
}

TEST(PlanTest, BadRequestIsInvalidArgument) {
  v1::PlanRequest r = ObviousPot();
  r.set_max_shots(99);
  v1::PlanResponse resp;
  const ApiStatus st = Plan(r, &resp);
  EXPECT_EQ(st.code, ApiStatus::Code::kInvalidArgument);
  EXPECT_NE(st.message.find("max_shots = 99"), std::string::npos) << st.message;
}

TEST(PlanStatusTest, EveryPlannerOutcomeHasOneApiStatus) {
  using planner::PlanStatus;
  using Code = ApiStatus::Code;
  const std::pair<PlanStatus, Code> expected[] = {
      {PlanStatus::kOk, Code::kOk},
      {PlanStatus::kNoPot, Code::kOk},
      {PlanStatus::kBudgetSpent, Code::kOk},
      {PlanStatus::kInvalidRequest, Code::kInvalidArgument},
      {PlanStatus::kDeadline, Code::kDeadlineExceeded},
      {PlanStatus::kCancelled, Code::kCancelled},
  };
  for (const auto& [status, code] : expected) {
    planner::PlanAnswer a;
    a.status = status;
    a.reason = "why";
    a.simulations = 12;
    const ApiStatus st = StatusOf(a);
    EXPECT_EQ(st.code, code) << planner::ToString(status);
    if (code != Code::kOk) {
      EXPECT_NE(st.message, "") << planner::ToString(status);
    }
  }
}

// The comment block nearest above `field`'s declaration in `proto` (skipping the
// declarations of the fields it shares the block with).
std::string CommentAbove(const std::string& proto, const std::string& field) {
  std::istringstream in(proto);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find(" " + field + " = ") == std::string::npos) continue;
    size_t j = i;
    while (j > 0 && lines[j - 1].find("//") == std::string::npos) --j;
    std::string block;
    while (j > 0 && lines[j - 1].find("//") != std::string::npos) block = lines[--j] + "\n" + block;
    return block;
  }
  return "";
}

std::string RangeText(double lo, double hi) {
  char text[64];
  std::snprintf(text, sizeof text, "[%.12g, %.12g]", lo, hi);
  return text;
}

TEST(PlanProtoTest, CommentsQuoteThePlannersRanges) {
  std::ifstream file(SNOOKER_PROTO_DIR "/snooker/v1/plan.proto");
  ASSERT_TRUE(file) << SNOOKER_PROTO_DIR;
  const std::string proto((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  namespace lim = planner::limits;
  const double deg = 180 / physics::kPi;
  const struct {
    const char* field;
    std::string range;
  } quoted[] = {
      {"min_speed", RangeText(lim::kMinSpeed.lo, lim::kMinSpeed.hi)},
      {"max_speed", RangeText(lim::kMaxSpeed.lo, lim::kMaxSpeed.hi)},
      {"max_topspin_fraction", RangeText(lim::kSpinFraction.lo, lim::kSpinFraction.hi)},
      {"cue_clearance_m", RangeText(lim::kCueClearance.lo, lim::kCueClearance.hi)},
      {"cue_radius_m", RangeText(lim::kCueRadius.lo, lim::kCueRadius.hi)},
      {"heading_sigma_deg", RangeText(lim::kHeadingSigma.lo * deg, lim::kHeadingSigma.hi * deg)},
      {"speed_sigma_fraction", RangeText(lim::kSpeedSigmaFraction.lo, lim::kSpeedSigmaFraction.hi)},
      {"topspin_sigma", RangeText(lim::kSpinSigma.lo, lim::kSpinSigma.hi)},
      {"position_sigma_mm", RangeText(lim::kPositionSigma.lo * 1e3, lim::kPositionSigma.hi * 1e3)},
      {"ball_position_sigma_mm", RangeText(lim::kPositionSigma.lo * 1e3, lim::kPositionSigma.hi * 1e3)},
      {"time_budget_ms", RangeText(limits::kPlanBudgetMs.lo, limits::kPlanBudgetMs.hi)},
      {"max_shots", RangeText(static_cast<double>(lim::kMaxShots.lo), static_cast<double>(lim::kMaxShots.hi))},
      {"max_simulations",
       RangeText(static_cast<double>(lim::kMaxSimulations.lo), static_cast<double>(lim::kMaxSimulations.hi))},
      {"monte_carlo_samples", RangeText(static_cast<double>(lim::kMonteCarloSamples.lo),
                                        static_cast<double>(lim::kMonteCarloSamples.hi))},
  };
  for (const auto& q : quoted) {
    const std::string comment = CommentAbove(proto, q.field);
    ASSERT_NE(comment, "") << q.field;
    EXPECT_NE(comment.find(q.range), std::string::npos) << q.field << " should quote " << q.range << ":\n" << comment;
  }
}

}  // namespace
}  // namespace snooker::server
