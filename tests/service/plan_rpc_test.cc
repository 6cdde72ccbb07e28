// Plan and PlanStream through an in-process server and real stubs: the
// answer within the request's limits and deterministic for a seed, the stream's
// progress and final message, each bad input with its status and message, the
// vision repair's warning, a deadline shorter than the budget, a cancelled call, a
// full server, and a shutdown with plans in flight.
//
// No test asserts a duration tighter than a generous bound that only proves there is
// no hang: a held plan has a 10 s budget and the bound is at most half of that.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <future>
#include <memory>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "physics/core/params.h"
#include "physics/table/table.h"
#include "planner/planner.h"
#include "server/metrics.h"
#include "server/plan_convert.h"
#include "server/server.h"
#include "snooker/v1/service.grpc.pb.h"
#include "tests/service/requests.h"
#include "tests/service/server_support.h"
#include "tests/support/text.h"

namespace snooker::server {
namespace {

using Clock = std::chrono::steady_clock;
using server_support::ShotsOf;
using std::chrono::milliseconds;

using testing_requests::AddBall;

// A red 40 cm before the top-right pocket on its axis, the cue ball 40 cm behind it,
// the black on its spot; the work capped in simulations (not by the budget), so the
// answer is the same for the same seed.
v1::PlanRequest ObviousPot() {
  const physics::TableModel& table = physics::DefaultTable();
  const physics::Pocket& p = table.pocket(physics::PocketId::kTopRight);
  const physics::Vec2 red = p.mouth_centre - 0.4 * p.axis;
  const physics::Vec2 cue = red - 0.4 * p.axis;
  const physics::Vec2 black = table.spot(physics::Colour::kBlack);
  v1::PlanRequest r;
  AddBall(&r, "cue", v1::CUE, cue.x(), cue.y());
  AddBall(&r, "red-1", v1::RED, red.x(), red.y());
  AddBall(&r, "black", v1::BLACK, black.x(), black.y());
  r.set_max_simulations(300);
  r.set_monte_carlo_samples(16);
  r.set_time_budget_ms(10'000);
  r.set_seed(7);
  v1::RobotLimits* l = r.mutable_limits();
  l->set_min_speed(0.5);
  l->set_max_speed(4.0);
  l->set_max_topspin_fraction(0.8);
  l->set_max_sidespin_fraction(0.3);
  return r;
}

// A plan that takes its whole (long) budget: 15 reds spread over the table, no
// simulation cap and the most Monte Carlo samples (9.2 s of a 10 s budget on the
// development machine, more on a sanitizer build: its time caps it).
v1::PlanRequest LongPlan(double budget_ms) {
  v1::PlanRequest r;
  AddBall(&r, "cue", v1::CUE, 0.889, 1.2);
  for (int i = 0; i < 15; ++i) {
    AddBall(&r, "red-" + std::to_string(i + 1), v1::RED, 0.3 + 0.59 * (i % 3), 1.6 + 0.35 * (i / 3));
  }
  r.set_time_budget_ms(budget_ms);
  r.set_max_simulations(100'000'000);
  r.set_monte_carlo_samples(100'000);
  r.set_max_shots(20);
  return r;
}

// Every shot inside the request's limits, every probability in [0, 1], every id one
// of the table's.
void ExpectWithinLimits(const v1::PlanRequest& request, const v1::PlanResponse& response) {
  const double radius = physics::BallParams{}.radius;
  const v1::RobotLimits& l = request.limits();
  const planner::RobotLimits defaults;  // the server's defaults are the planner's
  const double lo = l.has_min_speed() ? l.min_speed() : defaults.min_speed;
  const double hi = l.has_max_speed() ? l.max_speed() : defaults.max_speed;
  const double top = l.has_max_topspin_fraction() ? l.max_topspin_fraction() : defaults.max_topspin_fraction;
  const double side =
      l.has_max_sidespin_fraction() ? l.max_sidespin_fraction() : defaults.max_sidespin_fraction;
  for (const v1::PlannedShot& s : response.shots()) {
    EXPECT_GE(s.speed(), lo - 1e-9);
    EXPECT_LE(s.speed(), hi + 1e-9);
    const double rolling = s.speed() / radius;
    EXPECT_LE(std::abs(s.topspin()), top * rolling * (1 + 1e-9) + 1e-9);
    EXPECT_LE(std::abs(s.sidespin()), side * rolling * (1 + 1e-9) + 1e-9);
    EXPECT_GE(s.pot_probability(), 0);
    EXPECT_LE(s.pot_probability(), 1);
    EXPECT_GE(s.foul_probability(), 0);
    EXPECT_LE(s.foul_probability(), 1);
    EXPECT_NE(s.kind(), v1::SHOT_KIND_UNSPECIFIED);
    EXPECT_EQ(s.route() != v1::POT_ROUTE_UNSPECIFIED, s.kind() == v1::POT);
    EXPECT_EQ(s.has_cue_ball_start(), request.cue_in_hand());
    EXPECT_TRUE(std::isfinite(s.heading_deg()));
    bool known = false;
    for (const v1::Ball& b : request.table().balls()) known = known || b.id() == s.object_ball();
    EXPECT_TRUE(known) << s.object_ball();
  }
}

class PlanRpcTest : public testing::Test {
 protected:
  void StartServer(ServerOptions options = {}) {
    test_server_ = std::make_unique<server_support::TestServer>(options);
    ASSERT_NE(test_server_->server, nullptr);
    server_ = test_server_->server.get();
    stub_ = test_server_->stub.get();
  }
  std::string Log() const { return test_server_->log.str(); }

  grpc::Status Plan(const v1::PlanRequest& request, v1::PlanResponse* response,
                    std::optional<milliseconds> deadline = std::nullopt) {
    grpc::ClientContext ctx;
    if (deadline) ctx.set_deadline(std::chrono::system_clock::now() + *deadline);
    return stub_->Plan(&ctx, request, response);
  }

  // Waits (at most 20 s) until `n` plans are running in the server.
  bool WaitUntilPlanning(std::int64_t n) {
    const auto give_up = Clock::now() + std::chrono::seconds(20);
    while ((server_->counts().plans < n || server_->counts().running < n) && Clock::now() < give_up) {
      std::this_thread::sleep_for(milliseconds(2));
    }
    return server_->counts().plans >= n;
  }

  // Waits (at most 30 s) until the server has answered every call it received.
  void WaitUntilIdle() {
    EXPECT_EQ(server_support::WaitUntilAnswered(*server_, 0, std::chrono::seconds(30)).in_flight(), 0);
  }

  std::unique_ptr<server_support::TestServer> test_server_;
  Server* server_ = nullptr;
  v1::ShotPlanner::Stub* stub_ = nullptr;
};

// A plan in flight through the callback stub; its status once answered.
struct AsyncPlan {
  AsyncPlan(v1::ShotPlanner::Stub* stub, const v1::PlanRequest& request) : request_(request) {
    stub->async()->Plan(&context, &request_, &response,
                        [this](grpc::Status s) { done.set_value(std::move(s)); });
  }
  ~AsyncPlan() {
    if (!waited_) Wait();  // the callback uses this object
  }
  grpc::Status Wait() {
    waited_ = true;
    auto f = done.get_future();
    EXPECT_EQ(f.wait_for(std::chrono::seconds(60)), std::future_status::ready);
    return f.get();
  }
  grpc::ClientContext context;
  v1::PlanResponse response;
  std::promise<grpc::Status> done;

 private:
  v1::PlanRequest request_;
  bool waited_ = false;
};

TEST_F(PlanRpcTest, PlansShotsWithinTheLimitsTheSameForTheSameSeed) {
  StartServer();
  const v1::PlanRequest request = ObviousPot();
  v1::PlanResponse a, b;
  const grpc::Status st = Plan(request, &a);
  ASSERT_TRUE(st.ok()) << st.error_message();
  ASSERT_GT(a.shots_size(), 0) << a.reason();
  EXPECT_EQ(a.shots(0).object_ball(), "red-1");
  EXPECT_EQ(a.shots(0).pocket(), "top-right");
  EXPECT_TRUE(a.final());
  EXPECT_EQ(a.warnings_size(), 0);
  EXPECT_GT(a.simulations(), 0);
  EXPECT_EQ(a.simulation_cap(), 300);  // the request's max_simulations
  EXPECT_FALSE(a.cut_short());
  ExpectWithinLimits(request, a);
  ASSERT_TRUE(Plan(request, &b).ok());
  EXPECT_EQ(ShotsOf(a), ShotsOf(b));
  WaitUntilIdle();
  const std::string log = Log();
  EXPECT_TRUE(Mentions(log, "method=Plan peer=ipv4:127.0.0.1:")) << log;
  EXPECT_TRUE(Mentions(log, "status=OK")) << log;
  EXPECT_TRUE(Mentions(log, "simulations=" + std::to_string(a.simulations()))) << log;
  EXPECT_FALSE(Mentions(log, "cut_short")) << log;
  EXPECT_EQ(server_->counts().plans_cut_short, 0);
}

TEST_F(PlanRpcTest, PlanStreamSendsProgressThenTheFinalAnswerAsPlanGivesIt) {
  StartServer();
  const v1::PlanRequest request = ObviousPot();
  v1::PlanResponse unary;
  ASSERT_TRUE(Plan(request, &unary).ok());
  grpc::ClientContext ctx;
  auto reader = stub_->PlanStream(&ctx, request);
  std::vector<v1::PlanResponse> messages;
  v1::PlanResponse m;
  while (messages.size() < 1000 && reader->Read(&m)) messages.push_back(m);
  const grpc::Status st = reader->Finish();
  ASSERT_TRUE(st.ok()) << st.error_message();
  ASSERT_GE(messages.size(), 2u);
  for (std::size_t i = 0; i + 1 < messages.size(); ++i) {
    EXPECT_FALSE(messages[i].final());
    ASSERT_EQ(messages[i].shots_size(), 1);
    ExpectWithinLimits(request, messages[i]);
    // The best verified so far, before any Monte Carlo: its nominal run's worth.
    EXPECT_EQ(messages[i].shots(0).monte_carlo_samples(), 0);
    EXPECT_FALSE(messages[i].shots(0).has_handovers());
    EXPECT_TRUE(std::isfinite(messages[i].shots(0).expected_points()));
  }
  const v1::PlanResponse& last = messages.back();
  EXPECT_TRUE(last.final());
  EXPECT_EQ(ShotsOf(last), ShotsOf(unary));
  for (const v1::PlannedShot& shot : last.shots()) {
    EXPECT_GT(shot.monte_carlo_samples(), 0);
    EXPECT_TRUE(shot.has_handovers());
  }
  EXPECT_EQ(last.simulations(), unary.simulations());
  WaitUntilIdle();
  EXPECT_GE(server_->counts().progress_messages, 1);
  EXPECT_TRUE(Mentions(Log(), "method=PlanStream")) << Log();
}

struct BadPlan {
  const char* name;
  void (*edit)(v1::PlanRequest* r);
  const char* message;  // part of the status message: the field and its value
};

const BadPlan kBadPlans[] = {
    {"SixteenReds",
     [](v1::PlanRequest* r) {
       for (int i = 0; i < 16; ++i) AddBall(r, "r" + std::to_string(i), v1::RED, 0.2 + 0.08 * i, 1.0);
     },
     "table.balls = 17 (reds: at most 15)"},
    {"TwoBlacks", [](v1::PlanRequest* r) { AddBall(r, "black-2", v1::BLACK, 0.3, 0.3); },
     "table.balls = 2 (black balls: at most one)"},
    {"BallOnNotOnTheTable", [](v1::PlanRequest* r) { r->set_ball_on(v1::BALL_ON_PINK); },
     "ball_on = BALL_ON_PINK (no such ball on the table)"},
    {"MinSpeedAboveMaxSpeed",
     [](v1::PlanRequest* r) {
       r->mutable_limits()->set_min_speed(3);
       r->mutable_limits()->set_max_speed(2);
     },
     "limits.max_speed = 2 (must exceed limits.min_speed (3 m/s))"},
    {"NegativeNoise", [](v1::PlanRequest* r) { r->mutable_noise()->set_speed_sigma_fraction(-0.1); },
     "noise.speed_sigma_fraction = -0.1"},
    {"NanNoise", [](v1::PlanRequest* r) { r->mutable_noise()->set_heading_sigma_deg(NAN); },
     "noise.heading_sigma_deg = nan"},
    {"BudgetZero", [](v1::PlanRequest* r) { r->set_time_budget_ms(0); },
     "time_budget_ms = 0 (must be in [1, 10000] ms"},
    {"BudgetOverTheMaximum", [](v1::PlanRequest* r) { r->set_time_budget_ms(20'000); },
     "time_budget_ms = 20000 (must be in [1, 10000] ms"},
    {"VisionToleranceOverTheServers", [](v1::PlanRequest* r) { r->set_vision_tolerance_mm(5); },
     "vision_tolerance_mm = 5"},
    {"BeyondTheVisionTolerance",
     [](v1::PlanRequest* r) {  // the black 3 mm into red-1
       const v1::Vec2 red = r->table().balls(1).position();
       r->mutable_table()->mutable_balls(2)->mutable_position()->set_x(red.x() + 0.0525 - 0.003);
       r->mutable_table()->mutable_balls(2)->mutable_position()->set_y(red.y());
     },
     "beyond the vision tolerance of 1 mm"},
    {"CueInHandWithACueBall", [](v1::PlanRequest* r) { r->set_cue_in_hand(true); },
     "table.balls = 1 CUE ball (\"cue\") (must have none: the cue ball is in hand (cue_in_hand)"},
    {"CueInHandWithABallNamedCue",
     [](v1::PlanRequest* r) {
       r->set_cue_in_hand(true);
       r->mutable_table()->mutable_balls()->DeleteSubrange(0, 1);
       r->mutable_table()->mutable_balls(1)->set_id("cue");  // the black
     },
     "table.balls[1].id = \"cue\" (a BLACK ball) (is taken with cue_in_hand"},
    {"BreakValueAboveAMaximumBreak", [](v1::PlanRequest* r) { r->set_break_value(148); },
     "break_value = 148 (must be in [0, 147] points)"},
    {"KindUnspecified", [](v1::PlanRequest* r) { r->add_kinds(v1::SHOT_KIND_UNSPECIFIED); },
     "kinds[0] = SHOT_KIND_UNSPECIFIED (must be POT, SAFETY, ESCAPE, BREAK_OFF or FOUL)"},
    {"RouteOutOfTheEnum", [](v1::PlanRequest* r) { r->add_routes(static_cast<v1::PotRoute>(9)); },
     "routes[0] = 9 (must be DIRECT, PLANT, DOUBLE or KICK)"},
    {"NoCueBallNotInHand", [](v1::PlanRequest* r) { r->mutable_table()->mutable_balls()->DeleteSubrange(0, 1); },
     "table.balls = 0 CUE balls (must have exactly one, or none with cue_in_hand set: the planner then places "
     "it)"},
};

void PrintTo(const BadPlan& p, std::ostream* os) { *os << p.name; }

class PlanBadInputTest : public PlanRpcTest, public testing::WithParamInterface<BadPlan> {};

TEST_P(PlanBadInputTest, IsInvalidArgumentNamingTheFieldAndValue) {
  StartServer();
  v1::PlanRequest request = ObviousPot();
  GetParam().edit(&request);
  v1::PlanResponse response;
  const grpc::Status st = Plan(request, &response);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(Mentions(st.error_message(), GetParam().message)) << st.error_message();
  // The stream says the same, with no message before it.
  grpc::ClientContext ctx;
  auto reader = stub_->PlanStream(&ctx, request);
  v1::PlanResponse m;
  EXPECT_FALSE(reader->Read(&m));
  const grpc::Status stream = reader->Finish();
  EXPECT_EQ(stream.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(stream.error_message(), st.error_message());
}

INSTANTIATE_TEST_SUITE_P(Cases, PlanBadInputTest, testing::ValuesIn(kBadPlans),
                         [](const testing::TestParamInfo<BadPlan>& p) { return std::string(p.param.name); });

// With the cue ball in hand the table has none; every shot (until the planner
// places the cue ball there may be none) says where in the D to place it.
TEST_F(PlanRpcTest, WithTheCueBallInHandATableWithoutOneIsPlanned) {
  StartServer();
  v1::PlanRequest request = ObviousPot();
  request.mutable_table()->mutable_balls()->DeleteSubrange(0, 1);
  request.set_cue_in_hand(true);
  v1::PlanResponse response;
  const grpc::Status st = Plan(request, &response);
  ASSERT_TRUE(st.ok()) << st.error_message();
  EXPECT_TRUE(response.final());
  if (response.shots_size() == 0) {
    EXPECT_NE(response.reason(), "");
  }
  ExpectWithinLimits(request, response);
  const physics::TableSpec& spec = physics::DefaultTable().spec();
  for (const v1::PlannedShot& s : response.shots()) {
    const v1::Vec2& at = s.cue_ball_start();
    EXPECT_LE(at.y(), spec.baulk_line + 1e-6);
    EXPECT_LE(std::hypot(at.x() - spec.width / 2, at.y() - spec.baulk_line), spec.d_radius + 1e-6);
  }
}

TEST_F(PlanRpcTest, SmallVisionErrorsAreRepairedWithAWarning) {
  StartServer();
  v1::PlanRequest request = ObviousPot();
  // The black 0.4 mm into red-1's far side, as vision might report it.
  const v1::Vec2 red = request.table().balls(1).position();
  const double touching = 2 * physics::BallParams{}.radius;
  request.mutable_table()->mutable_balls(2)->mutable_position()->set_x(red.x() - touching + 0.0004);
  request.mutable_table()->mutable_balls(2)->mutable_position()->set_y(red.y());
  v1::PlanResponse response;
  const grpc::Status st = Plan(request, &response);
  ASSERT_TRUE(st.ok()) << st.error_message();
  ASSERT_GE(response.warnings_size(), 1);
  double moved = 0;
  for (const v1::Warning& w : response.warnings()) {
    EXPECT_TRUE(w.ball_id() == "red-1" || w.ball_id() == "black") << w.ball_id();
    EXPECT_GT(w.moved_mm(), 0);
    EXPECT_LE(w.moved_mm(), 1.0);
    EXPECT_TRUE(Mentions(w.message(), "overlapped")) << w.message();
    moved += w.moved_mm();
  }
  EXPECT_NEAR(moved, 0.4, 1e-3);  // the least displacement that resolves it
  // With no repair asked for, the same table is refused.
  request.set_vision_tolerance_mm(0);
  const grpc::Status refused = Plan(request, &response);
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(Mentions(refused.error_message(), "overlap")) << refused.error_message();
}

// A deadline far shorter than the budget: the best shots so far (OK) or, with none,
// DEADLINE_EXCEEDED; either way long before the budget would have ended.
// The log line is written before a call is answered. A log stream that refuses it,
// by a throw or by its state alone, loses the line (counted) and never the answer,
// which would otherwise wait for the client's deadline.
TEST_F(PlanRpcTest, ALogThatRefusesItsLinesLosesThemAndNotTheCalls) {
  StartServer();
  std::ostream& log = test_server_->log;
  server_support::RefusingBuffer refusing;
  std::streambuf* const kept = log.rdbuf(&refusing);
  for (const bool throws : {true, false}) {
    SCOPED_TRACE(throws ? "the stream throws" : "the stream only fails");
    log.clear();
    log.exceptions(throws ? std::ios::badbit : std::ios::goodbit);
    const std::int64_t lost = server_->counts().log_lines_lost;
    v1::PlanResponse plan;
    const grpc::Status planned = Plan(ObviousPot(), &plan, milliseconds(30'000));
    ASSERT_TRUE(planned.ok()) << planned.error_message();
    EXPECT_GT(plan.shots_size(), 0);
    grpc::ClientContext stream_ctx;
    stream_ctx.set_deadline(std::chrono::system_clock::now() + milliseconds(30'000));
    auto reader = stub_->PlanStream(&stream_ctx, ObviousPot());
    v1::PlanResponse m;
    int messages = 0;
    while (messages < 1000 && reader->Read(&m)) ++messages;
    const grpc::Status streamed = reader->Finish();
    ASSERT_TRUE(streamed.ok()) << streamed.error_message();
    grpc::ClientContext collide_ctx;
    collide_ctx.set_deadline(std::chrono::system_clock::now() + milliseconds(30'000));
    v1::CollideResponse collided;
    const grpc::Status collide = stub_->Collide(&collide_ctx, testing_requests::PaperCollide(), &collided);
    ASSERT_TRUE(collide.ok()) << collide.error_message();
    EXPECT_EQ(server_support::WaitUntilAnswered(*server_, 0, std::chrono::seconds(20)).in_flight(), 0);
    EXPECT_EQ(server_->counts().log_lines_lost - lost, 3);
  }
  log.exceptions(std::ios::goodbit);
  log.clear();
  log.rdbuf(kept);
  // The stream takes lines again once it can: the next call is logged.
  v1::PlanResponse plan;
  ASSERT_TRUE(Plan(ObviousPot(), &plan, milliseconds(30'000)).ok());
  EXPECT_EQ(server_support::WaitUntilAnswered(*server_, 0, std::chrono::seconds(20)).in_flight(), 0);
  EXPECT_TRUE(Mentions(Log(), "method=Plan ")) << Log();
}

TEST_F(PlanRpcTest, ADeadlineShorterThanTheBudgetEndsThePlan) {
  StartServer();
  const v1::PlanRequest request = LongPlan(10'000);
  v1::PlanResponse warm;
  ASSERT_TRUE(Plan(ObviousPot(), &warm).ok());  // the planner's tables are built once
  for (const int deadline_ms : {300, 2}) {
    v1::PlanResponse response;
    const auto t0 = Clock::now();
    const grpc::Status st = Plan(request, &response, milliseconds(deadline_ms));
    const auto took = Clock::now() - t0;
    EXPECT_TRUE(st.ok() || st.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED)
        << deadline_ms << ": " << st.error_code() << " " << st.error_message();
    if (st.ok()) {
      EXPECT_GT(response.shots_size(), 0) << response.reason();
      EXPECT_TRUE(response.cut_short());
      ExpectWithinLimits(request, response);
    }
    EXPECT_LT(took, milliseconds(deadline_ms) + std::chrono::seconds(2)) << deadline_ms;
  }
  WaitUntilIdle();
  // Every plan the server took but the warm-up (capped in simulations) was cut short
  // by its deadline, answered or not; the 2 ms call may have expired before it was sent.
  const CallCounts counts = server_->counts();
  std::int64_t plans = 0;
  for (const std::int64_t n : counts.methods[static_cast<std::size_t>(MethodIndex("Plan"))].by_status) plans += n;
  EXPECT_GE(plans, 2);
  EXPECT_EQ(counts.plans_cut_short, plans - 1);
  EXPECT_EQ(Occurrences(Log(), "cut_short=1"), plans - 1);
}

// The server's own maximum ends a plan without a client deadline the same way.
TEST_F(PlanRpcTest, TheServersMaximumCallTimeEndsAPlan) {
  ServerOptions options;
  options.max_call = milliseconds(200);
  StartServer(options);
  v1::PlanResponse response;
  const auto t0 = Clock::now();
  const grpc::Status st = Plan(LongPlan(10'000), &response);
  EXPECT_TRUE(st.ok() || st.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED) << st.error_message();
  if (st.ok()) {
    EXPECT_GT(response.shots_size(), 0);
  } else {
    EXPECT_TRUE(Mentions(st.error_message(), "deadline")) << st.error_message();
  }
  EXPECT_LT(Clock::now() - t0, std::chrono::seconds(5));
}

TEST_F(PlanRpcTest, ACancelledPlanStops) {
  StartServer();
  AsyncPlan call(stub_, LongPlan(10'000));
  ASSERT_TRUE(WaitUntilPlanning(1));
  const auto t0 = Clock::now();
  call.context.TryCancel();
  EXPECT_EQ(call.Wait().error_code(), grpc::StatusCode::CANCELLED);
  WaitUntilIdle();
  EXPECT_LT(Clock::now() - t0, std::chrono::seconds(5));  // the budget was 10 s
  EXPECT_EQ(server_->counts().with(grpc::StatusCode::CANCELLED), 1);
  EXPECT_EQ(server_->counts().plans, 0);
}

TEST_F(PlanRpcTest, AFullServerRefusesMorePlansAtOnce) {
  ServerOptions options;
  options.max_plans = 1;
  StartServer(options);
  AsyncPlan held(stub_, LongPlan(10'000));
  ASSERT_TRUE(WaitUntilPlanning(1));
  v1::PlanResponse response;
  const grpc::Status st = Plan(ObviousPot(), &response);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_TRUE(Mentions(st.error_message(), "--max-plans")) << st.error_message();
  grpc::ClientContext ctx;
  auto reader = stub_->PlanStream(&ctx, ObviousPot());
  v1::PlanResponse m;
  EXPECT_FALSE(reader->Read(&m));
  EXPECT_EQ(reader->Finish().error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  // Other methods are not plans: they still run.
  v1::GetModelResponse model;
  grpc::ClientContext model_ctx;
  EXPECT_TRUE(stub_->GetModel(&model_ctx, {}, &model).ok());
  EXPECT_EQ(model.service().max_plans(), 1);
  held.context.TryCancel();
  EXPECT_EQ(held.Wait().error_code(), grpc::StatusCode::CANCELLED);
  WaitUntilIdle();
  // Room again.
  EXPECT_TRUE(Plan(ObviousPot(), &response).ok());
}

// Shutdown with a plan and a plan stream in flight (10 s budgets) and a 100 ms
// grace: both are cancelled after the grace and the shutdown ends long before the
// budgets would have.
TEST_F(PlanRpcTest, ShutdownWithPlansInFlightIsBounded) {
  ServerOptions options;
  options.workers = 2;
  StartServer(options);
  AsyncPlan unary(stub_, LongPlan(10'000));
  grpc::ClientContext stream_ctx;
  auto reader = stub_->PlanStream(&stream_ctx, LongPlan(10'000));
  ASSERT_TRUE(WaitUntilPlanning(2));
  const auto t0 = Clock::now();
  server_->Shutdown(milliseconds(100));
  const auto took = Clock::now() - t0;
  EXPECT_GE(took, milliseconds(100));  // the grace was given
  EXPECT_LT(took, std::chrono::seconds(5));
  const grpc::Status a = unary.Wait();
  v1::PlanResponse m;
  for (int i = 0; i < 1000 && reader->Read(&m);) ++i;
  const grpc::Status b = reader->Finish();
  for (const grpc::Status& st : {a, b}) {
    EXPECT_TRUE(st.error_code() == grpc::StatusCode::CANCELLED ||
                st.error_code() == grpc::StatusCode::UNAVAILABLE)
        << st.error_code() << " " << st.error_message();
  }
  EXPECT_EQ(server_->counts().with(grpc::StatusCode::CANCELLED), 2);
  EXPECT_EQ(server_->counts().in_flight(), 0);
  EXPECT_EQ(server_->counts().plans, 0);
}

TEST(PlanDefaultsTest, AnUnsetBudgetIsTheServersDefault) {
  v1::PlanRequest r;
  EXPECT_DOUBLE_EQ(PlanRequestFrom(r, 25.0).time_budget, 0.025);
  r.set_time_budget_ms(40);
  EXPECT_DOUBLE_EQ(PlanRequestFrom(r, 25.0).time_budget, 0.040);
}

}  // namespace
}  // namespace snooker::server
