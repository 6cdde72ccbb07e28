// Tests of the position value (planner/position.h).
#include "planner/position.h"

#include <gtest/gtest.h>

#include "planner/planner.h"

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

}  // namespace
}  // namespace snooker::planner
