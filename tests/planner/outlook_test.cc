// Tests of the outlook (planner/outlook.h): the snooker check on tables whose answer
// the geometry fixes, checked against the simulator; the touching ball; the cost of
// a snooker by its stated model; the ball in hand's grid in the D.
#include "planner/outlook.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "planner/geometry.h"
#include "planner/planner.h"
#include "planner/selfplay.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

PotContext Context() { return Planner::Default().ContextFor(PlanRequest{}); }
const physics::TableModel& Model() { return physics::DefaultTable(); }
double R() { return Model().ball_radius(); }
double Mid() { return Model().spec().width / 2; }

// The first ball the cue ball touches when `shot` is played (-1: none), by the
// simulator, stopping at that contact.
int FirstHit(const TableState& t, int cue, const physics::Shot& shot) {
  physics::Simulator sim(Model(), physics::SimParams{});
  std::vector<physics::BallState> balls(t.balls.size());
  for (size_t i = 0; i < t.balls.size(); ++i) {
    balls[i].r = t.balls[i].position;
    if (static_cast<int>(i) == cue) balls[i] = physics::StruckBall(shot, t.balls[i].position);
  }
  physics::SimStatus st = sim.Start(balls, physics::RunOptions::Lean());
  for (int k = 0; k < 5000 && st == physics::SimStatus::kRunning; ++k) {
    st = sim.Step();
    const physics::SimEvent& ev = sim.last_event();
    if (st == physics::SimStatus::kRunning && ev.kind == physics::EventKind::kBallBall &&
        (ev.ball == cue || ev.other == cue)) {
      return ev.ball == cue ? ev.other : ev.ball;
    }
  }
  return -1;
}

physics::Shot Stroke(double heading, double speed = 1.5) {
  physics::Shot s;
  s.heading = heading;
  s.speed = speed;
  return s;
}

// The cue ball at (mid, 1.0), a red 1 m up the table, a pink half-way, `s` to the
// side (+x). A stroke whose line passes the red's centre at offset b passes the
// pink's at about |s - b/2|, and |b| <= 2R sin(80 deg) = 51.7 mm: it clears the
// pink by 2R + 0.5 mm = 53 mm only when |s - b/2| >= 53 mm.
TableState Hidden(double s) {
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(Mid(), 1.0)},
             {BallKind::kRed, Vec2(Mid(), 2.0)},
             {BallKind::kPink, Vec2(Mid() + s, 1.5)}};
  return t;
}

TEST(OutlookTest, ABallHalfWayHidesTheBallOnWhenCentred) {
  const PotContext ctx = Context();
  for (double s : {0.0, 0.010, 0.025, -0.025}) {
    const SnookerCheck c = CheckSnooker(Hidden(s), 0, BallOn::kRed, ctx, 13);
    EXPECT_EQ(c.balls_on, 1) << s;
    EXPECT_EQ(c.hittable, 0) << s;
    EXPECT_TRUE(c.snookered) << s;
    EXPECT_EQ(c.hittable_share, 0) << s;
    EXPECT_EQ(c.touching, -1);
  }
  // The simulator agrees for the centred pink: no stroke across the red's whole
  // width (every contact, the thinnest included) reaches it first.
  const TableState t = Hidden(0);
  const double half = std::asin(2 * R() / 1.0);
  for (int k = 0; k <= 120; ++k) {
    const double h = physics::kPi / 2 - half + 2 * half * k / 120;
    EXPECT_NE(FirstHit(t, 0, Stroke(h)), 1) << h;
  }
}

TEST(OutlookTest, ABallOffTheLineLeavesOnlyTheThinContactOnTheFarSide) {
  const PotContext ctx = Context();
  // s = 30 mm: only b = -51.7 mm clears (30 + 25.9 = 55.9 mm); the next sample,
  // b = -43.1 mm, passes at 51.5 mm.
  const TableState t = Hidden(0.030);
  EXPECT_FALSE(CheckSnooker(t, 0, BallOn::kRed, ctx, 13).snookered);
  const auto h = DirectHitHeading(t, 0, 1, ctx, 13);
  ASSERT_TRUE(h.has_value());
  const double b = 1.0 * std::sin(physics::kPi / 2 - *h);  // offset of the line at the red
  EXPECT_NEAR(b, -2 * R() * std::sin(ctx.max_cut), 1e-9);
  EXPECT_EQ(FirstHit(t, 0, Stroke(*h)), 1);
  // The full ball alone (one sample) is blocked.
  EXPECT_FALSE(CanHitDirectly(t, 0, 1, ctx, 1));
  // With the pink 60 mm aside the full ball is open and chosen first.
  const auto full = DirectHitHeading(Hidden(0.060), 0, 1, ctx, 13);
  ASSERT_TRUE(full.has_value());
  EXPECT_NEAR(*full, physics::kPi / 2, 1e-12);
}

TEST(OutlookTest, ShareCountsTheBallsOnHittable) {
  TableState t = Hidden(0);
  t.balls.push_back({BallKind::kRed, Vec2(0.3, 1.0)});
  t.balls.push_back({BallKind::kBlack, Vec2(1.4, 3.0)});
  const SnookerCheck c = CheckSnooker(t, 0, BallOn::kRed, Context(), 13);
  EXPECT_EQ(c.balls_on, 2);
  EXPECT_EQ(c.hittable, 1);
  EXPECT_DOUBLE_EQ(c.hittable_share, 0.5);
  EXPECT_FALSE(c.snookered);
  // On the black: the black is in the open, off the line of the pink and the red.
  const SnookerCheck b = CheckSnooker(t, 0, BallOn::kBlack, Context(), 13);
  EXPECT_EQ(b.balls_on, 1);
  EXPECT_EQ(b.hittable, 1);
  // No ball on: neither snookered nor anything to hit.
  const SnookerCheck none = CheckSnooker(t, 0, BallOn::kYellow, Context(), 13);
  EXPECT_EQ(none.balls_on, 0);
  EXPECT_FALSE(none.snookered);
  EXPECT_EQ(none.hittable_share, 0);
}

TEST(OutlookTest, TouchingBallOnMeansNotSnookered) {
  // The red behind the pink is hidden, but a second red touches the cue ball
  // (a 50 um gap, under kTouchingGap): it counts as hit.
  TableState t = Hidden(0);
  t.balls.push_back({BallKind::kRed, Vec2(Mid() - 2 * R() - 50e-6, 1.0)});
  const SnookerCheck c = CheckSnooker(t, 0, BallOn::kRed, Context(), 13);
  EXPECT_EQ(c.touching, 3);
  EXPECT_TRUE(c.touching_on);
  EXPECT_FALSE(c.snookered);
  EXPECT_EQ(c.hittable, 1);
  EXPECT_FALSE(DirectHitHeading(t, 0, 3, Context(), 13).has_value());
  // 2 mm away it is not touching, and is simply hittable.
  t.balls[3].position.x() -= 2e-3;
  const SnookerCheck d = CheckSnooker(t, 0, BallOn::kRed, Context(), 13);
  EXPECT_EQ(d.touching, -1);
  EXPECT_EQ(d.hittable, 1);
}

TEST(OutlookTest, TouchingBallNotOnBlocksOnlyStrokesTowardsIt) {
  PotContext ctx = Context();
  ctx.cue.max_elevation = 0;  // a level cue (a raised one could pass over the yellow)
  const Vec2 cue(Mid(), 1.0);
  // A yellow touching the cue ball straight up the table, the red beyond it.
  TableState ahead;
  ahead.balls = {{BallKind::kCue, cue},
                 {BallKind::kYellow, cue + Vec2(0, 2 * R() + 50e-6)},
                 {BallKind::kRed, Vec2(Mid(), 2.0)}};
  const SnookerCheck a = CheckSnooker(ahead, 0, BallOn::kRed, ctx, 13);
  EXPECT_EQ(a.touching, 1);
  EXPECT_FALSE(a.touching_on);
  EXPECT_TRUE(a.snookered);
  // The red square to the side: the stroke is along the touching line's normal,
  // away from the yellow, and the cue's room behind the cue ball is clear.
  TableState aside = ahead;
  aside.balls[2].position = Vec2(0.3, 1.0);
  EXPECT_FALSE(CheckSnooker(aside, 0, BallOn::kRed, ctx, 13).snookered);
  // The red straight behind: the stroke is away from the yellow but the cue would
  // have to pass through it.
  TableState behind = ahead;
  behind.balls[2].position = Vec2(Mid(), 0.4);
  EXPECT_TRUE(CheckSnooker(behind, 0, BallOn::kRed, ctx, 13).snookered);
}

TEST(OutlookTest, SnookerCostFollowsTheOneCushionModel) {
  const PotContext ctx = Context();
  const OutlookOptions options;
  const Outlook o = EvaluateOutlook(Hidden(0), BallOn::kRed, ctx, options);
  EXPECT_TRUE(o.snooker.snookered);
  EXPECT_EQ(o.pot_ball, -1);  // the red's pots all start with the pink in the way
  // The escape off a side cushion: the mirror bounce is half-way, 1.5 m up, on
  // the line a ball centre touches the cushion at.
  ASSERT_EQ(o.escape.ball, 1);
  EXPECT_TRUE(o.escape.cushion == 2 || o.escape.cushion == 4) << o.escape.cushion;
  const double across = Mid() - Model().cushion_contact_distance();
  const double leg = std::hypot(across, 0.5);
  EXPECT_NEAR(o.escape.to_cushion, leg, 1e-9);
  EXPECT_NEAR(o.escape.to_ball, leg - 2 * R(), 1e-9);
  const double sh = ctx.noise.heading, sv = ctx.noise.position;
  const double sigma = std::sqrt(std::pow((2 * leg - 2 * R()) * sh, 2) +
                                 std::pow((leg - 2 * R()) * options.rebound_sigma, 2) + 2 * sv * sv);
  const double miss = 2 * (1 - NormalCdf(2 * R() / sigma));
  EXPECT_NEAR(o.foul_probability, miss, 1e-12);
  EXPECT_EQ(o.penalty, 4);
  EXPECT_NEAR(o.expected_penalty, 4 * miss, 1e-12);
  // On the pink instead (the pink is in the open): nothing to pay.
  const Outlook pink = EvaluateOutlook(Hidden(0), BallOn::kPink, ctx, options);
  EXPECT_FALSE(pink.snooker.snookered);
  EXPECT_EQ(pink.expected_penalty, 0);
  EXPECT_EQ(pink.escape.ball, -1);
}

TEST(OutlookTest, TheEscapeIsThereInTheSimulator) {
  // The mirror aim is a slow, spinless ball's; within a few degrees of it a
  // stroke at 2 m/s (enough to reach the red) reaches it first off the cushion.
  const PotContext ctx = Context();
  const TableState t = Hidden(0);
  const Outlook o = EvaluateOutlook(t, BallOn::kRed, ctx, {});
  ASSERT_EQ(o.escape.ball, 1);
  int hits = 0;
  double nearest = 1e9;
  for (int k = -60; k <= 60; ++k) {
    const double dh = k * 0.05 * physics::kPi / 180;
    if (FirstHit(t, 0, Stroke(o.escape.heading + dh, 2.0)) == 1) {
      ++hits;
      nearest = std::min(nearest, std::abs(dh));
    }
  }
  EXPECT_GT(hits, 0);
  EXPECT_LT(nearest, 3.0 * physics::kPi / 180);
}

TEST(OutlookTest, CagedCueBallHasNoEscape) {
  // Six colours around the cue ball, 2 mm apart from it and 2 mm from each other
  // (centres 2R + 2 mm from the cue ball, 60 deg apart): every stroke and the cue
  // are blocked for a level cue, no one-cushion path leaves the cage.
  PotContext ctx = Context();
  ctx.cue.max_elevation = 0;
  const Vec2 c(Mid(), 1.2);
  TableState t;
  t.balls = {{BallKind::kCue, c}, {BallKind::kRed, Vec2(0.4, 2.5)}};
  const BallKind colours[] = {BallKind::kYellow, BallKind::kGreen, BallKind::kBrown,
                              BallKind::kBlue, BallKind::kPink, BallKind::kBlack};
  for (int k = 0; k < 6; ++k) {
    const double a = physics::kPi / 6 + k * physics::kPi / 3;
    t.balls.push_back({colours[k], c + (2 * R() + 2e-3) * Vec2(std::cos(a), std::sin(a))});
  }
  const OutlookOptions options;
  const Outlook o = EvaluateOutlook(t, BallOn::kRed, ctx, options);
  EXPECT_TRUE(o.snooker.snookered);
  EXPECT_EQ(o.escape.ball, -1);
  EXPECT_EQ(o.foul_probability, options.blind_miss);
  EXPECT_EQ(o.penalty, 4);
  EXPECT_EQ(o.expected_penalty, options.blind_miss * 4);
  // On the black, one of the cage (2 mm off, not touching): the stroke at it has
  // the ball opposite right behind the cue ball, so the cue has no room; snookered
  // on the black, the penalty is its value.
  const Outlook black = EvaluateOutlook(t, BallOn::kBlack, ctx, options);
  EXPECT_TRUE(black.snooker.snookered);
  EXPECT_EQ(black.snooker.touching, -1);
  EXPECT_EQ(black.penalty, 7);
  EXPECT_EQ(black.expected_penalty, options.blind_miss * 7);
}

TEST(OutlookTest, PotsAreThePositionValue) {
  const PotContext ctx = Context();
  Rng rng(5);
  for (int k = 0; k < 10; ++k) {
    const TableState t = RandomFrame(rng, 10, Model());
    const Outlook o = EvaluateOutlook(t, BallOn::kRed, ctx, {});
    const PositionValue v = EvaluatePosition(t, BallOn::kRed, ctx, PositionOptions{});
    EXPECT_EQ(o.expected_points, v.expected_points);
    EXPECT_EQ(o.position_value, v.value);
    EXPECT_EQ(o.pot_probability, v.next_probability);
    EXPECT_EQ(o.pot_ball, v.next_ball);
    EXPECT_FALSE(o.placement.has_value());
  }
}

TEST(OutlookTest, OpenContactsHitTheirBallFirstInTheSimulator) {
  // On random 10-red tables: every red the check finds hittable is reached first
  // by a stroke along the heading it found.
  const PotContext ctx = Context();
  Rng rng(11);
  int checked = 0, hidden = 0;
  for (int k = 0; k < 20; ++k) {
    const TableState t = RandomFrame(rng, 10, Model());
    const int cue = t.cue_index();
    for (size_t i = 0; i < t.balls.size(); ++i) {
      if (t.balls[i].kind != BallKind::kRed) continue;
      const auto h = DirectHitHeading(t, cue, static_cast<int>(i), ctx, 13);
      if (!h) {
        ++hidden;
        continue;
      }
      ++checked;
      EXPECT_EQ(FirstHit(t, cue, Stroke(*h, 2.0)), static_cast<int>(i)) << k << " " << i;
    }
  }
  EXPECT_GT(checked, 150);
  EXPECT_GT(hidden, 0);  // some are hidden, so the check is not vacuous
}

// The grid of the D as outlook.h states it.
std::vector<Vec2> DGrid(const OutlookOptions& o) {
  std::vector<Vec2> grid;
  const Vec2 centre = Model().spot(physics::Colour::kBrown) - Vec2(0, o.d_inset);
  grid.push_back(centre);
  for (int ring = 1; ring <= o.d_rings; ++ring) {
    const double rho = (Model().spec().d_radius - 2 * o.d_inset) * ring / o.d_rings;
    for (int j = 0; j < o.d_angles; ++j) {
      const double a = physics::kPi * (1.0 + static_cast<double>(j) / (o.d_angles - 1));
      grid.push_back(centre + rho * Vec2(std::cos(a), std::sin(a)));
    }
  }
  return grid;
}

TEST(OutlookTest, InHandPlaysFromTheBestFreePointOfTheD) {
  const PotContext ctx = Context();
  const OutlookOptions options;
  TableState t;
  for (int c = 0; c < physics::kColourCount; ++c) {
    t.balls.push_back({KindOf(static_cast<physics::Colour>(c)), Model().spot(static_cast<physics::Colour>(c))});
  }
  t.balls.push_back({BallKind::kRed, Vec2(0.35, 1.45)});
  t.balls.push_back({BallKind::kRed, Vec2(1.5, 2.9)});
  const Outlook o = EvaluateOutlook(t, BallOn::kRed, ctx, options);
  // 22 points; the brown's, the green's and the yellow's are taken.
  EXPECT_EQ(o.placements_tried, 19);
  ASSERT_TRUE(o.placement.has_value());
  const Vec2 brown = Model().spot(physics::Colour::kBrown);
  EXPECT_LE((*o.placement - brown).norm(), Model().spec().d_radius - options.d_inset + 1e-12);
  EXPECT_LE(o.placement->y(), brown.y() - options.d_inset + 1e-12);
  EXPECT_GT(o.pot_probability, 0.3);
  EXPECT_GE(o.pot_ball, 6);
  // It is the best free grid point by expected points less the expected penalty.
  int free = 0;
  for (const Vec2& p : DGrid(options)) {
    bool clear = true;
    for (const Ball& b : t.balls) clear = clear && (b.position - p).norm() >= 2 * R() + options.d_inset;
    if (!clear) continue;
    ++free;
    TableState placed = t;
    placed.balls.push_back({BallKind::kCue, p});
    const Outlook here = EvaluateOutlook(placed, BallOn::kRed, ctx, options);
    EXPECT_LE(here.expected_points - here.expected_penalty, o.expected_points - o.expected_penalty + 1e-12);
  }
  EXPECT_EQ(free, 19);
}

TEST(OutlookTest, InHandWithEveryPointTakenIsEmpty) {
  OutlookOptions options;
  options.d_rings = 0;  // the centre only, which the brown takes
  TableState t;
  t.balls = {{BallKind::kBrown, Model().spot(physics::Colour::kBrown)}, {BallKind::kRed, Vec2(0.5, 2.0)}};
  const Outlook o = EvaluateOutlook(t, BallOn::kRed, Context(), options);
  EXPECT_EQ(o.placements_tried, 0);
  EXPECT_FALSE(o.placement.has_value());
  EXPECT_EQ(o.expected_points, 0);
}


TEST(OutlookTest, TouchingCueBallStillPotsAwayFromTheTouchingBall) {
  const PotContext ctx = Context();
  const physics::Pocket& p = Model().pocket(physics::PocketId::kTopRight);
  // A red 0.5 m from the top-right corner, the cue ball 0.3 m straight behind it,
  // and a yellow touching the cue ball from behind, off the cue's line (the cue
  // passes it by 1.5 mm beyond the stick's clearance).
  const Vec2 red = p.mouth_centre - 0.5 * p.axis;
  const Vec2 cue = red - 0.3 * p.axis;
  const Vec2 side = Vec2(-p.axis.y(), p.axis.x());
  const double reach = 2 * R() + 50e-6;  // touching
  const double off = R() + ctx.cue.radius + 1.5e-3;  // the yellow's centre off the cue's axis
  TableState t;
  t.balls = {{BallKind::kCue, cue},
             {BallKind::kRed, red},
             {BallKind::kYellow, cue - std::sqrt(reach * reach - off * off) * p.axis + off * side}};
  const Outlook o = EvaluateOutlook(t, BallOn::kRed, ctx, {});
  EXPECT_EQ(o.snooker.touching, 2);
  EXPECT_FALSE(o.snooker.snookered);
  EXPECT_EQ(o.pot_ball, 1);
  EXPECT_GT(o.pot_probability, 0.5);
  // The same with the red touching instead of the yellow: the red is on (deemed
  // hit), but it is not potted by playing into it; no other red, no pot.
  TableState touching_red;
  touching_red.balls = {{BallKind::kCue, cue}, {BallKind::kRed, cue + reach * p.axis}};
  const Outlook r = EvaluateOutlook(touching_red, BallOn::kRed, ctx, {});
  EXPECT_TRUE(r.snooker.touching_on);
  EXPECT_FALSE(r.snooker.snookered);
  EXPECT_EQ(r.pot_ball, -1);
  EXPECT_EQ(r.expected_points, 0);
}

TEST(OutlookTest, InHandWithPerBallSigmasMatchesTheDefault) {
  // Each ball's own vision sigma, all at the default: the placed ball gets the
  // default too, and the answer is the one without per-ball sigmas.
  PotContext ctx = Context();
  Rng rng(8);
  TableState t = RandomFrame(rng, 10, Model());
  t.balls.erase(t.balls.begin() + t.cue_index());
  const Outlook plain = EvaluateOutlook(t, BallOn::kRed, ctx, {});
  ctx.position_sigma.assign(t.balls.size(), ctx.noise.position);
  const Outlook per_ball = EvaluateOutlook(t, BallOn::kRed, ctx, {});
  EXPECT_EQ(plain.expected_points, per_ball.expected_points);
  EXPECT_EQ(plain.placement, per_ball.placement);
  EXPECT_GT(plain.placements_tried, 0);
}

}  // namespace
}  // namespace snooker::planner
