#include "physics/motion/motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "physics/motion/slip_phase.h"

namespace snooker::physics {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Closed forms evaluated two ways agree to rounding: speeds of a few m/s and times
// of a few seconds carry errors of ~1e-15; 1e-12 leaves a wide margin. m, m/s, rad/s, s.
constexpr double kClosedFormTol = 1e-12;
// Energy checks: kinetic energies are ~0.1-1 J; rounding is ~1e-16 J. J.
constexpr double kEnergyTol = 1e-12;
// RK4 with 20000 steps on a smooth (piecewise constant acceleration) ODE: ~1e-12 m.
constexpr double kIntegrationTol = 1e-9;

class MotionTest : public ::testing::Test {
 protected:
  BallParams ball_;
  ClothParams cloth_;
  double R() const { return ball_.radius; }

  BallState Make(Vec2 r, Vec3 v, Vec3 w) const {
    BallState s;
    s.r = r;
    s.v = v;
    s.w = w;
    return Settle(s, ball_);
  }
  // Rolling at velocity v (horizontal) with sidespin wz.
  BallState Rolling(Vec2 v, double wz) const {
    return Make(Vec2(0.5, 0.5), Vec3(v.x(), v.y(), 0), Vec3(-v.y() / R(), v.x() / R(), wz));
  }
};

TEST_F(MotionTest, StunShotSlidesTwelveFortyNinthsAndLeavesAtFiveSevenths) {
  const double mu_g = cloth_.mu_s * cloth_.g;
  for (const Vec2& dir : {Vec2(0, 1), Vec2(0.6, -0.8), Vec2(-1, 0)}) {
    const double v0 = 2.3;
    const BallState s = Make(Vec2(0.3, 0.4), Vec3(v0 * dir.x(), v0 * dir.y(), 0), Vec3::Zero());
    ASSERT_EQ(s.s, MotionState::kSliding);
    const double t_s = TransitionTime(s, ball_, cloth_);
    EXPECT_NEAR(t_s, 2 * v0 / (7 * mu_g), kClosedFormTol);
    const BallState e = Evolve(s, t_s, ball_, cloth_);
    EXPECT_EQ(e.s, MotionState::kRolling);
    EXPECT_NEAR(Vec2(e.v.x(), e.v.y()).norm(), 5.0 / 7.0 * v0, kClosedFormTol);
    EXPECT_NEAR((e.r - s.r).norm(), 12 * v0 * v0 / (49 * mu_g), kClosedFormTol);
    EXPECT_NEAR((e.r - s.r).normalized().dot(dir), 1.0, kClosedFormTol);
    EXPECT_LE(ClothSlip(e, ball_).norm(), kClosedFormTol);  // slip exactly 0 up to R (v / R)
  }
}

TEST_F(MotionTest, RollingBallStopsAfterVSquaredOverTwoMuRG) {
  const double mu_g = cloth_.mu_r * cloth_.g;
  const double v0 = 1.5;
  const BallState s = Rolling(Vec2(v0 * 0.8, v0 * 0.6), 0.0);
  ASSERT_EQ(s.s, MotionState::kRolling);
  const double t_r = TransitionTime(s, ball_, cloth_);
  EXPECT_NEAR(t_r, v0 / mu_g, kClosedFormTol);
  EXPECT_NEAR(mu_g, 0.1256, 1e-4);  // about 0.125 m/s^2 measured (docs/physics-notes.md section 9)
  const BallState e = Evolve(s, t_r, ball_, cloth_);
  EXPECT_EQ(e.s, MotionState::kStationary);
  EXPECT_EQ(e.v, Vec3::Zero());
  EXPECT_EQ(e.w, Vec3::Zero());
  EXPECT_NEAR((e.r - s.r).norm(), v0 * v0 / (2 * mu_g), kClosedFormTol);
  // Halfway in time it has covered three quarters of the distance.
  const BallState h = Evolve(s, t_r / 2, ball_, cloth_);
  EXPECT_NEAR((h.r - s.r).norm(), 0.75 * v0 * v0 / (2 * mu_g), kClosedFormTol);
  EXPECT_LE(ClothSlip(h, ball_).norm(), kClosedFormTol);
}

TEST_F(MotionTest, DrawShotReversesDirection) {
  const double mu_g = cloth_.mu_s * cloth_.g;
  const double v0 = 2.0;
  // Backspin three times the rolling spin: u = v + R wx = 4 v0 along +y.
  const BallState s = Make(Vec2(0.9, 1.0), Vec3(0, v0, 0), Vec3(3 * v0 / R(), 0, 0));
  ASSERT_EQ(s.s, MotionState::kSliding);
  const double t_s = TransitionTime(s, ball_, cloth_);
  EXPECT_NEAR(t_s, 8 * v0 / (7 * mu_g), kClosedFormTol);
  // Stops (still sliding) at t = v0 / (mu_s g), v0^2 / (2 mu_s g) up the table.
  const double t_stop = v0 / mu_g;
  const BallState m = Evolve(s, t_stop, ball_, cloth_);
  EXPECT_EQ(m.s, MotionState::kSliding);
  EXPECT_NEAR(m.v.norm(), 0.0, kClosedFormTol);
  EXPECT_NEAR(m.r.y() - s.r.y(), v0 * v0 / (2 * mu_g), kClosedFormTol);
  // Ends the slip coming back at v0 - (2/7) 4 v0 = -v0 / 7, then rolls back.
  const BallState e = Evolve(s, t_s, ball_, cloth_);
  EXPECT_EQ(e.s, MotionState::kRolling);
  EXPECT_NEAR(e.v.y(), -v0 / 7, kClosedFormTol);
  EXPECT_NEAR(e.v.x(), 0.0, kClosedFormTol);
  EXPECT_NEAR(e.r.y() - s.r.y(), v0 * t_s - 0.5 * mu_g * t_s * t_s, kClosedFormTol);
  const BallState later = Evolve(e, 1.0, ball_, cloth_);
  EXPECT_LT(later.r.y(), e.r.y());
}

TEST_F(MotionTest, SidespinDecaysAtSpinDecelInEveryState) {
  const double decel = cloth_.spin_decel;
  for (double wz : {11.0, -11.0}) {
    const BallState s = Make(Vec2(1, 1), Vec3::Zero(), Vec3(0, 0, wz));
    ASSERT_EQ(s.s, MotionState::kSpinning);
    EXPECT_NEAR(TransitionTime(s, ball_, cloth_), 0.5, kClosedFormTol);
    EXPECT_NEAR(Evolve(s, 0.25, ball_, cloth_).w.z(), wz / 2, kClosedFormTol);
    const BallState e = Evolve(s, 0.5, ball_, cloth_);
    EXPECT_EQ(e.s, MotionState::kStationary);
    EXPECT_EQ(e.w.z(), 0.0);
    EXPECT_EQ(e.r, s.r);
  }
  // While rolling: the Z spin runs out at wz / decel, the ball keeps rolling.
  const BallState roll = Rolling(Vec2(0, 1.0), 30.0);
  const BallState a = Evolve(roll, 1.0, ball_, cloth_);
  EXPECT_NEAR(a.w.z(), 30.0 - decel, kClosedFormTol);
  const BallState b = Evolve(roll, 2.0, ball_, cloth_);
  EXPECT_EQ(b.w.z(), 0.0);
  EXPECT_EQ(b.s, MotionState::kRolling);
  // While sliding.
  const BallState slide = Make(Vec2(1, 1), Vec3(1, 0, 0), Vec3(0, 0, -5.0));
  const double t = 0.5 * TransitionTime(slide, ball_, cloth_);
  EXPECT_NEAR(Evolve(slide, t, ball_, cloth_).w.z(), -5.0 + decel * t, kClosedFormTol);
  // A slow roll that stops before its sidespin does leaves the ball spinning.
  const BallState slow = Rolling(Vec2(0.1, 0), 30.0);
  const double t_r = TransitionTime(slow, ball_, cloth_);
  const BallState c = Evolve(slow, t_r, ball_, cloth_);
  EXPECT_EQ(c.s, MotionState::kSpinning);
  EXPECT_NEAR(c.w.z(), 30.0 - decel * t_r, kClosedFormTol);
}

TEST_F(MotionTest, EvolveComposesWithinAPhase) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const BallState s = Make(Vec2(1 + u(rng), 2 + u(rng)), Vec3(3 * u(rng), 3 * u(rng), 0),
                             Vec3(100 * u(rng), 100 * u(rng), 50 * u(rng)));
    const double t_end = TransitionTime(s, ball_, cloth_);
    ASSERT_TRUE(std::isfinite(t_end));
    const double t1 = 0.3 * t_end, t2 = 0.5 * t_end;
    const BallState once = Evolve(s, t1 + t2, ball_, cloth_);
    const BallState mid = Evolve(s, t1, ball_, cloth_);
    const BallState twice = Evolve(mid, t2, ball_, cloth_);
    EXPECT_EQ(mid.s, s.s);
    EXPECT_NEAR(TransitionTime(mid, ball_, cloth_), t_end - t1, kClosedFormTol);
    EXPECT_LE((once.r - twice.r).norm(), kClosedFormTol);
    EXPECT_LE((once.v - twice.v).norm(), kClosedFormTol);
    EXPECT_LE((once.w - twice.w).norm(), 1e-9);  // rad/s: spins are ~100 rad/s
  }
}

TEST_F(MotionTest, EnergyNeverRisesAlongATrajectory) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const BallState s = Make(Vec2(0.9, 1.8), Vec3(4 * u(rng), 4 * u(rng), 0),
                             Vec3(200 * u(rng), 200 * u(rng), 60 * u(rng)));
    double previous = KineticEnergy(s, ball_);
    BallState cur = s;
    for (int step = 0; step < 700; ++step) {
      cur = EvolveThrough(cur, 0.1, ball_, cloth_);
      const double e = KineticEnergy(cur, ball_);
      ASSERT_LE(e, previous + kEnergyTol) << "trial " << trial << " step " << step;
      previous = e;
    }
    EXPECT_EQ(cur.s, MotionState::kStationary) << "after 70 s every ball is at rest";
    EXPECT_EQ(KineticEnergy(cur, ball_), 0.0);
  }
}

TEST_F(MotionTest, EvolveThroughEqualsStepwiseTransitions) {
  const BallState s = Make(Vec2(0.5, 0.5), Vec3(1.0, 0.5, 0), Vec3(40, -20, 15));
  ASSERT_EQ(s.s, MotionState::kSliding);
  const double t1 = TransitionTime(s, ball_, cloth_);
  const BallState a = Evolve(s, t1, ball_, cloth_);
  ASSERT_EQ(a.s, MotionState::kRolling);
  const double t2 = TransitionTime(a, ball_, cloth_);
  const BallState b = Evolve(a, t2, ball_, cloth_);
  const BallState c = EvolveThrough(s, t1 + t2, ball_, cloth_);
  EXPECT_EQ(c.s, b.s);
  EXPECT_LE((c.r - b.r).norm(), kClosedFormTol);
  // Past every transition the ball is at rest where the roll ended.
  const BallState end = EvolveThrough(s, 100.0, ball_, cloth_);
  EXPECT_EQ(end.s, MotionState::kStationary);
  EXPECT_LE((end.r - b.r).norm(), kClosedFormTol);
  // Evolve alone never crosses a transition: it is clamped there.
  const BallState clamped = Evolve(s, 100.0, ball_, cloth_);
  EXPECT_EQ(clamped.s, MotionState::kRolling);
  EXPECT_LE((clamped.r - a.r).norm(), kClosedFormTol);
}

// The closed form assumes the slip keeps its direction; integrate the equations of
// motion with the friction direction recomputed from the state at every stage.
TEST_F(MotionTest, SlidingMatchesIntegratedEquationsOfMotion) {
  const BallState s = Make(Vec2(0.2, 0.3), Vec3(1.2, 2.0, 0), Vec3(-30, 70, 10));
  ASSERT_EQ(s.s, MotionState::kSliding);
  const double t_s = TransitionTime(s, ball_, cloth_);
  const double mu_g = cloth_.mu_s * cloth_.g;
  // y = (x, y, vx, vy, wx, wy)
  using State = Eigen::Matrix<double, 6, 1>;
  const auto rhs = [&](const State& y) {
    const Vec2 u(y(2) - R() * y(5), y(3) + R() * y(4));
    const Vec2 uh = u / u.norm();
    State d;
    d << y(2), y(3), -mu_g * uh.x(), -mu_g * uh.y(), -2.5 * mu_g / R() * uh.y(),
        2.5 * mu_g / R() * uh.x();
    return d;
  };
  State y;
  y << s.r.x(), s.r.y(), s.v.x(), s.v.y(), s.w.x(), s.w.y();
  constexpr int kSteps = 20000;
  const double t_end = 0.9 * t_s;  // stay clear of u = 0, where u / |u| is undefined
  const double h = t_end / kSteps;
  for (int i = 0; i < kSteps; ++i) {
    const State k1 = rhs(y), k2 = rhs(y + 0.5 * h * k1), k3 = rhs(y + 0.5 * h * k2),
                k4 = rhs(y + h * k3);
    y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  const BallState e = Evolve(s, t_end, ball_, cloth_);
  EXPECT_NEAR(e.r.x(), y(0), kIntegrationTol);
  EXPECT_NEAR(e.r.y(), y(1), kIntegrationTol);
  EXPECT_NEAR(e.v.x(), y(2), kIntegrationTol);
  EXPECT_NEAR(e.v.y(), y(3), kIntegrationTol);
  EXPECT_NEAR(e.w.x(), y(4), 1e-7);  // rad/s, spins ~70 rad/s
  EXPECT_NEAR(e.w.y(), y(5), 1e-7);
  EXPECT_NEAR(ClothSlip(e, ball_).norm(), 3.5 * mu_g * (t_s - t_end), kClosedFormTol);
}

// Agreement with the other engineer's slip-phase code (physics/motion/slip_phase.h).
TEST_F(MotionTest, SlipEndMatchesSlipPhaseEnd) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const BallState s = Make(Vec2(1, 1), Vec3(3 * u(rng), 3 * u(rng), 0),
                             Vec3(150 * u(rng), 150 * u(rng), 40 * u(rng)));
    ASSERT_EQ(s.s, MotionState::kSliding);
    const SlipEnd ref = SlipPhaseEnd(BallMotion{s.v, s.w}, ball_, cloth_);
    const double t_s = TransitionTime(s, ball_, cloth_);
    const BallState e = Evolve(s, t_s, ball_, cloth_);
    EXPECT_NEAR(t_s, ref.time, kClosedFormTol);
    EXPECT_LE((Vec2(e.v.x(), e.v.y()) - ref.velocity).norm(), kClosedFormTol);
    EXPECT_LE((e.r - s.r - ref.displacement).norm(), kClosedFormTol);
    EXPECT_NEAR(e.w.z(), ref.sidespin, kClosedFormTol);
  }
}

TEST_F(MotionTest, PositionPolynomialTracksEvolve) {
  for (const BallState& s : {Make(Vec2(1, 1), Vec3(1, 2, 0), Vec3(10, -50, 3)),
                             Rolling(Vec2(-0.7, 1.1), -4.0)}) {
    const PositionPoly p = PositionPolynomial(s, ball_, cloth_);
    const double t_end = TransitionTime(s, ball_, cloth_);
    for (double f : {0.0, 0.1, 0.5, 0.99, 1.0}) {
      const BallState e = Evolve(s, f * t_end, ball_, cloth_);
      EXPECT_LE((p.At(f * t_end) - e.r).norm(), kClosedFormTol);
      if (f < 1.0) {
        EXPECT_LE((p.VelocityAt(f * t_end) - Vec2(e.v.x(), e.v.y())).norm(), kClosedFormTol);
      }
    }
  }
  // At rest the polynomial is constant.
  const PositionPoly rest =
      PositionPolynomial(Make(Vec2(1, 2), Vec3::Zero(), Vec3(0, 0, 5)), ball_, cloth_);
  EXPECT_EQ(rest.b, Vec2::Zero());
  EXPECT_EQ(rest.a, Vec2::Zero());
}

TEST_F(MotionTest, ClassificationUsesDocumentedTolerances) {
  BallState s;
  s.v = Vec3(0.5 * kSpeedTolerance, 0, 0);
  s.w = Vec3(0, 0.5 * kSpeedTolerance / R(), 0.5 * kSpinTolerance);
  EXPECT_EQ(ClassifyMotion(s, ball_), MotionState::kStationary);
  s.w.z() = 2 * kSpinTolerance;
  EXPECT_EQ(ClassifyMotion(s, ball_), MotionState::kSpinning);
  s.v = Vec3(1.0, 0, 0);
  s.w = Vec3(0, (1.0 - 0.5 * kSlipTolerance) / R(), 0);
  EXPECT_EQ(ClassifyMotion(s, ball_), MotionState::kRolling);
  s.w = Vec3(0, (1.0 - 2 * kSlipTolerance) / R(), 0);
  EXPECT_EQ(ClassifyMotion(s, ball_), MotionState::kSliding);
  s.s = MotionState::kPocketed;
  EXPECT_EQ(ClassifyMotion(s, ball_), MotionState::kPocketed);
}

TEST_F(MotionTest, SettleRemovesResiduesAndVerticalVelocity) {
  BallState s;
  s.v = Vec3(1.0, 0.0, 0.05);  // a small jump left by an impact
  s.w = Vec3(0, (1.0 - 0.5 * kSlipTolerance) / R(), 3.0);
  const BallState r = Settle(s, ball_);
  EXPECT_EQ(r.s, MotionState::kRolling);
  EXPECT_EQ(r.v.z(), 0.0);
  EXPECT_EQ(r.w.y(), 1.0 / R());
  EXPECT_EQ(r.w.z(), 3.0);
  BallState rest;
  rest.v = Vec3(0.1 * kSpeedTolerance, 0, 0);
  rest.w = Vec3(0, 0, 0.1 * kSpinTolerance);
  const BallState q = Settle(rest, ball_);
  EXPECT_EQ(q.s, MotionState::kStationary);
  EXPECT_EQ(q.v, Vec3::Zero());
  EXPECT_EQ(q.w, Vec3::Zero());
}

TEST_F(MotionTest, ZeroCoefficientsMeanNoTransition) {
  ClothParams frictionless = cloth_;
  frictionless.mu_s = 0;
  frictionless.mu_r = 0;
  frictionless.spin_decel = 0;
  const BallState slide = Make(Vec2(1, 1), Vec3(1, 0, 0), Vec3::Zero());
  EXPECT_EQ(TransitionTime(slide, ball_, frictionless), kInf);
  const BallState e = Evolve(slide, 2.0, ball_, frictionless);
  EXPECT_NEAR(e.r.x(), 3.0, kClosedFormTol);
  EXPECT_EQ(TransitionTime(Rolling(Vec2(1, 0), 0), ball_, frictionless), kInf);
  EXPECT_EQ(TransitionTime(Make(Vec2(1, 1), Vec3::Zero(), Vec3(0, 0, 1)), ball_, frictionless),
            kInf);
  EXPECT_EQ(TransitionTime(BallState{}, ball_, cloth_), kInf);  // stationary
}

TEST_F(MotionTest, BadTimesLeaveTheStateUnchanged) {
  const BallState s = Make(Vec2(1, 1), Vec3(1, 0, 0), Vec3::Zero());
  EXPECT_EQ(Evolve(s, -1.0, ball_, cloth_).r, s.r);
  EXPECT_EQ(Evolve(s, NAN, ball_, cloth_).r, s.r);
  EXPECT_EQ(EvolveThrough(s, NAN, ball_, cloth_).r, s.r);
  EXPECT_EQ(Evolve(s, 0.0, ball_, cloth_).r, s.r);
}

TEST_F(MotionTest, KineticEnergyOfARollingBallIsSevenTenthsMVSquared) {
  const double v = 1.3;
  const BallState s = Rolling(Vec2(v, 0), 0.0);
  EXPECT_NEAR(KineticEnergy(s, ball_), 0.7 * ball_.mass * v * v, kEnergyTol);
}

}  // namespace
}  // namespace snooker::physics
