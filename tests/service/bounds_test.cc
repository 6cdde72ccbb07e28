// Every request's work, output and error message is bounded, and each bad value is
// INVALID_ARGUMENT naming it, through the library API
// (server/api.h, server/convert.h, server/decode.h).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "physics/core/limits.h"
#include "server/api.h"
#include "server/convert.h"
#include "server/decode.h"
#include "server/limits.h"
#include "tests/service/requests.h"
#include "tests/support/text.h"

namespace snooker::server {
namespace {

namespace req = testing_requests;
using Code = ApiStatus::Code;

v1::SimulateRequest Stacked(int balls) {
  v1::SimulateRequest r;
  for (int i = 0; i < balls; ++i) {
    req::AddBall(&r, i == 0 ? "cue" : "red-" + std::to_string(i), i == 0 ? v1::CUE : v1::RED, 0.9,
                 1.0);
  }
  r.mutable_shot()->set_speed(1);
  return r;
}

// 10 000 balls at one point (a 320 KB request) cost 95 s and 4.6 GB before: the count
// is now checked before anything that grows with it.
TEST(RequestBoundsTest, TenThousandBallsAreRefusedWithAShortMessage) {
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(Stacked(10'000), &resp);
  EXPECT_EQ(st.code, Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "table.balls = 10000 balls (at most 32)")) << st.message;
  EXPECT_LT(st.message.size(), 100u) << st.message;
}

// At most 32 balls, but all at one point: 496 overlapping pairs (a 4 MB message for
// 300 balls before). The first few are named, the rest counted.
TEST(RequestBoundsTest, ManyProblemsGiveTheFirstFewAndACount) {
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(Stacked(physics::limits::kMaxBalls), &resp);
  EXPECT_EQ(st.code, Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "cue and red-1 overlap by 0.0525 m")) << st.message;
  EXPECT_TRUE(Mentions(st.message, "and 491 more")) << st.message;  // 496 - 5
  EXPECT_LT(st.message.size(), 1000u) << st.message;
}

TEST(RequestBoundsTest, ManyBadFieldsGiveTheFirstFewAndACount) {
  v1::SimulateRequest r = req::BreakOff(1, 0, 0);
  for (int i = 1; i < r.table().balls_size(); ++i) r.mutable_table()->mutable_balls(i)->set_kind(v1::BallKind(99));
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(r, &resp);
  EXPECT_EQ(st.code, Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "table.balls[1].kind = 99")) << st.message;
  EXPECT_TRUE(Mentions(st.message, "; and 16 more problems")) << st.message;  // 21 - 5
  EXPECT_LT(st.message.size(), limits::kMaxMessageBytes);
}

// A 400 KB id gave a 2 GB response (ids are repeated in every event).
TEST(RequestBoundsTest, AOneMegabyteIdIsRefusedAndNotEchoed) {
  v1::SimulateRequest r = req::BreakOff(1, 0, 0);
  r.mutable_table()->mutable_balls(3)->set_id(std::string(1 << 20, 'x'));
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(r, &resp);
  EXPECT_EQ(st.code, Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "table.balls[3].id = \"xxxxxxxxxxxxxxxxxxxxxxxx...\" (1048576 bytes)"))
      << st.message.substr(0, 500);
  EXPECT_TRUE(Mentions(st.message, "at most 64 bytes")) << st.message.substr(0, 500);
  EXPECT_LT(st.message.size(), 300u);
}

TEST(RequestBoundsTest, AnIdOfTheLimitIsAccepted) {
  v1::SimulateRequest r = req::BreakOff(1, 0, 0);
  r.mutable_table()->mutable_balls(3)->set_id(std::string(physics::limits::kMaxIdBytes, 'x'));
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(r, &resp);
  EXPECT_TRUE(st.ok()) << st.message;
}

// An id with a newline or an escape sequence would forge lines of the command line's
// output or drive a terminal; one of any other printable UTF-8 is kept as it is.
TEST(RequestBoundsTest, AnIdWithAControlCharacterIsRefused) {
  for (const std::string& id : {std::string("red\nfake line"), std::string("\x1b[2Jred"), std::string("a\0b", 3),
                               std::string("del\x7f")}) {
    v1::SimulateRequest r = req::BreakOff(1, 0, 0);
    r.mutable_table()->mutable_balls(3)->set_id(id);
    v1::SimulateResponse resp;
    const ApiStatus st = Simulate(r, &resp);
    EXPECT_EQ(st.code, Code::kInvalidArgument) << QuoteId(id);
    EXPECT_TRUE(Mentions(st.message, "table.balls[3].id = " + QuoteId(id) + " (must hold no control characters)"))
        << st.message;
  }
  v1::SimulateRequest r = req::BreakOff(1, 0, 0);
  r.mutable_table()->mutable_balls(3)->set_id("rouge n\u00b0 3 \u2014 ok");
  v1::SimulateResponse resp;
  EXPECT_TRUE(Simulate(r, &resp).ok());
}

TEST(QuoteIdTest, CutsAtACharacterBoundaryAndEscapesControlBytes) {
  EXPECT_EQ(QuoteId("red-1"), "\"red-1\"");
  EXPECT_EQ(QuoteId("a\"b\\c\n"), "\"a\\\"b\\\\c\\x0a\"");
  // 23 ASCII bytes, then a 2-byte character across the 24-byte cut: not split.
  const std::string id = std::string(23, 'a') + "\xc3\xa9" + "zzz";
  EXPECT_EQ(QuoteId(id), "\"" + std::string(23, 'a') + "...\" (28 bytes)");
}

TEST(CollideBoundsTest, StepsBeyondTheCapAreRefused) {
  for (const std::int32_t steps : {physics::limits::kMaxFixedSteps + 1, 536'870'911,
                                   std::numeric_limits<std::int32_t>::max()}) {
    v1::CollideRequest r = req::PaperCollide();
    r.mutable_solver()->set_integrator(v1::IMPULSE_INTEGRATOR_FIXED_STEP);
    r.mutable_solver()->set_steps(steps);
    v1::CollideResponse resp;
    const ApiStatus st = Collide(r, &resp);
    EXPECT_EQ(st.code, Code::kInvalidArgument) << steps;
    EXPECT_TRUE(Mentions(st.message, "solver.steps = " + std::to_string(steps))) << st.message;
    EXPECT_TRUE(Mentions(st.message, "[1, 10000000]")) << st.message;
  }
}

// `4 * steps` overflowed an int32 from 2^29 steps (UBSan aborted): the cap is computed
// in 64 bits and clamped.
TEST(CollideBoundsTest, StepCapIsComputedWithoutOverflow) {
  v1::ImpulseSolverOptions o;
  o.set_integrator(v1::IMPULSE_INTEGRATOR_FIXED_STEP);
  o.set_steps(physics::limits::kMaxFixedSteps);
  EXPECT_EQ(SolverOptionsFrom(o).max_steps, 4 * physics::limits::kMaxFixedSteps);
  o.set_steps(std::numeric_limits<std::int32_t>::max());  // not valid, but converted safely
  EXPECT_EQ(SolverOptionsFrom(o).max_steps, std::numeric_limits<std::int32_t>::max());
}

// Speed 1e308 answered "not approaching: " (no reason), 1e-300 RESOURCE_EXHAUSTED.
TEST(CollideBoundsTest, SpeedsOutsideTheImpactRangeAreInvalidArgumentNamingTheValue) {
  for (const auto& [speed, text] : {std::pair{1e308, "speed = 1e+308"}, std::pair{1e-300, "speed = 1e-300"},
                                    std::pair{0.0, "speed = 0"}, std::pair{101.0, "speed = 101"}}) {
    v1::CollideRequest r = req::PaperCollide();
    r.set_speed(speed);
    v1::CollideResponse resp;
    const ApiStatus st = Collide(r, &resp);
    EXPECT_EQ(st.code, Code::kInvalidArgument) << speed;
    EXPECT_TRUE(Mentions(st.message, text)) << st.message;
    EXPECT_TRUE(Mentions(st.message, "must be in [1e-06, 100] m/s")) << st.message;
  }
}

TEST(CollideBoundsTest, NotApproachingSaysWhy) {
  v1::CollideRequest r;
  r.set_speed(1e-6);
  r.set_cut_angle_deg(89.9999);
  r.set_topspin(1000);
  v1::CollideResponse resp;
  const ApiStatus st = Collide(r, &resp);
  EXPECT_EQ(st.code, Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "not approaching: speed = 1e-06 m/s at cut_angle_deg = 89.9999"))
      << st.message;
  EXPECT_TRUE(Mentions(st.message, "approach speed of 1.7")) << st.message;
}

// Unknown enum values were taken silently as the defaults.
TEST(CollideBoundsTest, UnknownEnumValuesAreRejected) {
  v1::CollideRequest r = req::PaperCollide();
  r.mutable_solver()->set_integrator(v1::ImpulseIntegrator(7));
  r.mutable_parameters()->set_friction_law(v1::BallBallFrictionLaw(9));
  v1::CollideResponse resp;
  const ApiStatus st = Collide(r, &resp);
  EXPECT_EQ(st.code, Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "parameters.friction_law = 9 (must be one of "
                                   "BALL_BALL_FRICTION_LAW_UNSPECIFIED (0)"))
      << st.message;
  EXPECT_TRUE(Mentions(st.message, "solver.integrator = 7")) << st.message;
  EXPECT_TRUE(Mentions(st.message, "IMPULSE_INTEGRATOR_FIXED_STEP (2)")) << st.message;
}

// The exponential law's b and c are checked against physics/core/limits.h's ranges,
// named by their fields; mu at zero speed, mu_bb + b, may reach 1 and no more.
TEST(CollideBoundsTest, ExponentialLawNumbersOutsideTheirRangesAreRejectedByName) {
  v1::CollideRequest r = req::PaperCollide();
  r.mutable_parameters()->set_friction_law(v1::BALL_BALL_FRICTION_LAW_EXPONENTIAL);
  r.mutable_parameters()->set_mu_bb(0.05);
  r.mutable_parameters()->set_slip_gain(0.95);
  r.mutable_parameters()->set_slip_decay(physics::limits::kSlipDecay.hi);
  v1::CollideResponse resp;
  ASSERT_EQ(Collide(r, &resp).code, Code::kOk);

  r.mutable_parameters()->set_slip_gain(0.96);
  r.mutable_parameters()->set_slip_decay(physics::limits::kSlipDecay.hi + 1);
  const ApiStatus st = Collide(r, &resp);
  EXPECT_EQ(st.code, Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "parameters.slip_gain = 0.96 (must be at most 1 - mu_bb")) << st.message;
  EXPECT_TRUE(Mentions(st.message, "parameters.slip_decay = 101")) << st.message;

  r.mutable_parameters()->set_slip_gain(-0.1);
  r.mutable_parameters()->set_slip_decay(1);
  const ApiStatus negative = Collide(r, &resp);
  EXPECT_EQ(negative.code, Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(negative.message, "parameters.slip_gain = -0.1")) << negative.message;
}

TEST(SimulateBoundsTest, UnknownBallKindIsRejected) {
  v1::SimulateRequest r = req::BreakOff(1, 0, 0);
  r.mutable_table()->mutable_balls(2)->set_kind(v1::BallKind(99));
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(r, &resp);
  EXPECT_EQ(st.code, Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "table.balls[2].kind = 99 (ball \"red-2\")")) << st.message;
}

// A heading of 1e300 deg was accepted as is. Headings are now accepted within ten
// turns and normalised into [0, 360); beyond that, or not finite, they are refused.
TEST(SimulateBoundsTest, AbsurdHeadingsAreRefused) {
  for (const auto& [h, text] : {std::pair{1e300, "shot.heading_deg = 1e+300"},
                                std::pair{-3600.5, "shot.heading_deg = -3600.5"},
                                std::pair{std::nan(""), "shot.heading_deg = nan"}}) {
    v1::SimulateRequest r = req::BreakOff(1, 0, 0);
    r.mutable_shot()->set_heading_deg(h);
    v1::SimulateResponse resp;
    const ApiStatus st = Simulate(r, &resp);
    EXPECT_EQ(st.code, Code::kInvalidArgument) << h;
    EXPECT_TRUE(Mentions(st.message, text)) << st.message;
    EXPECT_TRUE(Mentions(st.message, "must be in [-3600, 3600] deg")) << st.message;
  }
}

TEST(SimulateBoundsTest, HeadingsAreNormalisedIntoOneTurn) {
  EXPECT_EQ(NormalizedHeadingDeg(90), 90);
  EXPECT_EQ(NormalizedHeadingDeg(450), 90);
  EXPECT_EQ(NormalizedHeadingDeg(-270), 90);
  EXPECT_EQ(NormalizedHeadingDeg(-90), 270);
  EXPECT_EQ(NormalizedHeadingDeg(3600), 0);
  EXPECT_EQ(NormalizedHeadingDeg(-1e-20), 0);  // not 360
  // The same shot given as 90, 450 or -270 degrees ends in exactly the same place.
  v1::SimulateRequest r = req::BreakOff(3, 0, 0);
  const double h = r.shot().heading_deg();
  v1::SimulateResponse base;
  ASSERT_TRUE(Simulate(r, &base).ok());
  for (const double turns : {1.0, -1.0, 9.0}) {
    r.mutable_shot()->set_heading_deg(h + 360 * turns);
    if (NormalizedHeadingDeg(r.shot().heading_deg()) != h) continue;  // rounding in h + 360k
    v1::SimulateResponse other;
    ASSERT_TRUE(Simulate(r, &other).ok());
    ASSERT_EQ(other.final_balls_size(), base.final_balls_size());
    for (int i = 0; i < base.final_balls_size(); ++i) {
      EXPECT_EQ(other.final_balls(i).position().x(), base.final_balls(i).position().x()) << turns;
      EXPECT_EQ(other.final_balls(i).position().y(), base.final_balls(i).position().y()) << turns;
    }
  }
}

TEST(SimulateBoundsTest, EveryNumericOptionIsBounded) {
  struct Case {
    void (*spoil)(v1::SimulationOptions*);
    const char* must_mention;
  };
  const Case cases[] = {
      {[](v1::SimulationOptions* o) { o->set_max_events(1'000'001); }, "options.max_events = 1000001"},
      {[](v1::SimulationOptions* o) { o->set_max_events(-5); }, "options.max_events = -5"},
      {[](v1::SimulationOptions* o) { o->set_max_time_s(1e9); }, "options.max_time_s = 1e+09"},
      {[](v1::SimulationOptions* o) { o->set_tolerance(0); }, "options.tolerance = 0"},
      {[](v1::SimulationOptions* o) { o->set_path_sample_s(1e-9); }, "options.path_sample_s = 1e-09"},
  };
  for (const Case& c : cases) {
    v1::SimulateRequest r = req::BreakOff(1, 0, 0);
    c.spoil(r.mutable_options());
    v1::SimulateResponse resp;
    const ApiStatus st = Simulate(r, &resp);
    EXPECT_EQ(st.code, Code::kInvalidArgument) << c.must_mention;
    EXPECT_TRUE(Mentions(st.message, c.must_mention)) << st.message;
  }
}

// The response is bounded: events x ids and paths. A limit below the answer's size
// refuses it with RESOURCE_EXHAUSTED, naming what to ask less of, and no partial answer.
TEST(SimulateBoundsTest, AnAnswerLargerThanTheLimitIsRefused) {
  const v1::SimulateRequest r = req::BreakOff(7, 0, 0);
  v1::SimulateResponse full;
  ASSERT_TRUE(Simulate(r, &full).ok());
  CallLimits limits;
  limits.max_response_bytes = full.ByteSizeLong() / 2;
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(r, &resp, limits);
  EXPECT_EQ(st.code, Code::kResourceExhausted);
  EXPECT_TRUE(Mentions(st.message, "larger than " + std::to_string(limits.max_response_bytes) + " bytes"))
      << st.message;
  EXPECT_TRUE(Mentions(st.message, "options.max_events")) << st.message;
  EXPECT_EQ(resp.ByteSizeLong(), 0u);
}

// The finest sampling of the longest shot on a full table stays within the path
// point budget (plus one point per knot) and the response limit.
TEST(SimulateBoundsTest, PathsStayWithinThePointBudget) {
  v1::SimulateRequest r = req::Heavy();
  r.mutable_options()->set_tolerance(1e-10);
  r.mutable_options()->set_path_sample_s(1e-4);
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(r, &resp);
  ASSERT_TRUE(st.ok()) << st.message;
  std::int64_t points = 0;
  for (const v1::BallPath& p : resp.paths()) points += p.points_size();
  EXPECT_GT(points, limits::kMaxPathPoints / 2);  // the budget is used ...
  EXPECT_LE(points, limits::kMaxPathPoints + 2 * resp.events_size() + 2 * resp.paths_size());  // ... not exceeded
  EXPECT_LE(resp.ByteSizeLong(), limits::kMaxResponseBytes);
}

// The interrupt is checked inside the run: a deadline already passed stops it at the
// first check, a cancellation likewise, each with its own status.
TEST(InterruptTest, APassedDeadlineStopsTheRunAtItsFirstCheck) {
  CallLimits limits;
  limits.interrupt.deadline = std::chrono::steady_clock::now() - std::chrono::milliseconds(1);
  limits.interrupt.check_every = 8;
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(req::Heavy(), &resp, limits);
  EXPECT_EQ(st.code, Code::kDeadlineExceeded);
  EXPECT_TRUE(Mentions(st.message, "the call's deadline passed after 8 events")) << st.message;
  EXPECT_EQ(resp.ByteSizeLong(), 0u);
}

TEST(InterruptTest, ACancelFlagStopsTheRun) {
  const std::atomic<bool> cancelled{true};
  CallLimits limits;
  limits.interrupt.cancelled = &cancelled;
  limits.interrupt.check_every = 8;
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(req::Heavy(), &resp, limits);
  EXPECT_EQ(st.code, Code::kCancelled);
  EXPECT_TRUE(Mentions(st.message, "the call was cancelled after 8 events")) << st.message;
}

// The transport's cancellation test (grpc::ServerContext::IsCancelled) is polled:
// here it turns true on its third poll, so the run stops after 3 x 8 events.
TEST(InterruptTest, APolledCancellationStopsTheRunWhereItTurnsTrue) {
  int polls = 0;
  CallLimits limits;
  limits.interrupt.poll = [](void* c) { return ++*static_cast<int*>(c) >= 3; };
  limits.interrupt.poll_context = &polls;
  limits.interrupt.check_every = 8;
  v1::SimulateResponse resp;
  const ApiStatus st = Simulate(req::Heavy(), &resp, limits);
  EXPECT_EQ(st.code, Code::kCancelled);
  EXPECT_TRUE(Mentions(st.message, "after 24 events")) << st.message;
  EXPECT_EQ(polls, 3);
}

TEST(InterruptTest, ACollisionAfterItsDeadlineIsNotAnswered) {
  CallLimits limits;
  limits.interrupt.deadline = std::chrono::steady_clock::now() - std::chrono::milliseconds(1);
  v1::CollideResponse resp;
  const ApiStatus st = Collide(req::PaperCollide(), &resp, limits);
  EXPECT_EQ(st.code, Code::kDeadlineExceeded);
  EXPECT_TRUE(Mentions(st.message, "deadline passed")) << st.message;
}

TEST(ParseRequestTest, BytesThatDoNotParseAreInvalidArgumentWithAReason) {
  v1::SimulateRequest r;
  // Not wire format: a field number 0 tag.
  ApiStatus st = ParseRequest(std::string("\x00\x01\x02", 3), &r);
  EXPECT_EQ(st.code, Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "not a valid snooker.v1.SimulateRequest (3 bytes)")) << st.message;
  EXPECT_TRUE(Mentions(st.message, "not Protocol Buffers wire format")) << st.message;
  // Wire format, but field 1 (table, a message) holds bytes that are not.
  st = ParseRequest(std::string("\x0a\x03\x00\x01\x02", 5), &r);
  EXPECT_EQ(st.code, Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "a nested message does not parse")) << st.message;
  // A ball id that is not UTF-8.
  v1::SimulateRequest bad = req::BreakOff(1, 0, 0);
  bad.mutable_table()->mutable_balls(0)->set_id("\xff\xfe");
  std::string bytes;
  bad.SerializePartialToString(&bytes);
  st = ParseRequest(bytes, &r);
  EXPECT_EQ(st.code, Code::kInvalidArgument);
  EXPECT_TRUE(Mentions(st.message, "UTF-8")) << st.message;
  // A valid one parses.
  req::BreakOff(1, 0, 0).SerializeToString(&bytes);
  EXPECT_TRUE(ParseRequest(bytes, &r).ok());
  EXPECT_EQ(r.table().balls_size(), 22);
}

TEST(ParseRequestTest, AnOversizedRequestIsRefusedUnread) {
  v1::CollideRequest r;
  const ApiStatus st = ParseRequest(std::string(limits::kMaxRequestBytes + 1, '\0'), &r);
  EXPECT_EQ(st.code, Code::kResourceExhausted);
  EXPECT_TRUE(Mentions(st.message, "larger than 4194304 bytes")) << st.message;
}

}  // namespace
}  // namespace snooker::server
