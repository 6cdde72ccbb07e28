// The cluster resolution (physics/sim/cluster.h) on its own: which balls and
// contacts make a cluster, and what the impulse problem's solution guarantees - no
// contact left approaching, Newton restitution where it has a solution, the plastic
// one where it does not, kinetic energy never rising, momentum kept along a free line.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "physics/motion/motion.h"
#include "physics/sim/cluster.h"
#include "tests/support/scenarios.h"

namespace snooker::physics {
namespace {

using scenarios::AtRest;
using scenarios::kR;

// Separation speeds are solved to 1e-12 m/s; this leaves room for the sums of a few
// impulses. m/s.
constexpr double kSpeedTol = 1e-10;

class ClusterTest : public testing::Test {
 protected:
  // A cluster of the given states, gathered around the pair (0, 1) with its
  // contacts found on the default table.
  Cluster Make(const std::vector<BallState>& balls) const {
    Cluster c;
    c.balls = static_cast<int>(balls.size());
    for (int i = 0; i < c.balls; ++i) c.state[i] = balls[static_cast<size_t>(i)];
    GatherCluster(0, 1, params_.ball.radius, &c);
    FindClusterContacts(table_, table_.cushion_contact_distance(), params_, &c);
    return c;
  }
  double Energy(const Cluster& c) const {
    double e = 0;
    for (int k = 0; k < c.count; ++k) e += KineticEnergy(c.state[c.members[k]], params_.ball);
    return e;
  }
  static double Separation(const Cluster& c, const ClusterContact& k) {
    const Vec2 va = c.state[k.a].v.head<2>();
    return k.b >= 0 ? (c.state[k.b].v.head<2>() - va).dot(k.n) : va.dot(k.n);
  }

  const TableModel& table_ = DefaultTable();
  SimParams params_;
};

// A ball sliding at `speed` along +y (no spin: it slides on the cloth).
BallState Sliding(const Vec2& r, double speed) {
  BallState s = AtRest(r);
  s.v = Vec3(0, speed, 0);
  s.s = MotionState::kSliding;
  return s;
}

TEST_F(ClusterTest, GathersTouchingBallsBreadthFirstAndLeavesOthersOut) {
  const Vec2 o(0.889, 1.0);
  const double d = 2 * kR;
  // 0 and 1 touch, 2 touches 1, 3 touches 2, 4 is a hair too far from 3, 5 touches 3
  // but is pocketed.
  std::vector<BallState> balls = {AtRest(o), AtRest(o + Vec2(0, d)), AtRest(o + Vec2(0, 2 * d)),
                                  AtRest(o + Vec2(0, 3 * d)), AtRest(o + Vec2(0, 4 * d + 1e-6)),
                                  AtRest(o + Vec2(d, 3 * d))};
  balls[5].s = MotionState::kPocketed;
  const Cluster c = Make(balls);
  ASSERT_EQ(c.count, 4);
  EXPECT_EQ(c.members[0], 0);
  EXPECT_EQ(c.members[1], 1);
  EXPECT_EQ(c.members[2], 2);
  EXPECT_EQ(c.members[3], 3);
  // Three ball-ball contacts along the line and none with the table, far from it.
  ASSERT_EQ(c.contact_count, 3);
  for (int k = 0; k < c.contact_count; ++k) {
    EXPECT_GE(c.contacts[k].b, 0);
    EXPECT_NEAR(c.contacts[k].n.y(), 1.0, 1e-12);  // from the lower index to the higher
  }
}

TEST_F(ClusterTest, FindsTheCushionABallTouches) {
  const double x = table_.cushion_contact_distance();  // frozen to the left cushion
  const Cluster c = Make({AtRest(Vec2(x + 2 * kR, 1.0)), AtRest(Vec2(x, 1.0))});
  ASSERT_EQ(c.count, 2);
  int boundary = 0;
  for (int k = 0; k < c.contact_count; ++k) {
    if (c.contacts[k].b >= 0) continue;
    ++boundary;
    EXPECT_EQ(c.contacts[k].a, 1);
    EXPECT_NEAR(c.contacts[k].n.x(), 1.0, 1e-12);  // from the cushion to the ball
  }
  EXPECT_EQ(boundary, 1);
}

// Head-on on a line of touching balls: the Newton solution exists, every contact
// that approached separates at e times its approach, none approaches, the line's
// momentum is kept and no energy is made. Up to the longest line there can be
// (limits::kMaxBalls): Gauss-Seidel converges slowly along a line, and a line of nine
// or more once ran out of sweeps and was stopped dead.
TEST_F(ClusterTest, NewtonsCradleKeepsMomentumAndSeparatesAtRestitution) {
  for (const int n : {3, 9, 16, Cluster::kMaxBalls}) {
    SCOPED_TRACE(std::to_string(n) + " balls in a line");
    const Vec2 o(0.889, 0.4);
    const double v0 = 1.0;
    std::vector<BallState> balls = {Sliding(o, v0)};
    for (int i = 1; i < n; ++i) balls.push_back(AtRest(o + Vec2(0, 2 * kR * i)));
    Cluster c = Make(balls);
    ASSERT_EQ(c.count, n);
    ASSERT_EQ(c.contact_count, n - 1);  // none with the table
    const double before = Energy(c);
    SolveCluster(params_, &c);
    double momentum = 0;
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(c.state[i].v.x(), 0.0, kSpeedTol);
      momentum += c.state[i].v.y();
    }
    EXPECT_NEAR(momentum, v0, kSpeedTol);
    for (int k = 0; k < c.contact_count; ++k) EXPECT_GE(Separation(c, c.contacts[k]), -kSpeedTol);
    // The first contact approached at v0: it separates at e v0 at least.
    EXPECT_GE(c.state[1].v.y() - c.state[0].v.y(), params_.cluster_restitution * v0 - kSpeedTol);
    EXPECT_LE(Energy(c), before);
  }
}

// A ball driven into a ball frozen to a cushion: the wall takes the impulse, nothing
// approaches the cushion afterwards and no energy is made.
TEST_F(ClusterTest, BallPressedAgainstACushionDoesNotGoThroughIt) {
  const double x = table_.cushion_contact_distance();
  BallState moving = AtRest(Vec2(x + 2 * kR, 1.0));
  moving.v = Vec3(-0.5, 0.0, 0.0);
  moving.s = MotionState::kSliding;
  Cluster c = Make({moving, AtRest(Vec2(x, 1.0))});
  const double before = Energy(c);
  SolveCluster(params_, &c);
  for (int k = 0; k < c.contact_count; ++k) EXPECT_GE(Separation(c, c.contacts[k]), -kSpeedTol);
  EXPECT_GE(c.state[0].v.x(), 0.0);  // the moving ball comes back, or stops
  EXPECT_LE(Energy(c), before);
}

// With restitution 0 (plastic) the solution leaves the approaching contacts at zero
// normal relative speed: the line moves as one.
TEST_F(ClusterTest, PlasticSolutionMovesTheLineTogether) {
  params_.cluster_restitution = 0;
  const Vec2 o(0.889, 1.0);
  Cluster c = Make({Sliding(o, 0.9), AtRest(o + Vec2(0, 2 * kR)), AtRest(o + Vec2(0, 4 * kR))});
  SolveCluster(params_, &c);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(c.state[i].v.y(), 0.3, kSpeedTol) << "ball " << i;
}

}  // namespace
}  // namespace snooker::physics
