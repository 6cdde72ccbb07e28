// Tests of the fast pot-probability estimate (planner/pot_estimate.h): its lateral
// spread against sampled ghost-ball geometry, and its probability against Monte
// Carlo with the full simulator on a set of positions.
#include "planner/pot_estimate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "planner/candidates.h"
#include "planner/planner.h"
#include "planner/random.h"
#include "planner/robustness.h"
#include "planner/search.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

constexpr double kR = 0.02625;

TEST(PotEstimateTest, WindowProbabilityIsTheGaussianMassInside) {
  PocketWindow w;
  w.empty = false;
  w.lo = -0.01;
  w.hi = 0.01;
  EXPECT_NEAR(WindowProbability(0, 0.01, w), 0.682689492, 1e-8);  // +-1 sigma
  EXPECT_NEAR(WindowProbability(0.01, 0.01, w), 0.477249868, 1e-8);
  EXPECT_EQ(WindowProbability(0.005, 0, w), 1.0);
  EXPECT_EQ(WindowProbability(0.02, 0, w), 0.0);
  w.empty = true;
  EXPECT_EQ(WindowProbability(0, 0.01, w), 0.0);
}

// The object ball's line at the mouth when the balls really are at cue/object and
// the cue ball runs along `heading`: its offset from `mouth` (left of its travel).
double GeometricOffset(const Vec2& cue, const Vec2& object, double heading, const Vec2& mouth) {
  const Vec2 u(std::cos(heading), std::sin(heading));
  const double b = Cross(u, object - cue);
  const double s = u.dot(object - cue) - std::sqrt(4 * kR * kR - b * b);
  const Vec2 n = (object - (cue + s * u)) / (2 * kR);
  return (object - mouth).dot(Left(n));
}

// The first-order spread matches sampled exact geometry (heading and vision noise,
// no throw) within 3 % (the sampling error of 20000 draws is 0.5 %).
TEST(PotEstimateTest, LateralSigmaMatchesSampledGeometry) {
  NoiseModel noise;
  noise.topspin = noise.sidespin = noise.speed_fraction = 0;
  struct Pot { Vec2 cue, object, mouth; double cut_deg; };
  const std::vector<Pot> pots = {
      {Vec2(0.5, 0.5), Vec2(0.6, 1.6), Vec2(0.03, 3.54), 0},
      {Vec2(1.2, 0.8), Vec2(0.7, 1.8), Vec2(0.03, 3.54), 35},
      {Vec2(0.3, 2.9), Vec2(0.9, 3.0), Vec2(1.75, 3.54), -60}};
  Rng rng(3);
  for (const Pot& p : pots) {
    const Vec2 to_mouth = p.mouth - p.object;
    const auto aim = AimAlong(p.cue, p.object, Direction(to_mouth), kR);
    ASSERT_TRUE(aim);
    const double nominal = GeometricOffset(p.cue, p.object, aim->heading, p.mouth);
    double sum2 = 0;
    const int n = 20000;
    for (int k = 0; k < n; ++k) {
      const Vec2 c = p.cue + noise.position * Vec2(rng.Gaussian(), rng.Gaussian());
      const Vec2 o = p.object + noise.position * Vec2(rng.Gaussian(), rng.Gaussian());
      const double h = aim->heading + noise.heading * rng.Gaussian();
      const double e = GeometricOffset(c, o, h, p.mouth) - nominal;
      sum2 += e * e;
    }
    const double sampled = std::sqrt(sum2 / n);
    const double sigma = LateralSigma(p.cue, p.object, aim->heading, aim->cut, to_mouth.norm(), 1.0,
                                      noise.position, noise.position, noise,
                                      ThrowModel::Default(), kR);
    EXPECT_NEAR(sigma / sampled, 1.0, 0.03) << "cut " << physics::RadToDeg(aim->cut);
  }
}

// The heading's lever: a straight pot with the cue ball d behind the object ball
// and the mouth L beyond it turns the line at the mouth by L (d / 2R - 1) per
// radian (the ghost-ball geometry), and LateralSigma's heading term is that gain.
TEST(PotEstimateTest, HeadingGainIsTheGhostBallLever) {
  const Vec2 cue(0.5, 0.5), object(0.5, 0.9), mouth(0.5, 2.0);
  const double d = (object - cue).norm(), L = (mouth - object).norm();
  EXPECT_NEAR(HeadingGain(cue, object, physics::kPi / 2, 0, L, kR), L * (d / (2 * kR) - 1), 1e-12);
  // A 35 deg cut: only heading noise, no positions, no throw terms.
  NoiseModel noise;
  noise.position = noise.topspin = noise.sidespin = noise.speed_fraction = 0;
  const Vec2 c2(1.2, 0.8), o2(0.7, 1.8), m2(0.03, 3.54);
  const auto aim = AimAlong(c2, o2, Direction(m2 - o2), kR);
  ASSERT_TRUE(aim);
  const double gain = HeadingGain(c2, o2, aim->heading, aim->cut, (m2 - o2).norm(), kR);
  EXPECT_NEAR(LateralSigma(c2, o2, aim->heading, aim->cut, (m2 - o2).norm(), 1.0, 0, 0, noise,
                           ThrowModel::Default(), kR),
              noise.heading * gain, 1e-12);
  // Squirt and throw known to a fraction: that fraction of each, through its lever.
  noise.squirt_fraction = 0.15;
  noise.throw_fraction = 0.1;
  EXPECT_NEAR(SquirtSigma(-0.02, gain, noise), 0.15 * 0.02 * gain, 1e-15);
  EXPECT_NEAR(ThrowSigma(0.03, 1.2, noise), 0.1 * 0.03 * 1.2, 1e-15);
  EXPECT_EQ(SquirtSigma(0.02, gain, ModelWorldNoise()), 0);
  EXPECT_EQ(ThrowSigma(0.03, 1.2, ModelWorldNoise()), 0);
}

// The squirt's spread matches sampled exact geometry: a squirt known to 15 % is a
// heading error of 15 % of it, through the same ghost-ball lever as the aim's
// (within 3 %; the sampling error of 20000 draws is 0.5 %).
TEST(PotEstimateTest, TheSquirtsSpreadMatchesSampledGeometry) {
  NoiseModel noise;
  noise.squirt_fraction = 0.15;
  const double squirt = physics::DegToRad(1.2);  // about what 0.2 R of side gives
  struct Pot { Vec2 cue, object, mouth; };
  const std::vector<Pot> pots = {{Vec2(0.5, 0.5), Vec2(0.6, 1.6), Vec2(0.03, 3.54)},
                                 {Vec2(1.2, 0.8), Vec2(0.7, 1.8), Vec2(0.03, 3.54)},
                                 {Vec2(0.3, 2.9), Vec2(0.9, 3.0), Vec2(1.75, 3.54)}};
  Rng rng(4);
  for (const Pot& p : pots) {
    const auto aim = AimAlong(p.cue, p.object, Direction(p.mouth - p.object), kR);
    ASSERT_TRUE(aim);
    const double nominal = GeometricOffset(p.cue, p.object, aim->heading, p.mouth);
    double sum2 = 0;
    const int n = 20000;
    for (int k = 0; k < n; ++k) {
      const double h = aim->heading + noise.squirt_fraction * squirt * rng.Gaussian();
      const double e = GeometricOffset(p.cue, p.object, h, p.mouth) - nominal;
      sum2 += e * e;
    }
    const double gain = HeadingGain(p.cue, p.object, aim->heading, aim->cut, (p.mouth - p.object).norm(), kR);
    EXPECT_NEAR(SquirtSigma(squirt, gain, noise) / std::sqrt(sum2 / n), 1.0, 0.03)
        << "cut " << physics::RadToDeg(aim->cut);
  }
}

// Agreement with Monte Carlo: on seeded random two-ball positions (every pocket the
// candidates keep, cuts up to 70 deg), the estimate for the plain rolling pot it
// assumes (RollingPotShot) against 200 noisy full simulations of that shot. The
// binomial error of 200 samples is at most 0.035; the estimate's own error is
// larger on long cut pots (first-order spread, tabulated windows). Named
// tolerances: each position within kEach, the mean within kMean.
constexpr double kEach = 0.15;
constexpr double kMean = 0.06;
constexpr int kSamples = 200;

TEST(PotEstimateTest, AgreesWithMonteCarloOnASetOfPositions) {
  const Planner& planner = Planner::Default();
  const physics::TableModel& table = physics::DefaultTable();
  ShotSimulator sim(table, planner.config().full);
  double sum_abs = 0;
  int positions = 0;
  for (int f = 0; f < 12; ++f) {
    Rng rng(DeriveSeed(99, static_cast<std::uint64_t>(f)));
    TableState t;
    t.balls = {{BallKind::kCue, Vec2(rng.Uniform(0.1, 1.6), rng.Uniform(0.1, 3.4))},
               {BallKind::kRed, Vec2(rng.Uniform(0.1, 1.6), rng.Uniform(0.1, 3.4))}};
    PlanRequest req;
    req.table = t;
    const PotContext ctx = planner.ContextFor(req);
    for (const Candidate& c : EnumerateCandidates(t, BallOn::kRed, ctx).candidates) {
      if (std::abs(c.estimate.aim.cut) > physics::DegToRad(70)) continue;
      const auto shot = RollingPotShot(t.balls[0].position, t.balls[1].position, c.estimate,
                                       planner.config().full);
      ASSERT_TRUE(shot);
      const ShotSetup setup{&t, 0, 1, c.pocket, BallOn::kRed};
      Rng mc(DeriveSeed(5, static_cast<std::uint64_t>(f), static_cast<std::uint64_t>(c.pocket)));
      std::vector<Vec2> truth;
      int dropped = 0;
      for (int k = 0; k < kSamples; ++k) {
        SampleTruePositions(t, ctx, mc, &truth);
        // The estimate is of the object ball dropping (not of where the cue ball
        // goes after): run to the end, count the object ball's drops.
        const ShotOutcome& out = sim.Run(setup, SampleExecution(*shot, ctx.noise, mc), truth,
                                         ShotSimulator::Mode::kFull, {});
        dropped += out.first_hit == 1 && out.object_pocket == static_cast<int>(c.pocket);
      }
      const double rate = static_cast<double>(dropped) / kSamples;
      EXPECT_NEAR(c.estimate.probability, rate, kEach)
          << "position " << f << " " << physics::ToString(c.pocket);
      sum_abs += std::abs(c.estimate.probability - rate);
      ++positions;
    }
  }
  ASSERT_GE(positions, 10);
  EXPECT_LT(sum_abs / positions, kMean) << positions << " positions";
  RecordProperty("mean_abs_difference", std::to_string(sum_abs / positions));
}

TEST(PotEstimateTest, LongerAndThinnerPotsAreHarder) {
  const PocketModel& pockets = PocketModel::Default();
  const ThrowModel& throws = ThrowModel::Default();
  const NoiseModel noise;
  const physics::Pocket& p = physics::DefaultTable().pocket(physics::PocketId::kTopRight);
  const Vec2 object = p.mouth_centre - 0.5 * p.axis;
  double last = 2;
  for (const double back : {0.2, 0.6, 1.2, 2.0}) {  // straight, cue ball further back
    const auto e = EstimatePot(object - back * p.axis, object, p.id, noise.position, noise.position,
                               noise, pockets, throws);
    ASSERT_TRUE(e);
    EXPECT_LT(e->probability, last + 1e-12);
    last = e->probability;
  }
  const Vec2 side(-p.axis.y(), p.axis.x());
  last = 2;
  for (const double deg : {0.0, 20.0, 40.0, 60.0}) {  // same distance, thinner cuts
    const double a = physics::DegToRad(deg);
    const Vec2 cue = object - 0.8 * (std::cos(a) * p.axis + std::sin(a) * side);
    const auto e = EstimatePot(cue, object, p.id, noise.position, noise.position, noise, pockets, throws);
    ASSERT_TRUE(e);
    EXPECT_LT(e->probability, last + 1e-12) << deg;
    last = e->probability;
  }
}

// Two lines are the same to the bit (both absent, or every field equal).
bool SameLine(const std::optional<PocketLine>& a, const std::optional<PocketLine>& b) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  return a->direction == b->direction && a->distance == b->distance && a->window.lo == b->window.lo &&
         a->window.hi == b->window.hi && a->window.empty == b->window.empty;
}

// The cache answers what LineIntoPocket answers, from the cache or not: balls over
// the table, every pocket, two arrival speeds, looked up twice.
TEST(PocketLineCacheTest, AnswersExactlyWhatLineIntoPocketDoesAndRemembersIt) {
  const PocketModel& model = PocketModel::Default();
  PocketLineCache cache;
  int lookups = 0, closed = 0, second_pass = 0, second_pass_hits = 0;
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < 5; ++i) {
      for (int j = 0; j < 4; ++j) {
        const Vec2 ball(0.15 + 0.35 * i, 0.3 + 0.95 * j + 0.01 * i);
        for (int k = 0; k < physics::kPocketCount; ++k) {
          const auto pocket = static_cast<physics::PocketId>(k);
          for (const double speed : {kTypicalArrivalSpeed, 1.7}) {
            const auto want = LineIntoPocket(model, ball, pocket, speed);
            closed += pass == 0 && !want ? 1 : 0;
            const std::int64_t before = cache.hits();
            EXPECT_TRUE(SameLine(cache.Line(model, ball, pocket, speed), want)) << i << " " << j << " " << k;
            if (pass == 1) {
              ++second_pass;
              second_pass_hits += static_cast<int>(cache.hits() - before);
            }
            // The same key again at once is always the cache's.
            const std::int64_t hits = cache.hits();
            EXPECT_TRUE(SameLine(cache.Line(model, ball, pocket, speed), want));
            EXPECT_EQ(cache.hits(), hits + 1);
            lookups += 2;
          }
        }
      }
    }
  }
  EXPECT_GT(closed, 0);  // closed pockets are remembered as such too
  EXPECT_EQ(cache.hits() + cache.misses(), lookups);
  // 240 keys in 256 places: the second pass finds most of the first's lines.
  EXPECT_GT(second_pass_hits, second_pass / 2);
}

// A cache handed another pocket model (a coarser table of windows) answers for that
// model, not with the lines it remembers from the first.
TEST(PocketLineCacheTest, AnotherPocketModelIsAnotherKey) {
  PocketModel::Options coarse;
  coarse.angle_step = 10.0 * physics::kPi / 180;
  coarse.arrival_speeds = {0.5};
  coarse.scan_step = 0.005;
  coarse.bisections = 2;
  const PocketModel other(physics::DefaultTable(), physics::SimParams{}, coarse);
  const PocketModel& model = PocketModel::Default();
  ASSERT_NE(other.serial(), model.serial());
  PocketLineCache cache;
  int differ = 0;
  for (int i = 0; i < 6; ++i) {
    const Vec2 ball(0.3 + 0.2 * i, 2.6 + 0.1 * i);
    for (int k = 0; k < physics::kPocketCount; ++k) {
      const auto pocket = static_cast<physics::PocketId>(k);
      const auto first = cache.Line(model, ball, pocket);
      const auto second = cache.Line(other, ball, pocket);
      EXPECT_TRUE(SameLine(first, LineIntoPocket(model, ball, pocket)));
      EXPECT_TRUE(SameLine(second, LineIntoPocket(other, ball, pocket)));
      differ += SameLine(first, second) ? 0 : 1;
    }
  }
  EXPECT_GT(differ, 0);  // the two models do give different lines
  EXPECT_EQ(cache.hits(), 0);
}

}  // namespace
}  // namespace snooker::planner
