// Tests of the position value (planner/position.h).
#include "planner/position.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "planner/planner.h"
#include "planner/search.h"
#include "tests/planner/demo_plans.h"

namespace snooker::planner {
namespace {

using physics::PocketId;
using physics::Vec2;

PotContext Context() { return Planner::Default().ContextFor(PlanRequest{}); }

TableState WithCueAt(const Vec2& cue) {
  const physics::Pocket& p = physics::DefaultTable().pocket(PocketId::kTopRight);
  TableState t;
  t.balls = {{BallKind::kCue, cue}, {BallKind::kRed, p.mouth_centre - 0.5 * p.axis}};
  return t;
}

TEST(PositionTest, AShortStraightPotIsWorthMoreThanALongThinOne) {
  const physics::Pocket& p = physics::DefaultTable().pocket(PocketId::kTopRight);
  const Vec2 red = p.mouth_centre - 0.5 * p.axis;
  const PositionValue good = EvaluatePosition(WithCueAt(red - 0.3 * p.axis), BallOn::kRed, Context(), {});
  const PositionValue poor = EvaluatePosition(WithCueAt(Vec2(1.6, 0.4)), BallOn::kRed, Context(), {});
  EXPECT_EQ(good.next_ball, 1);
  EXPECT_EQ(good.next_pocket, PocketId::kTopRight);
  EXPECT_GT(good.value, 0.95);
  EXPECT_LT(poor.value, good.value - 0.05);
  // Expected points: a red's 1 plus the continuation.
  EXPECT_NEAR(good.expected_points, good.value * (1 + PositionOptions{}.continuation), 1e-9);
}

TEST(PositionTest, AlternativesAddValue) {
  const physics::Pocket& p = physics::DefaultTable().pocket(PocketId::kTopRight);
  TableState one = WithCueAt(p.mouth_centre - 0.8 * p.axis);
  TableState two = one;
  const physics::Pocket& q = physics::DefaultTable().pocket(PocketId::kMiddleRight);
  two.balls.push_back({BallKind::kRed, q.mouth_centre - 0.3 * q.axis});
  const PositionValue v1 = EvaluatePosition(one, BallOn::kRed, Context(), {});
  const PositionValue v2 = EvaluatePosition(two, BallOn::kRed, Context(), {});
  EXPECT_GT(v2.value, v1.value + 0.1);
  EXPECT_LE(v2.value, 1.0 + 0.33 + 0.15);
}

TEST(PositionTest, CushionAndCrampedCueBallArePenalised) {
  const physics::TableModel& table = physics::DefaultTable();
  const physics::Pocket& p = table.pocket(PocketId::kMiddleRight);
  // A red in front of the middle pocket and the cue ball straight behind it; a
  // yellow just beside the cue's line behind the cue ball cramps the stroke.
  const Vec2 red = p.mouth_centre - 0.4 * p.axis;
  const Vec2 cue = red - 0.4 * p.axis;
  TableState open;
  open.balls = {{BallKind::kCue, cue}, {BallKind::kRed, red}};
  TableState cramped = open;
  cramped.balls.push_back({BallKind::kYellow, cue - 0.06 * p.axis + Vec2(0, 0.036)});
  const PositionValue a = EvaluatePosition(open, BallOn::kRed, Context(), {});
  const PositionValue b = EvaluatePosition(cramped, BallOn::kRed, Context(), {});
  EXPECT_GT(a.value, 0.9);
  EXPECT_LT(b.value, a.value);
  // Frozen to the top cushion, pot a red along it into the top-right corner.
  const double c = table.cushion_contact_distance();
  TableState rail;
  rail.balls = {{BallKind::kCue, Vec2(0.6, table.spec().length - c)},
                {BallKind::kRed, Vec2(1.2, table.spec().length - c - 0.001)}};
  TableState off = rail;
  off.balls[0].position.y() -= 2 * table.ball_radius();
  off.balls[1].position.y() -= 2 * table.ball_radius();
  const PositionValue on_rail = EvaluatePosition(rail, BallOn::kRed, Context(), {});
  const PositionValue free = EvaluatePosition(off, BallOn::kRed, Context(), {});
  EXPECT_LT(on_rail.value, free.value);
}

TEST(PositionTest, NothingOnIsWorthNothing) {
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(0.5, 0.5)}, {BallKind::kBlack, physics::DefaultTable().spot(physics::Colour::kBlack)}};
  const PositionValue v = EvaluatePosition(t, BallOn::kRed, Context(), {});
  EXPECT_EQ(v.value, 0);
  EXPECT_EQ(v.next_ball, -1);
}

// The search's position over the cue ball's end spread (ScoreLeave with a spread):
// three-point Gauss-Hermite along it, the end weighted 2/3 and the points sqrt(3)
// spreads either side 1/6 each, every point valued as EvaluatePosition values the
// table the rules leave (the red gone, the black to play); points beyond a
// cushion's contact line held on it.
TEST(PositionSpreadTest, ThePositionIsTheQuadratureMeanAlongTheSpread) {
  const physics::TableModel& model = physics::DefaultTable();
  const PotContext ctx = Context();
  SearchSettings settings;
  const Vec2 black = model.spot(physics::Colour::kBlack);
  TableState table;
  table.balls = {{BallKind::kCue, Vec2(0.6, 2.0)}, {BallKind::kRed, Vec2(1.2, 2.9)}, {BallKind::kBlack, black}};
  const std::vector<int> potted = {1};
  const double d = model.cushion_contact_distance();
  struct Case {
    Vec2 end;
    Vec2 spread;
  } cases[] = {
      {black + Vec2(0.10, -0.35), Vec2(0.0, 0.12)},   // along the black's line: nearer and farther
      {black + Vec2(-0.5, -0.30), Vec2(-0.20, 0.0)},  // towards the left cushion: one point held on it
  };
  for (const Case& c : cases) {
    const std::vector<Vec2> finals = {c.end, model.pocket(PocketId::kTopRight).mouth_centre, black};
    const Leave nominal = ScoreLeave(table, BallOn::kRed, 1, finals, potted, 0.9, ctx, settings);
    LeaveScratch scratch;
    const Leave spread = ScoreLeave(table, BallOn::kRed, 1, finals, potted, 0.9, ctx, settings, &scratch, c.spread);
    double value = 0, points = 0;
    const std::pair<double, double> nodes[] = {{0.0, 2.0 / 3}, {-std::sqrt(3.0), 1.0 / 6}, {std::sqrt(3.0), 1.0 / 6}};
    for (const auto& [s, w] : nodes) {
      const Vec2 p = c.end + s * c.spread;
      TableState after;
      after.balls = {{BallKind::kCue, Vec2(std::clamp(p.x(), d, model.spec().width - d),
                                           std::clamp(p.y(), d, model.spec().length - d))},
                     {BallKind::kBlack, black}};
      const PositionValue v = EvaluatePosition(after, BallOn::kAnyColour, ctx, settings.position);
      value += w * v.value;
      points += w * v.expected_points;
    }
    EXPECT_NEAR(spread.position.value, value, 1e-12);
    EXPECT_NEAR(spread.position.expected_points, points, 1e-9);
    // The nominal end's own value is what the spread leaves out.
    EXPECT_GT(std::abs(spread.position.expected_points - nominal.position.expected_points), 0.05);
    EXPECT_NEAR(spread.score - nominal.score,
                0.9 * (spread.position.expected_points - nominal.position.expected_points), 1e-9);
    EXPECT_EQ(spread.next_ball, nominal.next_ball);  // the ball the stroke plays for
    // The table is handed back as it was: the cue ball at its end.
    EXPECT_EQ(scratch.after.balls[static_cast<size_t>(scratch.after.cue_index())].position, c.end);
  }
  // No spread, or pot-only play: the nominal end alone.
  const std::vector<Vec2> finals = {black + Vec2(0.1, -0.35), Vec2(1.2, 3.5), black};
  const Vec2 spread(0.0, 0.12);
  EXPECT_EQ(ScoreLeave(table, BallOn::kRed, 1, finals, potted, 0.9, ctx, settings, nullptr, Vec2::Zero()).score,
            ScoreLeave(table, BallOn::kRed, 1, finals, potted, 0.9, ctx, settings).score);
  settings.position_play = false;
  EXPECT_EQ(ScoreLeave(table, BallOn::kRed, 1, finals, potted, 0.9, ctx, settings, nullptr, spread).score, 0.9);
}

// A position valued with a cache of the lines is the position valued without, to the
// bit, the cache cold or warm from other tables and other cue balls; and a table
// valued again with its cue ball moved finds its lines in the cache.
TEST(PositionTest, ACacheOfLinesChangesNoValue) {
  const PotContext ctx = Context();
  const PositionOptions options;
  const physics::TableModel& model = physics::DefaultTable();
  PocketLineCache lines;
  for (int t = 0; t < 4; ++t) {
    TableState table;
    table.balls.push_back({BallKind::kCue, Vec2(0.5 + 0.2 * t, 1.2 + 0.3 * t)});
    for (int i = 0; i < 6; ++i) {
      table.balls.push_back({BallKind::kRed, Vec2(0.25 + 0.24 * i, 2.2 + 0.13 * ((i + t) % 4))});
    }
    table.balls.push_back({BallKind::kBlack, model.spot(physics::Colour::kBlack)});
    table.balls.push_back({BallKind::kPink, model.spot(physics::Colour::kPink)});
    for (const BallOn on : {BallOn::kRed, BallOn::kAnyColour}) {
      for (int c = 0; c < 3; ++c) {
        table.balls[0].position = Vec2(0.5 + 0.2 * t + 0.1 * c, 1.2 + 0.3 * t - 0.05 * c);
        const std::int64_t misses = lines.misses(), hits = lines.hits();
        const PositionValue plain = EvaluatePosition(table, on, ctx, options);
        const PositionValue cached = EvaluatePosition(table, on, ctx, options, &lines);
        EXPECT_EQ(cached.value, plain.value) << t << " " << c;
        EXPECT_EQ(cached.expected_points, plain.expected_points) << t << " " << c;
        EXPECT_EQ(cached.next_ball, plain.next_ball);
        EXPECT_EQ(cached.next_pocket, plain.next_pocket);
        EXPECT_EQ(cached.next_probability, plain.next_probability);
        if (c > 0) {  // the object balls did not move
          EXPECT_GE(lines.hits() - hits, 9 * (lines.misses() - misses)) << t << " " << c;
          EXPECT_GT(lines.hits(), hits);
        }
      }
    }
  }
  EXPECT_GT(lines.hits(), lines.misses());
}

// A full table (fifteen reds spread about and the six colours on their spots) keeps
// its lines through a change of the ball on: the reds' lines and the colours' fit the
// cache together, so that valuing both again from a new cue ball position misses
// hardly any (a set of the cache holds eight lines; six pockets a ball).
TEST(PositionTest, AFullTablesLinesStayInTheCache) {
  const PotContext ctx = Context();
  const PositionOptions options;
  const physics::TableModel& model = physics::DefaultTable();
  TableState table;
  table.balls.push_back({BallKind::kCue, Vec2(0.9, 1.0)});
  for (int i = 0; i < 15; ++i) {
    table.balls.push_back({BallKind::kRed, Vec2(0.2 + 0.35 * (i % 5), 2.0 + 0.4 * (i / 5) + 0.03 * i)});
  }
  for (const physics::Colour c :
       {physics::Colour::kYellow, physics::Colour::kGreen, physics::Colour::kBrown,
        physics::Colour::kBlue, physics::Colour::kPink, physics::Colour::kBlack}) {
    table.balls.push_back({KindOf(c), model.spot(c)});
  }
  PocketLineCache lines;
  for (const BallOn on : {BallOn::kRed, BallOn::kAnyColour}) EvaluatePosition(table, on, ctx, options, &lines);
  const std::int64_t first_misses = lines.misses(), hits = lines.hits();
  EXPECT_GE(first_misses, 100);  // 21 object balls, six pockets each
  table.balls[0].position = Vec2(1.1, 1.3);
  for (const BallOn on : {BallOn::kRed, BallOn::kAnyColour}) {
    const PositionValue plain = EvaluatePosition(table, on, ctx, options);
    const PositionValue cached = EvaluatePosition(table, on, ctx, options, &lines);
    EXPECT_EQ(cached.value, plain.value);
    EXPECT_EQ(cached.expected_points, plain.expected_points);
  }
  const std::int64_t new_misses = lines.misses() - first_misses;
  EXPECT_GE(lines.hits() - hits, 20 * new_misses) << new_misses << " misses";
  EXPECT_GE(lines.hits() - hits, first_misses / 2);
}

// A candidate's search with a kept scratch, its cache of lines warm from the searches
// before it, finds the very shots a search with a scratch of its own finds, with the
// position spread as without it.
TEST(PositionTest, ASearchWithAKeptScratchFindsTheSameShots) {
  const TableState table = testing_tables::DemoTable();
  const Planner& planner = Planner::Default();
  const PotContext ctx = planner.ContextFor(PlanRequest{});
  const CandidateSet set = EnumerateCandidates(table, BallOn::kRed, ctx);
  ASSERT_GE(set.candidates.size(), 3u);
  ShotSimulator sim(*ctx.table, planner.config().search);
  LeaveScratch kept;
  for (const double spread : {0.0, 2.0}) {
    SearchSettings settings;
    settings.position_spread = spread;
    for (size_t i = 0; i < 3; ++i) {
      const Candidate& cand = set.candidates[i];
      const SearchResult own = SearchCandidate(table, BallOn::kRed, cand, ctx, settings, sim, StopControl{});
      const SearchResult warm = SearchCandidate(table, BallOn::kRed, cand, ctx, settings, sim, StopControl{}, &kept);
      ASSERT_EQ(own.best.has_value(), warm.best.has_value()) << i;
      EXPECT_EQ(own.evaluations, warm.evaluations) << i;
      if (!own.best) continue;
      EXPECT_EQ(own.best->score, warm.best->score) << "candidate " << i << ", spread " << spread;
      EXPECT_EQ(own.best->shot.speed, warm.best->shot.speed) << i;
      EXPECT_EQ(own.best->cut, warm.best->cut) << i;
      EXPECT_EQ(own.best->position.expected_points, warm.best->position.expected_points) << i;
    }
  }
  EXPECT_GT(kept.lines.hits(), kept.lines.misses());
}

}  // namespace
}  // namespace snooker::planner
