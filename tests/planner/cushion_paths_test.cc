// Tests of the mirror paths off cushions (planner/cushion_paths.h): the geometry of
// one and two cushions, each refusal, and, with the full simulator, that the heading
// which really puts a rolling ball through the target lies in the path's aim bracket
// (the table of the mirror's error in the header comes from MirrorErrorTable).
#include "planner/cushion_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "planner/geometry.h"
#include "tests/planner/cushion_roll.h"

namespace snooker::planner {
namespace {

using physics::Vec2;
using testing_roll::Roller;

const physics::TableModel& Table() { return physics::DefaultTable(); }
double C() { return Table().cushion_contact_distance(); }
constexpr double kR = 0.02625;
double Deg(double rad) { return rad * physics::kDegPerRad; }

// S and T symmetric about the normal through a point of the left-baulk cushion,
// `leg` (m) from the contact point, the path meeting the cushion at `incidence`.
struct Symmetric {
  Vec2 start, target, contact;
};
Symmetric LeftCushion(double incidence, double leg, double contact_y = 0.9, double leg_out = -1) {
  const Vec2 p(C(), contact_y);
  return {p + leg * Vec2(std::cos(incidence), -std::sin(incidence)),
          p + (leg_out < 0 ? leg : leg_out) * Vec2(std::cos(incidence), std::sin(incidence)), p};
}

TEST(CushionPathsTest, OneCushionIsTheMirror) {
  const Symmetric s = LeftCushion(physics::DegToRad(30), 0.6);
  const std::array<CushionLine, 1> left = {CushionLine::kLeft};
  PathRefusal why;
  const auto path = MirrorPath(Table(), s.start, s.target, left, {}, &why);
  ASSERT_TRUE(path) << ToString(why);
  EXPECT_EQ(path->cushions, 1);
  EXPECT_NEAR((path->contacts[0].point - s.contact).norm(), 0, 1e-12);
  EXPECT_NEAR(Deg(path->contacts[0].incidence), 30, 1e-9);
  EXPECT_STREQ(Table().segments()[static_cast<size_t>(path->contacts[0].segment)].name, "left-baulk");
  EXPECT_NEAR(path->legs[0], 0.6, 1e-12);
  EXPECT_NEAR(path->legs[1], 0.6, 1e-12);
  EXPECT_NEAR(path->length, 1.2, 1e-12);
  EXPECT_NEAR(Deg(WrapAngle(path->heading - Direction(s.contact - s.start))), 0, 1e-9);
  // Unfolded, the path is one straight segment of its length.
  const Vec2 unfolded = path->Unfold(1, s.target);
  EXPECT_NEAR((unfolded - s.start).norm(), path->length, 1e-12);
  EXPECT_NEAR(Deg(WrapAngle(Direction(unfolded - s.start) - path->heading)), 0, 1e-9);
  EXPECT_NEAR((path->Fold(1, unfolded) - s.target).norm(), 0, 1e-12);
  EXPECT_TRUE(path->bracket.Contains(0));
}

TEST(CushionPathsTest, TwoCushionsAroundACorner) {
  // Off the left cushion, then the top cushion, back down the table.
  const Vec2 start(0.3, 2.6), target(1.5, 3.0);
  const std::array<CushionLine, 2> lines = {CushionLine::kLeft, CushionLine::kTop};
  PathRefusal why;
  const auto path = MirrorPath(Table(), start, target, lines, {}, &why);
  ASSERT_TRUE(path) << ToString(why);
  EXPECT_EQ(path->cushions, 2);
  EXPECT_NEAR(path->contacts[0].point.x(), C(), 1e-12);
  EXPECT_NEAR(path->contacts[1].point.y(), Table().spec().length - C(), 1e-12);
  // Angle in equals angle out at each contact.
  for (int i = 0; i < 2; ++i) {
    const Vec2 in = (path->points[static_cast<size_t>(i + 1)] - path->points[static_cast<size_t>(i)]).normalized();
    const Vec2 out = (path->points[static_cast<size_t>(i + 2)] - path->points[static_cast<size_t>(i + 1)]).normalized();
    const Vec2 n = path->contacts[static_cast<size_t>(i)].contact_line.normal;
    EXPECT_NEAR(-in.dot(n), out.dot(n), 1e-12);
    EXPECT_NEAR(Cross(n, in), Cross(n, out), 1e-12);
  }
  const Vec2 unfolded = path->Unfold(2, target);
  EXPECT_NEAR((unfolded - start).norm(), path->length, 1e-12);
  EXPECT_NEAR((path->Fold(2, unfolded) - target).norm(), 0, 1e-12);
  EXPECT_NEAR(path->LengthAfter(0), path->legs[1] + path->legs[2], 1e-12);
}

TEST(CushionPathsTest, EachRefusal) {
  PathRefusal why;
  const std::array<CushionLine, 1> left = {CushionLine::kLeft};
  // Into the middle pocket's mouth.
  const Symmetric mouth = LeftCushion(physics::DegToRad(30), 0.5, Table().spec().length / 2);
  EXPECT_FALSE(MirrorPath(Table(), mouth.start, mouth.target, left, {}, &why));
  EXPECT_EQ(why, PathRefusal::kOffCushion);
  // Within the jaw margin of the baulk-left corner's jaw.
  const Symmetric jaw = LeftCushion(physics::DegToRad(30), 0.1, 0.08);
  EXPECT_FALSE(MirrorPath(Table(), jaw.start, jaw.target, left, {}, &why));
  EXPECT_EQ(why, PathRefusal::kOffCushion);
  // A glance along the cushion.
  const Symmetric glance = LeftCushion(physics::DegToRad(80), 0.5);
  EXPECT_FALSE(MirrorPath(Table(), glance.start, glance.target, left, {}, &why));
  EXPECT_EQ(why, PathRefusal::kGlancing);
  // A ball frozen to the cushion cannot be played off it.
  EXPECT_FALSE(MirrorPath(Table(), Vec2(C(), 0.5), Vec2(0.5, 0.9), left, {}, &why));
  EXPECT_EQ(why, PathRefusal::kOutside);
  // The same line twice.
  const std::array<CushionLine, 2> twice = {CushionLine::kLeft, CushionLine::kLeft};
  EXPECT_FALSE(MirrorPath(Table(), Vec2(0.5, 0.5), Vec2(0.5, 0.9), twice, {}, &why));
  // Two cushions that the straight line cannot meet in that order: the right
  // cushion first, then the left, towards a target beside the right cushion.
  const std::array<CushionLine, 2> order = {CushionLine::kTop, CushionLine::kBaulk};
  EXPECT_TRUE(MirrorPath(Table(), Vec2(0.5, 1.0), Vec2(0.6, 1.2), order, {}, &why)) << ToString(why);
}

TEST(CushionPathsTest, LegsMarginSeesABallOnEitherLeg) {
  const Symmetric s = LeftCushion(physics::DegToRad(40), 0.6);
  const std::array<CushionLine, 1> left = {CushionLine::kLeft};
  const auto path = MirrorPath(Table(), s.start, s.target, left);
  ASSERT_TRUE(path);
  TableState t;
  t.balls = {{BallKind::kCue, s.start}, {BallKind::kRed, s.target + 0.2 * Vec2(1, 0)}};
  EXPECT_GT(LegsMargin(*path, 2 * kR, t, 0), 0);
  // A ball on the second leg, then one on the first.
  t.balls.push_back({BallKind::kBlue, 0.5 * (s.contact + s.target)});
  EXPECT_LT(LegsMargin(*path, 2 * kR, t, 0), 0);
  const Vec2 in = (s.contact - s.start).normalized();
  t.balls.back().position = 0.5 * (s.contact + s.start) + (2 * kR + 0.002) * Left(in);
  EXPECT_LT(LegsMargin(*path, 2 * kR + 0.0025, t, 0), 0);
  EXPECT_GT(LegsMargin(*path, 2 * kR + 0.0005, t, 0), 0);
  // The ball at the target is skipped on the last leg only.
  t.balls.back().position = s.target;
  EXPECT_LT(LegsMargin(*path, 2 * kR, t, 0), 0);
  EXPECT_GT(LegsMargin(*path, 2 * kR, t, 0, -1, 2), 0);
  std::vector<CushionPath> out;
  const int added = AppendCushionPaths(Table(), t, s.start, s.target, 1, 2 * kR, 0, -1, 2, {}, out);
  EXPECT_EQ(added, static_cast<int>(out.size()));
  bool left_found = false;
  for (const CushionPath& q : out) left_found |= q.cushions == 1 && q.contacts[0].line == CushionLine::kLeft;
  EXPECT_TRUE(left_found);
}

// The heading that really passes the target, against the mirror's, for a rolling
// ball: inside the bracket for every speed (1 to 4 m/s) and pair of legs (0.3 to
// 1 m) at each incidence; printed for legs of 0.6 m as the table in
// cushion_paths.h.
TEST(CushionPathsTest, MirrorErrorTable) {
  Roller roller;
  const std::array<CushionLine, 1> left = {CushionLine::kLeft};
  const double speeds[] = {1.0, 2.0, 3.0, 4.0};
  const double legs[] = {0.3, 0.6, 1.0};
  int checked = 0;
  for (int inc = 5; inc <= 75; inc += 10) {
    std::printf("  %3d       ", inc);
    for (double speed : speeds) {
      for (double leg_in : legs) {
        for (double leg_out : legs) {
          const Symmetric s = LeftCushion(physics::DegToRad(inc), leg_in, 1.07, leg_out);
          const auto path = MirrorPath(Table(), s.start, s.target, left);
          ASSERT_TRUE(path);
          const Vec2 along = (s.target - s.contact).normalized();
          auto h = roller.TrueHeading(s.start, path->heading, speed, s.target, along, 1, physics::DegToRad(8));
          if (!h) h = roller.TrueHeading(s.start, path->heading, speed, s.target, along, 1, physics::DegToRad(12));
          ASSERT_TRUE(h) << inc << " deg, " << speed << " m/s";
          const double dh = WrapAngle(*h - path->heading);
          ++checked;
          EXPECT_TRUE(path->bracket.Contains(dh))
              << inc << " deg, " << speed << " m/s, legs " << leg_in << " " << leg_out << ": " << Deg(dh)
              << " deg not in [" << Deg(path->bracket.lo) << ", " << Deg(path->bracket.hi) << "]";
          // It is the path: the left-baulk cushion, and nothing else, before the target.
          const auto pass = roller.Run(s.start, *h, speed, s.target, along, 1);
          EXPECT_EQ(pass.cushions, std::vector<int>{path->contacts[0].segment});
          if (leg_in == 0.6 && leg_out == 0.6) {
            std::printf("%+6.2f %+6.2f     ", Deg(dh), Deg(dh / ReboundHeadingGain(*path, 0)));
          }
        }
      }
    }
    std::printf("\n");
  }
  EXPECT_EQ(checked, 8 * 4 * 9);
}

// Two cushions: the brackets of both contacts add up, and cover the true heading.
TEST(CushionPathsTest, TwoCushionBracketCoversTheTrueHeading) {
  Roller roller;
  struct Case {
    Vec2 start, target;
    std::array<CushionLine, 2> lines;
  };
  const Case cases[] = {
      {Vec2(0.3, 2.6), Vec2(1.5, 3.0), {CushionLine::kLeft, CushionLine::kTop}},
      {Vec2(0.5, 0.6), Vec2(0.6, 1.5), {CushionLine::kLeft, CushionLine::kRight}},
      {Vec2(1.2, 0.6), Vec2(0.4, 1.2), {CushionLine::kBaulk, CushionLine::kLeft}},
  };
  for (const Case& k : cases) {
    const auto path = MirrorPath(Table(), k.start, k.target, k.lines);
    ASSERT_TRUE(path);
    const Vec2 along = (k.target - path->points[2]).normalized();
    for (double speed : {2.0, 3.0, 4.0}) {
      const auto h = roller.TrueHeading(k.start, path->heading, speed, k.target, along, 2, physics::DegToRad(8));
      ASSERT_TRUE(h) << speed << " m/s";
      const double dh = WrapAngle(*h - path->heading);
      EXPECT_TRUE(path->bracket.Contains(dh)) << speed << " m/s: " << Deg(dh) << " deg not in ["
                                              << Deg(path->bracket.lo) << ", " << Deg(path->bracket.hi) << "]";
      const auto pass = roller.Run(k.start, *h, speed, k.target, along, 2);
      EXPECT_EQ(pass.cushions, (std::vector<int>{path->contacts[0].segment, path->contacts[1].segment}));
    }
  }
}

// The rebound's speed sensitivity, d(eps)/d(ln speed) by differences of 2 % in
// speed, rolling, legs of 0.6 m: its root mean square over a few incidences and
// speeds is within a factor of two of ReboundSpeedSensitivity's.
TEST(CushionPathsTest, ReboundSpeedSensitivityMatchesTheSimulator) {
  Roller roller;
  const std::array<CushionLine, 1> left = {CushionLine::kLeft};
  double measured2 = 0, tabled2 = 0;
  for (double inc : {15.0, 35.0, 55.0, 65.0}) {
    const Symmetric s = LeftCushion(physics::DegToRad(inc), 0.6, 1.07);
    const auto path = MirrorPath(Table(), s.start, s.target, left);
    ASSERT_TRUE(path);
    const Vec2 along = (s.target - s.contact).normalized();
    for (double speed : {1.5, 2.0, 3.0}) {
      const auto h0 = roller.TrueHeading(s.start, path->heading, speed, s.target, along, 1, physics::DegToRad(8));
      const auto h1 = roller.TrueHeading(s.start, path->heading, 1.02 * speed, s.target, along, 1, physics::DegToRad(8));
      ASSERT_TRUE(h0 && h1);
      const double d = WrapAngle(*h1 - *h0) / ReboundHeadingGain(*path, 0) / std::log(1.02);
      measured2 += d * d;
      tabled2 += std::pow(ReboundSpeedSensitivity(path->contacts[0].incidence), 2);
    }
  }
  const double ratio = std::sqrt(measured2 / tabled2);
  std::printf("rebound speed sensitivity: measured / tabulated (rms) %.2f\n", ratio);
  EXPECT_GT(ratio, 0.5);
  EXPECT_LT(ratio, 2.0);
}

}  // namespace
}  // namespace snooker::planner
