// Tests of physics/impact/ball_ball.h in three layers: the paper's published tables, laws
// that hold whatever the inputs, and the contract shared by both integrators.
#include "physics/impact/ball_ball.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <iomanip>
#include <sstream>
#include <array>
#include <random>
#include <utility>
#include <string>

#include "physics/core/limits.h"
#include "physics/motion/slip_phase.h"
#include "tests/physics/impact/impact_test_support.h"
#include "tests/physics/impact/paper_shots.h"

namespace snooker::physics {
namespace {

using test::Adaptive;
using test::FixedStep;
using test::kRoundingRel;
using test::MaxDifference;

// The paper prints speeds to 3 decimals and angles to 2: the required tolerances,
// 0.005 m/s and 0.05 deg (docs/physics-notes.md section 11), allow for that rounding.
constexpr double kPaperSpeedTol = 0.005;  // m/s
constexpr double kPaperAngleTolDeg = 0.05;
// Fixed-step N for the paper's tables: the scheme's error is about 2e-3 m/s * 1000/N
// (first order, measured), so N = 1e4 is well inside the tolerances.
constexpr int kPaperFixedSteps = 10000;

struct Outcome {
  SlipEnd cue, object;
  double cue_exit_deg, object_exit_deg;
};

Outcome RunShot(const PaperShot& shot, const ImpulseSolverOptions& options) {
  const BallParams ball;
  const BallBallParams contact;
  const ClothParams cloth;
  const double cut = DegToRad(shot.cut_deg);
  const ImpactState in = PaperIncidentState(shot.speed, shot.speed / ball.radius, 0.0, cut);
  const ImpactResult r = ResolveImpact(in, ball, contact, cloth.mu_s, options);
  EXPECT_EQ(r.status, ImpactStatus::kOk);
  const Vec2 incoming(std::sin(cut), std::cos(cut));
  Outcome o;
  o.cue = SlipPhaseEnd(r.out.c, ball, cloth);
  o.object = SlipPhaseEnd(r.out.o, ball, cloth);
  o.cue_exit_deg = RadToDeg(AngleBetween(o.cue.velocity, incoming));
  o.object_exit_deg = RadToDeg(AngleBetween(o.object.velocity, incoming));
  return o;
}

// ---------------------------------------------------------------------------
// Layer 1: the paper's Tables 1 and 2, predicted columns.

class PaperTablesTest : public testing::TestWithParam<int> {};

TEST_P(PaperTablesTest, AdaptiveReproducesPredictedColumns) {
  const PaperShot& s = kPaperShots[GetParam()];
  const Outcome o = RunShot(s, Adaptive());
  EXPECT_NEAR(o.cue.speed, s.predicted_cue_speed, kPaperSpeedTol);
  EXPECT_NEAR(o.object.speed, s.predicted_object_speed, kPaperSpeedTol);
  EXPECT_NEAR(o.cue_exit_deg, s.predicted_cue_exit_deg, kPaperAngleTolDeg);
  EXPECT_NEAR(o.object_exit_deg, s.predicted_object_exit_deg, kPaperAngleTolDeg);
}

TEST_P(PaperTablesTest, FixedStepSchemeReproducesPredictedColumns) {
  const PaperShot& s = kPaperShots[GetParam()];
  const Outcome o = RunShot(s, FixedStep(kPaperFixedSteps));
  EXPECT_NEAR(o.cue.speed, s.predicted_cue_speed, kPaperSpeedTol);
  EXPECT_NEAR(o.object.speed, s.predicted_object_speed, kPaperSpeedTol);
  EXPECT_NEAR(o.cue_exit_deg, s.predicted_cue_exit_deg, kPaperAngleTolDeg);
  EXPECT_NEAR(o.object_exit_deg, s.predicted_object_exit_deg, kPaperAngleTolDeg);
}

// The model errs against the measured columns as the paper says its model does:
// the paper's error columns are (predicted - measured) / predicted for speeds and
// (predicted - measured) / measured for angles, in percent, from unrounded values.
// Our model must land within 1 percentage point of each printed error.
TEST_P(PaperTablesTest, ErrorAgainstMeasurementMatchesThePapersOwn) {
  constexpr double kPercentTol = 1.0;
  const PaperShot& s = kPaperShots[GetParam()];
  const Outcome o = RunShot(s, Adaptive());
  EXPECT_NEAR(100 * (o.cue.speed - s.measured_cue_speed) / o.cue.speed, s.paper_cue_speed_err_pct,
              kPercentTol);
  EXPECT_NEAR(100 * (o.object.speed - s.measured_object_speed) / o.object.speed,
              s.paper_object_speed_err_pct, kPercentTol);
  EXPECT_NEAR(100 * (o.cue_exit_deg - s.measured_cue_exit_deg) / s.measured_cue_exit_deg,
              s.paper_cue_exit_err_pct, kPercentTol);
  EXPECT_NEAR(100 * (o.object_exit_deg - s.measured_object_exit_deg) / s.measured_object_exit_deg,
              s.paper_object_exit_err_pct, kPercentTol);
}

// Named after the row of the paper's tables: Row1 ... Row5.
INSTANTIATE_TEST_SUITE_P(FiveShots, PaperTablesTest, testing::Range(0, 5),
                         [](const testing::TestParamInfo<int>& p) {
                           return "Row" + std::to_string(p.param + 1);
                         });

// ---------------------------------------------------------------------------
// Layer 2: laws, for both integrators.

struct IntegratorCase {
  std::string name;
  ImpulseSolverOptions options;
  double tol;  // accuracy of the integrator at these options, m/s
};

// gtest and ctest show the case by its name.
void PrintTo(const IntegratorCase& c, std::ostream* os) { *os << c.name; }

// A random incident state (the shots of the accuracy tests): V0 in 0.05-8 m/s, cut
// 0-max_cut_deg, top- and sidespin within +-2.5 V0/R; four draws of `rng`, in that
// order.
struct RandomIncident {
  ImpactState in;
  double v0 = 0;  // m/s
};
RandomIncident NextRandomIncident(std::mt19937_64& rng, double max_cut_deg, double radius) {
  std::uniform_real_distribution<double> u(0, 1);
  const double v0 = 0.05 + 7.95 * u(rng);
  const double cut = DegToRad(max_cut_deg * u(rng));
  const double top = (2 * u(rng) - 1) * 2.5 * v0 / radius;
  const double side = (2 * u(rng) - 1) * 2.5 * v0 / radius;
  return {PaperIncidentState(v0, top, side, cut), v0};
}

class LawsTest : public testing::TestWithParam<IntegratorCase> {
 protected:
  // Random incident states: V0 in 0.05-8 m/s, cut 0-89 deg, spins +-2.5 V0/R.
  ImpactState RandomShot(std::mt19937_64& rng) const {
    return NextRandomIncident(rng, 89.0, ball_.radius).in;
  }
  BallParams ball_;
  BallBallParams contact_;
  double mu_s_ = ClothParams{}.mu_s;
};

TEST_P(LawsTest, KineticEnergyNeverRises) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 300; ++i) {
    const ImpactState in = RandomShot(rng);
    const ImpactResult r = ResolveImpact(in, ball_, contact_, mu_s_, GetParam().options);
    ASSERT_EQ(r.status, ImpactStatus::kOk) << "case " << i;
    EXPECT_LE(KineticEnergy(r.out, ball_), KineticEnergy(in, ball_) * (1 + kRoundingRel))
        << "case " << i;
  }
}

TEST_P(LawsTest, FrictionlessElasticHeadOnPassesAllSpeedToObjectBall) {
  const BallBallParams c{.mu_bb = 0, .e = 1};
  const ImpactState in = PaperIncidentState(2.0, 30.0, -12.0, 0.0);
  const ImpactResult r = ResolveImpact(in, ball_, c, mu_s_, GetParam().options);
  ASSERT_EQ(r.status, ImpactStatus::kOk);
  EXPECT_NEAR(r.out.c.v.norm(), 0.0, GetParam().tol);
  EXPECT_NEAR(r.out.o.v.y(), 2.0, GetParam().tol);
  EXPECT_NEAR(r.out.o.v.x(), 0.0, GetParam().tol);
}

TEST_P(LawsTest, FrictionlessElasticCutSendsBallsOffAtRightAngles) {
  const BallBallParams c{.mu_bb = 0, .e = 1};
  for (double cut_deg : {10.0, 33.0, 60.0, 85.0}) {
    const ImpactState in = PaperIncidentState(1.5, 57.0, 20.0, DegToRad(cut_deg));
    const ImpactResult r = ResolveImpact(in, ball_, c, mu_s_, GetParam().options);
    ASSERT_EQ(r.status, ImpactStatus::kOk);
    const Vec2 vc(r.out.c.v.x(), r.out.c.v.y()), vo(r.out.o.v.x(), r.out.o.v.y());
    EXPECT_NEAR(RadToDeg(AngleBetween(vc, vo)), 90.0, 1e-3) << cut_deg;
    EXPECT_NEAR(vc.norm(), 1.5 * std::sin(DegToRad(cut_deg)), GetParam().tol);
  }
}

TEST_P(LawsTest, WithoutBallBallFrictionSpinsAreUntouched) {
  const BallBallParams c{.mu_bb = 0, .e = 0.89};
  std::mt19937_64 rng(11);
  for (int i = 0; i < 50; ++i) {
    const ImpactState in = RandomShot(rng);
    const ImpactResult r = ResolveImpact(in, ball_, c, mu_s_, GetParam().options);
    ASSERT_EQ(r.status, ImpactStatus::kOk);
    EXPECT_EQ(r.out.c.w, in.c.w);
    EXPECT_EQ(r.out.o.w, in.o.w);
  }
}

// Eq. 3f and its twin for O: friction at A turns both balls about Z alike, and
// the cloth exerts no torque about Z.
TEST_P(LawsTest, BothZSpinsChangeByTheSameAmount) {
  std::mt19937_64 rng(13);
  for (int i = 0; i < 200; ++i) {
    const ImpactState in = RandomShot(rng);
    const ImpactResult r = ResolveImpact(in, ball_, contact_, mu_s_, GetParam().options);
    ASSERT_EQ(r.status, ImpactStatus::kOk);
    const double dc = r.out.c.w.z() - in.c.w.z();
    const double d_o = r.out.o.w.z() - in.o.w.z();
    EXPECT_NEAR(dc, d_o, 1e-9 * (1 + std::abs(in.c.w.z()))) << "case " << i;
  }
}

// Without cloth friction only internal forces act horizontally.
TEST_P(LawsTest, WithoutClothFrictionHorizontalMomentumIsConserved) {
  std::mt19937_64 rng(17);
  for (int i = 0; i < 100; ++i) {
    const ImpactState in = RandomShot(rng);
    const ImpactResult r = ResolveImpact(in, ball_, contact_, 0.0, GetParam().options);
    ASSERT_EQ(r.status, ImpactStatus::kOk);
    const Vec3 p0 = in.c.v + in.o.v, p1 = r.out.c.v + r.out.o.v;
    EXPECT_NEAR(p1.x(), p0.x(), 1e-12 * (1 + p0.norm()));
    EXPECT_NEAR(p1.y(), p0.y(), 1e-12 * (1 + p0.norm()));
  }
}

TEST_P(LawsTest, BallsThatDoNotApproachAreANoOp) {
  for (double cut_deg : {90.0, 120.0, 180.0}) {
    const ImpactState in = PaperIncidentState(1.0, 10.0, 5.0, DegToRad(cut_deg));
    const ImpactResult r = ResolveImpact(in, ball_, contact_, mu_s_, GetParam().options);
    EXPECT_EQ(r.status, ImpactStatus::kNotApproaching) << cut_deg;
    EXPECT_EQ(r.out.c.v, in.c.v);
    EXPECT_EQ(r.out.c.w, in.c.w);
  }
}

TEST_P(LawsTest, NonFiniteInputIsRejectedWithItsName) {
  ImpactState in = PaperIncidentState(1.0, 10.0, 5.0, 0.3);
  in.c.w.y() = std::nan("");
  const ImpactResult r = ResolveImpact(in, ball_, contact_, mu_s_, GetParam().options);
  EXPECT_EQ(r.status, ImpactStatus::kInvalidInput);
  EXPECT_NE(ValidateImpact(in, ball_, contact_, mu_s_, GetParam().options).find("C angular velocity"),
            std::string::npos);
  in = PaperIncidentState(1.0, 10.0, 5.0, 0.3);
  in.o.v.x() = INFINITY;
  EXPECT_EQ(ResolveImpact(in, ball_, contact_, mu_s_, GetParam().options).status,
            ImpactStatus::kInvalidInput);
}

// Beyond limits::kMaxImpactSpeedScale the input is rejected, and named, before any
// arithmetic can overflow; at the bound it is solved.
TEST_P(LawsTest, InputFasterThanTheSpeedScaleBoundIsRejectedWithItsName) {
  const double bound = limits::kMaxImpactSpeedScale;
  const ImpactState at = PaperIncidentState(bound, 0.0, 0.0, 0.3);
  EXPECT_EQ(ResolveImpact(at, ball_, contact_, mu_s_, GetParam().options).status, ImpactStatus::kOk);
  EXPECT_EQ(ValidateImpact(at, ball_, contact_, mu_s_, GetParam().options), "");
  ImpactState fast = PaperIncidentState(1.0, 0.0, 0.0, 0.3);
  fast.o.w.z() = 2 * bound / ball_.radius;  // the object ball's spin alone
  ImpactState huge = PaperIncidentState(1.0, 0.0, 0.0, 0.3);
  huge.c.w = Vec3(-1.5e308, 1e308, -1.7e308);  // finite; its squares overflow
  for (const ImpactState& in : {fast, huge}) {
    const ImpactResult r = ResolveImpact(in, ball_, contact_, mu_s_, GetParam().options);
    EXPECT_EQ(r.status, ImpactStatus::kInvalidInput);
    EXPECT_EQ(r.out.c.w, in.c.w);
    EXPECT_NE(ValidateImpact(in, ball_, contact_, mu_s_, GetParam().options).find("speed scale = "),
              std::string::npos);
  }
}

// A ball outside limits::kBallMass and kBallRadius is rejected and named: the solvers
// hold M v and 1/M, which overflow for a mass near the largest double or a tiny one.
TEST(BallParamsTest, MassAndRadiusOutsideTheLibraryRangesAreRejectedWithTheirNames) {
  const ImpactState in = PaperIncidentState(1.0, 10.0, 5.0, 0.3);
  const BallParams ok;
  EXPECT_EQ(ValidateBallParams(ok), "");
  EXPECT_TRUE(BallParamsValid(ok));
  struct Case {
    double mass, radius;
    const char* named;
  };
  for (const Case& c : {Case{1.3e308, 0.02625, "mass = "}, Case{1e-310, 0.02625, "mass = "},
                        Case{11.0, 0.02625, "mass = "}, Case{0.1406, 2.0, "radius = "},
                        Case{0.1406, -0.02625, "radius = "}}) {
    BallParams ball;
    ball.mass = c.mass;
    ball.radius = c.radius;
    EXPECT_FALSE(BallParamsValid(ball)) << c.mass << " " << c.radius;
    EXPECT_NE(ValidateBallParams(ball).find(c.named), std::string::npos) << ValidateBallParams(ball);
    EXPECT_EQ(ResolveImpact(in, ball, {}, 0.2, Adaptive()).status, ImpactStatus::kInvalidInput);
    EXPECT_NE(ValidateImpact(in, ball, {}, 0.2, Adaptive()).find(c.named), std::string::npos);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Integrators, LawsTest,
    testing::Values(IntegratorCase{"FixedStep", FixedStep(20000), 1e-12},
                    IntegratorCase{"Adaptive", Adaptive(), 1e-9}),
    [](const testing::TestParamInfo<IntegratorCase>& p) { return p.param.name; });

// ---------------------------------------------------------------------------
// Layer 3: the numerical schemes.

TEST(FixedStepTest, NonPositiveStepCountIsRejected) {
  const ImpactState in = PaperIncidentState(1.0, 0.0, 0.0, 0.2);
  for (int n : {0, -5}) {
    const ImpulseSolverOptions o = FixedStep(n);
    EXPECT_EQ(ResolveImpact(in, {}, {}, 0.21, o).status, ImpactStatus::kInvalidInput);
    EXPECT_NE(ValidateImpact(in, {}, {}, 0.21, o).find("steps = " + std::to_string(n)),
              std::string::npos);
  }
}

TEST(FixedStepTest, StepCapStopsTheScheme) {
  ImpulseSolverOptions o = FixedStep(1000);
  o.max_steps = 10;  // the impact needs about N/2
  const ImpactResult r = ResolveImpact(PaperIncidentState(1.0, 0.0, 0.0, 0.2), {}, {}, 0.21, o);
  EXPECT_EQ(r.status, ImpactStatus::kStepLimit);
  EXPECT_EQ(r.work.steps, 10);
}

// The paper's scheme holds each step's friction to the step's end, so a step whose
// slip passes zero drives it on the other way, and at coarse steps that overshoot adds
// energy: at most 28 (mu (1 + e))^2 / N^2 of M ydot^2 / 4 per reversal (dp = (1 + e)
// M ydot / N, a friction impulse of mu dp, the slip's inverse mass 7/M). The impact is
// the one the ball-ball fuzzer found (fuzz/ball_ball_fuzz.cc bounds the rise by 10/N
// + 56 (mu (1 + e) / N)^2): 9.9 m/s with 27 rad/s of spin on the line of centres, mu
// near 1 and e = 1. With two steps its energy rises 5.4 times over, more than the
// first-order 10/N allows; from four steps on energy is lost, as the adaptive
// integrator finds, and 10 000 steps agree with it.
TEST(FixedStepTest, CoarseStepsOvershootTheSlipAndAddEnergyWithinTheBound) {
  const BallParams ball;
  ImpactState in;
  in.c.v = Vec3(-0.40656371281401726, 9.8755194680894931, 0);
  in.c.w = Vec3(27.427746949582215, 1.1291686143678643, 27.450980379374187);
  BallBallParams contact;
  contact.mu_bb = 0.99810049019696301;
  contact.e = 1;
  const double mu_s = 0.49218749993724487;
  auto rise = [&](const ImpulseSolverOptions& o) {
    const ImpactResult r = ResolveImpact(in, ball, contact, mu_s, o);
    EXPECT_EQ(r.status, ImpactStatus::kOk);
    return KineticEnergy(r.out, ball) / KineticEnergy(in, ball) - 1;
  };
  const double kick = contact.mu_bb * (1 + contact.e) / 2;  // N = 2
  const double coarse = rise(FixedStep(2));
  EXPECT_GT(coarse, 10.0 / 2);
  EXPECT_LE(coarse, 10.0 / 2 + 56 * kick * kick);
  const double exact = rise(Adaptive());
  EXPECT_LT(exact, 0);
  for (int n : {4, 16, 256}) EXPECT_LT(rise(FixedStep(n)), 0) << "N " << n;
  EXPECT_NEAR(rise(FixedStep(10000)), exact, 1e-4);
}

// First order: where no slip sticks, the change between N and 2N steps halves each
// time N doubles (measured ratio 2.00).
TEST(FixedStepTest, ConvergesAtFirstOrderAsStepsGrow) {
  const BallParams ball;
  for (const PaperShot& s : kPaperShots) {
    const ImpactState in =
        PaperIncidentState(s.speed, s.speed / ball.radius, 0.0, DegToRad(s.cut_deg));
    double previous = INFINITY;
    for (int n = 500; n <= 16000; n *= 2) {
      const ImpactState a = ResolveImpact(in, ball, {}, 0.21, FixedStep(n)).out;
      const ImpactState b = ResolveImpact(in, ball, {}, 0.21, FixedStep(2 * n)).out;
      const double change = MaxDifference(a, b, ball.radius);
      if (n > 500) {
        EXPECT_GT(previous / change, 1.8) << "V0 " << s.speed << " N " << n;
        EXPECT_LT(previous / change, 2.2) << "V0 " << s.speed << " N " << n;
      }
      previous = change;
    }
  }
}

// Where the slip at A sticks, the paper's scheme chatters around zero slip (its
// friction flips every step) and its error falls only in envelope: measured to drop
// 70x to 230x from N = 1.6e4 to 1e6, not monotonically. These shots stick.
TEST(FixedStepTest, ConvergesInEnvelopeWhereTheSlipSticks) {
  const BallParams ball;
  const std::array<ImpactState, 3> shots = {
      PaperIncidentState(1.5, 0.0, 0.0, 0.2),  // stun, small cut
      PaperIncidentState(2.0, 0.0, 30.0, 0.3),  // stun with side
      PaperIncidentState(1.2, -5.0, 20.0, 0.15),
  };
  for (const ImpactState& in : shots) {
    const ImpactResult fine = ResolveImpact(in, ball, {}, 0.21, Adaptive(1e-13));
    ASSERT_EQ(fine.a.stick, 1);
    const ImpulseSolverOptions coarse = FixedStep(16000), dense = FixedStep(1024000);
    const double e_coarse =
        MaxDifference(ResolveImpact(in, ball, {}, 0.21, coarse).out, fine.out, ball.radius);
    const double e_dense =
        MaxDifference(ResolveImpact(in, ball, {}, 0.21, dense).out, fine.out, ball.radius);
    EXPECT_LT(e_dense, e_coarse / 20);
    EXPECT_LT(e_dense, 1e-6);
  }
}

// Both integrators solve the same ODE: the fixed-step result approaches the
// adaptive one like 1/N.
TEST(AdaptiveTest, AgreesWithFixedStepSchemeRunFine) {
  const BallParams ball;
  for (const PaperShot& s : kPaperShots) {
    const ImpactState in =
        PaperIncidentState(s.speed, s.speed / ball.radius, 0.0, DegToRad(s.cut_deg));
    const ImpactState fine = ResolveImpact(in, ball, {}, 0.21, Adaptive(1e-12)).out;
    const double e1 = MaxDifference(ResolveImpact(in, ball, {}, 0.21, FixedStep(4000)).out, fine,
                                   ball.radius);
    const double e2 = MaxDifference(ResolveImpact(in, ball, {}, 0.21, FixedStep(64000)).out, fine,
                                    ball.radius);
    EXPECT_LT(e2, e1 / 10) << "error should drop 16x from N = 4000 to 64000";
    EXPECT_LT(e2, 1e-4);
  }
}

// At default settings, over 1000 seeded random shots (V0 0.05-8 m/s, cut 0-89.9
// deg, top- and sidespin within +-2.5 V0/R): velocities within 1e-5 m/s and spins
// within 1e-3 rad/s of the converged answer. The reference is the integrator at
// tolerance 1e-13; that it is converged is shown on every tenth shot against
// tolerance 1e-14 (agreement within 1e-9 m/s, far below what is asserted).
TEST(AdaptiveTest, DefaultToleranceIsAccurateOnRandomShots) {
  constexpr int kShots = 1000;
  constexpr double kVelocityTol = 1e-5;    // m/s, the required accuracy
  constexpr double kSpinTol = 1e-3;        // rad/s, the required accuracy
  constexpr double kReferenceTol = 1e-13;  // relative local error of the reference
  constexpr double kConvergedTol = 1e-9;   // m/s between the two references
  const BallParams ball;
  std::mt19937_64 rng(2024);
  double worst_v = 0, worst_w = 0, worst_ref = 0;
  for (int i = 0; i < kShots; ++i) {
    const auto [in, v0] = NextRandomIncident(rng, 89.9, ball.radius);
    const ImpactResult r = ResolveImpact(in, ball, {}, 0.21, Adaptive());
    const ImpactResult ref = ResolveImpact(in, ball, {}, 0.21, Adaptive(kReferenceTol));
    ASSERT_EQ(r.status, ImpactStatus::kOk) << i;
    ASSERT_EQ(ref.status, ImpactStatus::kOk) << i;
    for (const auto& [a, b] : {std::pair{r.out.c, ref.out.c}, std::pair{r.out.o, ref.out.o}}) {
      worst_v = std::max(worst_v, (a.v - b.v).cwiseAbs().maxCoeff());
      worst_w = std::max(worst_w, (a.w - b.w).cwiseAbs().maxCoeff());
    }
    if (i % 10 == 0) {
      const ImpactResult ref2 = ResolveImpact(in, ball, {}, 0.21, Adaptive(1e-14));
      worst_ref = std::max(worst_ref, MaxDifference(ref.out, ref2.out, ball.radius));
    }
  }
  EXPECT_LE(worst_ref, kConvergedTol);
  EXPECT_LE(worst_v, kVelocityTol);
  EXPECT_LE(worst_w, kSpinTol);
  auto sci = [](double x) {
    std::ostringstream o;
    o << std::scientific << std::setprecision(2) << x;
    return o.str();
  };
  RecordProperty("worst_velocity_error_mps", sci(worst_v));
  RecordProperty("worst_spin_error_radps", sci(worst_w));
  RecordProperty("reference_spread_mps", sci(worst_ref));
}

// Marlow's slip-dependent friction is evaluated along the impact. A full-ball hit
// with sidespin only keeps the slip at A along X with nothing else acting on it:
// ds/dP_I = -7 mu(s) / M, and with mu = a + b exp(-c s) this integrates to
// G(s0) - G(s_f) = 7 P_f / M, G(s) = (s + ln(a + b exp(-c s)) / c) / a, where the
// normal impulse is P_f = (1 + e) M V0 / 2 (two free balls). The constant law gives
// s0 - s_f = 7 mu P_f / M instead.
TEST(AdaptiveTest, MarlowFrictionFollowsTheSlipSpeedAlongTheImpact) {
  constexpr double a = 9.951e-3, b = 0.108, c = 1.088;  // Marlow (paper 2.4.2)
  const BallParams ball;
  const double v0 = 1.0, side = 60.0;  // slip R * 60 = 1.575 m/s: it never sticks
  const ImpactState in = PaperIncidentState(v0, 0.0, side, 0.0);
  const double p_final = (1 + 0.89) * ball.mass * v0 / 2;
  auto slip = [&](const ImpactState& s) {
    return std::abs(s.c.v.x() - ball.radius * s.c.w.z() - s.o.v.x() - ball.radius * s.o.w.z());
  };
  const BallBallParams marlow{.mu_bb = 0.05, .e = 0.89, .friction_law = BallBallFrictionLaw::kMarlow};
  const ImpactResult r = ResolveImpact(in, ball, marlow, 0.21, Adaptive(1e-12));
  ASSERT_EQ(r.status, ImpactStatus::kOk);
  EXPECT_NEAR(r.impulse_final, p_final, 1e-12);
  auto g = [&](double s) { return (s + std::log(a + b * std::exp(-c * s)) / c) / a; };
  EXPECT_NEAR(g(slip(in)) - g(slip(r.out)), 7 * p_final / ball.mass, 1e-8);
  // And the constant law, for contrast.
  const ImpactResult k = ResolveImpact(in, ball, {}, 0.21, Adaptive(1e-12));
  EXPECT_NEAR(slip(in) - slip(k.out), 7 * 0.05 * p_final / ball.mass, 1e-9);
  EXPECT_GT(std::abs(slip(r.out) - slip(k.out)), 0.01);  // the laws really differ
}

// The exponential family mu = a + b exp(-c s) follows the same closed form for any
// (a, b, c), and its two named members are the constant and Marlow laws exactly.
TEST(AdaptiveTest, ExponentialFrictionLawFollowsItsClosedFormAndHoldsBothNamedLaws) {
  constexpr double a = 0.02, b = 0.09, c = 2.5;
  const BallParams ball;
  const ImpactState in = PaperIncidentState(1.0, 0.0, 60.0, 0.0);
  const double p_final = (1 + 0.89) * ball.mass * 1.0 / 2;
  auto slip = [&](const ImpactState& s) {
    return std::abs(s.c.v.x() - ball.radius * s.c.w.z() - s.o.v.x() - ball.radius * s.o.w.z());
  };
  BallBallParams law{.mu_bb = a, .e = 0.89, .friction_law = BallBallFrictionLaw::kExponential};
  law.slip_gain = b;
  law.slip_decay = c;
  const ImpactResult r = ResolveImpact(in, ball, law, 0.21, Adaptive(1e-12));
  ASSERT_EQ(r.status, ImpactStatus::kOk);
  auto g = [&](double s) { return (s + std::log(a + b * std::exp(-c * s)) / c) / a; };
  EXPECT_NEAR(g(slip(in)) - g(slip(r.out)), 7 * p_final / ball.mass, 1e-8);

  BallBallParams as_marlow = law;
  as_marlow.mu_bb = 9.951e-3, as_marlow.slip_gain = 0.108, as_marlow.slip_decay = 1.088;
  const BallBallParams marlow{.mu_bb = 0.05, .e = 0.89, .friction_law = BallBallFrictionLaw::kMarlow};
  const ImpactState cut = PaperIncidentState(1.3, 20.0, -15.0, 0.5);
  EXPECT_LT(MaxDifference(ResolveImpact(cut, ball, as_marlow, 0.21, Adaptive(1e-12)).out,
                          ResolveImpact(cut, ball, marlow, 0.21, Adaptive(1e-12)).out, ball.radius),
            1e-12);
  BallBallParams as_constant = law;
  as_constant.mu_bb = 0.05, as_constant.slip_gain = 0, as_constant.slip_decay = 3;
  EXPECT_LT(MaxDifference(ResolveImpact(cut, ball, as_constant, 0.21, Adaptive(1e-12)).out,
                          ResolveImpact(cut, ball, {}, 0.21, Adaptive(1e-12)).out, ball.radius),
            1e-12);
}

TEST(AdaptiveTest, ExponentialFrictionLawOutOfRangeIsRejectedByName) {
  const ImpactState in = PaperIncidentState(1.0, 0.0, 0.0, 0.3);
  BallBallParams law{.mu_bb = 0.5, .e = 0.89, .friction_law = BallBallFrictionLaw::kExponential};
  law.slip_gain = 0.6;  // mu(0) = 1.1
  law.slip_decay = 1;
  EXPECT_EQ(ResolveImpact(in, {}, law, 0.21, Adaptive(1e-10)).status, ImpactStatus::kInvalidInput);
  EXPECT_NE(ValidateImpact(in, {}, law, 0.21, Adaptive(1e-10)).find("slip_gain = 0.6"), std::string::npos);
  law.slip_gain = 0.1;
  law.slip_decay = -1;
  EXPECT_NE(ValidateImpact(in, {}, law, 0.21, Adaptive(1e-10)).find("slip_decay = -1"), std::string::npos);
  law.slip_decay = 1;
  EXPECT_EQ(ValidateImpact(in, {}, law, 0.21, Adaptive(1e-10)), "");
}

// The exponential law's ranges live in physics/core/limits.h; the solver's quiet
// check on every call (ExponentialLawInRange) and the validator that names the bad
// value must agree everywhere, at the bounds and just outside them, NaN and
// infinities included.
TEST(AdaptiveTest, ExponentialLawRangeCheckAgreesWithTheValidator) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double hi_gain = limits::kSlipGain.hi, hi_decay = limits::kSlipDecay.hi;
  int valid = 0, invalid = 0;
  for (const double mu_bb : {0.0, 0.05, 0.5, 1.0}) {
    for (const double gain : {-1e-9, 0.0, 0.3, 0.95, 0.950001, hi_gain, hi_gain + 1e-9, nan, inf}) {
      for (const double decay : {-1e-9, 0.0, 3.0, hi_decay, hi_decay * (1 + 1e-12), nan, -inf}) {
        BallBallParams law{.mu_bb = mu_bb, .e = 0.89, .friction_law = BallBallFrictionLaw::kExponential};
        law.slip_gain = gain;
        law.slip_decay = decay;
        const bool in_range = ExponentialLawInRange(mu_bb, gain, decay);
        EXPECT_EQ(in_range, ValidateBallBallParams(law).empty())
            << "mu_bb " << mu_bb << " b " << gain << " c " << decay << ": " << ValidateBallBallParams(law);
        EXPECT_EQ(in_range, ResolveImpact(PaperIncidentState(1.0, 0.0, 0.0, 0.3), {}, law, 0.21, Adaptive(1e-8))
                                    .status != ImpactStatus::kInvalidInput)
            << "mu_bb " << mu_bb << " b " << gain << " c " << decay;
        (in_range ? valid : invalid) += 1;
      }
    }
  }
  // Both answers occur: mu(0) = 1 exactly is in range, 1 + 1e-9 is not.
  EXPECT_TRUE(ExponentialLawInRange(0.05, 0.95, hi_decay));
  EXPECT_FALSE(ExponentialLawInRange(0.05, 0.950001, 0));
  EXPECT_GT(valid, 20);
  EXPECT_GT(invalid, 100);
}

// The impact-speed form is the constant law at mu = a + b exp(-c v_n), v_n the
// normal approach speed (the incident speed times cos(cut) on a ball at rest): the
// same answer to the last bit, a higher coefficient for a gentler impact, and a
// slip-form law with the same numbers gives a different answer.
TEST(AdaptiveTest, ImpactSpeedFrictionLawIsTheConstantLawAtItsImpactSpeed) {
  constexpr double a = 0.01, b = 0.14, c = 0.6;
  const BallParams ball;
  BallBallParams law{.mu_bb = a, .e = 0.89, .friction_law = BallBallFrictionLaw::kExponentialImpactSpeed};
  law.slip_gain = b;
  law.slip_decay = c;
  EXPECT_EQ(ValidateBallBallParams(law), "");
  for (const double speed : {0.3, 1.0, 2.5}) {
    for (const double cut : {0.2, 0.6, 1.1}) {
      const ImpactState in = PaperIncidentState(speed, 0.7 * speed / ball.radius, -10.0, cut);
      const double v_n = speed * std::cos(cut);
      const BallBallParams constant{.mu_bb = a + b * std::exp(-c * v_n), .e = 0.89};
      const ImpactResult r = ResolveImpact(in, ball, law, 0.21, Adaptive(1e-10));
      ASSERT_EQ(r.status, ImpactStatus::kOk) << speed << " " << cut;
      EXPECT_EQ(MaxDifference(r.out, ResolveImpact(in, ball, constant, 0.21, Adaptive(1e-10)).out, ball.radius),
                0.0)
          << speed << " " << cut;
      EXPECT_EQ(AtImpactSpeed(law, v_n).mu_bb, constant.mu_bb);
      EXPECT_EQ(AtImpactSpeed(law, v_n).friction_law, BallBallFrictionLaw::kConstant);
    }
  }
  EXPECT_GT(AtImpactSpeed(law, 0.2).mu_bb, AtImpactSpeed(law, 2.0).mu_bb);
  const BallBallParams slip_form = WithFrictionCurve(law, FrictionCurveOf(law));
  ASSERT_EQ(slip_form.friction_law, BallBallFrictionLaw::kExponential);
  const ImpactState cut = PaperIncidentState(2.0, 0.0, 0.0, 0.5);
  EXPECT_GT(MaxDifference(ResolveImpact(cut, ball, law, 0.21, Adaptive(1e-10)).out,
                          ResolveImpact(cut, ball, slip_form, 0.21, Adaptive(1e-10)).out, ball.radius),
            1e-3);
  // Its range rules are the slip form's.
  law.slip_gain = 0.995;  // mu(0) = 1.005
  EXPECT_EQ(ResolveImpact(cut, ball, law, 0.21, Adaptive(1e-10)).status, ImpactStatus::kInvalidInput);
  EXPECT_NE(ValidateImpact(cut, ball, law, 0.21, Adaptive(1e-10)).find("slip_gain = 0.995"), std::string::npos);
  law.friction_law = static_cast<BallBallFrictionLaw>(5);
  law.slip_gain = b;
  EXPECT_NE(ValidateBallBallParams(law).find("friction_law = 5"), std::string::npos);
  EXPECT_EQ(ResolveImpact(cut, ball, law, 0.21, Adaptive(1e-10)).status, ImpactStatus::kInvalidInput);
}

TEST(AdaptiveTest, ToleranceOutOfRangeIsRejected) {
  const ImpactState in = PaperIncidentState(1.0, 0.0, 0.0, 0.2);
  for (double tol : {0.0, 1e-20, 0.5, std::nan("")}) {
    EXPECT_EQ(ResolveImpact(in, {}, {}, 0.21, Adaptive(tol)).status, ImpactStatus::kInvalidInput)
        << tol;
  }
}

// ---------------------------------------------------------------------------
// The search fidelity tier (ImpulseFidelity::kSearch).

// kSearch is the adaptive integrator at kSearchTolerance, whatever the rest of the
// options say.
TEST(SearchFidelityTest, IsTheAdaptiveIntegratorAtTheSearchTolerance) {
  const ImpactState in = PaperIncidentState(1.3, 20.0, -15.0, 0.4);
  ImpulseSolverOptions search = FixedStep(10);
  search.tolerance = 1e-3;
  search.fidelity = ImpulseFidelity::kSearch;
  const ImpactResult a = ResolveImpact(in, {}, {}, 0.21, search);
  const ImpactResult b = ResolveImpact(in, {}, {}, 0.21, Adaptive(kSearchTolerance));
  ASSERT_EQ(a.status, ImpactStatus::kOk);
  EXPECT_EQ(MaxDifference(a.out, b.out, BallParams{}.radius), 0.0);
  EXPECT_EQ(a.work.rhs_evals, b.work.rhs_evals);
}

// The documented accuracy of the tier, on the shots of
// AdaptiveTest.DefaultToleranceIsAccurateOnRandomShots: within 2e-5 of the incident
// speed of a converged answer (measured: 8.2e-6), for less than half the work of the
// default tolerance (measured: 11 against 37 right-hand sides a collision).
TEST(SearchFidelityTest, MeetsItsDocumentedAccuracyForLessWork) {
  constexpr double kSearchRelTol = 2e-5;  // of V0, velocities and R * spins
  const BallParams ball;
  std::mt19937_64 rng(2024);
  double worst = 0;
  long search_work = 0, default_work = 0;
  for (int i = 0; i < 1000; ++i) {
    const auto [in, v0] = NextRandomIncident(rng, 89.9, ball.radius);
    const ImpactResult s = ResolveImpact(in, ball, {}, 0.21, test::Search());
    const ImpactResult ref = ResolveImpact(in, ball, {}, 0.21, Adaptive(1e-13));
    const ImpactResult d = ResolveImpact(in, ball, {}, 0.21, Adaptive());
    ASSERT_EQ(s.status, ImpactStatus::kOk) << i;
    ASSERT_EQ(ref.status, ImpactStatus::kOk) << i;
    worst = std::max(worst, MaxDifference(s.out, ref.out, ball.radius) / v0);
    search_work += s.work.rhs_evals;
    default_work += d.work.rhs_evals;
  }
  EXPECT_LE(worst, kSearchRelTol);
  EXPECT_LT(2 * search_work, default_work);
}

// The two Runge-Kutta pairs (ImpulseSolverOptions::method) converge to the same
// answer: on random shots, each at tolerance 1e-9 lies within 1e-7 m/s of a reference
// the other computed at 1e-13; at that tolerance DOP853 is the more accurate of the two
// over the set.
TEST(MethodTest, BothPairsConvergeToTheSameAnswer) {
  const BallParams ball;
  std::mt19937_64 rng(2025);
  constexpr ImpulseMethod kDop853 = ImpulseMethod::kDormandPrince853;
  const ImpulseSolverOptions dp54 = Adaptive(1e-9), dop853 = Adaptive(1e-9, kDop853);
  const ImpulseSolverOptions ref54 = Adaptive(1e-13), ref853 = Adaptive(1e-13, kDop853);
  double worst54 = 0, worst853 = 0, refs = 0;
  for (int i = 0; i < 200; ++i) {
    const auto [in, v0] = NextRandomIncident(rng, 89.9, ball.radius);
    const ImpactResult a = ResolveImpact(in, ball, {}, 0.21, dp54);
    const ImpactResult b = ResolveImpact(in, ball, {}, 0.21, dop853);
    const ImpactResult ra = ResolveImpact(in, ball, {}, 0.21, ref54);
    const ImpactResult rb = ResolveImpact(in, ball, {}, 0.21, ref853);
    for (const ImpactResult* r : {&a, &b, &ra, &rb}) ASSERT_EQ(r->status, ImpactStatus::kOk) << i;
    worst54 = std::max(worst54, MaxDifference(a.out, rb.out, ball.radius));
    worst853 = std::max(worst853, MaxDifference(b.out, ra.out, ball.radius));
    refs = std::max(refs, MaxDifference(ra.out, rb.out, ball.radius));
  }
  EXPECT_LT(refs, 1e-9);
  EXPECT_LT(worst54, 1e-7);
  EXPECT_LT(worst853, 1e-7);
  EXPECT_LT(worst853, worst54);
}

TEST(MethodTest, UnknownMethodIsRejectedWithItsName) {
  ImpulseSolverOptions o;
  o.method = static_cast<ImpulseMethod>(5);
  const ImpactState in = PaperIncidentState(1.0, 0.0, 0.0, 0.2);
  EXPECT_EQ(ResolveImpact(in, {}, {}, 0.21, o).status, ImpactStatus::kInvalidInput);
  EXPECT_NE(ValidateImpact(in, {}, {}, 0.21, o).find("method = 5"), std::string::npos);
}

// The search tier runs Dormand-Prince 5(4), the cheaper pair at its tolerance, whatever
// the options ask for.
TEST(SearchFidelityTest, UsesTheCheaperPairWhateverTheOptionsSay) {
  const ImpactState in = PaperIncidentState(1.3, 20.0, -15.0, 0.4);
  ImpulseSolverOptions search;
  search.method = ImpulseMethod::kDormandPrince853;
  search.fidelity = ImpulseFidelity::kSearch;
  const ImpactResult a = ResolveImpact(in, {}, {}, 0.21, search);
  const ImpactResult b = ResolveImpact(in, {}, {}, 0.21, Adaptive(kSearchTolerance));
  ASSERT_EQ(a.status, ImpactStatus::kOk);
  EXPECT_EQ(MaxDifference(a.out, b.out, BallParams{}.radius), 0.0);
  EXPECT_EQ(EffectiveOptions(search).method, ImpulseMethod::kDormandPrince54);
}

TEST(SearchFidelityTest, UnknownFidelityIsRejectedWithItsName) {
  ImpulseSolverOptions o;
  o.fidelity = static_cast<ImpulseFidelity>(7);
  const ImpactState in = PaperIncidentState(1.0, 0.0, 0.0, 0.2);
  EXPECT_EQ(ResolveImpact(in, {}, {}, 0.21, o).status, ImpactStatus::kInvalidInput);
  EXPECT_NE(ValidateImpact(in, {}, {}, 0.21, o).find("fidelity = 7"), std::string::npos);
}

}  // namespace
}  // namespace snooker::physics
