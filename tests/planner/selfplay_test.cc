// Tests of self-play (planner/selfplay.h): the random frames are what the header
// describes, and a short run's statistics are consistent with its frames.
#include "planner/selfplay.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>

namespace snooker::planner {
namespace {

using physics::Vec2;

TEST(SelfPlayTest, RandomFramesAreValidMidFrameTables) {
  const physics::TableModel& table = physics::DefaultTable();
  Rng rng(8);
  for (int k = 0; k < 50; ++k) {
    const int reds = 6 + k % 5;
    const TableState t = RandomFrame(rng, reds, table);
    EXPECT_EQ(t.reds(), reds);
    EXPECT_EQ(t.Count(BallKind::kCue), 1);
    for (int c = 0; c < physics::kColourCount; ++c) {
      const BallKind kind = KindOf(static_cast<physics::Colour>(c));
      ASSERT_EQ(t.Count(kind), 1);
      for (const Ball& b : t.balls) {
        if (b.kind == kind) {
          EXPECT_EQ(b.position, table.spot(static_cast<physics::Colour>(c)));
        }
      }
    }
    std::vector<physics::BallPlacement> placed;
    for (const Ball& b : t.balls) placed.push_back({"", b.position});
    EXPECT_EQ(table.ValidatePlacement(placed), "");
    // Scattered reds touch nothing.
    for (size_t i = 0; i < t.balls.size(); ++i) {
      for (size_t j = i + 1; j < t.balls.size(); ++j) {
        EXPECT_GT((t.balls[i].position - t.balls[j].position).norm(), 2 * table.ball_radius());
      }
    }
  }
}

TEST(SelfPlayTest, PercentileIsNearestRank) {
  const std::vector<double> v = {5, 1, 4, 2, 3};
  EXPECT_EQ(Percentile(v, 0.5), 3);
  EXPECT_EQ(Percentile(v, 0.99), 5);
  EXPECT_EQ(Percentile(v, 0.0), 1);
  EXPECT_EQ(Percentile({}, 0.5), 0);
}

// A short self-play whose plans are capped in simulations, so that it is a function
// of its seed.
SelfPlayOptions ShortRun(int frames, std::uint64_t seed, int max_shots_per_frame) {
  SelfPlayOptions o;
  o.frames = frames;
  o.seed = seed;
  o.time_budget = 30;
  o.max_simulations = 100;
  o.monte_carlo_samples = 8;
  o.max_shots_per_frame = max_shots_per_frame;
  return o;
}

// Frame for frame the same breaks, attempts and ends.
bool SameFrames(const SelfPlayReport& a, const SelfPlayReport& b) {
  if (a.records.size() != b.records.size()) return false;
  for (size_t i = 0; i < a.records.size(); ++i) {
    const FrameRecord &x = a.records[i], &y = b.records[i];
    if (x.points != y.points || x.attempts != y.attempts || x.end != y.end) return false;
  }
  return true;
}

TEST(SelfPlayTest, AShortRunIsConsistent) {
  const SelfPlayOptions o = ShortRun(2, 3, 4);
  const SelfPlayReport r = RunSelfPlay(Planner::Default(), o);
  ASSERT_EQ(r.frames, 2);
  ASSERT_EQ(r.records.size(), 2u);
  int shots = 0, pots = 0, total = 0;
  for (const FrameRecord& f : r.records) {
    EXPECT_GE(f.reds, 6);
    EXPECT_LE(f.reds, 10);
    EXPECT_LE(f.pots, f.attempts);
    // Reds and colours alternate: a break of n pots scores at least n.
    EXPECT_GE(f.points, f.pots);
    EXPECT_FALSE(f.end.empty());
    shots += f.attempts;
    pots += f.pots;
    total += f.points;
    EXPECT_GE(r.max_break, f.points);
  }
  EXPECT_EQ(r.shots, shots);
  EXPECT_EQ(r.pots, pots);
  EXPECT_DOUBLE_EQ(r.mean_break, total / 2.0);
  EXPECT_GE(static_cast<int>(r.plan_ms.size()), shots);
  EXPECT_LE(r.plan_ms_p50, r.plan_ms_p99);
  EXPECT_EQ(r.plans_cut_short, 0);  // capped in simulations, with a budget of 30 s
  // Same seed, same frames.
  const SelfPlayReport again = RunSelfPlay(Planner::Default(), o);
  for (size_t i = 0; i < r.records.size(); ++i) {
    EXPECT_EQ(r.records[i].points, again.records[i].points);
    EXPECT_EQ(r.records[i].end, again.records[i].end);
  }
}

// Plans that the clock ends are counted: a budget of 1 ms that buys a million
// simulations a millisecond ends every plan's search by the clock.
TEST(SelfPlayTest, PlansTheClockCutShortAreCounted) {
  PlannerConfig config;
  config.simulations_per_ms = 1e6;
  const Planner planner(config);
  SelfPlayOptions o = ShortRun(1, 3, 3);
  o.time_budget = 1e-3;
  o.max_simulations = 0;
  o.threads = 1;
  const SelfPlayReport r = RunSelfPlay(planner, o);
  ASSERT_GT(r.plan_ms.size(), 0u);
  EXPECT_EQ(r.plans_cut_short, static_cast<int>(r.plan_ms.size()));
}

// A world with a real table's uncertainty: with the squirt and throw fractions at 0
// it is the model itself, to the point (the noise's draws are the same); with them
// set, the strokes play differently.
TEST(SelfPlayTest, AnUncertainWorldIsTheModelWhenNothingIsUncertain) {
  SelfPlayOptions o = ShortRun(3, 5, 6);
  const SelfPlayReport model = RunSelfPlay(Planner::Default(), o);
  ASSERT_GT(model.shots, 3);
  o.uncertain_world = true;
  EXPECT_TRUE(SameFrames(RunSelfPlay(Planner::Default(), o), model));
  // Known to 100 % (the most a request may say), the strokes play otherwise.
  o.noise.squirt_fraction = o.noise.throw_fraction = 1;
  const SelfPlayReport uncertain = RunSelfPlay(Planner::Default(), o);
  o.uncertain_world = false;
  EXPECT_FALSE(SameFrames(uncertain, RunSelfPlay(Planner::Default(), o)));
}

}  // namespace
}  // namespace snooker::planner
