// The planner's hot path allocates nothing once its buffers have grown: a search's
// and a Monte Carlo's every evaluation is a simulation and the scoring of the table
// it leaves. This executable counts the global operator new (its own, so that no
// other test pays for the count), and asserts that a reused simulator and a reused
// LeaveScratch make no allocation on a repeated evaluation.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <vector>

#include "physics/table/table.h"
#include "planner/layout.h"
#include "planner/planner.h"
#include "planner/robustness.h"
#include "planner/search.h"
#include "planner/shot_sim.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// GCC pairs the operator new it sees with the free in these deletes and warns; they
// are this file's own pair.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace snooker::planner {
namespace {

using physics::PocketId;
using physics::Vec2;

// A red in line with the top-right pocket and the cue ball behind it, the colours on
// their spots and three reds of the pack.
TableState Table() {
  const physics::TableModel& model = physics::DefaultTable();
  const physics::Pocket& p = model.pocket(PocketId::kTopRight);
  TableState t;
  const Vec2 red = p.mouth_centre - 0.4 * p.axis;
  t.balls = {{BallKind::kCue, red - 0.5 * p.axis}, {BallKind::kRed, red}};
  for (const physics::Colour c : {physics::Colour::kYellow, physics::Colour::kGreen, physics::Colour::kBrown,
                                  physics::Colour::kBlue, physics::Colour::kPink, physics::Colour::kBlack}) {
    t.balls.push_back({KindOf(c), model.spot(c)});
  }
  for (int i : {0, 5, 10}) t.balls.push_back({BallKind::kRed, model.reds()[static_cast<size_t>(i)]});
  return t;
}

struct Scene {
  TableState table = Table();
  PotContext ctx = Planner::Default().ContextFor(PlanRequest{});
  LayoutSummary layout;
  SearchSettings settings;
  Scene() {
    LayoutOptions o;
    o.pockets = ctx.pockets;
    layout = SummarizeLayout(table, *ctx.table, o);
    ctx.layout = &layout;
  }
};

// Allocations made by f(), run once to grow the buffers and then counted.
template <class F>
long AllocationsOfASecondRun(F f) {
  f();
  const long before = g_allocations.load();
  f();
  return g_allocations.load() - before;
}

TEST(AllocationTest, TheCounterSeesAnAllocation) {
  const long before = g_allocations.load();
  auto* v = new std::vector<int>(100);
  EXPECT_GE(g_allocations.load() - before, 2);
  delete v;
}

TEST(AllocationTest, AReusedSimulatorAndScratchScoreAPotWithoutAllocating) {
  Scene s;
  const physics::Pocket& p = s.ctx.table->pocket(PocketId::kTopRight);
  const ShotSetup setup{&s.table, 0, 1, p.id, BallOn::kRed};
  ShotSimulator sim(*s.ctx.table, physics::SimParams{});
  LeaveScratch scratch;
  std::vector<Vec2> finals;
  finals.reserve(s.table.balls.size());
  const physics::Shot shot{1.5, std::atan2(p.axis.y(), p.axis.x()), -1.5 / 0.02625, 0};  // screw: no in-off
  double score = 0, over_spread = 0;
  const long n = AllocationsOfASecondRun([&] {
    const ShotOutcome& out = sim.Run(setup, shot, {}, ShotSimulator::Mode::kDecide, {});
    ASSERT_TRUE(out.success);
    finals.clear();
    for (const physics::BallState& b : sim.final_balls()) finals.push_back(b.r);
    score = ScoreLeave(s.table, BallOn::kRed, 1, finals, out.potted, 1.0, s.ctx, s.settings, &scratch)
                .score;
    // The position over the cue ball's end spread (the search's position_spread).
    over_spread = ScoreLeave(s.table, BallOn::kRed, 1, finals, out.potted, 1.0, s.ctx, s.settings, &scratch,
                             0.05 * out.cue_last_direction)
                      .score;
  });
  EXPECT_EQ(n, 0);
  EXPECT_GT(score, 1.0);  // the red's point and a colour to follow
  EXPECT_GT(over_spread, 1.0);
  EXPECT_NE(over_spread, score);  // the cue ball came back: it had a spread to value
}

TEST(AllocationTest, ScoringALeaveThatRespotsAColourDoesNotAllocateWithAScratch) {
  Scene s;
  // The pink dropped with the red: it comes back to its spot (the rules' re-spot).
  std::vector<Vec2> finals;
  for (const Ball& b : s.table.balls) finals.push_back(b.position);
  const int pink = 6;
  ASSERT_EQ(s.table.balls[pink].kind, BallKind::kPink);
  const std::vector<int> potted = {1, pink};
  LeaveScratch scratch;
  const long n = AllocationsOfASecondRun(
      [&] { ScoreLeave(s.table, BallOn::kRed, 1, finals, potted, 0.9, s.ctx, s.settings, &scratch); });
  EXPECT_EQ(n, 0);
  ASSERT_EQ(scratch.after.balls.size(), s.table.balls.size() - 1);  // the red down, the pink back
  EXPECT_EQ(scratch.after.balls.back().kind, BallKind::kPink);
}

// A safety's table goes to the opponent: their outlook (a snooker check, their
// pots) is scored on the scratch's table without allocating either.
TEST(AllocationTest, ScoringASafetyAndAMonteCarloSampleDoesNotAllocateWithAScratch) {
  Scene s;
  const physics::Pocket& p = s.ctx.table->pocket(PocketId::kTopRight);
  std::vector<Vec2> finals;
  for (const Ball& b : s.table.balls) finals.push_back(b.position);
  finals[0] = Vec2(0.9, 0.5);  // the cue ball sent to baulk
  LeaveScratch scratch;
  Leave safety;
  const long n = AllocationsOfASecondRun(
      [&] { safety = ScoreSafety(s.table, BallOn::kRed, 1, finals, {}, s.ctx, s.settings, &scratch); });
  EXPECT_EQ(n, 0);
  ASSERT_TRUE(safety.opponent.has_value());
  EXPECT_LE(safety.score, 0.0);  // what the opponent can expect, negated
  // The same table as a Monte Carlo sample of a safety that played it.
  ShotSetup setup{&s.table, 0, 1, p.id, BallOn::kRed};
  setup.kind = ShotKind::kSafety;
  ShotOutcome out;
  out.first_hit = 1;
  out.success = true;
  double score = 1;
  const long m = AllocationsOfASecondRun(
      [&] { score = MonteCarloScore(setup, out, finals, s.ctx, s.settings, &scratch).score; });
  EXPECT_EQ(m, 0);
  EXPECT_DOUBLE_EQ(score, safety.score);
}

// An in-off: the opponent has the cue ball in hand, and their outlook places it on
// the D's grid in the scratch's own table, without allocating once it has grown.
TEST(AllocationTest, ScoringAnInOffSampleDoesNotAllocateWithAScratch) {
  Scene s;
  const physics::Pocket& p = s.ctx.table->pocket(PocketId::kTopRight);
  const ShotSetup setup{&s.table, 0, 1, p.id, BallOn::kRed};
  std::vector<Vec2> finals;
  for (const Ball& b : s.table.balls) finals.push_back(b.position);
  ShotOutcome out;
  out.first_hit = 1;
  out.foul = Foul::kCuePotted;
  out.potted = {0};
  LeaveScratch scratch;
  SampleWorth worth;
  const long n = AllocationsOfASecondRun(
      [&] { worth = MonteCarloScore(setup, out, finals, s.ctx, s.settings, &scratch); });
  EXPECT_EQ(n, 0);
  ASSERT_TRUE(worth.handed_over);
  EXPECT_LE(worth.score, -4.0);  // the penalty at least, and the table handed over
  // The in-hand table was placed in the scratch: every ball left and the cue ball.
  EXPECT_EQ(scratch.placed.balls.size(), s.table.balls.size());
  EXPECT_EQ(scratch.placed.balls.back().kind, BallKind::kCue);
  // Without a scratch the same sample scores the same.
  EXPECT_DOUBLE_EQ(MonteCarloScore(setup, out, finals, s.ctx, s.settings).score, worth.score);
}

// The Monte Carlo's blocks: a worker keeps a SampleScratch, so that a block after
// its first (another stream, the same stroke) runs its samples, and scores the
// tables they leave, without allocating; also when vision gives every ball its own
// sigma, which the scoring of the table left sets aside.
TEST(AllocationTest, AMonteCarloBlockWithAKeptScratchDoesNotAllocate) {
  Scene s;
  s.ctx.position_sigma.assign(s.table.balls.size(), 0.3e-3);
  const physics::Pocket& p = s.ctx.table->pocket(PocketId::kTopRight);
  const ShotSetup setup{&s.table, 0, 1, p.id, BallOn::kRed};
  const Planner& planner = Planner::Default();
  ShotSimulator sim(*s.ctx.table, planner.config().full);
  const physics::Shot screw{1.5, std::atan2(p.axis.y(), p.axis.x()), -1.5 / 0.02625, 0};  // no in-off
  const physics::CueStrike cue =
      LevelStrikeFor(screw, s.ctx.cue_params(), planner.config().full.ball, planner.config().full.cloth.g);
  SampleScratch scratch;
  std::uint64_t seed = 1;
  MonteCarloTally tally;
  const long n = AllocationsOfASecondRun([&] {
    tally = RunSamples(setup, cue, s.ctx, s.settings, sim, StopControl{}, seed++, 8, true, &scratch);
  });
  EXPECT_EQ(n, 0);
  EXPECT_EQ(tally.samples, 8);
  EXPECT_GE(tally.successes, 7);  // a straight 0.4 m pot under the request's default noise
  EXPECT_EQ(tally.line_samples, 8);
  // Without a kept scratch the same block allocates its buffers every time, which
  // is what the count above would see.
  const long own = AllocationsOfASecondRun(
      [&] { RunSamples(setup, cue, s.ctx, s.settings, sim, StopControl{}, seed++, 8, true); });
  EXPECT_GT(own, 0);
}

}  // namespace
}  // namespace snooker::planner
