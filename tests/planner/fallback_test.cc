// The fallback's scan (planner/fallback.h): a legal stroke for a cue ball that only a
// raised cue can play, within the request's spin limits; and for a cue ball hemmed in
// by balls not on, the foul that costs least, only when the caller allows one.
#include "planner/fallback.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "physics/table/table.h"
#include "planner/geometry.h"
#include "planner/planner.h"
#include "planner/robustness.h"
#include "planner/rules.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

// The cue ball frozen to the left cushion, a red across the table straight out from
// it and another along the cushion behind a colour: every stroke at the red needs a
// raised cue, and the tip's height is capped by the topspin limit.
TEST(FallbackScanTest, RaisesTheCueWithinTheSpinLimits) {
  const physics::TableModel& model = physics::DefaultTable();
  const double c = model.cushion_contact_distance();
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(c, 1.8)}, {BallKind::kRed, Vec2(1.2, 1.8)}};
  // With topspin up to 1.2 of the rolling spin a raised stroke exists; at 0.9 the tip
  // cannot be high enough, and any stroke found keeps the limit.
  for (const double limit : {1.25, 1.2, 0.9}) {
    const Planner& planner = Planner::Default();
    PlanRequest r;
    r.table = t;
    r.limits.max_topspin_fraction = limit;
    PotContext ctx = planner.ContextFor(r);
    SearchSettings settings = planner.config().search_settings;
    settings.limits = r.limits;
    ShotSimulator sim(model, planner.config().full);
    const auto found = FindLegalStroke(t, 0, BallOn::kRed, ctx, settings, sim, physics::Interrupt{}, FallbackOptions{});
    if (limit >= 1.2) {
      ASSERT_TRUE(found.has_value()) << "limit " << limit;
    } else if (!found) {
      continue;
    }
    EXPECT_GT(found->cue.elevation, 0) << "limit " << limit;
    EXPECT_LE(std::abs(found->shot.topspin), limit * found->shot.speed / model.ball_radius() * (1 + 1e-12));
    // The shot is what the cue gives, exactly.
    const physics::StrikeResult res =
        physics::Strike(found->cue, ctx.cue_params(), planner.config().full.ball, planner.config().full.cloth.g);
    EXPECT_EQ(res.status, physics::StrikeStatus::kOk);
    EXPECT_EQ(res.shot.speed, found->shot.speed);
    EXPECT_EQ(res.shot.topspin, found->shot.topspin);
  }
}

// The same cue ball with topspin capped at 0.9 of the rolling spin: no stroke at the
// red can be played (its headings need the cue raised, and the tip then higher than the
// cap allows), so the scan turns to every heading around the cue ball, and answers a
// stroke the robot can play: one that reaches the red off the cushions, or else the
// foul that costs least.
TEST(FallbackScanTest, WhenNoStrokeAtABallOnCanBePlayedAnyHeadingWill) {
  const physics::TableModel& model = physics::DefaultTable();
  const double c = model.cushion_contact_distance();
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(c, 1.8)}, {BallKind::kRed, Vec2(1.2, 1.8)}};
  const Planner& planner = Planner::Default();
  PlanRequest r;
  r.table = t;
  r.limits.max_topspin_fraction = 0.9;
  PotContext ctx = planner.ContextFor(r);
  SearchSettings settings = planner.config().search_settings;
  settings.limits = r.limits;
  ShotSimulator sim(model, planner.config().full);
  FallbackOptions no_ring;
  no_ring.ring_headings = 0;
  no_ring.allow_foul = true;
  ASSERT_FALSE(FindLegalStroke(t, 0, BallOn::kRed, ctx, settings, sim, physics::Interrupt{}, no_ring).has_value())
      << "a stroke at the red was playable: the table no longer tests the ring";
  FallbackOptions options;
  options.allow_foul = true;
  const auto found = FindLegalStroke(t, 0, BallOn::kRed, ctx, settings, sim, physics::Interrupt{}, options);
  ASSERT_TRUE(found.has_value());
  // Played again it does what its kind says, and the cue gives it within the limits.
  const physics::StrikeResult res =
      physics::Strike(found->cue, ctx.cue_params(), planner.config().full.ball, planner.config().full.cloth.g);
  ASSERT_EQ(res.status, physics::StrikeStatus::kOk);
  EXPECT_TRUE(WithinLimits(res.shot, settings.limits, model.ball_radius()));
  EXPECT_GE(CueMargin(t, 0, found->cue.heading, settings.limits.cue, model), 0);
  const ShotSetup setup{&t, 0, 1, physics::PocketId::kBaulkLeft, BallOn::kRed, ShotKind::kSafety, -1, -1};
  const ShotOutcome& out = sim.Run(setup, res.shot, {}, ShotSimulator::Mode::kToRest, physics::Interrupt{});
  ASSERT_EQ(out.status, physics::SimStatus::kAtRest);
  if (found->kind == ShotKind::kFoul) {
    EXPECT_NE(out.foul, Foul::kNone);
  } else {
    EXPECT_EQ(out.foul, Foul::kNone);
    EXPECT_EQ(out.first_hit, 1);
    EXPECT_GT(out.cue_cushions_first, 0);
    EXPECT_EQ(found->kind, ShotKind::kEscape);
  }
}

// The cue ball in a ring of six reds with a colour on: the gaps between the reds (1 mm)
// are narrower than a ball, so every stroke hits a red first and fouls.
TableState HemmedIn() {
  const physics::TableModel& model = physics::DefaultTable();
  const Vec2 c(0.6, 2.2);
  const double ring = 2 * model.ball_radius() + 0.001;
  TableState t;
  t.balls = {{BallKind::kCue, c}};
  for (int k = 0; k < 6; ++k) {
    const double a = k * physics::kPi / 3 + 0.3;
    t.balls.push_back({BallKind::kRed, c + ring * Vec2(std::cos(a), std::sin(a))});
  }
  for (const auto& [kind, colour] : {std::pair{BallKind::kYellow, physics::Colour::kYellow},
                                     {BallKind::kGreen, physics::Colour::kGreen},
                                     {BallKind::kBrown, physics::Colour::kBrown},
                                     {BallKind::kBlue, physics::Colour::kBlue},
                                     {BallKind::kPink, physics::Colour::kPink},
                                     {BallKind::kBlack, physics::Colour::kBlack}}) {
    t.balls.push_back({kind, model.spot(colour)});
  }
  return t;
}

struct Scan {
  PotContext ctx;
  SearchSettings settings;
  ShotSimulator sim{physics::DefaultTable(), Planner::Default().config().full};
  explicit Scan(const TableState& t) {
    PlanRequest r;
    r.table = t;
    ctx = Planner::Default().ContextFor(r);
    settings = Planner::Default().config().search_settings;
  }
  std::optional<FallbackShot> Find(const TableState& t, bool allow_foul) {
    FallbackOptions options;
    options.allow_foul = allow_foul;
    return FindLegalStroke(t, 0, BallOn::kAnyColour, ctx, settings, sim, physics::Interrupt{}, options);
  }
  // What the stroke `shot` aimed at `object` scores when played to rest: the
  // Monte Carlo's points for one sample without noise.
  double Score(const TableState& t, int object, const physics::Shot& shot, ShotOutcome* out = nullptr) {
    const ShotSetup setup{&t, 0, object, physics::PocketId::kBaulkLeft, BallOn::kAnyColour, ShotKind::kFoul, -1, -1};
    const ShotOutcome& o = sim.Run(setup, shot, {}, ShotSimulator::Mode::kToRest, physics::Interrupt{});
    std::vector<Vec2> finals;
    for (const physics::BallState& b : sim.final_balls()) finals.push_back(b.r);
    PotContext after = ctx;
    after.position_sigma.clear();
    if (out != nullptr) *out = o;
    return MonteCarloScore(setup, o, finals, after, settings).score;
  }
};

TEST(FallbackScanTest, HemmedInItAnswersTheLeastCostlyFoulOnlyWhenAllowed) {
  const TableState t = HemmedIn();
  Scan scan(t);
  EXPECT_FALSE(scan.Find(t, false).has_value()) << "no legal stroke exists, and no foul was allowed";
  const auto found = scan.Find(t, true);
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->kind, ShotKind::kFoul);
  ASSERT_GE(found->object, 7);  // a colour
  EXPECT_GT(found->simulations, 0);
  // Played again it fouls, on a red, and scores what the scan said.
  ShotOutcome out;
  EXPECT_DOUBLE_EQ(scan.Score(t, found->object, found->shot, &out), found->score);
  EXPECT_NE(out.foul, Foul::kNone);
  ASSERT_GE(out.first_hit, 1);
  EXPECT_EQ(t.balls[static_cast<size_t>(out.first_hit)].kind, BallKind::kRed);
  // It nominates the yellow, the cheapest colour: the penalty is 4, the least a foul
  // can cost, and the score is that and what the opponent can expect.
  EXPECT_EQ(t.balls[static_cast<size_t>(found->object)].kind, BallKind::kYellow);
  EXPECT_EQ(FoulPenalty(t, BallOn::kAnyColour, BallKind::kYellow, out.first_hit, out.potted), 4);
  EXPECT_LE(found->score, -4.0);
  // It is no worse than the level, central stroke straight at any of the four
  // nearest colours, soft or firm, where the cue clears: the scan tried those too.
  const FallbackOptions options;
  const physics::CueParams& cue = scan.ctx.cue_params();
  const physics::BallParams& ball = Planner::Default().config().full.ball;
  std::vector<std::pair<double, int>> colours;
  for (int i = 7; i < static_cast<int>(t.balls.size()); ++i) {
    colours.emplace_back((t.balls[static_cast<size_t>(i)].position - t.balls[0].position).norm(), i);
  }
  std::sort(colours.begin(), colours.end());
  colours.resize(static_cast<size_t>(options.max_balls));
  int compared = 0;
  for (const auto& [distance, object] : colours) {
    const Vec2 d = t.balls[static_cast<size_t>(object)].position - t.balls[0].position;
    if (CueMargin(t, 0, std::atan2(d.y(), d.x()), RobotLimits{}.cue, physics::DefaultTable()) < 0) continue;
    for (const double v : {options.soft, options.firm}) {
      physics::CueStrike k;
      k.heading = std::atan2(d.y(), d.x());
      k.speed = physics::CueSpeedFor(v, 0.0, 0.0, cue, ball);
      const physics::StrikeResult s = physics::Strike(k, cue, ball, Planner::Default().config().full.cloth.g);
      if (s.status != physics::StrikeStatus::kOk) continue;
      EXPECT_GE(found->score, scan.Score(t, found->object, s.shot) - 1e-9) << "at ball " << object << ", " << v << " m/s";
      ++compared;
    }
  }
  EXPECT_GT(compared, 0);
}

// The cue ball touching a black behind it and a blue and a pink on either side, the
// red far up the table: the one heading that plays away from all three runs between
// the blue and the pink, along both their tangents. The rounding of that heading
// (cos of -90 deg is not 0) once made it a push into one of them, and the plan had no
// stroke at all; now it plays it (off the baulk cushion, a foul on the black).
TEST(FallbackScanTest, TouchingOnThreeSidesItPlaysBetweenTheSideBalls) {
  const double r = physics::DefaultTable().ball_radius();
  const Vec2 c(0.889, 0.5);
  TableState t;
  t.balls = {{BallKind::kCue, c},
             {BallKind::kBlack, c + Vec2(0, 2 * r)},
             {BallKind::kBlue, c - Vec2(2 * r, 0)},
             {BallKind::kPink, c + Vec2(2 * r, 0)},
             {BallKind::kRed, Vec2(0.889, 3.0)}};
  ASSERT_EQ(TouchingCueBall(t, physics::DefaultTable()).size(), 3u);
  Scan scan(t);
  FallbackOptions options;
  options.allow_foul = true;
  const auto found =
      FindLegalStroke(t, 0, BallOn::kRed, scan.ctx, scan.settings, scan.sim, physics::Interrupt{}, options);
  ASSERT_TRUE(found.has_value());
  const Vec2 u(std::cos(found->cue.heading), std::sin(found->cue.heading));
  EXPECT_NEAR(u.y(), -1.0, 1e-12) << "straight down the table, between the blue and the pink";
  for (int i = 1; i <= 3; ++i) EXPECT_FALSE(PlaysInto(u, t.balls[static_cast<size_t>(i)].position - c)) << i;
  EXPECT_TRUE(PlaysInto(Vec2(1e-9, -1).normalized(), t.balls[3].position - c)) << "a nanoradian towards the pink";
}

}  // namespace
}  // namespace snooker::planner
