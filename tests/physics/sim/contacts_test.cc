// Resting contacts (physics/sim/contacts.h) and clusters, on their own and through
// the simulator (physics/sim/simulate.h, physics/events/detect.h): balls frozen to a
// cushion, a knuckle, a jaw wall or another ball are ordinary states; touching packs
// and jammed clusters come to rest well under the event cap. Each case reported
// broken is here, then seeded sweeps over many such states.
#include <gtest/gtest.h>

#include <algorithm>
#include <ostream>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "physics/motion/motion.h"
#include "physics/sim/contacts.h"
#include "physics/sim/simulate.h"
#include "tests/support/invariants.h"
#include "tests/support/sanitizers.h"
#include "tests/support/scenarios.h"

namespace snooker::physics {
namespace {

using scenarios::AtRest;
using scenarios::kR;
using scenarios::Struck;

// A run "comes to rest well under the cap" when it needs at most this share of it.
constexpr std::int32_t kWellUnderCap = 2000;  // of SimParams::max_events = 5000

class ContactsTest : public testing::Test {
 protected:
  const TableModel& table_ = DefaultTable();
  SimParams params_;
};

// Reported: the cue ball frozen to the left cushion (its centre exactly the contact
// distance from the nose, as vision reports a ball touching it) and played along
// it. Time went back at every event (a cushion contact at 0.1387 s, a knuckle at
// 1.089 s, again and again) until the event cap.
TEST_F(ContactsTest, BallFrozenToTheCushionPlayedAlongItRollsOn) {
  const Vec2 start(0.02437211521390788, 1.0);
  ASSERT_NEAR(start.x(), table_.cushion_contact_distance(), 1e-15);
  Simulator sim(table_, params_);
  ASSERT_EQ(sim.Run(std::vector<BallState>{Struck(start, 1.0, kPi / 2, 0, 0)}), SimStatus::kAtRest);
  EXPECT_TRUE(invariants::RunKeepsInvariants(sim, table_));
  EXPECT_LT(sim.event_count(), 10);
  const Vec2 end = sim.final_balls()[0].r;
  // It slides, rolls along the nose past the middle pocket's jaws and stops: the
  // stun-then-roll distance of a 1 m/s ball is about 2.2 m.
  EXPECT_NEAR(end.x(), start.x(), 1e-9);
  EXPECT_GT(end.y(), 3.0);
}

// Every straight cushion, either way along it, from several points along it and
// with any spin: the ball keeps to the cushion or leaves it, time never goes back.
TEST_F(ContactsTest, BallsFrozenToEveryCushionComeToRest) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const double c = table_.cushion_contact_distance();
  Simulator sim(table_, params_);
  int runs = 0;
  for (int k = 0; k < TableModel::kCushionCount; ++k) {
    const CushionSegment& seg = table_.segments()[static_cast<size_t>(k)];
    const Vec2 along = (seg.p1 - seg.p0).normalized();
    for (int shot = 0; shot < 300; ++shot) {
      const Vec2 at = seg.p0 + (0.06 + u(rng) * ((seg.p1 - seg.p0).norm() - 0.12)) * along + c * seg.normal;
      // A third exactly along the cushion, a third into it, a third away from it.
      const double base = std::atan2(along.y(), along.x()) + (u(rng) < 0.5 ? 0 : kPi);
      const int kind = shot % 3;
      const double turn = kind == 0 ? 0.0 : (kind == 1 ? -1 : 1) * u(rng) * 1.2;
      const double sign = seg.normal.x() * std::sin(base) - seg.normal.y() * std::cos(base) > 0 ? 1 : -1;
      const double speed = 0.05 + 5 * u(rng);
      const BallState cue = Struck(at, speed, base + sign * turn, (2 * u(rng) - 1) * 2 * speed / kR,
                                   (2 * u(rng) - 1) * 2 * speed / kR);
      ASSERT_EQ(sim.Run(std::vector<BallState>{cue}), SimStatus::kAtRest) << seg.name << " shot " << shot;
      ASSERT_LT(sim.event_count(), kWellUnderCap) << seg.name << " shot " << shot;
      ASSERT_TRUE(invariants::RunKeepsInvariants(sim, table_)) << seg.name << " shot " << shot;
      ++runs;
    }
  }
  EXPECT_EQ(runs, 1800);
}

// A ball touching each knuckle, anywhere on its exposed arc (from the nose's normal
// round to the jaw wall's: the boundary is tangent-continuous there, so every such
// place is on the bed or in the pocket's mouth), or touching a jaw wall, struck in
// any direction with any spin.
TEST_F(ContactsTest, BallsBesideEveryJawComeToRest) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  const double c = table_.cushion_contact_distance();
  const auto segments = table_.segments();
  Simulator sim(table_, params_);
  int runs = 0;
  for (int k = 0; k < TableModel::kJawCount; ++k) {
    const JawCircle& jaw = table_.jaws()[static_cast<size_t>(k)];
    const CushionSegment& wall = segments[static_cast<size_t>(TableModel::kCushionCount + k)];
    Vec2 nose_normal = Vec2::Zero();
    for (int g = 0; g < TableModel::kCushionCount; ++g) {
      for (const Vec2& end : {segments[static_cast<size_t>(g)].p0, segments[static_cast<size_t>(g)].p1}) {
        if (std::abs((end - jaw.centre).norm() - jaw.radius) < 1e-9) nose_normal = segments[static_cast<size_t>(g)].normal;
      }
    }
    ASSERT_GT(nose_normal.norm(), 0.5) << "jaw " << k;
    const double from = std::atan2(nose_normal.y(), nose_normal.x());
    double span = std::atan2(wall.normal.y(), wall.normal.x()) - from;
    span = std::remainder(span, 2 * kPi);  // the shorter way round
    for (int shot = 0; shot < 150; ++shot) {
      Vec2 at;
      if (shot % 4 == 3) {  // on the jaw wall, part way along it
        at = wall.p0 + (0.2 + 0.6 * u(rng)) * (wall.p1 - wall.p0) + c * wall.normal;
      } else {
        const double a = from + u(rng) * span;
        at = jaw.centre + (jaw.radius + c) * Vec2(std::cos(a), std::sin(a));
      }
      const double speed = 0.05 + 4 * u(rng);
      const BallState cue = Struck(at, speed, 2 * kPi * u(rng), (2 * u(rng) - 1) * 2 * speed / kR,
                                   (2 * u(rng) - 1) * 2 * speed / kR);
      ASSERT_EQ(sim.Run(std::vector<BallState>{cue}), SimStatus::kAtRest) << "jaw " << k << " shot " << shot;
      ASSERT_LT(sim.event_count(), kWellUnderCap) << "jaw " << k << " shot " << shot;
      ASSERT_TRUE(invariants::RunKeepsInvariants(sim, table_)) << "jaw " << k << " shot " << shot;
      ++runs;
    }
  }
  EXPECT_EQ(runs, TableModel::kJawCount * 150);
}

// The cue ball frozen to an object ball (and to the cushion as well), struck into
// it, along the tangent and away from it, with any spin.
TEST_F(ContactsTest, BallsFrozenToAnotherComeToRest) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(0, 1);
  const double c = table_.cushion_contact_distance();
  Simulator sim(table_, params_);
  for (int shot = 0; shot < 2000; ++shot) {
    const bool on_cushion = shot % 2 == 1;
    const Vec2 object = on_cushion ? Vec2(c, 0.5 + 2.5 * u(rng)) : Vec2(0.3 + 1.2 * u(rng), 0.3 + 3 * u(rng));
    const double a = on_cushion ? (u(rng) - 0.5) * kPi : 2 * kPi * u(rng);
    const Vec2 cue = object + 2 * kR * Vec2(std::cos(a), std::sin(a));
    if (!table_.ValidatePlacement(std::vector<BallPlacement>{{"cue", cue}, {"red", object}}).empty()) {
      continue;
    }
    const double speed = 0.05 + 5 * u(rng);
    std::vector<BallState> balls = {Struck(cue, speed, 2 * kPi * u(rng), (2 * u(rng) - 1) * 2 * speed / kR,
                                           (2 * u(rng) - 1) * 2 * speed / kR),
                                    AtRest(object)};
    ASSERT_EQ(sim.Run(balls), SimStatus::kAtRest) << "shot " << shot;
    ASSERT_LT(sim.event_count(), kWellUnderCap) << "shot " << shot;
    ASSERT_TRUE(invariants::RunKeepsInvariants(sim, table_)) << "shot " << shot;
  }
}

// Reported: a break-off into the default rack with the reds 1 mm apart, from
// (0.739, 0.65) at 8 m/s with heavy draw and side, made three reds exchange impacts
// every 6e-9 s (inelastic collapse) until the event cap.
TEST_F(ContactsTest, ReportedBreakOffLivelockComesToRest) {
  std::vector<BallState> balls = {
      Struck(Vec2(0.739, 0.65), 8, DegToRad(76.3428956568571), -87.55043567626248, -43.26523841569752)};
  for (const BallState& b : scenarios::RackWithGap(1e-3, table_)) balls.push_back(b);
  Simulator sim(table_, params_);
  ASSERT_EQ(sim.Run(balls), SimStatus::kAtRest);
  EXPECT_LT(sim.event_count(), kWellUnderCap);
  EXPECT_TRUE(invariants::RunKeepsInvariants(sim, table_));
}

// A ball pressed by its own spin into a still ball, with no approach speed: the
// resting contact is resolved once, not found again and again at one instant.
TEST_F(ContactsTest, PressingContactIsResolvedOnce) {
  const Vec2 object(0.9, 1.8);
  BallState cue = AtRest(object - Vec2(2 * kR, 0));
  cue.w = Vec3(0, 30, 0);  // slip -R wy along x: friction drives it towards +x, into the red
  cue.s = MotionState::kSliding;
  Simulator sim(table_, params_);
  ASSERT_EQ(sim.Run(std::vector<BallState>{cue, AtRest(object)}), SimStatus::kAtRest);
  ASSERT_GE(sim.events().size(), 1u);
  EXPECT_EQ(sim.events()[0].kind, EventKind::kBallBall);
  EXPECT_EQ(sim.events()[0].contact, ContactStart::kPressing);
  EXPECT_EQ(sim.events()[0].time, 0.0);
  int pressing = 0;
  for (const SimEvent& e : sim.events()) pressing += e.contact == ContactStart::kPressing;
  EXPECT_EQ(pressing, 1);
  EXPECT_TRUE(invariants::RunKeepsInvariants(sim, table_));
}

// A ball against the left cushion, still, its spin driving it into the cushion: a
// resting contact, resolved once (no normal velocity left, no slip into the
// cushion); it then rolls along or away and never meets that cushion again.
TEST_F(ContactsTest, BallPressedIntoACushionIsHeldOnce) {
  const double c = table_.cushion_contact_distance();
  BallState ball = AtRest(Vec2(c, 1.2));
  ball.w = Vec3(3.0, -40.0, 5.0);  // slip (-R wy, R wx) along +x: friction drives it to -x
  ball.s = MotionState::kSliding;
  Simulator sim(table_, params_);
  ASSERT_EQ(sim.Run(std::vector<BallState>{ball}), SimStatus::kAtRest);
  ASSERT_GE(sim.events().size(), 1u);
  EXPECT_EQ(sim.events()[0].kind, EventKind::kCushion);
  EXPECT_EQ(sim.events()[0].contact, ContactStart::kPressing);
  EXPECT_EQ(sim.events()[0].time, 0.0);
  int cushion = 0;
  for (const SimEvent& e : sim.events()) cushion += e.kind == EventKind::kCushion;
  EXPECT_EQ(cushion, 1);
  EXPECT_NEAR(sim.final_balls()[0].r.x(), c, 1e-9);  // it stayed against the cushion
  EXPECT_TRUE(invariants::RunKeepsInvariants(sim, table_));
}

// A slow, spinning ball that reaches a cushion while its spin drives it on into it
// would bounce in ever shorter flights; it is held once a flight would rise less
// than resting_contact_excursion off the cushion.
TEST_F(ContactsTest, BouncesAgainstACushionEndInAHold) {
  // Found by a seeded search: a slow ball 7 um from the left cushion, drifting
  // into it and along it, its spin driving it on into the cushion.
  BallState ball = AtRest(Vec2(0.024379, 1.2));
  ball.v = Vec3(-0.0079, 0.1140, 0.0);
  ball.w = Vec3(38.738, -48.449, 48.760);
  ball.s = MotionState::kSliding;
  Simulator sim(table_, params_);
  ASSERT_EQ(sim.Run(std::vector<BallState>{ball}), SimStatus::kAtRest);
  auto cushion_events = [](const Simulator& s) {
    int n = 0;
    for (const SimEvent& e : s.events()) n += e.kind == EventKind::kCushion;
    return n;
  };
  const int held = cushion_events(sim);
  EXPECT_GE(held, 2);
  EXPECT_LT(held, 50);
  EXPECT_TRUE(invariants::RunKeepsInvariants(sim, table_));
  // Without the hold the same ball bounces many more times.
  SimParams bouncing = params_;
  bouncing.resting_contact_excursion = 0;
  Simulator endless(table_, bouncing);
  endless.Run(std::vector<BallState>{ball});  // reaches the event cap
  EXPECT_GT(cushion_events(endless), 100 * held);
  RecordProperty("cushion_events_held", held);
  RecordProperty("cushion_events_without_hold", cushion_events(endless));
}

struct BreakOffSweep {
  double gap;  // m between neighbouring reds
  const char* name;
};
// How gtest (and so ctest's test list) prints the parameter.
void PrintTo(const BreakOffSweep& s, std::ostream* os) { *os << s.name; }

class BreakOffSweepTest : public testing::TestWithParam<BreakOffSweep> {};

// 1000 seeded random break-offs per gap (250 under the sanitizers): each comes to rest
// well under the event cap and keeps the invariants. docs/resting-contacts.md has the
// event counts.
TEST_P(BreakOffSweepTest, ComeToRestWellUnderTheCap) {
  constexpr int kBreakOffs = sanitizers::SweepCases(1000);
  std::mt19937_64 rng(0x5eed0000u + static_cast<unsigned>(GetParam().gap * 1e6));
  Simulator sim(DefaultTable(), SimParams{});
  std::vector<std::int32_t> events;
  for (int k = 0; k < kBreakOffs; ++k) {
    const std::vector<BallState> balls = scenarios::RandomBreakOff(GetParam().gap, rng);
    ASSERT_EQ(sim.Run(balls), SimStatus::kAtRest) << "break-off " << k;
    ASSERT_LT(sim.event_count(), kWellUnderCap) << "break-off " << k;
    ASSERT_TRUE(invariants::RunKeepsInvariants(sim, DefaultTable())) << "break-off " << k;
    events.push_back(sim.event_count());
  }
  std::sort(events.begin(), events.end());
  RecordProperty("events_p50", events[kBreakOffs / 2]);
  RecordProperty("events_p99", events[kBreakOffs * 99 / 100]);
  RecordProperty("events_max", events.back());
}

INSTANTIATE_TEST_SUITE_P(Gaps, BreakOffSweepTest,
                         testing::Values(BreakOffSweep{0, "Touching"}, BreakOffSweep{1e-6, "Gap1um"},
                                         BreakOffSweep{1e-4, "Gap100um"}, BreakOffSweep{1e-3, "Gap1mm"}),
                         [](const testing::TestParamInfo<BreakOffSweep>& p) { return std::string(p.param.name); });

// ---- The rules on their own (physics/sim/contacts.h) ----

// Rounding of a few operations on speeds of order 1 m/s. m/s.
constexpr double kRuleTol = 1e-12;

TEST_F(ContactsTest, AfterImpactRestsOnlyBallsSlowerThanRestSpeed) {
  BallState slow = Settle(scenarios::Rolling(Vec2(1, 1), Vec2(0, 1), 0.5 * params_.rest_speed),
                          params_.ball);
  slow.w.z() = 3.0;  // Z spin is kept
  const BallState rested = AfterImpact(slow, params_);
  EXPECT_EQ(rested.v.head<2>().norm(), 0.0);
  EXPECT_EQ(rested.w.z(), 3.0);
  EXPECT_EQ(rested.s, MotionState::kSpinning);
  const BallState fast = Settle(
      scenarios::Rolling(Vec2(1, 1), Vec2(0, 1), 2 * params_.rest_speed), params_.ball);
  EXPECT_EQ(AfterImpact(fast, params_).v, fast.v);
}

// A sliding ball driven into a cushion (normal +x, from the cushion to the ball):
// held against it, it has no normal velocity and no normal cloth slip left, keeps
// its motion along the cushion and loses energy.
TEST_F(ContactsTest, HoldAgainstLeavesNoNormalVelocityOrSlip) {
  const Vec2 n(1, 0);
  BallState s = AtRest(Vec2(table_.cushion_contact_distance(), 1.0));
  s.v = Vec3(-0.2, 0.7, 0.0);
  s.w = Vec3(4.0, 9.0, 2.0);
  s = Settle(s, params_.ball);
  ASSERT_EQ(s.s, MotionState::kSliding);
  const BallState held = HoldAgainst(s, n, params_);
  EXPECT_NEAR(held.v.head<2>().dot(n), 0.0, kRuleTol);
  EXPECT_NEAR(ClothSlip(held, params_.ball).dot(n), 0.0, kRuleTol);
  EXPECT_NEAR(held.v.y(), 0.7, kRuleTol);
  EXPECT_EQ(held.w.z(), 2.0);
  EXPECT_LT(KineticEnergy(held, params_.ball), KineticEnergy(s, params_.ball));
}

// b rolls away from a along the line of centres n; its deceleration presses the
// two together. Slow, both stop; faster, b loses its motion along n and keeps the
// rest; pressed a second time at the same instant (level 1), b stops.
TEST_F(ContactsTest, HoldTogetherStopsSlowPairsAndTheMotionAlongTheLine) {
  const Vec2 n(0, 1);
  const BallState a = AtRest(Vec2(0.889, 1.0));
  auto rolling_b = [&](const Vec2& dir, double speed) {
    return Settle(scenarios::Rolling(a.r + 2 * kR * n, dir, speed), params_.ball);
  };
  BallState a1 = a, b1 = rolling_b(n, 0.5 * params_.resting_pair_speed);
  HoldTogether(&a1, &b1, n, 0, 0, params_);
  EXPECT_EQ(b1.v.head<2>().norm(), 0.0);
  EXPECT_EQ(a1.v.head<2>().norm(), 0.0);

  const Vec2 diagonal = Vec2(1, 1).normalized();
  BallState a2 = a, b2 = rolling_b(diagonal, 0.2);
  HoldTogether(&a2, &b2, n, 0, 0, params_);
  EXPECT_NEAR(b2.v.head<2>().dot(n), 0.0, kRuleTol);
  EXPECT_NEAR(b2.v.x(), 0.2 * diagonal.x(), kRuleTol);

  BallState a3 = a, b3 = rolling_b(diagonal, 0.2);
  HoldTogether(&a3, &b3, n, 0, 1, params_);
  EXPECT_EQ(b3.v.head<2>().norm(), 0.0);
}

}  // namespace
}  // namespace snooker::physics
