// The Monte Carlo's Gaussian fit of a direct pot's lines at the pocket: its closed
// form, when it stands aside, and its agreement with counting where counting is
// precise; and the tally of the runs that hand the table over.
#include "planner/robustness.h"

#include <gtest/gtest.h>

#include <cmath>

#include "planner/geometry.h"
#include "planner/planner.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

// 48 samples, all potted and all inside the window, z of mean 0 and spread s:
// the fit's chance of a line inside is 2 Phi(1 / s) - 1, and the mean score (10 a
// pot) moves by the fit's shortfall times a pot's worth against a miss's (with no
// miss sampled, the miss hands the opponent the pot's 10).
TEST(PotTailFitTest, TheCorrectionIsTheFittedShortfallTimesWhatAMissCosts) {
  const double s = 0.4;
  MonteCarloTally t;
  t.samples = t.successes = t.line_samples = t.line_inside = 48;
  t.score_sum = t.success_score_sum = 480;
  t.z_sum = 0;
  t.z2_sum = 47 * s * s;
  const double fitted = 2 * NormalCdf(1 / s) - 1;
  EXPECT_NEAR(t.fitted_line_rate(), fitted, 1e-12);
  EXPECT_NEAR(t.tail_corrected_score(16), 10 + (fitted - 1) * 20, 1e-12);
  EXPECT_LT(t.tail_corrected_score(16), t.mean_score());
  // A sampled miss sets what a miss costs: 44 pots at 10, 4 misses at -30.
  t.successes = t.line_inside = 44;
  t.success_score_sum = 440;
  t.score_sum = 320;
  EXPECT_NEAR(t.tail_corrected_score(16), 320.0 / 48 + (fitted - 44.0 / 48) * 40, 1e-12);
}

TEST(PotTailFitTest, TooFewLinesNoPotOrNoSpreadLeaveTheMeanAlone) {
  MonteCarloTally t;
  t.samples = t.successes = t.line_samples = t.line_inside = 12;
  t.score_sum = t.success_score_sum = 120;
  t.z2_sum = 11 * 0.25;
  EXPECT_EQ(t.tail_corrected_score(16), t.mean_score());
  t.successes = t.line_inside = 0;
  t.success_score_sum = 0;
  t.score_sum = -60;
  EXPECT_EQ(t.tail_corrected_score(4), t.mean_score());
  // Every line the same, inside: the fit and the count agree on 1.
  MonteCarloTally same;
  same.samples = same.successes = same.line_samples = same.line_inside = 20;
  same.score_sum = same.success_score_sum = 200;
  same.z_sum = 20 * 0.3;
  same.z2_sum = 20 * 0.09;
  EXPECT_NEAR(same.tail_corrected_score(16), same.mean_score(), 1e-9);
}

// A straight red 0.6 m from the baulk-left pocket and the cue ball 1 m behind it
// (a pot 1.6 m long), struck true at 1.5 m/s with a level centre cue, under
// `aim_deg` of aim noise; the Monte Carlo's inputs for it.
struct StraightPot {
  explicit StraightPot(double aim_deg)
      : planner(Planner::Default()),
        model(physics::DefaultTable()),
        pocket(model.pocket(physics::PocketId::kBaulkLeft)),
        table(Table(pocket)),
        ctx(Context(planner, table, aim_deg)),
        settings(planner.config().search_settings),
        sim(model, planner.config().full),
        cue(LevelStrikeFor({1.5, Direction(pocket.axis), 0, 0}, ctx.cue_params(), planner.config().full.ball,
                           planner.config().full.cloth.g)),
        setup{&table, 0, 1, pocket.id, BallOn::kRed} {}

  MonteCarloTally Run(std::uint64_t seed, int count, bool measure_line = false) {
    return RunSamples(setup, cue, ctx, settings, sim, StopControl{}, seed, count, measure_line);
  }

  const Planner& planner;
  const physics::TableModel& model;
  const physics::Pocket& pocket;
  const TableState table;
  const PotContext ctx;
  const SearchSettings& settings;
  ShotSimulator sim;
  const physics::CueStrike cue;
  const ShotSetup setup;

 private:
  static TableState Table(const physics::Pocket& p) {
    TableState t;
    const Vec2 red = p.mouth_centre - 0.6 * p.axis;
    t.balls = {{BallKind::kCue, red - 1.0 * p.axis}, {BallKind::kRed, red}};
    return t;
  }
  static PotContext Context(const Planner& planner, const TableState& t, double aim_deg) {
    PlanRequest r;
    r.table = t;
    r.noise.aim = aim_deg * physics::kPi / 180;
    return planner.ContextFor(r);
  }
};

// The straight pot under aim noise: the share of lines inside the tabulated window
// is what drops, and the Gaussian fit of the lines gives that share within the
// count's own sampling error.
class PotTailSamplesTest : public ::testing::TestWithParam<double> {};

TEST_P(PotTailSamplesTest, TheFitAgreesWithTheCountAndTheCountWithThePots) {
  StraightPot pot(GetParam());
  ASSERT_NE(pot.ctx.pockets, nullptr);
  const int n = 400;
  const MonteCarloTally tally = pot.Run(5, n, true);
  ASSERT_EQ(tally.samples, n);
  EXPECT_EQ(tally.line_samples, n) << "every sample met the red and measured its line";
  const double counted = static_cast<double>(tally.line_inside) / n;
  const double fitted = tally.fitted_line_rate();
  const double error = 3 * std::sqrt(std::max(counted * (1 - counted), 0.01) / n);
  EXPECT_NEAR(counted, tally.success_rate(), error);
  EXPECT_NEAR(fitted, counted, error);
  // Without measure_line nothing is tallied.
  const MonteCarloTally plain = pot.Run(5, 8);
  EXPECT_EQ(plain.line_samples, 0);
}

// The straight pot under 0.3 deg of aim noise misses often (about 60 % of runs).
// Every miss hands the table over (the red stays on it), no pot does, and a
// handed-over run is worth to the striker exactly minus what the opponent can expect
// from it (no foul, no snooker: the striker's cue ball stays in the open). The red
// left near the pocket is what the opponent is most likely to pot.
TEST(HandoverTallyTest, EveryMissOfAPotHandsTheOpponentWhatTheyCanExpect) {
  StraightPot pot(0.3);
  const MonteCarloTally tally = pot.Run(11, 200);
  ASSERT_EQ(tally.samples, 200);
  ASSERT_EQ(tally.fouls, 0);
  ASSERT_GT(tally.successes, 0);
  ASSERT_LT(tally.successes, 200) << "the noise should make some runs miss";
  EXPECT_EQ(tally.handovers, tally.samples - tally.successes);
  EXPECT_EQ(tally.handovers_snookered, 0);
  const double miss_score_sum = tally.score_sum - tally.success_score_sum;
  EXPECT_NEAR(miss_score_sum, -tally.opponent_points_sum, 1e-9 * std::max(1.0, tally.opponent_points_sum));
  EXPECT_LT(miss_score_sum, 0);
  const double mean_pot = tally.opponent_pot_sum / tally.handovers;
  EXPECT_GT(mean_pot, 0.5) << "a missed red 0.6 m from the pocket is left for them";
  EXPECT_LE(mean_pot, 1.0);
  // Blocks add up: two blocks' tallies, added, are their handovers together.
  const MonteCarloTally a = pot.Run(12, 100);
  const MonteCarloTally b = pot.Run(13, 100);
  MonteCarloTally both = a;
  both.Add(b);
  EXPECT_EQ(both.handovers, a.handovers + b.handovers);
  EXPECT_EQ(both.handovers_snookered, a.handovers_snookered + b.handovers_snookered);
  EXPECT_EQ(both.opponent_pot_sum, a.opponent_pot_sum + b.opponent_pot_sum);
  EXPECT_EQ(both.opponent_points_sum, a.opponent_points_sum + b.opponent_points_sum);
  EXPECT_GT(both.handovers, 0);
}

INSTANTIATE_TEST_SUITE_P(AimNoise, PotTailSamplesTest, ::testing::Values(0.05, 0.1, 0.2),
                         [](const ::testing::TestParamInfo<double>& param) {
                           return "Sigma" + std::to_string(static_cast<int>(std::lround(param.param * 1000))) +
                                  "MilliDeg";
                         });

}  // namespace
}  // namespace snooker::planner
