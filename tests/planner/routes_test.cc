// Tests of the route candidates (planner/routes.h). For each route, a constructed
// table whose candidate, played by the full simulator at its geometric aim (or at
// one of a few aims spread over its bracket: no search), does what the route says:
// the named ball into the named pocket by that route, the first ball hit the one
// intended; and tables where the route is refused for the reason it names.
#include "planner/routes.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <tuple>
#include <vector>

#include "physics/core/shot.h"
#include "planner/planner.h"
#include "planner/random.h"
#include "planner/robustness.h"
#include "planner/selfplay.h"
#include "planner/shot_sim.h"

namespace snooker::planner {
namespace {

using physics::PocketId;
using physics::Vec2;

constexpr double kR = 0.02625;
const physics::TableModel& Table() { return physics::DefaultTable(); }
Vec2 Turn(const Vec2& v, double deg) {
  const double a = physics::DegToRad(deg);
  return {v.x() * std::cos(a) - v.y() * std::sin(a), v.x() * std::sin(a) + v.y() * std::cos(a)};
}

PotContext Context() { return Planner::Default().ContextFor(PlanRequest{}); }

// What one full-fidelity run did, as the routes name things.
struct Played {
  int first_hit = -1;
  std::vector<int> potted;
  std::vector<int> pocket_of;       // per ball, -1 if not potted
  std::vector<int> cue_cushions;    // the cue ball's cushion segments before its first ball contact
  std::vector<int> object_cushions; // `watched` ball's cushion segments before it dropped
  int watched_first_contact = -1;   // the first ball `watched` touched
  // The watched ball's line at the pocket's mouth right after the cue ball hit it
  // (shot_sim.h ObjectLine), when the cue ball hit it first.
  std::optional<double> line_offset;
};

class Player {
 public:
  Player() : sim_(Table(), PlannerConfig().full) {}

  Played Play(const TableState& t, int cue, int watched, const physics::Shot& shot,
              PocketId pocket = PocketId::kBaulkLeft) {
    ShotSetup setup{&t, cue, watched, pocket, BallOn::kRed};
    const ShotOutcome& out = sim_.Run(setup, shot, {}, ShotSimulator::Mode::kFull, {});
    Played p;
    p.first_hit = out.first_hit;
    if (out.line.valid) p.line_offset = out.line.offset;
    p.potted = out.potted;
    for (size_t i = 0; i < t.balls.size(); ++i) p.pocket_of.push_back(sim_.simulator().pocket_of(static_cast<int>(i)));
    bool cue_touched = false, watched_down = false;
    for (const physics::SimEvent& e : sim_.simulator().events()) {
      if (e.kind == physics::EventKind::kBallBall) {
        if (e.ball == cue || e.other == cue) cue_touched = true;
        if (p.watched_first_contact < 0 && (e.ball == watched || e.other == watched)) {
          p.watched_first_contact = e.ball == watched ? e.other : e.ball;
        }
      } else if (e.kind == physics::EventKind::kCushion) {
        if (e.ball == cue && !cue_touched) p.cue_cushions.push_back(e.where);
        if (e.ball == watched && !watched_down) p.object_cushions.push_back(e.where);
      } else if (e.kind == physics::EventKind::kPocket && e.ball == watched) {
        watched_down = true;
      }
    }
    return p;
  }

 private:
  ShotSimulator sim_;
};

std::vector<int> Segments(const CushionPath& path) {
  std::vector<int> s;
  for (int i = 0; i < path.cushions; ++i) s.push_back(path.contacts[static_cast<size_t>(i)].segment);
  return s;
}

// The shots of a candidate's aim: the nominal one, then `n` spread evenly over its
// bracket (the cut's for kCut, the heading's for kHeading), struck rolling.
std::vector<physics::Shot> Aims(const TableState& t, int cue, const RouteCandidate& cand, double speed, int n) {
  std::vector<physics::Shot> shots;
  for (int k = -1; k < n; ++k) {
    const double f = k < 0 ? -1 : static_cast<double>(k) / (n - 1);
    physics::Shot s{speed, cand.heading, speed / kR, 0};
    if (cand.aim == AimBy::kCut) {
      const double cut = cand.cut + (k < 0 ? 0 : cand.cut_bracket.lo + f * cand.cut_bracket.width());
      const auto h = HeadingForCut(t.balls[static_cast<size_t>(cue)].position,
                                   t.balls[static_cast<size_t>(cand.first_ball)].position, cut, kR);
      if (!h) continue;
      s.heading = *h;
    } else if (k >= 0) {
      s.heading = cand.heading + cand.heading_bracket.lo + f * cand.heading_bracket.width();
    }
    shots.push_back(s);
  }
  return shots;
}

// Did the run do what the candidate says?
bool DidTheRoute(const RouteCandidate& cand, const Played& p) {
  if (p.first_hit != cand.first_ball) return false;
  if (cand.route == Route::kEscape) return p.cue_cushions == Segments(*cand.path);
  const int b = cand.potted_ball;
  if (p.pocket_of[static_cast<size_t>(b)] != static_cast<int>(*cand.pocket)) return false;
  switch (cand.route) {
    case Route::kPlant: return p.watched_first_contact == cand.first_ball && p.object_cushions.empty();
    case Route::kDouble: return p.object_cushions == Segments(*cand.path);
    case Route::kKick: return p.cue_cushions == Segments(*cand.path) && p.object_cushions.empty();
    case Route::kEscape: return true;
  }
  return false;
}

// Plays the nominal aim and `n` aims over the bracket; how many did the route (the
// nominal's verdict in *nominal).
int Replay(const TableState& t, int cue, const RouteCandidate& cand, double speed, int n, bool* nominal) {
  Player player;
  int ok = 0;
  bool first = true;
  for (const physics::Shot& s : Aims(t, cue, cand, speed, n)) {
    const bool did = DidTheRoute(cand, player.Play(t, cue, cand.potted_ball >= 0 ? cand.potted_ball : cand.first_ball, s));
    if (first && nominal) *nominal = did;
    if (!first) ok += did ? 1 : 0;
    first = false;
  }
  return ok;
}

const physics::Pocket& Pocket(PocketId id) { return Table().pocket(id); }

// ---------------------------------------------------------------------- plants

// A plant into the top-right pocket: B 0.4 m out, A sending it in at a 15 deg cut
// from 0.3 m, the cue ball cutting A at 20 deg from 0.4 m.
TableState PlantTable() {
  const physics::Pocket& p = Pocket(PocketId::kTopRight);
  const Vec2 b = p.mouth_centre - 0.4 * p.axis;
  const Vec2 ghost_b = b - 2 * kR * p.axis;
  const Vec2 dir_a = Turn(p.axis, 15);
  const Vec2 a = ghost_b - 0.3 * dir_a;
  const Vec2 ghost_a = a - 2 * kR * dir_a;
  const Vec2 c = ghost_a - 0.4 * Turn(dir_a, -20);
  TableState t;
  t.balls = {{BallKind::kCue, c}, {BallKind::kRed, a}, {BallKind::kRed, b},
             {BallKind::kBlack, Table().spot(physics::Colour::kBlack)},
             {BallKind::kRed, Vec2(0.4, 1.0)}};
  return t;
}

TEST(RoutesTest, PlantPotsTheSecondRed) {
  const TableState t = PlantTable();
  RouteRefusal why;
  const auto cand = AssessPlant(t, 0, BallOn::kRed, 1, 2, PocketId::kTopRight, Context(), {}, &why);
  ASSERT_TRUE(cand) << ToString(why);
  EXPECT_EQ(cand->route, Route::kPlant);
  EXPECT_FALSE(cand->set);
  EXPECT_EQ(cand->aim, AimBy::kCut);
  EXPECT_NEAR(std::abs(cand->cut) * physics::kDegPerRad, 20, 0.5);
  EXPECT_TRUE(cand->cut_bracket.Contains(0));
  EXPECT_GT(cand->probability, 0.05);
  bool nominal = false;
  const int ok = Replay(t, 0, *cand, 2.0, 9, &nominal);
  EXPECT_GT(ok, 0) << "no aim of the bracket pots B by the plant";
  // The plant is harder than potting B directly from where A's ghost position is.
  const auto direct = EstimatePot(t.balls[1].position, t.balls[2].position, PocketId::kTopRight, 0.2e-3, 0.2e-3,
                                  NoiseModel{}, *Context().pockets, *Context().throws);
  ASSERT_TRUE(direct);
  EXPECT_LT(cand->probability, direct->probability);
  std::printf("plant: P = %.3f, cut %.2f deg [%+.2f, %+.2f], %d of 9 aims pot, nominal %s\n", cand->probability,
              cand->cut * physics::kDegPerRad, cand->cut_bracket.lo * physics::kDegPerRad,
              cand->cut_bracket.hi * physics::kDegPerRad, ok, nominal ? "pots" : "misses");
}

TEST(RoutesTest, PlantRefusals) {
  const PotContext ctx = Context();
  RouteRefusal why;
  TableState t = PlantTable();
  // A ball between A and B's ghost position.
  const Vec2 a = t.balls[1].position, b = t.balls[2].position;
  t.balls[4].position = 0.5 * (a + b) + 0.01 * Left((b - a).normalized());
  EXPECT_FALSE(AssessPlant(t, 0, BallOn::kRed, 1, 2, PocketId::kTopRight, ctx, {}, &why));
  EXPECT_EQ(why, RouteRefusal::kFirstBallPath);
  // A ball on B's line into the pocket.
  const physics::Pocket& p = Pocket(PocketId::kTopRight);
  t.balls[4].position = b + 0.2 * p.axis;
  EXPECT_FALSE(AssessPlant(t, 0, BallOn::kRed, 1, 2, PocketId::kTopRight, ctx, {}, &why));
  EXPECT_EQ(why, RouteRefusal::kObjectBallPath);
  // A ball between the cue ball and A.
  t.balls[4].position = 0.5 * (t.balls[0].position + a);
  EXPECT_FALSE(AssessPlant(t, 0, BallOn::kRed, 1, 2, PocketId::kTopRight, ctx, {}, &why));
  EXPECT_EQ(why, RouteRefusal::kCueBallPath);
  // Colours: neither with a colour on, nor a red onto a colour.
  t = PlantTable();
  t.balls[1].kind = BallKind::kBlue;
  t.balls[2].kind = BallKind::kPink;
  EXPECT_FALSE(AssessPlant(t, 0, BallOn::kAnyColour, 1, 2, PocketId::kTopRight, ctx, {}, &why));
  EXPECT_EQ(why, RouteRefusal::kNotOn);
  t.balls[1].kind = BallKind::kRed;
  EXPECT_FALSE(AssessPlant(t, 0, BallOn::kRed, 1, 2, PocketId::kTopRight, ctx, {}, &why));
  EXPECT_EQ(why, RouteRefusal::kNotOn);
  EXPECT_TRUE(EnumeratePlants(t, 0, BallOn::kAnyColour, ctx).empty());
}

TEST(RoutesTest, PlantChanceFallsFasterThanADirectPots) {
  const PotContext ctx = Context();
  const physics::Pocket& p = Pocket(PocketId::kTopRight);
  // A straight plant and the straight pot of B from A's place, B 0.3 m and then
  // 0.9 m from the mouth: the plant's error is larger and grows faster.
  auto sigmas = [&](double lb, double la) {
    const Vec2 b = p.mouth_centre - lb * p.axis;
    const Vec2 a = b - la * p.axis;
    const Vec2 c = a - 0.3 * p.axis;
    TableState t;
    t.balls = {{BallKind::kCue, c}, {BallKind::kRed, a}, {BallKind::kRed, b}};
    const auto plant = AssessPlant(t, 0, BallOn::kRed, 1, 2, PocketId::kTopRight, ctx);
    const auto direct = EstimatePot(a, b, PocketId::kTopRight, 0.2e-3, 0.2e-3, ctx.noise, *ctx.pockets, *ctx.throws);
    EXPECT_TRUE(plant && direct);
    return std::pair<double, double>{plant ? plant->sigma : 0, direct ? direct->sigma : 1};
  };
  const auto near = sigmas(0.3, 0.3), far = sigmas(0.9, 0.3), long_a = sigmas(0.3, 0.9);
  EXPECT_GT(near.first, near.second);
  EXPECT_GT(far.first - near.first, far.second - near.second);
  // A's own distance is amplified too (the direct pot of B does not see it).
  EXPECT_GT(long_a.first, 1.5 * near.first);
}

// A set pointing into the top-right pocket: pots along the line of centres whatever
// the cue ball's angle within the bracket.
TEST(RoutesTest, SetPotsAlongTheLineOfCentres) {
  const physics::Pocket& p = Pocket(PocketId::kTopRight);
  const Vec2 b = p.mouth_centre - 0.5 * p.axis;
  const Vec2 a = b - (2 * kR + 1e-4) * p.axis;
  TableState t;
  t.balls = {{BallKind::kCue, a - 0.5 * Turn(p.axis, 30)}, {BallKind::kRed, a}, {BallKind::kRed, b}};
  RouteRefusal why;
  const auto cand = AssessPlant(t, 0, BallOn::kRed, 1, 2, PocketId::kTopRight, Context(), {}, &why);
  ASSERT_TRUE(cand) << ToString(why);
  EXPECT_TRUE(cand->set);
  EXPECT_GT(cand->probability, 0.5);
  bool nominal = false;
  const int ok = Replay(t, 0, *cand, 1.5, 9, &nominal);
  EXPECT_TRUE(nominal);
  EXPECT_GE(ok, 5);
  // Turned 10 deg off the pocket, the set is not on.
  t.balls[1].position = b - (2 * kR + 1e-4) * Turn(p.axis, 10);
  t.balls[0].position = t.balls[1].position - 0.5 * Turn(p.axis, 30);
  EXPECT_FALSE(AssessPlant(t, 0, BallOn::kRed, 1, 2, PocketId::kTopRight, Context(), {}, &why));
  EXPECT_TRUE(why == RouteRefusal::kUnlikely || why == RouteRefusal::kPocketAngle) << ToString(why);
}

// --------------------------------------------------------------------- doubles

// A red near the right cushion, doubled across the table into the middle-left pocket.
TableState DoubleTable() {
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(1.0, 1.25)}, {BallKind::kRed, Vec2(1.45, 1.50)},
             {BallKind::kBlack, Table().spot(physics::Colour::kBlack)}, {BallKind::kRed, Vec2(0.5, 0.5)}};
  return t;
}

TEST(RoutesTest, DoubleAcrossIntoTheMiddle) {
  const TableState t = DoubleTable();
  RouteRefusal why;
  const auto cand = AssessDouble(t, 0, BallOn::kRed, 1, PocketId::kMiddleLeft, CushionLine::kRight, Context(), {}, &why);
  ASSERT_TRUE(cand) << ToString(why);
  ASSERT_TRUE(cand->path);
  EXPECT_EQ(cand->path->cushions, 1);
  EXPECT_STREQ(Table().segments()[static_cast<size_t>(cand->path->contacts[0].segment)].name, "right-baulk");
  EXPECT_GT(cand->probability, 0.01);
  bool nominal = false;
  const int ok = Replay(t, 0, *cand, 3.0, 13, &nominal);
  EXPECT_GT(ok, 0) << "no aim of the bracket doubles the red";
  std::printf("double: P = %.3f, cut %.2f deg [%+.2f, %+.2f], %d of 13 aims pot, nominal %s\n", cand->probability,
              cand->cut * physics::kDegPerRad, cand->cut_bracket.lo * physics::kDegPerRad,
              cand->cut_bracket.hi * physics::kDegPerRad, ok, nominal ? "pots" : "misses");
  // Among every double of the table it is there.
  bool found = false;
  for (const RouteCandidate& c : EnumerateDoubles(t, 0, BallOn::kRed, Context())) {
    found |= c.first_ball == 1 && c.pocket == PocketId::kMiddleLeft && c.path->contacts[0].line == CushionLine::kRight;
  }
  EXPECT_TRUE(found);
}

TEST(RoutesTest, DoubleRefusals) {
  const PotContext ctx = Context();
  RouteRefusal why;
  TableState t = DoubleTable();
  // Off the cushion of the pocket itself.
  EXPECT_FALSE(AssessDouble(t, 0, BallOn::kRed, 1, PocketId::kMiddleLeft, CushionLine::kLeft, ctx, {}, &why));
  EXPECT_EQ(why, RouteRefusal::kNoCushionPath);
  const auto cand = AssessDouble(t, 0, BallOn::kRed, 1, PocketId::kMiddleLeft, CushionLine::kRight, ctx);
  ASSERT_TRUE(cand);
  // A ball on the way back across the table.
  t.balls[3].position = 0.5 * (cand->path->points[1] + cand->path->points[2]);
  EXPECT_FALSE(AssessDouble(t, 0, BallOn::kRed, 1, PocketId::kMiddleLeft, CushionLine::kRight, ctx, {}, &why));
  EXPECT_EQ(why, RouteRefusal::kObjectBallPath);
  // A ball on the way to the cushion.
  t.balls[3].position = 0.5 * (cand->path->points[0] + cand->path->points[1]);
  EXPECT_FALSE(AssessDouble(t, 0, BallOn::kRed, 1, PocketId::kMiddleLeft, CushionLine::kRight, ctx, {}, &why));
  EXPECT_EQ(why, RouteRefusal::kObjectBallPath);
  // The black is not on.
  EXPECT_FALSE(AssessDouble(t, 0, BallOn::kRed, 2, PocketId::kMiddleLeft, CushionLine::kRight, ctx, {}, &why));
  EXPECT_EQ(why, RouteRefusal::kNotOn);
}

// ----------------------------------------------------------------------- kicks

// The cue ball snookered behind the blue from a red near the top-right pocket; the
// kick off the left cushion.
TableState KickTable() {
  TableState t;
  const Vec2 red(1.35, 3.15);
  const Vec2 cue(0.5, 2.15);
  t.balls = {{BallKind::kCue, cue}, {BallKind::kRed, red}, {BallKind::kBlue, 0.5 * (cue + red)}};
  return t;
}

TEST(RoutesTest, KickOffTheSideCushion) {
  const TableState t = KickTable();
  const PotContext ctx = Context();
  // Direct, the blue is in the way.
  EXPECT_FALSE(AssessPot(t, 0, 1, PocketId::kTopRight, ctx));
  const std::array<CushionLine, 1> left = {CushionLine::kLeft};
  RouteRefusal why;
  const auto cand = AssessKick(t, 0, BallOn::kRed, 1, PocketId::kTopRight, left, ctx, {}, &why);
  ASSERT_TRUE(cand) << ToString(why);
  EXPECT_EQ(cand->aim, AimBy::kHeading);
  EXPECT_TRUE(cand->heading_bracket.Contains(0));
  bool nominal = false;
  const int ok = Replay(t, 0, *cand, 2.5, 81, &nominal);
  EXPECT_GT(ok, 0) << "no heading of the bracket kicks the red in";
  std::printf("kick: P = %.4f, heading bracket [%+.3f, %+.3f] deg, %d of 81 aims pot, nominal %s\n",
              cand->probability, cand->heading_bracket.lo * physics::kDegPerRad,
              cand->heading_bracket.hi * physics::kDegPerRad, ok, nominal ? "pots" : "misses");
  // A second ball on the cushion leg refuses it.
  TableState blocked = t;
  blocked.balls.push_back({BallKind::kPink, 0.5 * (cand->path->points[0] + cand->path->points[1])});
  EXPECT_FALSE(AssessKick(blocked, 0, BallOn::kRed, 1, PocketId::kTopRight, left, ctx, {}, &why));
  EXPECT_EQ(why, RouteRefusal::kCueBallPath);
  // Off the right cushion the cue ball would come at the red from the pocket's side.
  const std::array<CushionLine, 1> right = {CushionLine::kRight};
  EXPECT_FALSE(AssessKick(t, 0, BallOn::kRed, 1, PocketId::kTopRight, right, ctx, {}, &why));
  EXPECT_EQ(why, RouteRefusal::kCutTooThin);
}

// Two cushions need more precision than the bracket's even spread gives: a scan of
// 201 headings over the bracket, then 41 between each two neighbours where the red's
// line at the mouth crosses the window's centre.
int ScanKick(const TableState& t, const RouteCandidate& cand, double speed) {
  Player player;
  auto play = [&](double h, bool* did) {
    const Played p = player.Play(t, 0, cand.potted_ball, physics::Shot{speed, h, speed / kR, 0}, *cand.pocket);
    *did = DidTheRoute(cand, p);
    return p.first_hit == cand.first_ball && p.line_offset ? *p.line_offset - cand.window.centre() : 1e9;
  };
  constexpr int kCoarse = 200, kFine = 40;
  std::vector<double> headings, offsets;
  int pots = 0;
  for (int k = 0; k <= kCoarse; ++k) {
    bool did = false;
    headings.push_back(cand.heading + cand.heading_bracket.lo + k * cand.heading_bracket.width() / kCoarse);
    offsets.push_back(play(headings.back(), &did));
    pots += did ? 1 : 0;
  }
  for (int k = 0; k < kCoarse; ++k) {
    if (offsets[k] > 1 || offsets[k + 1] > 1 || (offsets[k] < 0) == (offsets[k + 1] < 0)) continue;
    for (int j = 1; j < kFine; ++j) {
      bool did = false;
      play(headings[k] + j * (headings[k + 1] - headings[k]) / kFine, &did);
      pots += did ? 1 : 0;
    }
  }
  return pots;
}

TEST(RoutesTest, KickOffTwoCushions) {
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(0.6, 1.2)}, {BallKind::kRed, Vec2(1.45, 3.30)},
             {BallKind::kBlue, Table().spot(physics::Colour::kBlue)}};
  int tried = 0, potted = 0;
  for (const RouteCandidate& cand : EnumerateKicks(t, 0, BallOn::kRed, Context())) {
    if (cand.path->cushions != 2 || tried >= 2) continue;
    ++tried;
    // Fast enough to reach the red at 2 m/s through two cushions that keep 0.8 of
    // the speed each.
    const double speed = std::sqrt(4 + 2 * 0.1256 * cand.path->length) / 0.64;
    const int pots = ScanKick(t, cand, speed);
    potted += pots > 0 ? 1 : 0;
    std::printf("two-cushion kick into %s off %s, %s: P = %.4f, %.2f m at %.1f m/s, %d aims pot\n",
                physics::ToString(*cand.pocket), ToString(cand.path->contacts[0].line),
                ToString(cand.path->contacts[1].line), cand.probability, cand.path->length, speed, pots);
  }
  EXPECT_EQ(tried, 2);
  EXPECT_EQ(potted, 2);
  // Up the table, down it and up again: 9 m, refused.
  const std::array<CushionLine, 2> top_baulk = {CushionLine::kTop, CushionLine::kBaulk};
  RouteRefusal why;
  EXPECT_FALSE(AssessKick(t, 0, BallOn::kRed, 1, PocketId::kTopRight, top_baulk, Context(), {}, &why));
  EXPECT_EQ(why, RouteRefusal::kTooLong);
}

// --------------------------------------------------------------------- escapes

// The cue ball snookered on the only red by the blue and the pink.
TableState SnookerTable() {
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(0.9, 1.0)}, {BallKind::kRed, Vec2(0.9, 2.2)},
             {BallKind::kBlue, Vec2(0.9, 1.6)}, {BallKind::kPink, Vec2(1.3, 1.6)}};
  return t;
}

TEST(RoutesTest, EscapeOffOneCushionHitsTheRed) {
  const TableState t = SnookerTable();
  const PotContext ctx = Context();
  const std::array<CushionLine, 1> left = {CushionLine::kLeft};
  RouteRefusal why;
  const auto cand = AssessEscape(t, 0, BallOn::kRed, 1, left, ctx, {}, &why);
  ASSERT_TRUE(cand) << ToString(why);
  EXPECT_EQ(KindOf(cand->route), ShotKind::kEscape);
  EXPECT_EQ(cand->potted_ball, -1);
  EXPECT_FALSE(cand->pocket);
  EXPECT_GT(cand->probability, 0.9);
  // The mirror's aim hits the red at moderate speeds; at every speed some heading
  // of the bracket does.
  int nominal_hits = 0;
  for (double speed : {1.0, 1.5, 2.5}) {
    bool nominal = false;
    const int ok = Replay(t, 0, *cand, speed, 9, &nominal);
    nominal_hits += nominal ? 1 : 0;
    EXPECT_GT(ok, 0) << speed << " m/s";
    std::printf("escape at %.1f m/s: miss %.4f, heading bracket [%+.3f, %+.3f] deg, %d of 9 aims hit, nominal %s\n",
                speed, cand->miss_probability, cand->heading_bracket.lo * physics::kDegPerRad,
                cand->heading_bracket.hi * physics::kDegPerRad, ok, nominal ? "hits" : "misses");
  }
  EXPECT_GE(nominal_hits, 2);
  // Ranked: the enumerator's best escape is at least as likely to hit.
  const auto all = EnumerateEscapes(t, 0, BallOn::kRed, ctx);
  ASSERT_FALSE(all.empty());
  EXPECT_LE(all.front().miss_probability, cand->miss_probability);
  for (size_t i = 1; i < all.size(); ++i) {
    // By the miss in steps of 0.001, then fewer cushions, then shorter.
    const auto key = [](const RouteCandidate& c) {
      return std::tuple{std::floor(c.miss_probability / 1e-3), c.path->cushions, c.distance};
    };
    EXPECT_LE(key(all[i - 1]), key(all[i]));
  }
  // Here the one-cushion escapes come first: every clear escape is nearly sure.
  EXPECT_EQ(all.front().path->cushions, 1);
}

TEST(RoutesTest, EscapeOffTwoCushionsHitsTheRed) {
  TableState t = SnookerTable();
  // Balls by both side cushions where the one-cushion escapes meet them (the
  // others, off the end cushions, run into the blue).
  t.balls.push_back({BallKind::kBrown, Vec2(0.07, 1.6)});
  t.balls.push_back({BallKind::kGreen, Vec2(Table().spec().width - 0.07, 1.6)});
  const std::array<CushionLine, 1> left = {CushionLine::kLeft};
  EXPECT_FALSE(AssessEscape(t, 0, BallOn::kRed, 1, left, Context()));
  const PotContext ctx = Context();
  // The three likeliest two-cushion escapes: a scan of their brackets finds
  // headings that hit the red off those two cushions.
  int tried = 0;
  for (const RouteCandidate& cand : EnumerateEscapes(t, 0, BallOn::kRed, ctx)) {
    if (cand.path->cushions != 2 || tried >= 3) continue;
    ++tried;
    const int ok = Replay(t, 0, cand, 3.0, 41, nullptr);
    EXPECT_GT(ok, 0) << ToString(cand.path->contacts[0].line) << " then " << ToString(cand.path->contacts[1].line);
    std::printf("two-cushion escape %s-%s: miss %.4f, bracket [%+.2f, %+.2f] deg, %d of 41 aims hit at 3 m/s\n",
                ToString(cand.path->contacts[0].line), ToString(cand.path->contacts[1].line), cand.miss_probability,
                cand.heading_bracket.lo * physics::kDegPerRad, cand.heading_bracket.hi * physics::kDegPerRad, ok);
  }
  EXPECT_GT(tried, 0);
}

TEST(RoutesTest, EscapeRefusedWhenEveryOffsetIsBlocked) {
  TableState t = SnookerTable();
  const PotContext ctx = Context();
  const std::array<CushionLine, 1> left = {CushionLine::kLeft};
  const auto open = AssessEscape(t, 0, BallOn::kRed, 1, left, ctx);
  ASSERT_TRUE(open);
  // A ball 10 cm along the first leg: no offset gets past it.
  const Vec2 u = (open->path->points[1] - open->path->points[0]).normalized();
  t.balls.push_back({BallKind::kBrown, t.balls[0].position + 0.1 * u});
  RouteRefusal why;
  EXPECT_FALSE(AssessEscape(t, 0, BallOn::kRed, 1, left, ctx, {}, &why));
  EXPECT_EQ(why, RouteRefusal::kCueBallPath);
  // A ball beside the red on the way in: the aim moves to the red's open side, and
  // still hits it.
  t.balls.pop_back();
  const Vec2 last = (open->path->points[2] - open->path->points[1]).normalized();
  t.balls.push_back({BallKind::kBrown, t.balls[1].position - 0.15 * last + 3 * kR * Left(last)});
  const auto side = AssessEscape(t, 0, BallOn::kRed, 1, left, ctx, {}, &why);
  ASSERT_TRUE(side) << ToString(why);
  // The clear run is narrower, and the aim is on the red's right (seen along the
  // last leg): the red is taken on its right-hand side and sent left, a positive cut.
  EXPECT_LT(side->heading_bracket.width(), open->heading_bracket.width());
  EXPECT_GT(side->cut, physics::DegToRad(5));
  EXPECT_GE(side->miss_probability, open->miss_probability);
  bool nominal = false;
  Replay(t, 0, *side, 1.5, 1, &nominal);
  EXPECT_TRUE(nominal);
}

// ------------------------------------------------------------ the estimates

// The estimate against Monte Carlo with the full simulator, as pot_estimate_test.cc
// checks the direct pot's: the aim centred first (the middle of the widest run of
// potting aims in a scan of 1001 over the bracket, struck rolling: the correction
// the search makes), then 300 samples of execution and vision noise. The binomial
// error of 300 samples is at most 0.03; each estimate within kEach (the direct
// pot's tolerance) of the sampled rate.
constexpr double kEach = 0.15;

double CentredAim(const TableState& t, const RouteCandidate& cand, double speed, ShotSimulator& sim) {
  const AimBracket b = cand.aim == AimBy::kCut ? cand.cut_bracket : cand.heading_bracket;
  constexpr int kScan = 1001;
  int run = -1, best_lo = -1, best_hi = -1;
  for (int k = 0; k <= kScan; ++k) {
    bool pots = false;
    if (k < kScan) {
      const double x = b.lo + k * b.width() / (kScan - 1);
      physics::Shot s{speed, cand.heading + x, speed / kR, 0};
      if (cand.aim == AimBy::kCut) s.heading = *HeadingForCut(t.balls[0].position, t.balls[static_cast<size_t>(cand.first_ball)].position, cand.cut + x, kR);
      const ShotSetup setup{&t, 0, cand.potted_ball, *cand.pocket, BallOn::kRed};
      const ShotOutcome& out = sim.Run(setup, s, {}, ShotSimulator::Mode::kFull, {});
      pots = out.first_hit == cand.first_ball && sim.simulator().pocket_of(cand.potted_ball) == static_cast<int>(*cand.pocket);
    }
    if (pots && run < 0) run = k;
    if (!pots && run >= 0) {
      if (k - run > best_hi - best_lo) best_lo = run, best_hi = k;
      run = -1;
    }
  }
  EXPECT_GE(best_lo, 0) << "no aim pots";
  return b.lo + 0.5 * (best_lo + best_hi - 1) * b.width() / (kScan - 1);
}

double SampledRate(const TableState& t, const RouteCandidate& cand, double speed, const PotContext& ctx) {
  ShotSimulator sim(Table(), PlannerConfig().full);
  const double x = CentredAim(t, cand, speed, sim);
  physics::Shot shot{speed, cand.heading + x, speed / kR, 0};
  if (cand.aim == AimBy::kCut) shot.heading = *HeadingForCut(t.balls[0].position, t.balls[static_cast<size_t>(cand.first_ball)].position, cand.cut + x, kR);
  Rng rng(DeriveSeed(17, static_cast<std::uint64_t>(cand.potted_ball), static_cast<std::uint64_t>(*cand.pocket)));
  std::vector<Vec2> truth;
  constexpr int kSamples = 300;
  int potted = 0;
  const ShotSetup setup{&t, 0, cand.potted_ball, *cand.pocket, BallOn::kRed};
  for (int k = 0; k < kSamples; ++k) {
    SampleTruePositions(t, ctx, rng, &truth);
    const ShotOutcome& out = sim.Run(setup, SampleExecution(shot, ctx.noise, rng), truth, ShotSimulator::Mode::kFull, {});
    potted += out.first_hit == cand.first_ball && sim.simulator().pocket_of(cand.potted_ball) == static_cast<int>(*cand.pocket);
  }
  return static_cast<double>(potted) / kSamples;
}

TEST(RoutesTest, EstimatesAgreeWithMonteCarlo) {
  const PotContext ctx = Context();
  const physics::Pocket& p = Pocket(PocketId::kTopRight);
  struct Case {
    const char* name;
    TableState table;
    std::optional<RouteCandidate> cand;
    double speed;
  };
  std::vector<Case> cases;
  for (const auto& [lb, la, cut_ab] : {std::tuple{0.6, 0.4, 15.0}, std::tuple{0.3, 0.2, 30.0}}) {
    const Vec2 b = p.mouth_centre - lb * p.axis;
    const Vec2 dir_a = Turn(p.axis, cut_ab);
    const Vec2 a = b - 2 * kR * p.axis - la * dir_a;
    TableState t;
    t.balls = {{BallKind::kCue, a - 2 * kR * dir_a - 0.4 * Turn(dir_a, -20)}, {BallKind::kRed, a}, {BallKind::kRed, b}};
    cases.push_back({"plant", t, AssessPlant(t, 0, BallOn::kRed, 1, 2, PocketId::kTopRight, ctx), 2.0});
  }
  for (const Vec2& red : {Vec2(1.35, 1.5), Vec2(1.5, 1.65)}) {
    TableState t;
    t.balls = {{BallKind::kCue, Vec2(1.0, red.y() - 0.25)}, {BallKind::kRed, red}};
    cases.push_back({"double", t, AssessDouble(t, 0, BallOn::kRed, 1, PocketId::kMiddleLeft, CushionLine::kRight, ctx), 3.0});
  }
  const std::array<CushionLine, 1> left = {CushionLine::kLeft};
  cases.push_back({"kick", KickTable(), AssessKick(KickTable(), 0, BallOn::kRed, 1, PocketId::kTopRight, left, ctx), 2.5});
  for (const Case& c : cases) {
    ASSERT_TRUE(c.cand) << c.name;
    const double rate = SampledRate(c.table, *c.cand, c.speed, ctx);
    EXPECT_NEAR(c.cand->probability, rate, kEach) << c.name;
    std::printf("%s: estimate %.3f, Monte Carlo %.3f\n", c.name, c.cand->probability, rate);
  }
}

// ------------------------------------------------------------------ full frames

TEST(RoutesTest, EnumeratorsOnFullFramesAreCheap) {
  const PotContext ctx = Context();
  Rng rng(7);
  double us[4] = {0, 0, 0, 0};
  int counts[4] = {0, 0, 0, 0};
  constexpr int kFrames = 20;
  for (int f = 0; f < kFrames; ++f) {
    const TableState t = RandomFrame(rng, 15, Table());
    const int cue = t.cue_index();
    for (int r = 0; r < 4; ++r) {
      const auto start = std::chrono::steady_clock::now();
      std::vector<RouteCandidate> out;
      switch (r) {
        case 0: out = EnumeratePlants(t, cue, BallOn::kRed, ctx); break;
        case 1: out = EnumerateDoubles(t, cue, BallOn::kRed, ctx); break;
        case 2: out = EnumerateKicks(t, cue, BallOn::kRed, ctx); break;
        default: out = EnumerateEscapes(t, cue, BallOn::kRed, ctx); break;
      }
      us[r] += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
      counts[r] += static_cast<int>(out.size());
      for (size_t i = 1; i < out.size() && r < 3; ++i) {
        EXPECT_GE(out[i - 1].probability, out[i].probability);
      }
      for (const RouteCandidate& c : out) {
        EXPECT_GE(c.cue_margin, 0);
        EXPECT_LE(c.heading_bracket.lo, 0);
        EXPECT_GE(c.heading_bracket.hi, 0);
        EXPECT_GE(c.probability, 0);
        EXPECT_LE(c.probability, 1);
      }
    }
  }
  std::printf("per call on a 15-red frame: plants %.0f us, doubles %.0f us, kicks %.0f us, escapes %.0f us "
              "(candidates per frame %.1f, %.1f, %.1f, %.1f)\n",
              us[0] / kFrames, us[1] / kFrames, us[2] / kFrames, us[3] / kFrames, counts[0] / double(kFrames),
              counts[1] / double(kFrames), counts[2] / double(kFrames), counts[3] / double(kFrames));
}

}  // namespace
}  // namespace snooker::planner
