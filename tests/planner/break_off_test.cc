// Tests of the break-off's geometry (planner/break_off.h): the rack recognised,
// the candidates' placements and cuts against the ghost-ball geometry, and their
// nominal strokes in the simulator.
#include "planner/break_off.h"

#include <gtest/gtest.h>

#include <cmath>

#include "planner/geometry.h"
#include "planner/random.h"
#include "planner/robustness.h"
#include "planner/shot_sim.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

const physics::TableModel& Model() { return physics::DefaultTable(); }

TableState Rack() {
  TableState t;
  for (int c = 0; c < physics::kColourCount; ++c) {
    t.balls.push_back({KindOf(static_cast<physics::Colour>(c)), Model().spot(static_cast<physics::Colour>(c))});
  }
  for (const Vec2& r : Model().reds()) t.balls.push_back({BallKind::kRed, r});
  return t;
}

struct Played {
  int first_hit = -1;
  bool cue_potted = false;
  int potted = 0;
  Vec2 cue_end = Vec2::Zero();
  int events = 0;
  physics::SimStatus status = physics::SimStatus::kAtRest;
};

Played Play(const TableState& rack, const BreakOffCandidate& c, double speed, double side, double cut) {
  TableState t = rack;
  t.balls.push_back({BallKind::kCue, c.placement});
  const int cue = static_cast<int>(t.balls.size()) - 1;
  physics::Shot shot;
  shot.speed = speed;
  shot.heading = *HeadingForCut(c.placement, c.target_position, cut, Model().ball_radius());
  shot.sidespin = side;
  ShotSimulator sim(Model(), physics::SimParams{});
  const ShotSetup setup{&t, cue, c.target, physics::PocketId::kTopRight, BallOn::kRed};
  const ShotOutcome& out = sim.Run(setup, shot, {}, ShotSimulator::Mode::kFull, {});
  Played p;
  p.first_hit = out.first_hit;
  p.status = out.status;
  p.events = out.events;
  for (int i : out.potted) {
    if (i == cue) p.cue_potted = true;
    ++p.potted;
  }
  p.cue_end = sim.final_balls()[static_cast<size_t>(cue)].r;
  return p;
}

TEST(BreakOffTest, TheRackIsRecognised) {
  const TableState rack = Rack();
  EXPECT_TRUE(IsBreakOffTable(rack, true, Model()));
  // Not in hand, or a cue ball on the table: no break-off.
  EXPECT_FALSE(IsBreakOffTable(rack, false, Model()));
  TableState with_cue = rack;
  with_cue.balls.push_back({BallKind::kCue, Vec2(0.9, 0.6)});
  EXPECT_FALSE(IsBreakOffTable(with_cue, true, Model()));
  // Every red off by 3 mm in some direction (a hand-set rack seen by vision): still
  // untouched; colours anywhere do not matter.
  TableState jitter = rack;
  int k = 0;
  for (Ball& b : jitter.balls) {
    if (b.kind == BallKind::kRed) b.position += 3e-3 * physics::HeadingVector(2.4 * k++);
  }
  jitter.balls[0].position = Vec2(0.3, 1.0);
  EXPECT_TRUE(IsBreakOffTable(jitter, true, Model()));
  // One red moved by 1 cm, or gone: the rack has been played.
  TableState moved = rack;
  moved.balls.back().position.x() += 0.01;
  EXPECT_FALSE(IsBreakOffTable(moved, true, Model()));
  TableState fourteen = rack;
  fourteen.balls.pop_back();
  EXPECT_FALSE(IsBreakOffTable(fourteen, true, Model()));
  // Fifteen reds, one of them away from the rack while the apex position is empty.
  TableState swapped = rack;
  swapped.balls[6].position = Vec2(0.5, 2.0);
  EXPECT_FALSE(IsBreakOffTable(swapped, true, Model()));
}

// The straight path from `from` to the contact of cut `cut` on `target` clears
// every other ball by 2R + clearance (computed here from the ghost-ball geometry).
bool PathClearOfOthers(const TableState& t, const Vec2& from, int target, double cut, double clearance) {
  const double r = Model().ball_radius();
  const Vec2 o = t.balls[static_cast<size_t>(target)].position;
  const double h = *HeadingForCut(from, o, cut, r);
  const Vec2 u = physics::HeadingVector(h);
  // The ghost ball: on the stroke's line, 2R from the target's centre.
  const double along = (o - from).dot(u);
  const double side = Cross(u, o - from);
  const Vec2 ghost = from + (along - std::sqrt(4 * r * r - side * side)) * u;
  EXPECT_NEAR((ghost - o).norm(), 2 * r, 1e-9);
  EXPECT_NEAR(side, 2 * r * std::sin(cut), 1e-9);
  for (size_t i = 0; i < t.balls.size(); ++i) {
    if (static_cast<int>(i) != target && SegmentDistance(from, ghost, t.balls[i].position) < 2 * r + clearance) {
      return false;
    }
  }
  return true;
}

TEST(BreakOffTest, CandidatesAreInTheDAndAimAtTheBackRowsEnds) {
  const TableState rack = Rack();
  const BreakOffOptions o;
  const std::vector<BreakOffCandidate> cands = BreakOffCandidates(rack, Model(), o);
  ASSERT_EQ(cands.size(), 6u);
  const Vec2 brown = Model().spot(physics::Colour::kBrown);
  const double r = Model().ball_radius();
  for (size_t k = 0; k < cands.size(); ++k) {
    const BreakOffCandidate& c = cands[k];
    EXPECT_EQ(c.right, k < 3);
    // In the D, behind the line, off the brown, yellow and green.
    EXPECT_LE((c.placement - brown).norm(), Model().spec().d_radius - o.line_inset);
    EXPECT_NEAR(c.placement.y(), brown.y() - o.line_inset, 1e-12);
    for (const Ball& b : rack.balls) EXPECT_GE((b.position - c.placement).norm(), 2 * r + o.ball_clearance);
    EXPECT_NEAR(std::abs(c.placement.x() - brown.x()), Model().spec().d_radius * static_cast<double>(k % 3 + 1) / 4, 1e-12);
    // The back row's end red on its own side: reds()[14] on the right, [10] on the left.
    const Vec2 end = Model().reds()[c.right ? 14 : 10];
    EXPECT_EQ(rack.balls[static_cast<size_t>(c.target)].position, end);
    EXPECT_EQ(c.target_position, end);
    // The cut: its sign by side, inside its range, nominal_offset past the fullest.
    EXPECT_EQ(c.cut > 0, c.right);
    EXPECT_LE(c.cut_lo, c.cut);
    EXPECT_LE(c.cut, c.cut_hi);
    const double fullest = c.right ? c.cut_lo : c.cut_hi;
    EXPECT_NEAR(std::abs(c.cut - fullest), o.nominal_offset, 1e-12);
    EXPECT_NEAR(c.heading, *HeadingForCut(c.placement, end, c.cut, r), 1e-15);
    // The fullest cut's path is clear; one step fuller it is not.
    EXPECT_TRUE(PathClearOfOthers(rack, c.placement, c.target, fullest, o.path_clearance));
    const double fuller = fullest - (c.right ? 1 : -1) * o.cut_step;
    EXPECT_FALSE(PathClearOfOthers(rack, c.placement, c.target, fuller, o.path_clearance));
    EXPECT_TRUE(PathClearOfOthers(rack, c.placement, c.target, c.cut, o.path_clearance));
    EXPECT_EQ(c.speed, o.speed);
    EXPECT_EQ(c.sidespin, c.right ? -o.side : o.side);
  }
  // The rack and the colours are symmetric about the long axis, so are the sides.
  for (size_t k = 0; k < 3; ++k) {
    const BreakOffCandidate &a = cands[k], &b = cands[k + 3];
    EXPECT_NEAR(a.placement.x() - brown.x(), brown.x() - b.placement.x(), 1e-12);
    EXPECT_NEAR(a.cut, -b.cut, 1e-12);
    EXPECT_NEAR(a.cut_lo, -b.cut_hi, 1e-12);
  }
}

TEST(BreakOffTest, AMovedEndRedLosesItsSide) {
  TableState t = Rack();
  // The right end red taken 2 cm away: only the left side is offered.
  for (Ball& b : t.balls) {
    if (b.kind == BallKind::kRed && b.position == Model().reds()[14]) b.position.x() += 0.02;
  }
  const auto cands = BreakOffCandidates(t, Model());
  ASSERT_EQ(cands.size(), 3u);
  for (const BreakOffCandidate& c : cands) EXPECT_FALSE(c.right);
  // The yellow on a placement's point: that placement is skipped.
  TableState blocked = Rack();
  const auto all = BreakOffCandidates(blocked, Model());
  blocked.balls[0].position = all[1].placement + Vec2(0, -0.01);
  EXPECT_EQ(BreakOffCandidates(blocked, Model()).size(), 5u);
}

// The soft break: from each placement of the thin break, a red whose line meets a
// red first at every cut of its range (never the pink or blue in front of the
// pack), full ball included; its nominal stroke, and the same at 1.5 times the
// pace, pots nothing, and at its pace moves the back row by under 5 cm.
TEST(BreakOffTest, SoftBreaksMeetARedFirstAndLeaveThePackNearlyWhole) {
  const TableState rack = Rack();
  const auto thin = BreakOffCandidates(rack, Model());
  const auto soft = SoftBreakCandidates(rack, Model());
  ASSERT_EQ(soft.size(), thin.size());
  const double r = Model().ball_radius();
  for (size_t k = 0; k < soft.size(); ++k) {
    const BreakOffCandidate& c = soft[k];
    EXPECT_TRUE(c.soft);
    EXPECT_EQ(c.placement, thin[k].placement);
    EXPECT_EQ(rack.balls[static_cast<size_t>(c.target)].kind, BallKind::kRed);
    EXPECT_LE(c.cut_lo, 0.0);
    EXPECT_GE(c.cut_hi, 0.0);
    EXPECT_EQ(c.cut, 0.0);
    EXPECT_EQ(c.sidespin, 0.0);
    for (double cut = c.cut_lo; cut <= c.cut_hi + 1e-12; cut += 0.25 * physics::kPi / 180) {
      TableState t = rack;
      t.balls.push_back({BallKind::kCue, c.placement});
      physics::Shot shot;
      shot.speed = c.speed;
      shot.heading = *HeadingForCut(c.placement, c.target_position, cut, r);
      ShotSimulator sim(Model(), physics::SimParams{});
      const int cue = static_cast<int>(t.balls.size()) - 1;
      const ShotSetup setup{&t, cue, c.target, physics::PocketId::kTopRight, BallOn::kRed};
      const ShotOutcome& out = sim.Run(setup, shot, {}, ShotSimulator::Mode::kFull, {});
      ASSERT_EQ(out.status, physics::SimStatus::kAtRest) << k << " " << cut;
      ASSERT_GE(out.first_hit, 0) << k << " " << cut;
      EXPECT_EQ(t.balls[static_cast<size_t>(out.first_hit)].kind, BallKind::kRed) << k << " " << cut;
    }
    for (double pace : {1.0, 1.5}) {
      TableState t = rack;
      t.balls.push_back({BallKind::kCue, c.placement});
      physics::Shot shot;
      shot.speed = pace * c.speed;
      shot.heading = c.heading;
      ShotSimulator sim(Model(), physics::SimParams{});
      const int cue = static_cast<int>(t.balls.size()) - 1;
      const ShotSetup setup{&t, cue, c.target, physics::PocketId::kTopRight, BallOn::kRed};
      const ShotOutcome& out = sim.Run(setup, shot, {}, ShotSimulator::Mode::kFull, {});
      ASSERT_EQ(out.status, physics::SimStatus::kAtRest);
      EXPECT_TRUE(out.potted.empty()) << k << " pace " << pace;
      // The back row (the rack's last five reds) stays within a few centimetres.
      double moved = 0;
      for (size_t i = 0; i < rack.balls.size(); ++i) {
        if (rack.balls[i].kind != BallKind::kRed || rack.balls[i].position.y() < Model().reds()[10].y() - 1e-9) continue;
        moved = std::max(moved, (sim.final_balls()[i].r - rack.balls[i].position).norm());
      }
      if (pace == 1.0) {
        EXPECT_LT(moved, 0.05) << k;
      }
    }
  }
  BreakOffOptions off;
  off.soft_break = false;
  EXPECT_TRUE(SoftBreakCandidates(rack, Model(), off).empty());
}

// The Monte Carlo's true racks, drawn around the rack seen with 0.2 mm of vision
// noise: every ball clear of every other and on the bed, and the break-off's
// nominal stroke simulates from each of them.
TEST(BreakOffTest, RacksDrawnAroundTheOneSeenAreSettledAndPlayable) {
  TableState t = Rack();
  const BreakOffCandidate c = BreakOffCandidates(t, Model()).front();
  t.balls.push_back({BallKind::kCue, c.placement});
  const int cue = static_cast<int>(t.balls.size()) - 1;
  PotContext ctx;
  ctx.table = &Model();
  ctx.noise.position = 0.2e-3;
  const double r = Model().ball_radius();
  ShotSimulator sim(Model(), physics::SimParams{});
  const ShotSetup setup{&t, cue, c.target, physics::PocketId::kTopRight, BallOn::kRed};
  physics::Shot shot;
  shot.speed = c.speed;
  shot.heading = c.heading;
  shot.sidespin = c.sidespin;
  Rng rng(5);
  std::vector<Vec2> truth;
  double moved = 0;
  for (int k = 0; k < 60; ++k) {
    SampleTruePositions(t, ctx, rng, &truth);
    ASSERT_EQ(truth.size(), t.balls.size());
    for (size_t i = 0; i < truth.size(); ++i) {
      moved = std::max(moved, (truth[i] - t.balls[i].position).norm());
      for (size_t j = i + 1; j < truth.size(); ++j) {
        ASSERT_GE((truth[j] - truth[i]).norm(), 2 * r - 1e-9) << "draw " << k << ": balls " << i << " and " << j;
      }
    }
    const ShotOutcome& out = sim.Run(setup, shot, truth, ShotSimulator::Mode::kFull, {});
    EXPECT_EQ(out.status, physics::SimStatus::kAtRest) << "draw " << k;
    EXPECT_EQ(out.first_hit, c.target) << "draw " << k;
  }
  // The draws are draws: the balls moved, by about the vision noise.
  EXPECT_GT(moved, 0.1e-3);
  EXPECT_LT(moved, 3e-3);
}

TEST(BreakOffTest, NominalStrokesHitTheEndRedFirstAndKeepTheCueBall) {
  // Each candidate's nominal stroke at 6, 6.5 and 7 m/s, in the simulator.
  const TableState rack = Rack();
  int kept = 0, played = 0;
  bool one_always_kept = false;
  for (const BreakOffCandidate& c : BreakOffCandidates(rack, Model())) {
    int kept_here = 0;
    for (double speed : {6.0, 6.5, 7.0}) {
      const Played p = Play(rack, c, speed, c.sidespin, c.cut);
      EXPECT_EQ(p.status, physics::SimStatus::kAtRest);
      EXPECT_EQ(p.first_hit, c.target) << c.placement.x() << " " << speed;
      ++played;
      if (!p.cue_potted) ++kept_here;
    }
    kept += kept_here;
    one_always_kept = one_always_kept || kept_here == 3;
  }
  EXPECT_TRUE(one_always_kept);
  EXPECT_GE(kept, played - 1);
}

}  // namespace
}  // namespace snooker::planner
