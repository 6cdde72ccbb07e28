// Path sampling (physics/sim/paths.h) on recorded runs: the interval grows to keep
// the samples under the cap, every knot is a sample, the first and last samples are
// the balls' start and final positions, and times do not go back.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "physics/sim/paths.h"
#include "tests/support/scenarios.h"

namespace snooker::physics {
namespace {

// A sample may lie a few units in the last place of its time past the next knot
// (paths.h); times here are below 100 s. s.
constexpr double kTimeRoundingTol = 1e-13;

struct PathCase {
  std::string name;
  std::vector<BallState> balls;
  double asked;           // s
  std::int64_t max_points;
};

void PrintTo(const PathCase& c, std::ostream* os) { *os << c.name; }

std::vector<PathCase> Cases() {
  std::mt19937_64 rng(11);
  return {
      {"PotAtDefaultInterval", scenarios::TwoBallPot(true), 0.02, 60'000},
      {"PotCappedHard", scenarios::TwoBallPot(true), 0.02, 200},
      {"BreakOffAtFineInterval", scenarios::BreakOff(), 0.001, 60'000},
      {"BreakOffCapped", scenarios::BreakOff(), 0.001, 2'000},
      {"PlannerShot", scenarios::PlannerWorkloadShot(rng), 0.05, 60'000},
  };
}

class PathsTest : public testing::TestWithParam<PathCase> {
 protected:
  const TableModel& table_ = DefaultTable();
};

TEST_P(PathsTest, SamplesKeepTheCapStartAtTheStartAndEndAtTheFinalPosition) {
  const PathCase& c = GetParam();
  Simulator sim(table_, SimParams{});
  ASSERT_EQ(sim.Run(c.balls), SimStatus::kAtRest);
  const int n = sim.ball_count();
  const double dt = PathSampleInterval(c.asked, sim.end_time(), n, c.max_points);
  EXPECT_GE(dt, c.asked);
  std::int64_t samples = 0, knots = 0;
  std::vector<PathSample> out;
  for (int i = 0; i < n; ++i) {
    SamplePath(sim, i, dt, &out);
    ASSERT_GE(out.size(), 1u);
    samples += static_cast<std::int64_t>(out.size());
    knots += static_cast<std::int64_t>(sim.path(i).size());
    // First and last points: the start and the final position, exactly.
    EXPECT_EQ(out.front().t, 0.0) << "ball " << i;
    EXPECT_EQ(out.front().r, c.balls[static_cast<size_t>(i)].r) << "ball " << i;
    EXPECT_EQ(out.back().r, sim.final_balls()[static_cast<size_t>(i)].r) << "ball " << i;
    const double end = sim.pocket_of(i) >= 0 ? sim.path(i).back().t : sim.end_time();
    EXPECT_EQ(out.back().t, end) << "ball " << i;
    // Times do not go back, and no two samples between knots are further apart than dt.
    for (size_t k = 1; k < out.size(); ++k) {
      EXPECT_GE(out[k].t, out[k - 1].t - kTimeRoundingTol) << "ball " << i << ", sample " << k;
      EXPECT_LE(out[k].t - out[k - 1].t, dt + kTimeRoundingTol) << "ball " << i << ", sample " << k;
    }
    // Every knot's time is a sample's.
    size_t s = 0;
    for (const PathKnot& knot : sim.path(i)) {
      while (s < out.size() && out[s].t != knot.t) ++s;
      EXPECT_LT(s, out.size()) << "ball " << i << ": no sample at knot t = " << knot.t;
    }
  }
  // Under the cap, knots and last points apart (paths.h).
  EXPECT_LE(samples, c.max_points + knots + n);
}

INSTANTIATE_TEST_SUITE_P(Runs, PathsTest, testing::ValuesIn(Cases()),
                         [](const testing::TestParamInfo<PathCase>& p) { return p.param.name; });

TEST(PathSampleIntervalTest, GrowsOnlyPastTheCap) {
  EXPECT_EQ(PathSampleInterval(0.02, 10.0, 22, 60'000), 0.02);  // 11 000 samples
  // 22 balls over 100 s at 0.02 s would be 110 000 samples: the interval doubles, less.
  EXPECT_DOUBLE_EQ(PathSampleInterval(0.02, 100.0, 22, 60'000), 100.0 * 22 / 60'000);
}

TEST(SamplePathTest, ABallThatNeverMovesIsSampledWhereItStands) {
  Simulator sim(DefaultTable(), SimParams{});
  const std::vector<BallState> balls = scenarios::TwoBallPot(true);
  ASSERT_EQ(sim.Run(balls), SimStatus::kAtRest);
  const int still = sim.ball_count() - 1;  // a red of the far triangle: never reached
  ASSERT_EQ(sim.path(still).size(), 1u);
  std::vector<PathSample> out;
  SamplePath(sim, still, 0.02, &out);
  // One sample every 0.02 s from its only knot to the end, all at its start.
  EXPECT_EQ(out.size(), static_cast<size_t>(std::ceil(sim.end_time() / 0.02)) + 1);
  for (const PathSample& p : out) EXPECT_EQ(p.r, balls.back().r);
}

}  // namespace
}  // namespace snooker::physics
