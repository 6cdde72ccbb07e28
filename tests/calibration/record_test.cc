// Tests of calibration/record.h: reproducible, plausible shots whose sightings
// are the world's simulation plus the stated noise.
#include "calibration/record.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "calibration/predict.h"

namespace snooker::calibration {
namespace {

using physics::Vec2;

bool Same(const Vec2& a, const Vec2& b) {
  return (a.array() == b.array()).all() || (a.array().isNaN() && b.array().isNaN()).all();
}

TEST(RecordTest, TheSameSeedGivesTheSameShots) {
  const physics::Model world;
  const std::vector<TrackedShot> a = Record(world, 6, 42, 1e-3), b = Record(world, 6, 42, 1e-3);
  const std::vector<TrackedShot> c = Record(world, 6, 43, 1e-3);
  ASSERT_EQ(a.size(), 6u);
  bool differs = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].balls.size(), b[i].balls.size());
    ASSERT_EQ(a[i].sightings.size(), b[i].sightings.size());
    for (std::size_t j = 0; j < a[i].sightings.size(); ++j) {
      EXPECT_EQ(a[i].sightings[j].t, b[i].sightings[j].t);
      for (std::size_t k = 0; k < a[i].balls.size(); ++k) {
        EXPECT_TRUE(Same(a[i].sightings[j].positions[k], b[i].sightings[j].positions[k]));
      }
    }
    differs = differs || a[i].balls[0] != c[i].balls[0];
  }
  EXPECT_TRUE(differs);
}

// Cue-form strikes in the stated ranges, two or three balls, sightings every
// 0.1 s until after rest, mostly with the object ball struck; the sightings are
// the world's positions plus noise of the stated size.
TEST(RecordTest, ShotsArePlausibleAndTheirNoiseIsAsStated) {
  const physics::Model world;
  constexpr double kNoise = 1e-3;
  const std::vector<TrackedShot> shots = Record(world, 30, 5, kNoise);
  Observations o;
  o.shots = shots;
  EXPECT_EQ(Validate(o), "");
  int struck = 0, three = 0, n = 0;
  double sum2 = 0;
  for (const TrackedShot& s : shots) {
    ASSERT_GE(s.balls.size(), 2u);
    ASSERT_LE(s.balls.size(), 3u);
    three += s.balls.size() == 3;
    const auto& k = std::get<physics::CueStrike>(s.strike);
    EXPECT_GE(k.speed, 0.5);
    EXPECT_LE(k.speed, 4.0);
    EXPECT_LE(std::hypot(k.side, k.height), 0.9 * physics::MiscueLimit(world.cue));
    EXPECT_LE(k.elevation, physics::DegToRad(5.0));
    EXPECT_NEAR(s.sightings[0].t, 0.1, 1e-12);
    const ShotPrediction p = PredictShot(s, world);
    ASSERT_EQ(p.error, "");
    EXPECT_GE(s.sightings.back().t, p.end_time);
    struck += (p.positions.back()[1] - s.balls[1]).norm() > 0.01;
    for (std::size_t j = 0; j < s.sightings.size(); ++j) {
      for (std::size_t b = 0; b < s.balls.size(); ++b) {
        const Vec2& seen = s.sightings[j].positions[b];
        if (std::isnan(seen.x())) continue;
        sum2 += (seen - p.positions[j][b]).squaredNorm();
        n += 2;
      }
    }
  }
  EXPECT_GE(struck, 18);  // most shots strike the object ball
  EXPECT_GE(three, 5);
  EXPECT_NEAR(std::sqrt(sum2 / n), kNoise, 0.05 * kNoise);
}

TEST(RecordTest, BadArgumentsAreNamed) {
  const physics::Model world;
  auto message = [&](auto call) -> std::string {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message([&] { Record(world, -1, 1, 0); }).find("shots = -1"), std::string::npos);
  EXPECT_NE(message([&] { Record(world, 1, 1, NAN); }).find("vision_noise_m = nan"), std::string::npos);
  RecordOptions o;
  o.max_cue_speed = 0.1;
  EXPECT_NE(message([&] { Record(world, 1, 1, 0, o); }).find("max_cue_speed = 0.1"), std::string::npos);
  physics::Model bad;
  bad.cloth.mu_s = -1;
  EXPECT_NE(message([&] { Record(bad, 1, 1, 0); }).find("world: cloth.mu_s = -1"), std::string::npos);
}

}  // namespace
}  // namespace snooker::calibration
