// Tests of a plan request's validation (planner/validate.h): every range of
// planner/limits.h holds at both ends and refuses the values just outside and NaN,
// each error naming the field, the value, its unit and the range; snooker's counts
// and the ball on are refused with their rule.
#include "planner/validate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "planner/limits.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

const physics::TableModel& Table() { return physics::DefaultTable(); }

PlanRequest Valid() {
  PlanRequest r;
  r.table.balls = {{BallKind::kCue, Vec2(0.9, 0.6)},
                   {BallKind::kRed, Vec2(0.9, 2.6)},
                   {BallKind::kBlack, Table().spot(physics::Colour::kBlack)}};
  return r;
}

// The errors of `r` for `field`.
std::vector<FieldError> ErrorsOf(const PlanRequest& r, const std::string& field) {
  std::vector<FieldError> out;
  for (const FieldError& e : ValidatePlanRequest(r, Table())) {
    if (e.field == field) out.push_back(e);
  }
  return out;
}

struct RangeCase {
  const char* name;
  const char* field;
  physics::Range range;
  Unit unit;
  void (*set)(PlanRequest* r, double x);
};

const RangeCase kRanges[] = {
    {"MinSpeed", "limits.min_speed", limits::kMinSpeed, Unit::kMetrePerSecond,
     [](PlanRequest* r, double x) {
       r->limits.min_speed = x;
       r->limits.max_speed = limits::kMaxSpeed.hi;  // kept above it
     }},
    {"MaxSpeed", "limits.max_speed", limits::kMaxSpeed, Unit::kMetrePerSecond,
     [](PlanRequest* r, double x) {
       r->limits.max_speed = x;
       r->limits.min_speed = 0;  // kept below it
     }},
    {"TopspinFraction", "limits.max_topspin_fraction", limits::kSpinFraction, Unit::kRollingSpin,
     [](PlanRequest* r, double x) { r->limits.max_topspin_fraction = x; }},
    {"SidespinFraction", "limits.max_sidespin_fraction", limits::kSpinFraction, Unit::kRollingSpin,
     [](PlanRequest* r, double x) { r->limits.max_sidespin_fraction = x; }},
    {"CueClearance", "limits.cue.length", limits::kCueClearance, Unit::kMetre,
     [](PlanRequest* r, double x) { r->limits.cue.length = x; }},
    {"CueRadius", "limits.cue.radius", limits::kCueRadius, Unit::kMetre,
     [](PlanRequest* r, double x) { r->limits.cue.radius = x; }},
    {"HeadingSigma", "noise.heading", limits::kHeadingSigma, Unit::kRadian,
     [](PlanRequest* r, double x) { r->noise.heading = x; }},
    {"SpeedSigma", "noise.speed_fraction", limits::kSpeedSigmaFraction, Unit::kFraction,
     [](PlanRequest* r, double x) { r->noise.speed_fraction = x; }},
    {"TopspinSigma", "noise.topspin", limits::kSpinSigma, Unit::kRadPerSecond,
     [](PlanRequest* r, double x) { r->noise.topspin = x; }},
    {"SidespinSigma", "noise.sidespin", limits::kSpinSigma, Unit::kRadPerSecond,
     [](PlanRequest* r, double x) { r->noise.sidespin = x; }},
    {"PositionSigma", "noise.position", limits::kPositionSigma, Unit::kMetre,
     [](PlanRequest* r, double x) { r->noise.position = x; }},
    {"BallPositionSigma", "position_sigma", limits::kPositionSigma, Unit::kMetre,
     [](PlanRequest* r, double x) { r->position_sigma = {0.2e-3, x, 0.2e-3}; }},
    {"TimeBudget", "time_budget", limits::kTimeBudget, Unit::kSecond,
     [](PlanRequest* r, double x) { r->time_budget = x; }},
    {"BreakValue", "break_value", limits::kBreakValue, Unit::kPoints,
     [](PlanRequest* r, double x) { r->break_value = x; }},
    {"PositionSpread", "position_spread", limits::kPositionSpread, Unit::kNone,
     [](PlanRequest* r, double x) { r->position_spread = x; }},
};

void PrintTo(const RangeCase& c, std::ostream* os) { *os << c.name; }

class RangeTest : public testing::TestWithParam<RangeCase> {};

TEST_P(RangeTest, BothEndsHoldAndTheValuesBeyondAreRefused) {
  const RangeCase& c = GetParam();
  for (const double x : {c.range.lo, c.range.hi, 0.5 * (c.range.lo + c.range.hi)}) {
    PlanRequest r = Valid();
    c.set(&r, x);
    EXPECT_TRUE(ErrorsOf(r, c.field).empty()) << c.field << " = " << x << ": "
                                              << Describe(ValidatePlanRequest(r, Table()));
  }
  const double below = std::nextafter(c.range.lo, -std::numeric_limits<double>::infinity());
  const double above = std::nextafter(c.range.hi, std::numeric_limits<double>::infinity());
  for (const double x : {below, above, std::numeric_limits<double>::quiet_NaN(),
                         std::numeric_limits<double>::infinity()}) {
    PlanRequest r = Valid();
    c.set(&r, x);
    const std::vector<FieldError> errors = ErrorsOf(r, c.field);
    ASSERT_EQ(errors.size(), 1u) << c.field << " = " << x << ": " << Describe(ValidatePlanRequest(r, Table()));
    const FieldError& e = errors[0];
    ASSERT_TRUE(e.value.has_value());
    EXPECT_TRUE(*e.value == x || (std::isnan(*e.value) && std::isnan(x))) << *e.value;
    EXPECT_EQ(e.unit, c.unit);
    ASSERT_TRUE(e.range.has_value());
    EXPECT_EQ(e.range->lo, c.range.lo);
    EXPECT_EQ(e.range->hi, c.range.hi);
    if (std::string(c.field) == "position_sigma") {
      EXPECT_EQ(e.ball, 1);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Limits, RangeTest, testing::ValuesIn(kRanges),
                         [](const testing::TestParamInfo<RangeCase>& p) { return p.param.name; });

struct CountCase {
  const char* name;
  const char* field;
  limits::IntRange range;
  void (*set)(PlanRequest* r, std::int64_t n);
};

const CountCase kCounts[] = {
    {"MaxShots", "max_shots", limits::kMaxShots,
     [](PlanRequest* r, std::int64_t n) { r->max_shots = static_cast<int>(n); }},
    {"Threads", "threads", limits::kThreads,
     [](PlanRequest* r, std::int64_t n) { r->threads = static_cast<int>(n); }},
    {"MaxSimulations", "max_simulations", limits::kMaxSimulations,
     [](PlanRequest* r, std::int64_t n) { r->max_simulations = n; }},
    {"MonteCarloSamples", "monte_carlo_samples", limits::kMonteCarloSamples,
     [](PlanRequest* r, std::int64_t n) { r->monte_carlo_samples = static_cast<int>(n); }},
};

void PrintTo(const CountCase& c, std::ostream* os) { *os << c.name; }

class CountTest : public testing::TestWithParam<CountCase> {};

TEST_P(CountTest, BothEndsHoldAndTheCountsBeyondAreRefused) {
  const CountCase& c = GetParam();
  for (const std::int64_t n : {c.range.lo, c.range.hi}) {
    PlanRequest r = Valid();
    c.set(&r, n);
    EXPECT_TRUE(ErrorsOf(r, c.field).empty()) << c.field << " = " << n;
  }
  for (const std::int64_t n : {c.range.lo - 1, c.range.hi + 1}) {
    PlanRequest r = Valid();
    c.set(&r, n);
    const std::vector<FieldError> errors = ErrorsOf(r, c.field);
    ASSERT_EQ(errors.size(), 1u) << c.field << " = " << n;
    EXPECT_EQ(errors[0].value, std::optional<double>(static_cast<double>(n)));
    ASSERT_TRUE(errors[0].range.has_value());
    EXPECT_EQ(errors[0].range->hi, static_cast<double>(c.range.hi));
  }
}

INSTANTIATE_TEST_SUITE_P(Limits, CountTest, testing::ValuesIn(kCounts),
                         [](const testing::TestParamInfo<CountCase>& p) { return p.param.name; });

TEST(ValidateTest, AValidRequestHasNoErrors) {
  EXPECT_TRUE(ValidatePlanRequest(Valid(), Table()).empty()) << Describe(ValidatePlanRequest(Valid(), Table()));
}

TEST(ValidateTest, TheFastestSpeedMustExceedTheSlowest) {
  PlanRequest r = Valid();
  r.limits.min_speed = 3;
  r.limits.max_speed = 2;
  const std::vector<FieldError> errors = ErrorsOf(r, "limits.max_speed");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].value, std::optional<double>(2));
  EXPECT_FALSE(errors[0].range.has_value());
  EXPECT_EQ(errors[0].rule, "must exceed limits.min_speed (3 m/s)");
}

TEST(ValidateTest, SnookersCountsAndTheBallOn) {
  PlanRequest r = Valid();
  r.table.balls.push_back({BallKind::kBlack, Vec2(0.3, 0.3)});
  r.table.balls.push_back({BallKind::kCue, Vec2(1.5, 0.3)});
  for (int i = 0; i < 15; ++i) r.table.balls.push_back({BallKind::kRed, Vec2(0.2 + 0.1 * i, 1.0)});
  r.ball_on = BallOn::kPink;
  const std::string d = Describe(ValidateTable(r.table, r.cue_in_hand, r.ball_on, Table()));
  EXPECT_NE(d.find("table.balls = 2 (cue balls: exactly one)"), std::string::npos) << d;
  EXPECT_NE(d.find("table.balls = 16 (reds: at most 15)"), std::string::npos) << d;
  EXPECT_NE(d.find("table.balls = 2 (black balls: at most one)"), std::string::npos) << d;
  EXPECT_NE(d.find("ball_on = pink (no such ball on the table)"), std::string::npos) << d;
}

TEST(ValidateTest, WithTheCueBallInHandTheTableHasNoCueBall) {
  PlanRequest r = Valid();
  r.table.balls.erase(r.table.balls.begin());  // the cue ball
  r.cue_in_hand = true;
  EXPECT_TRUE(ValidatePlanRequest(r, Table()).empty()) << Describe(ValidatePlanRequest(r, Table()));
  // The same table without the cue ball in hand lacks one.
  r.cue_in_hand = false;
  std::vector<FieldError> errors = ErrorsOf(r, "table.balls");
  ASSERT_EQ(errors.size(), 1u) << Describe(errors);
  EXPECT_EQ(errors[0].value, std::optional<double>(0));
  EXPECT_EQ(errors[0].rule, "cue balls: exactly one");
  // A cue ball on the table while it is in hand is one too many.
  r = Valid();
  r.cue_in_hand = true;
  errors = ErrorsOf(r, "table.balls");
  ASSERT_EQ(errors.size(), 1u) << Describe(errors);
  EXPECT_EQ(errors[0].value, std::optional<double>(1));
  EXPECT_EQ(Describe(errors), "table.balls = 1 (cue balls: none with cue_in_hand)");
}

TEST(ValidateTest, PlacementAndFinitePositions) {
  PlanRequest r = Valid();
  r.table.balls[1].position = r.table.balls[0].position;  // overlapping
  EXPECT_NE(Describe(ValidatePlanRequest(r, Table())).find("overlaps"), std::string::npos)
      << Describe(ValidatePlanRequest(r, Table()));
  r = Valid();
  r.table.balls[2].position.x() = std::nan("");
  const std::vector<FieldError> errors = ErrorsOf(r, "table.balls");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].ball, 2);
}

TEST(ValidateTest, OneSigmaPerBallOrNone) {
  PlanRequest r = Valid();
  r.position_sigma = {0.001};
  const std::vector<FieldError> errors = ErrorsOf(r, "position_sigma");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].value, std::optional<double>(1));
  EXPECT_NE(errors[0].rule.find("one per ball (3)"), std::string::npos) << errors[0].rule;
}

TEST(ValidateTest, TooManyBallsAreRefusedBeforeAnythingElse) {
  PlanRequest r = Valid();
  for (int i = 0; i < physics::limits::kMaxBalls; ++i) r.table.balls.push_back({BallKind::kRed, Vec2(0.1, 0.1)});
  const std::vector<FieldError> errors = ValidateTable(r.table, r.cue_in_hand, r.ball_on, Table());
  ASSERT_EQ(errors.size(), 1u) << Describe(errors);
  EXPECT_EQ(errors[0].value, std::optional<double>(static_cast<double>(r.table.balls.size())));
}

}  // namespace
}  // namespace snooker::planner
