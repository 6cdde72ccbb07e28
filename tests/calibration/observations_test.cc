// Tests of calibration/observations.h: valid sets pass; every kind of bad value is
// refused with a message naming the observation, the field and the value.
#include "calibration/observations.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "calibration/datasets.h"

namespace snooker::calibration {
namespace {

using physics::Vec2;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Two throws, two rebounds and one tracked shot of two balls, all valid.
Observations Valid() {
  Observations o;
  o.throws = AlciatoreStunThrow45();
  for (double v : {0.5, 1.5}) {
    CushionObservation r;
    r.speed = v;
    r.angle = physics::kPi / 2;
    r.topspin = v / 0.02625;
    r.rebound_speed = 0.9 * v;
    r.rebound_angle = physics::kPi / 2;
    o.rebounds.push_back(r);
  }
  TrackedShot s;
  s.balls = {Vec2(0.9, 1.0), Vec2(0.9, 1.8)};
  s.strike = physics::CueStrike{2.0, physics::kPi / 2, 0.1, 0.2, 0.05};
  for (int k = 1; k <= 5; ++k) s.sightings.push_back({0.1 * k, {Vec2(0.9, 1.0 + 0.1 * k), Vec2(0.9, 1.8)}});
  o.shots.push_back(s);
  return o;
}

TEST(ValidateTest, ValidSetsPass) {
  EXPECT_EQ(Validate(Valid()), "");
  Observations throws_only;
  throws_only.throws = AlciatoreStunThrow45();
  EXPECT_EQ(Validate(throws_only), "");
}

struct BadCase {
  const char* name;
  std::function<void(Observations*)> spoil;
  const char* message;  // a part of Validate's answer
};

// gtest prints a parameter with this (not as bytes).
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

const BadCase kBadCases[] = {
    {"ObjectBallSpeedNaN", [](Observations* o) { o->throws[3].object_ball_speed = kNaN; },
     "throw[3].object_ball_speed = nan (must be a finite number in (0, 10] m/s)"},
    {"ObjectBallSpeedTooHigh", [](Observations* o) { o->throws[2].object_ball_speed = 12; },
     "throw[2].object_ball_speed = 12 (must be a finite number in (0, 10] m/s)"},
    {"BothSpeeds", [](Observations* o) { o->throws[1].cue_ball_speed = 1.0; },
     "throw[1]: both cue_ball_speed and object_ball_speed are given (give exactly one)"},
    {"NoSpeed", [](Observations* o) { o->throws[0].object_ball_speed.reset(); },
     "throw[0]: neither cue_ball_speed nor object_ball_speed is given (give exactly one)"},
    {"CutSquare", [](Observations* o) { o->throws[4].cut = physics::kPi / 2; }, "throw[4].cut = 1.5708"},
    {"ThrowTooLarge", [](Observations* o) { o->throws[5].measured_throw = 1.0; }, "throw[5].measured_throw = 1 ("},
    {"SpinTooLarge", [](Observations* o) { o->throws[6].sidespin = 2000; }, "throw[6].sidespin = 2000 ("},
    {"SingleThrow", [](Observations* o) { o->throws.resize(1); }, "throw: 1 observation"},
    {"ContradictoryThrows",
     [](Observations* o) {
       o->throws[1] = o->throws[0];
       o->throws[1].measured_throw += physics::DegToRad(4);
     },
     "throw[0] and throw[1] contradict"},
    {"ReboundSpeedNegative", [](Observations* o) { o->rebounds[1].rebound_speed = -1; },
     "rebound[1].rebound_speed = -1 (must be a finite number in [0, 10] m/s)"},
    {"ReboundAngleOutOfRange", [](Observations* o) { o->rebounds[0].rebound_angle = 4.0; },
     "rebound[0].rebound_angle = 4 (must be in (0, pi) rad)"},
    {"ApproachAngleZero", [](Observations* o) { o->rebounds[0].angle = 0; }, "rebound[0].angle = 0 ("},
    {"SingleRebound", [](Observations* o) { o->rebounds.resize(1); }, "rebound: 1 observation"},
    {"ContradictoryRebounds",
     [](Observations* o) {
       o->rebounds[1] = o->rebounds[0];
       o->rebounds[1].rebound_speed += 0.3;
     },
     "rebound[0] and rebound[1] contradict"},
    {"TimesNotIncreasing", [](Observations* o) { o->shots[0].sightings[2].t = 0.15; },
     "shot[0].sightings[2].t = 0.15 (must be after the sighting before it"},
    {"PositionOffTable", [](Observations* o) { o->shots[0].sightings[1].positions[1].x() = 2.5; },
     "shot[0].sightings[1].positions[1].x = 2.5 (must be on the table"},
    {"PositionHalfNaN", [](Observations* o) { o->shots[0].sightings[0].positions[0].y() = kNaN; },
     "shot[0].sightings[0].positions[0].y = nan"},
    {"PositionCount", [](Observations* o) { o->shots[0].sightings[3].positions.pop_back(); },
     "shot[0].sightings[3].positions.size = 1 (must be the number of balls)"},
    {"NoSightings", [](Observations* o) { o->shots[0].sightings.clear(); }, "shot[0].sightings.size = 0"},
    {"BallsOverlap", [](Observations* o) { o->shots[0].balls[1] = Vec2(0.9, 1.03); }, "shot[0].balls: "},
    {"CueBallIndex", [](Observations* o) { o->shots[0].cue_ball = 2; }, "shot[0].cue_ball = 2 ("},
    {"TipOffMiscue", [](Observations* o) { std::get<physics::CueStrike>(o->shots[0].strike).side = 0.99; },
     "shot[0].cue.side = 0.99"},
    {"BallShotTooFast", [](Observations* o) { o->shots[0].strike = physics::Shot{15, 0, 0, 0, 0}; },
     "shot[0].shot.speed = 15"},
    {"Empty", [](Observations* o) { *o = Observations{}; }, "no observations"},
};

class BadObservation : public testing::TestWithParam<BadCase> {};

TEST_P(BadObservation, IsRefusedByName) {
  Observations o = Valid();
  GetParam().spoil(&o);
  const std::string message = Validate(o);
  EXPECT_NE(message.find(GetParam().message), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(Cases, BadObservation, testing::ValuesIn(kBadCases),
                         [](const testing::TestParamInfo<BadCase>& c) { return std::string(c.param.name); });

TEST(ValidateTest, RepeatsWithinTheToleranceAreNotContradictions) {
  Observations o = Valid();
  o.throws[1] = o.throws[0];
  o.throws[1].measured_throw += physics::DegToRad(2);
  o.rebounds[1] = o.rebounds[0];
  o.rebounds[1].rebound_speed += 0.1;
  EXPECT_EQ(Validate(o), "");
}

TEST(ValidateTest, ManyRepeatsOfOneInputGiveOneMessageNamingTheTwoFurthestApart) {
  Observations o = Valid();
  for (int i = 0; i < 5; ++i) o.throws.push_back(o.throws[2]);
  o.throws[9].measured_throw += physics::DegToRad(2);
  o.throws[11].measured_throw -= physics::DegToRad(2);  // 4 deg from throws[9]
  const std::string message = Validate(o);
  EXPECT_NE(message.find("throw[9] and throw[11] contradict"), std::string::npos) << message;
  EXPECT_EQ(message.find(';'), std::string::npos) << message;  // one message
  // A speed given as the cue ball's is another input than the same object ball speed.
  o = Valid();
  o.throws[1] = o.throws[0];
  o.throws[1].cue_ball_speed = o.throws[1].object_ball_speed;
  o.throws[1].object_ball_speed.reset();
  o.throws[1].measured_throw += physics::DegToRad(10);
  EXPECT_EQ(Validate(o), "");
}

TEST(ValidateTest, AnUnseenBallIsNaNInBoth) {
  Observations o = Valid();
  o.shots[0].sightings[4].positions[1] = Vec2(kNaN, kNaN);
  EXPECT_EQ(Validate(o), "");
}

TEST(ValidateTest, NamesEveryBadObservation) {
  Observations o = Valid();
  o.throws[0].cut = -1;
  o.throws[7].topspin = kNaN;
  const std::string message = Validate(o);
  EXPECT_NE(message.find("throw[0].cut = -1"), std::string::npos) << message;
  EXPECT_NE(message.find("throw[7].topspin = nan"), std::string::npos) << message;
}

}  // namespace
}  // namespace snooker::calibration
