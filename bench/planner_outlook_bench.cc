// Cost per call of the whole-frame judgements (Google Benchmark), on the
// self-play's mid-frame tables (planner/selfplay.h RandomFrame: colours on their
// spots, reds scattered, the cue ball free):
//  * BM_EvaluateOutlook/<reds>: planner/outlook.h with the cue ball on the table;
//  * BM_EvaluatePosition/<reds>: position.h on the same tables, for scale;
//  * BM_EvaluatePositionTwice/<reds> and ...TwiceCached/<reds>: each table valued
//    twice with the cue ball moved, without and with a kept PocketLineCache;
//  * BM_EvaluateOutlookInHand/<reds>: the same tables without the cue ball (the
//    grid in the D);
//  * BM_EvaluateOutlookSnookered: a constructed snooker (the escape search runs);
//  * BM_LayoutChange/<reds>: planner/layout.h between a table and the table a
//    random stroke at a red left (simulated, the rules applied);
//  * BM_LayoutChangeCached/<reds>: the same with the table before summarised once
//    (as a planner scoring many shots from one table calls it);
//  * BM_SummarizeLayout/<reds>: one table judged afresh;
//  * BM_BreakOffCandidates: planner/break_off.h on the full rack.
// One table per iteration, cycling over 64.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "planner/break_off.h"
#include "planner/geometry.h"
#include "planner/layout.h"
#include "planner/outlook.h"
#include "planner/planner.h"
#include "planner/selfplay.h"
#include "planner/shot_sim.h"

namespace snooker::planner::bench {
namespace {

constexpr int kTables = 64;

std::vector<TableState> Tables(int reds) {
  std::vector<TableState> tables;
  for (int k = 0; k < kTables; ++k) {
    Rng rng(DeriveSeed(77, static_cast<std::uint64_t>(reds), static_cast<std::uint64_t>(k)));
    tables.push_back(RandomFrame(rng, reds, physics::DefaultTable()));
  }
  return tables;
}

PotContext Context() { return Planner::Default().ContextFor(PlanRequest{}); }

void BM_EvaluateOutlook(benchmark::State& state) {
  const std::vector<TableState> tables = Tables(static_cast<int>(state.range(0)));
  const PotContext ctx = Context();
  const OutlookOptions options;
  size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(EvaluateOutlook(tables[k++ % tables.size()], BallOn::kRed, ctx, options));
  }
}
BENCHMARK(BM_EvaluateOutlook)->Arg(10)->Arg(15)->Unit(benchmark::kMicrosecond);

// For scale: position.h's EvaluatePosition on the same tables (the outlook's pots).
void BM_EvaluatePosition(benchmark::State& state) {
  const std::vector<TableState> tables = Tables(static_cast<int>(state.range(0)));
  const PotContext ctx = Context();
  const PositionOptions options;
  size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(EvaluatePosition(tables[k++ % tables.size()], BallOn::kRed, ctx, options));
  }
}
BENCHMARK(BM_EvaluatePosition)->Arg(10)->Unit(benchmark::kMicrosecond);

// Each table valued twice with the cue ball 5 cm apart (as the position spread's
// sides are), with `lines` kept across the tables or without a cache: with one, the
// second value finds the object balls' lines in it.
void ValueEachTableTwice(benchmark::State& state, PocketLineCache* lines) {
  std::vector<TableState> tables = Tables(static_cast<int>(state.range(0)));
  const PotContext ctx = Context();
  const PositionOptions options;
  size_t k = 0;
  for (auto _ : state) {
    TableState& t = tables[k++ % tables.size()];
    physics::Vec2& cue = t.balls[static_cast<size_t>(t.cue_index())].position;
    benchmark::DoNotOptimize(EvaluatePosition(t, BallOn::kRed, ctx, options, lines));
    cue.x() += 0.05;
    benchmark::DoNotOptimize(EvaluatePosition(t, BallOn::kRed, ctx, options, lines));
    cue.x() -= 0.05;
  }
}

void BM_EvaluatePositionTwiceCached(benchmark::State& state) {
  PocketLineCache lines;
  ValueEachTableTwice(state, &lines);
  state.counters["hit_rate"] =
      static_cast<double>(lines.hits()) / static_cast<double>(std::max<std::int64_t>(1, lines.hits() + lines.misses()));
}
BENCHMARK(BM_EvaluatePositionTwiceCached)->Arg(10)->Unit(benchmark::kMicrosecond);

// For scale: the two values without the cache.
void BM_EvaluatePositionTwice(benchmark::State& state) { ValueEachTableTwice(state, nullptr); }
BENCHMARK(BM_EvaluatePositionTwice)->Arg(10)->Unit(benchmark::kMicrosecond);

void BM_EvaluateOutlookInHand(benchmark::State& state) {
  std::vector<TableState> tables = Tables(static_cast<int>(state.range(0)));
  for (TableState& t : tables) t.balls.erase(t.balls.begin() + t.cue_index());
  const PotContext ctx = Context();
  const OutlookOptions options;
  size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(EvaluateOutlook(tables[k++ % tables.size()], BallOn::kRed, ctx, options));
  }
}
BENCHMARK(BM_EvaluateOutlookInHand)->Arg(10)->Unit(benchmark::kMicrosecond);

void BM_EvaluateOutlookSnookered(benchmark::State& state) {
  // Ten reds behind the pink and black, the cue ball below them (every red hidden).
  const physics::TableModel& model = physics::DefaultTable();
  const double mid = model.spec().width / 2, r = model.ball_radius();
  TableState t;
  t.balls = {{BallKind::kCue, {mid, 1.0}}, {BallKind::kPink, {mid - 1.1 * r, 1.5}},
             {BallKind::kBlack, {mid + 1.1 * r, 1.5}}};
  for (int k = 0; k < 10; ++k) t.balls.push_back({BallKind::kRed, {mid - 0.12 + 0.027 * k, 2.3}});
  const PotContext ctx = Context();
  const OutlookOptions options;
  const Outlook check = EvaluateOutlook(t, BallOn::kRed, ctx, options);
  for (auto _ : state) benchmark::DoNotOptimize(EvaluateOutlook(t, BallOn::kRed, ctx, options));
  state.counters["snookered"] = check.snooker.snookered ? 1 : 0;
  state.counters["escape"] = check.escape.ball >= 0 ? 1 : 0;
}
BENCHMARK(BM_EvaluateOutlookSnookered)->Unit(benchmark::kMicrosecond);

// Each table and the table a random stroke at one of its reds leaves.
std::vector<std::pair<TableState, TableState>> ShotPairs(int reds) {
  std::vector<std::pair<TableState, TableState>> pairs;
  ShotSimulator sim(physics::DefaultTable(), physics::SimParams{});
  Rng rng(9);
  std::vector<physics::Vec2> ends;
  for (const TableState& t : Tables(reds)) {
    const int cue = t.cue_index();
    int red = cue;
    while (t.balls[static_cast<size_t>(red)].kind != BallKind::kRed) {
      red = static_cast<int>(rng.Uniform() * static_cast<double>(t.balls.size()));
    }
    physics::Shot shot;
    shot.speed = rng.Uniform(1.0, 4.0);
    shot.heading = Direction(t.balls[static_cast<size_t>(red)].position - t.balls[static_cast<size_t>(cue)].position);
    const ShotSetup setup{&t, cue, red, physics::PocketId::kTopLeft, BallOn::kRed};
    const ShotOutcome& out = sim.Run(setup, shot, {}, ShotSimulator::Mode::kFull, {});
    ends.clear();
    for (const physics::BallState& b : sim.final_balls()) ends.push_back(b.r);
    pairs.emplace_back(t, ApplyShot(t, BallOn::kRed, ends, out.potted, out.foul != Foul::kNone, physics::DefaultTable()));
  }
  return pairs;
}

void BM_LayoutChange(benchmark::State& state) {
  const auto pairs = ShotPairs(static_cast<int>(state.range(0)));
  LayoutOptions options;
  options.pockets = &Planner::Default().pockets();
  size_t k = 0;
  double sum = 0;
  for (auto _ : state) {
    const auto& p = pairs[k++ % pairs.size()];
    const double change = LayoutChange(p.first, p.second, physics::DefaultTable(), options);
    benchmark::DoNotOptimize(change);
  }
  for (const auto& p : pairs) sum += std::abs(LayoutChange(p.first, p.second, physics::DefaultTable(), options));
  state.counters["mean_abs_points"] = sum / static_cast<double>(pairs.size());
}
BENCHMARK(BM_LayoutChange)->Arg(10)->Arg(15)->Unit(benchmark::kMicrosecond);

// As a planner calls it: the table before summarised once, each shot's table after.
void BM_LayoutChangeCached(benchmark::State& state) {
  const auto pairs = ShotPairs(static_cast<int>(state.range(0)));
  LayoutOptions options;
  options.pockets = &Planner::Default().pockets();
  std::vector<LayoutSummary> summaries;
  for (const auto& p : pairs) summaries.push_back(SummarizeLayout(p.first, physics::DefaultTable(), options));
  size_t k = 0;
  for (auto _ : state) {
    const size_t i = k++ % pairs.size();
    benchmark::DoNotOptimize(LayoutChange(pairs[i].first, summaries[i], pairs[i].second, physics::DefaultTable(), options));
  }
}
BENCHMARK(BM_LayoutChangeCached)->Arg(10)->Arg(15)->Unit(benchmark::kMicrosecond);

// SummarizeLayout of one table judged afresh (the before table's cost).
void BM_SummarizeLayout(benchmark::State& state) {
  const std::vector<TableState> tables = Tables(static_cast<int>(state.range(0)));
  LayoutOptions options;
  options.pockets = &Planner::Default().pockets();
  size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(SummarizeLayout(tables[k++ % tables.size()], physics::DefaultTable(), options));
  }
}
BENCHMARK(BM_SummarizeLayout)->Arg(10)->Unit(benchmark::kMicrosecond);

void BM_BreakOffCandidates(benchmark::State& state) {
  const physics::TableModel& model = physics::DefaultTable();
  TableState rack;
  for (int c = 0; c < physics::kColourCount; ++c) {
    rack.balls.push_back({KindOf(static_cast<physics::Colour>(c)), model.spot(static_cast<physics::Colour>(c))});
  }
  for (const physics::Vec2& r : model.reds()) rack.balls.push_back({BallKind::kRed, r});
  for (auto _ : state) benchmark::DoNotOptimize(BreakOffCandidates(rack, model));
}
BENCHMARK(BM_BreakOffCandidates)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace snooker::planner::bench

BENCHMARK_MAIN();
