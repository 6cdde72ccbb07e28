// Tests of Plan at the API edge (server/plan_api.h, server/plan_convert.h):
// validation names each bad field and value, units are converted at the edge, and
// the answer carries the table's ids (the cue ball placed from hand named "cue"),
// each shot's kind, route, first ball, foul probability, expected points, Monte
// Carlo runs, what a safety leaves the opponent, placement and balls' ends in their
// JSON names, every planner outcome has one API status, and the proto's comments
// quote the planner's ranges.
#include "server/plan_api.h"

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
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

// Whether p (m, table frame) is in the D: on or behind the baulk line, within the D's
// radius of its middle (a micrometre of slack for rounding).
bool InTheD(const v1::Vec2& p) {
  const physics::TableSpec& spec = physics::DefaultTable().spec();
  const double slack = 1e-6;
  return p.y() <= spec.baulk_line + slack &&
         std::hypot(p.x() - spec.width / 2, p.y() - spec.baulk_line) <= spec.d_radius + slack;
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

TEST(ValidatePlanRequestTest, TheBreakValueIsInPoints) {
  v1::PlanRequest r = ObviousPot();
  for (const double ok : {0.0, 30.0, 147.0}) {
    r.set_break_value(ok);
    EXPECT_TRUE(ValidatePlanRequest(r, physics::DefaultTable()).empty()) << ok;
  }
  for (const double bad : {-1.0, 147.5, static_cast<double>(NAN)}) {
    r.set_break_value(bad);
    const std::vector<FieldError> errors = ValidatePlanRequest(r, physics::DefaultTable());
    ASSERT_EQ(errors.size(), 1u) << bad;
    EXPECT_EQ(errors[0].field, "break_value");
    EXPECT_EQ(errors[0].rule, "must be in [0, 147] points");
  }
  r.set_break_value(-1);
  EXPECT_EQ(ValidatePlanRequest(r, physics::DefaultTable())[0].value, "-1");
}

TEST(ValidatePlanRequestTest, ThePositionSpreadIsInStandardDeviations) {
  v1::PlanRequest r = ObviousPot();
  for (const double ok : {0.0, 2.0, 4.0}) {
    r.set_position_spread(ok);
    EXPECT_TRUE(ValidatePlanRequest(r, physics::DefaultTable()).empty()) << ok;
  }
  for (const double bad : {-0.5, 4.5, static_cast<double>(NAN), static_cast<double>(INFINITY)}) {
    r.set_position_spread(bad);
    const std::vector<FieldError> errors = ValidatePlanRequest(r, physics::DefaultTable());
    ASSERT_EQ(errors.size(), 1u) << bad;
    EXPECT_EQ(errors[0].field, "position_spread");
    EXPECT_EQ(errors[0].rule, "must be in [0, 4]");
  }
  r.set_position_spread(4.5);
  EXPECT_EQ(ValidatePlanRequest(r, physics::DefaultTable())[0].value, "4.5");
}

// kinds and routes take the API's values, *_UNSPECIFIED excepted: a bad entry is
// named by its index, with its name or, when it names no value, its number.
TEST(ValidatePlanRequestTest, KindsAndRoutesNameEachBadEntry) {
  v1::PlanRequest r = ObviousPot();
  r.add_kinds(v1::POT);
  r.add_kinds(v1::SHOT_KIND_UNSPECIFIED);
  r.add_kinds(static_cast<v1::ShotKind>(42));
  r.add_routes(v1::POT_ROUTE_UNSPECIFIED);
  r.add_routes(v1::KICK);
  const std::vector<FieldError> errors = ValidatePlanRequest(r, physics::DefaultTable());
  ASSERT_EQ(Fields(errors), (std::vector<std::string>{"kinds[1]", "kinds[2]", "routes[0]"})) << Describe(errors);
  EXPECT_EQ(errors[0].value, "SHOT_KIND_UNSPECIFIED");
  EXPECT_EQ(errors[0].rule, "must be POT, SAFETY, ESCAPE, BREAK_OFF or FOUL");
  EXPECT_EQ(errors[1].value, "42");
  EXPECT_EQ(errors[2].value, "POT_ROUTE_UNSPECIFIED");
  EXPECT_EQ(errors[2].rule, "must be DIRECT, PLANT, DOUBLE or KICK");
  // Every named value is accepted, repeated or not.
  v1::PlanRequest all = ObviousPot();
  for (const v1::ShotKind k : {v1::POT, v1::SAFETY, v1::ESCAPE, v1::BREAK_OFF, v1::FOUL, v1::POT}) all.add_kinds(k);
  for (const v1::PotRoute k : {v1::DIRECT, v1::PLANT, v1::DOUBLE, v1::KICK}) all.add_routes(k);
  EXPECT_TRUE(ValidatePlanRequest(all, physics::DefaultTable()).empty());
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
  EXPECT_NE(d.find("table.balls = 0 CUE balls (must have exactly one, or none with cue_in_hand set"), std::string::npos)
      << d;
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
  EXPECT_FALSE(d.break_value.has_value());
  r.set_break_value(100);
  EXPECT_EQ(PlanRequestFrom(r).break_value, 100);
  EXPECT_FALSE(d.position_spread.has_value());
  r.set_position_spread(2);
  EXPECT_EQ(PlanRequestFrom(r).position_spread, 2);
  const planner::PlanRequest in_hand = PlanRequestFrom(ObviousPotInHand());
  EXPECT_TRUE(in_hand.cue_in_hand);
  EXPECT_EQ(in_hand.table.balls.size(), 2u);
}

// Empty kinds and routes are every one, lookahead unset is on and the thin break-off
// unset is the server's choice; given, they are exactly what was asked for
// (direct-pots' request: pots, direct, one-ply).
TEST(PlanRequestFromTest, KindsRoutesLookaheadAndTheThinBreakOff) {
  const planner::PlanRequest d = PlanRequestFrom(ObviousPot());
  EXPECT_EQ(d.kinds, planner::ShotKinds{});
  EXPECT_EQ(d.routes, planner::PotRoutes{});
  EXPECT_TRUE(d.lookahead);
  EXPECT_FALSE(d.thin_break_off.has_value());  // the server's configuration
  v1::PlanRequest r = ObviousPot();
  r.add_kinds(v1::POT);
  r.add_routes(v1::DIRECT);
  r.set_lookahead(false);
  r.set_thin_break_off(false);
  const planner::PlanRequest p = PlanRequestFrom(r);
  EXPECT_EQ(p.kinds, planner::ShotKinds::Of(planner::ShotKind::kPot));
  EXPECT_EQ(p.routes, planner::PotRoutes::Of(planner::PotRoute::kDirect));
  EXPECT_FALSE(p.lookahead);
  EXPECT_EQ(p.thin_break_off, std::optional<bool>(false));
  r.set_thin_break_off(true);
  EXPECT_EQ(PlanRequestFrom(r).thin_break_off, std::optional<bool>(true));
  r.add_kinds(v1::SAFETY);
  r.add_kinds(v1::POT);
  r.add_routes(v1::KICK);
  const planner::PlanRequest more = PlanRequestFrom(r);
  EXPECT_EQ(more.kinds, planner::ShotKinds::Of(planner::ShotKind::kPot).With(planner::ShotKind::kSafety));
  EXPECT_EQ(more.routes, planner::PotRoutes::Of(planner::PotRoute::kDirect).With(planner::PotRoute::kKick));
  // Each planner kind and route has its API value, and back.
  for (int k = 0; k < planner::kShotKindCount; ++k) {
    const auto kind = static_cast<planner::ShotKind>(k);
    EXPECT_EQ(ShotKindFrom(ToProto(kind)), kind) << planner::ToString(kind);
  }
  for (int k = 0; k < planner::kPotRouteCount; ++k) {
    const auto route = static_cast<planner::PotRoute>(k);
    EXPECT_EQ(PotRouteFrom(ToProto(route)), route) << planner::ToString(route);
  }
  EXPECT_FALSE(ShotKindFrom(v1::SHOT_KIND_UNSPECIFIED).has_value());
  EXPECT_FALSE(PotRouteFrom(v1::POT_ROUTE_UNSPECIFIED).has_value());
}

// A plan returns only the kinds and routes asked for: safeties alone where a pot is
// near certain, and pots alone by their route; none, saying why, when the table
// offers none of them.
TEST(PlanTest, ReturnsOnlyTheKindsAndRoutesAskedFor) {
  v1::PlanRequest r = ObviousPot();
  r.set_max_shots(5);
  r.add_kinds(v1::SAFETY);
  v1::PlanResponse safeties;
  ASSERT_TRUE(Plan(r, &safeties).ok());
  ASSERT_GT(safeties.shots_size(), 0) << safeties.reason();
  for (const v1::PlannedShot& s : safeties.shots()) EXPECT_EQ(s.kind(), v1::SAFETY) << s.ShortDebugString();
  r.clear_kinds();
  r.add_kinds(v1::POT);
  r.add_routes(v1::DIRECT);
  r.set_lookahead(false);
  v1::PlanResponse pots;
  ASSERT_TRUE(Plan(r, &pots).ok());
  ASSERT_GT(pots.shots_size(), 0) << pots.reason();
  for (const v1::PlannedShot& s : pots.shots()) {
    EXPECT_EQ(s.kind(), v1::POT) << s.ShortDebugString();
    EXPECT_EQ(s.route(), v1::DIRECT) << s.ShortDebugString();
  }
  // Kinds and routes this table does not offer (it is no break-off, and its one red
  // has no plant): no shot, and the reason names what was asked for.
  r.clear_kinds();
  r.clear_routes();
  r.add_kinds(v1::BREAK_OFF);
  v1::PlanResponse none;
  ASSERT_TRUE(Plan(r, &none).ok());
  EXPECT_EQ(none.shots_size(), 0);
  EXPECT_EQ(none.reason(), "no pot: no candidate for the ball on (red) among the shots asked for (kinds BREAK_OFF)");
  r.clear_kinds();
  r.add_kinds(v1::POT);
  r.add_routes(v1::PLANT);
  ASSERT_TRUE(Plan(r, &none).ok());
  EXPECT_EQ(none.shots_size(), 0);
  EXPECT_EQ(none.reason(),
            "no pot: no candidate for the ball on (red) among the shots asked for (kinds POT; routes PLANT)");
}

// The robot's cue-term limits hold for every shot answered, whichever search found
// it: the fallback's scan of headings once played a stroke at 1.8 m/s of cue speed on
// a table whose cue ball had no pot, for a robot whose cue goes no faster than 0.3.
TEST(PlanTest, EveryShotKeepsToTheRobotsCueSpeedAndElevation) {
  v1::PlanRequest scan;
  AddBall(&scan, "cue", v1::CUE, 0.9, 2.6);
  AddBall(&scan, "red-1", v1::RED, 1.3, 3.2);
  AddBall(&scan, "black", v1::BLACK, 0.889, 3.245);
  AddBall(&scan, "red-2", v1::RED, 0.3, 1.5);
  struct Limits {
    double min_cue_speed, max_cue_speed, max_elevation_deg;
  };
  for (v1::PlanRequest r : {scan, ObviousPot()}) {
    r.set_seed(1);
    r.set_time_budget_ms(60000);
    r.set_max_simulations(400);
    r.set_max_shots(5);
    for (const Limits l : {Limits{0.1, 0.3, 25}, Limits{0.1, 0.5, 0}, Limits{4.0, 4.1, 25}, Limits{0.1, 5.0, 0}}) {
      r.mutable_limits()->set_min_cue_speed(l.min_cue_speed);
      r.mutable_limits()->set_max_cue_speed(l.max_cue_speed);
      r.mutable_limits()->set_max_elevation_deg(l.max_elevation_deg);
      v1::PlanResponse resp;
      ASSERT_TRUE(Plan(r, &resp).ok());
      for (const v1::PlannedShot& s : resp.shots()) {
        EXPECT_GE(s.cue().speed(), l.min_cue_speed) << s.ShortDebugString();
        EXPECT_LE(s.cue().speed(), l.max_cue_speed) << s.ShortDebugString();
        EXPECT_LE(s.cue().elevation_deg(), l.max_elevation_deg + 1e-9) << s.ShortDebugString();
      }
      if (resp.shots_size() == 0) {
        EXPECT_FALSE(resp.reason().empty());
      }
      // Within the default cue-speed range both tables have a shot, level.
      if (l.max_cue_speed == 5.0) {
        EXPECT_GT(resp.shots_size(), 0) << resp.reason();
      }
    }
  }
}

// A cue ball in a ring of six reds 0.5 mm off: no direct pot survives pruning, and
// the fallback's scan finds a stroke that pots a red. The answer is that pot, and its
// reason no longer says "no pot" beside it.
TEST(PlanTest, AStrokeThatPotsIsNotAnsweredWithNoPotAsItsReason) {
  v1::PlanRequest r;
  const double radius = physics::BallParams{}.radius;
  AddBall(&r, "cue", v1::CUE, 0.9, 1.6);
  for (int i = 0; i < 6; ++i) {
    const double a = i * physics::kPi / 3 + 0.2;
    AddBall(&r, "r" + std::to_string(i), v1::RED, 0.9 + 2.02 * radius * std::cos(a), 1.6 + 2.02 * radius * std::sin(a));
  }
  AddBall(&r, "black", v1::BLACK, 0.889, 3.245);
  r.set_seed(1);
  r.set_time_budget_ms(60000);
  r.set_max_simulations(400);
  v1::PlanResponse resp;
  ASSERT_TRUE(Plan(r, &resp).ok());
  ASSERT_GT(resp.shots_size(), 0) << resp.reason();
  if (resp.shots(0).kind() == v1::FOUL) {
    EXPECT_NE(resp.reason().find("the foul that costs least"), std::string::npos) << resp.reason();
  } else {
    EXPECT_EQ(resp.reason(), "") << resp.shots(0).ShortDebugString();
  }
}

// A ball stopped on a pocket's lip, past the line of the cushion noses, is where the
// simulator leaves one; a table with it is planned from. The red there is the easy
// pot it is, and a cue ball there still gets a stroke.
TEST(PlanTest, ABallOnAPocketsLipIsPlannedFrom) {
  const physics::TableModel& table = physics::DefaultTable();
  const physics::Pocket& middle = table.pocket(physics::PocketId::kMiddleLeft);
  const physics::Vec2 lip = middle.mouth_centre + 0.003 * middle.axis;
  ASSERT_TRUE(table.InPocketMouth(lip));
  const physics::Vec2 black = table.spot(physics::Colour::kBlack);
  v1::PlanRequest red_on_lip;
  AddBall(&red_on_lip, "cue", v1::CUE, 0.6, 1.2);
  AddBall(&red_on_lip, "red-1", v1::RED, lip.x(), lip.y());
  AddBall(&red_on_lip, "black", v1::BLACK, black.x(), black.y());
  v1::PlanRequest cue_on_lip;
  AddBall(&cue_on_lip, "cue", v1::CUE, lip.x(), lip.y());
  AddBall(&cue_on_lip, "red-1", v1::RED, 0.9, 2.5);
  AddBall(&cue_on_lip, "black", v1::BLACK, black.x(), black.y());
  for (v1::PlanRequest* r : {&red_on_lip, &cue_on_lip}) {
    r->set_seed(1);
    r->set_time_budget_ms(60000);
    r->set_max_simulations(600);
    v1::PlanResponse resp;
    const ApiStatus st = Plan(*r, &resp);
    ASSERT_TRUE(st.ok()) << st.message;
    ASSERT_GT(resp.shots_size(), 0) << resp.reason();
    for (const v1::PlannedShot& s : resp.shots()) {
      EXPECT_TRUE(std::isfinite(s.expected_points()) && std::isfinite(s.speed())) << s.ShortDebugString();
    }
  }
  v1::PlanResponse pot;
  ASSERT_TRUE(Plan(red_on_lip, &pot).ok());
  EXPECT_EQ(pot.shots(0).kind(), v1::POT) << pot.shots(0).ShortDebugString();
  EXPECT_EQ(pot.shots(0).object_ball(), "red-1");
  EXPECT_GT(pot.shots(0).pot_probability(), 0.9) << pot.shots(0).ShortDebugString();
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
  // The first contact, by the tables' ids (a slide-to-roll transition may come first).
  const v1::Event* contact = nullptr;
  for (const v1::Event& e : s.events()) {
    if (e.kind() == v1::BALL_BALL) {
      contact = &e;
      break;
    }
  }
  ASSERT_NE(contact, nullptr);
  EXPECT_EQ(contact->balls(0), "white");
  EXPECT_EQ(contact->balls(1), "r7");
  EXPECT_EQ(s.first_ball(), "r7");
  bool potted = false;
  for (const v1::Event& e : s.events()) potted = potted || (e.kind() == v1::POCKET && e.pocket() == "top-right");
  EXPECT_TRUE(potted);
  EXPECT_GT(resp.simulations(), 0);
  EXPECT_GT(resp.elapsed_ms(), 0);
  EXPECT_GT(progress, 0);
  // The cue ball was on the table: a pot by a route, and no placement.
  EXPECT_EQ(s.kind(), v1::POT);
  EXPECT_NE(s.route(), v1::POT_ROUTE_UNSPECIFIED);
  EXPECT_FALSE(s.has_cue_ball_start());
  EXPECT_GE(s.foul_probability(), 0);
  EXPECT_LE(s.foul_probability(), 1);
}

// The planner's answer with the cue ball in hand; until the planner places it, a
// table without a cue ball may be answered with no shot, so the shots' assertions
// hold for whatever shots there are.
TEST(PlanTest, WithTheCueBallInHandEachShotPlacesItInTheD) {
  const v1::PlanRequest request = ObviousPotInHand();
  v1::PlanResponse resp;
  const ApiStatus st = Plan(request, &resp);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_TRUE(resp.final());
  if (resp.shots_size() == 0) {
    EXPECT_NE(resp.reason(), "");
  }
  for (const v1::PlannedShot& s : resp.shots()) {
    ASSERT_TRUE(s.has_cue_ball_start());
    EXPECT_TRUE(InTheD(s.cue_ball_start())) << s.cue_ball_start().ShortDebugString();
    EXPECT_NE(s.kind(), v1::SHOT_KIND_UNSPECIFIED);
    EXPECT_NE(s.first_ball(), "cue");
    ASSERT_GT(s.events_size(), 0);
    bool cue_moved = false;
    for (const v1::Event& e : s.events()) {
      for (const std::string& ball : e.balls()) {
        EXPECT_TRUE(ball == "cue" || ball == "r7" || ball == "the-black") << ball;
        cue_moved = cue_moved || ball == "cue";
      }
    }
    EXPECT_TRUE(cue_moved);
    if (s.balls_end_size() > 0) {
      ASSERT_EQ(s.balls_end_size(), 3);
      EXPECT_EQ(s.balls_end(0).ball(), "r7");
      EXPECT_EQ(s.balls_end(2).ball(), "cue");
    }
  }
}

TEST(PlanTest, ACueBallVisionSawOverlappingARedIsRepairedToTouchItAndPlaysAway) {
  // Vision put the cue ball 0.5 mm into red r7: the repair moves them apart to an
  // exact touch, and the touching-ball rule then has the cue ball play away from r7.
  v1::PlanRequest r = ObviousPot();
  const v1::Vec2 red = r.table().balls(1).position();
  const double x = red.x() - (2 * 0.02625 - 0.5e-3);
  r.mutable_table()->mutable_balls(0)->mutable_position()->set_x(x);
  r.mutable_table()->mutable_balls(0)->mutable_position()->set_y(red.y());
  v1::PlanResponse resp;
  PlanControl control;
  control.vision_tolerance_mm = 1;
  const ApiStatus st = Plan(r, &resp, control);
  ASSERT_TRUE(st.ok()) << st.message;
  ASSERT_EQ(resp.warnings_size(), 2);  // both balls moved by the least distance
  ASSERT_GT(resp.shots_size(), 0) << resp.reason();
  for (const v1::PlannedShot& s : resp.shots()) {
    // Away from the red: the heading's component towards it is not positive.
    const double h = s.heading_deg() * physics::kPi / 180;
    EXPECT_LE(std::cos(h), 1e-9) << s.heading_deg();
    EXPECT_GE(s.foul_probability(), 0);
  }
}

// Each probability of a shot is a count of its Monte Carlo runs, and the shots come
// best first by what they are worth in points: on a table with pots and on one with
// the black between the cue ball and the red, where an escape is ranked among them.
TEST(PlanTest, ShotsComeRankedByExpectedPointsAndTheirProbabilitiesCountTheRuns) {
  v1::PlanRequest snookered = ObviousPot();
  const v1::Vec2 cue = snookered.table().balls(0).position(), red = snookered.table().balls(1).position();
  snookered.mutable_table()->mutable_balls(2)->mutable_position()->set_x((cue.x() + red.x()) / 2);
  snookered.mutable_table()->mutable_balls(2)->mutable_position()->set_y((cue.y() + red.y()) / 2);
  for (const bool behind_the_black : {false, true}) {
    v1::PlanRequest request = behind_the_black ? snookered : ObviousPot();
    std::set<v1::ShotKind> kinds;
    request.set_max_shots(4);
    v1::PlanResponse resp;
    const ApiStatus st = Plan(request, &resp);
    ASSERT_TRUE(st.ok()) << st.message;
    ASSERT_GT(resp.shots_size(), 0) << resp.reason();
    for (int k = 0; k < resp.shots_size(); ++k) {
      const v1::PlannedShot& s = resp.shots(k);
      SCOPED_TRACE(testing::Message() << "shot " << k << ", " << v1::ShotKind_Name(s.kind()));
      kinds.insert(s.kind());
      ASSERT_GT(s.monte_carlo_samples(), 0);
      EXPECT_LE(s.monte_carlo_samples(), request.monte_carlo_samples());
      for (const double p : {s.pot_probability(), s.pocket_probability(), s.foul_probability()}) {
        const double runs = p * s.monte_carlo_samples();
        EXPECT_NEAR(runs, std::round(runs), 1e-9) << p;
      }
      EXPECT_TRUE(std::isfinite(s.expected_points()));
      // The runs that hand the table over are among those that did not pot.
      ASSERT_TRUE(s.has_handovers());
      const double pots = s.kind() == v1::POT ? s.pot_probability() * s.monte_carlo_samples() : 0;
      EXPECT_LE(s.handovers().runs() + std::lround(pots), s.monte_carlo_samples());
      EXPECT_LE(s.handovers().snookered_runs(), s.handovers().runs());
      if (k > 0) {
        EXPECT_LE(s.expected_points(), resp.shots(k - 1).expected_points());
      }
    }
    // A sure pot of a red, the black to follow: worth at least the red.
    if (resp.shots(0).kind() == v1::POT && resp.shots(0).pot_probability() == 1) {
      EXPECT_GE(resp.shots(0).expected_points(), 1);
    }
    // Behind the black, pots and another kind share one ranking.
    if (behind_the_black) {
      EXPECT_TRUE(kinds.count(v1::POT) == 1 && kinds.size() > 1);
    }
  }
}

TEST(PlanTest, BadRequestIsInvalidArgument) {
  v1::PlanRequest r = ObviousPot();
  r.set_max_shots(99);
  v1::PlanResponse resp;
  const ApiStatus st = Plan(r, &resp);
  EXPECT_EQ(st.code, ApiStatus::Code::kInvalidArgument);
  EXPECT_NE(st.message.find("max_shots = 99"), std::string::npos) << st.message;
}

// Index of `id`'s pocket in the default table's pockets (a kPocket event's `where`).
std::int16_t PocketIndex(physics::PocketId id) {
  const auto& pockets = physics::DefaultTable().pockets();
  for (std::size_t i = 0; i < pockets.size(); ++i) {
    if (pockets[i].id == id) return static_cast<std::int16_t>(i);
  }
  return -1;
}

physics::SimEvent Event(physics::EventKind kind, int ball, int other, int where) {
  physics::SimEvent e;
  e.kind = kind;
  e.ball = static_cast<std::int16_t>(ball);
  e.other = static_cast<std::int16_t>(other);
  e.where = static_cast<std::int16_t>(where);
  return e;
}

// A response in Protobuf's JSON form (as `snooker plan --json` prints it), parsed.
google::protobuf::Struct Json(const v1::PlanResponse& response) {
  google::protobuf::util::JsonPrintOptions options;
  options.always_print_primitive_fields = true;
  std::string text;
  EXPECT_TRUE(google::protobuf::util::MessageToJsonString(response, &text, options).ok());
  google::protobuf::Struct json;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(text, &json).ok()) << text;
  return json;
}

std::set<std::string> Keys(const google::protobuf::Struct& s) {
  std::set<std::string> keys;
  for (const auto& [name, value] : s.fields()) keys.insert(name);
  return keys;
}

const google::protobuf::Struct& ShotOf(const google::protobuf::Struct& json, int k) {
  return json.fields().at("shots").list_value().values(k).struct_value();
}

std::string Text(const google::protobuf::Struct& s, const char* key) { return s.fields().at(key).string_value(); }

TEST(PlanConvertTest, EachKindOfShotInTheApisNames) {
  v1::TableState table;
  testing_requests::AddBall(&table, "white", v1::CUE, 0.9, 0.6);
  testing_requests::AddBall(&table, "r7", v1::RED, 1.4, 3.2);
  testing_requests::AddBall(&table, "r8", v1::RED, 1.3, 3.0);
  testing_requests::AddBall(&table, "the-black", v1::BLACK, 0.889, 3.24);
  planner::PlanAnswer answer;
  planner::PlannedShot plant;  // r8 pots r7 into the top-left pocket
  plant.kind = planner::ShotKind::kPot;
  plant.route = planner::PotRoute::kPlant;
  plant.object_ball = 1;
  plant.first_ball = 2;
  plant.pocket = physics::PocketId::kTopLeft;
  plant.foul_probability = 0.125;
  plant.score = 61.5;
  plant.monte_carlo_samples = 8;
  plant.handovers = planner::Handovers{3, 1, 0.75, 20.5};  // 3 of the 8 runs missed
  plant.next_ball = 3;
  plant.balls_end = {{physics::Vec2(1.0, 1.0), std::nullopt},
                     {physics::Vec2(0.05, 3.52), physics::PocketId::kTopLeft},
                     {physics::Vec2(1.2, 2.9), std::nullopt},
                     {physics::Vec2(0.889, 3.24), std::nullopt}};
  planner::PlannedShot safety;  // a route and a pocket that a safety does not have
  safety.kind = planner::ShotKind::kSafety;
  safety.route = planner::PotRoute::kDouble;
  safety.object_ball = 2;
  safety.first_ball = 2;
  safety.pocket = physics::PocketId::kMiddleLeft;
  safety.foul_probability = 0.25;
  safety.opponent = planner::OpponentLeave{0.125, 4.5, true, 0.375, 5};
  planner::PlannedShot escape;  // the cue ball hits nothing
  escape.kind = planner::ShotKind::kEscape;
  escape.object_ball = 1;
  escape.first_ball = -1;
  escape.foul_probability = 1;
  planner::PlannedShot foul;  // nominates the black, hits r8 first
  foul.kind = planner::ShotKind::kFoul;
  foul.object_ball = 3;
  foul.first_ball = 2;
  foul.foul_probability = 0.875;
  answer.shots = {plant, safety, escape, foul};
  v1::PlanResponse response;
  ToProto(answer, table, physics::DefaultTable(), &response);
  ASSERT_EQ(response.shots_size(), 4);

  const v1::PlannedShot& p = response.shots(0);
  EXPECT_EQ(p.kind(), v1::POT);
  EXPECT_EQ(p.route(), v1::PLANT);
  EXPECT_EQ(p.object_ball(), "r7");
  EXPECT_EQ(p.first_ball(), "r8");
  EXPECT_EQ(p.pocket(), "top-left");
  EXPECT_EQ(p.next_ball(), "the-black");
  EXPECT_DOUBLE_EQ(p.foul_probability(), 0.125);
  EXPECT_DOUBLE_EQ(p.expected_points(), 61.5);
  EXPECT_EQ(p.monte_carlo_samples(), 8);
  ASSERT_TRUE(p.has_handovers());
  EXPECT_EQ(p.handovers().runs(), 3);
  EXPECT_EQ(p.handovers().snookered_runs(), 1);
  EXPECT_DOUBLE_EQ(p.handovers().mean_pot_probability(), 0.75);
  EXPECT_DOUBLE_EQ(p.handovers().mean_expected_points(), 20.5);
  EXPECT_FALSE(p.has_cue_ball_start());
  ASSERT_EQ(p.balls_end_size(), 4);
  EXPECT_EQ(p.balls_end(0).ball(), "white");
  EXPECT_EQ(p.balls_end(1).ball(), "r7");
  EXPECT_EQ(p.balls_end(1).pocket(), "top-left");
  EXPECT_DOUBLE_EQ(p.balls_end(1).position().y(), 3.52);
  EXPECT_EQ(p.balls_end(2).pocket(), "");
  EXPECT_DOUBLE_EQ(p.balls_end(2).position().x(), 1.2);

  const v1::PlannedShot& s = response.shots(1);
  EXPECT_EQ(s.kind(), v1::SAFETY);
  EXPECT_EQ(s.route(), v1::POT_ROUTE_UNSPECIFIED);  // for pots only
  EXPECT_EQ(s.pocket(), "");
  EXPECT_EQ(s.object_ball(), "r8");
  EXPECT_EQ(s.first_ball(), "r8");
  EXPECT_DOUBLE_EQ(s.foul_probability(), 0.25);
  ASSERT_TRUE(s.has_opponent());
  EXPECT_DOUBLE_EQ(s.opponent().pot_probability(), 0.125);
  EXPECT_DOUBLE_EQ(s.opponent().expected_points(), 4.5);
  EXPECT_TRUE(s.opponent().snookered());
  EXPECT_DOUBLE_EQ(s.opponent().foul_probability(), 0.375);
  EXPECT_DOUBLE_EQ(s.opponent().penalty_points(), 5);
  EXPECT_FALSE(p.has_opponent());
  EXPECT_FALSE(s.has_handovers()) << "no Monte Carlo ran for it";
  EXPECT_EQ(response.shots(2).kind(), v1::ESCAPE);
  EXPECT_EQ(response.shots(2).first_ball(), "");
  EXPECT_EQ(response.shots(3).kind(), v1::FOUL);
  EXPECT_EQ(response.shots(3).route(), v1::POT_ROUTE_UNSPECIFIED);
  EXPECT_EQ(response.shots(3).object_ball(), "the-black");
  EXPECT_EQ(response.shots(3).first_ball(), "r8");

  // The JSON names: the contract for tools outside the project.
  const google::protobuf::Struct json = Json(response);
  EXPECT_EQ(Keys(ShotOf(json, 0)),
            (std::set<std::string>{"speed", "headingDeg", "topspin", "sidespin", "cutDeg", "objectBall", "pocket",
                                   "potProbability", "pocketProbability", "positionValue", "nextBall",
                                   "cueBallEnd", "events", "kind", "route", "firstBall", "foulProbability",
                                   "ballsEnd", "swerveSpin", "cue", "expectedPoints", "monteCarloSamples",
                                   "handovers"}));
  EXPECT_EQ(Text(ShotOf(json, 0), "kind"), "POT");
  EXPECT_EQ(Text(ShotOf(json, 0), "route"), "PLANT");
  EXPECT_EQ(Text(ShotOf(json, 0), "firstBall"), "r8");
  EXPECT_EQ(ShotOf(json, 0).fields().at("foulProbability").number_value(), 0.125);
  EXPECT_EQ(ShotOf(json, 0).fields().at("expectedPoints").number_value(), 61.5);
  EXPECT_EQ(ShotOf(json, 0).fields().at("monteCarloSamples").number_value(), 8);
  EXPECT_EQ(Keys(ShotOf(json, 0).fields().at("handovers").struct_value()),
            (std::set<std::string>{"runs", "snookeredRuns", "meanPotProbability", "meanExpectedPoints"}));
  const google::protobuf::Struct& end = ShotOf(json, 0).fields().at("ballsEnd").list_value().values(1).struct_value();
  EXPECT_EQ(Keys(end), (std::set<std::string>{"ball", "position", "pocket"}));
  EXPECT_EQ(Text(end, "ball"), "r7");
  EXPECT_EQ(Text(end, "pocket"), "top-left");
  EXPECT_EQ(Keys(end.fields().at("position").struct_value()), (std::set<std::string>{"x", "y"}));
  EXPECT_EQ(Text(ShotOf(json, 1), "kind"), "SAFETY");
  EXPECT_EQ(Keys(ShotOf(json, 1).fields().at("opponent").struct_value()),
            (std::set<std::string>{"potProbability", "expectedPoints", "snookered", "foulProbability", "penaltyPoints"}));
  EXPECT_EQ(Text(ShotOf(json, 1), "route"), "POT_ROUTE_UNSPECIFIED");
  EXPECT_EQ(Text(ShotOf(json, 2), "kind"), "ESCAPE");
  EXPECT_EQ(Text(ShotOf(json, 3), "kind"), "FOUL");
  EXPECT_EQ(ShotOf(json, 3).fields().at("foulProbability").number_value(), 0.875);
}

TEST(PlanConvertTest, TheCueBallPlacedFromHandIsNamedCue) {
  v1::TableState table;  // no cue ball: it is in hand
  testing_requests::AddBall(&table, "red-1", v1::RED, 0.889, 2.0);
  testing_requests::AddBall(&table, "red-2", v1::RED, 0.95, 2.1);
  planner::PlannedShot s;
  s.kind = planner::ShotKind::kBreakOff;
  s.cue_start = physics::Vec2(0.8, 0.6);
  s.object_ball = 0;
  s.first_ball = 0;
  s.cue_ball_end = physics::Vec2(0.5, 1.5);
  // The cue ball (index 2, after the table's balls) hits red-1, which drops top-right.
  s.events = {Event(physics::EventKind::kBallBall, 0, 2, -1),
              Event(physics::EventKind::kTransition, 2, -1, -1),
              Event(physics::EventKind::kPocket, 0, -1, PocketIndex(physics::PocketId::kTopRight))};
  s.balls_end = {{physics::Vec2(1.75, 3.54), physics::PocketId::kTopRight},
                 {physics::Vec2(0.95, 2.1), std::nullopt},
                 {physics::Vec2(0.5, 1.5), std::nullopt}};
  planner::PlannedShot kick = s;
  kick.kind = planner::ShotKind::kPot;
  kick.route = planner::PotRoute::kKick;
  kick.cue_start = physics::Vec2(1.0, 0.5);
  kick.pocket = physics::PocketId::kTopRight;
  planner::PlanAnswer answer;
  answer.shots = {s, kick};
  v1::PlanResponse response;
  ToProto(answer, table, physics::DefaultTable(), &response);
  ASSERT_EQ(response.shots_size(), 2);
  const v1::PlannedShot& b = response.shots(0);
  EXPECT_EQ(b.kind(), v1::BREAK_OFF);
  EXPECT_EQ(b.route(), v1::POT_ROUTE_UNSPECIFIED);
  ASSERT_TRUE(b.has_cue_ball_start());
  EXPECT_DOUBLE_EQ(b.cue_ball_start().x(), 0.8);
  EXPECT_DOUBLE_EQ(b.cue_ball_start().y(), 0.6);
  EXPECT_EQ(b.first_ball(), "red-1");
  ASSERT_EQ(b.events_size(), 3);
  ASSERT_EQ(b.events(0).balls_size(), 2);
  EXPECT_EQ(b.events(0).balls(0), "red-1");
  EXPECT_EQ(b.events(0).balls(1), "cue");
  EXPECT_EQ(b.events(1).balls(0), "cue");
  EXPECT_EQ(b.events(2).balls(0), "red-1");
  EXPECT_EQ(b.events(2).pocket(), "top-right");
  ASSERT_EQ(b.balls_end_size(), 3);
  EXPECT_EQ(b.balls_end(0).ball(), "red-1");
  EXPECT_EQ(b.balls_end(0).pocket(), "top-right");
  EXPECT_EQ(b.balls_end(2).ball(), "cue");
  EXPECT_DOUBLE_EQ(b.balls_end(2).position().y(), 1.5);
  const v1::PlannedShot& k = response.shots(1);
  EXPECT_EQ(k.kind(), v1::POT);
  EXPECT_EQ(k.route(), v1::KICK);
  EXPECT_EQ(k.pocket(), "top-right");
  EXPECT_DOUBLE_EQ(k.cue_ball_start().x(), 1.0);
  // The table itself is left as it was.
  EXPECT_EQ(table.balls_size(), 2);

  const google::protobuf::Struct json = Json(response);
  const google::protobuf::Struct& start = ShotOf(json, 0).fields().at("cueBallStart").struct_value();
  EXPECT_EQ(Keys(start), (std::set<std::string>{"x", "y"}));
  EXPECT_EQ(start.fields().at("x").number_value(), 0.8);
  EXPECT_EQ(Text(ShotOf(json, 0), "kind"), "BREAK_OFF");
  EXPECT_EQ(Text(ShotOf(json, 1), "route"), "KICK");
  const auto& ends = ShotOf(json, 0).fields().at("ballsEnd").list_value();
  EXPECT_EQ(Text(ends.values(2).struct_value(), "ball"), "cue");
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
      {"break_value", RangeText(lim::kBreakValue.lo, lim::kBreakValue.hi)},
      {"position_spread", RangeText(lim::kPositionSpread.lo, lim::kPositionSpread.hi)},
  };
  for (const auto& q : quoted) {
    const std::string comment = CommentAbove(proto, q.field);
    ASSERT_NE(comment, "") << q.field;
    EXPECT_NE(comment.find(q.range), std::string::npos) << q.field << " should quote " << q.range << ":\n" << comment;
  }
}

}  // namespace
}  // namespace snooker::server
