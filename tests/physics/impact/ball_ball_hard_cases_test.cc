// Hard cases for the ball-ball solver: its numerical stability. Every case goes
// through the same checks: the adaptive integrator terminates within a step cap
// with status ok, every output is finite, kinetic energy does not rise, a 1e-9
// change of any input moves the output by no more than kContinuityBound, and the
// answer agrees with the paper's fixed-step scheme run fine.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "physics/impact/ball_ball.h"
#include "tests/physics/impact/impact_test_support.h"

namespace snooker::physics {
namespace {

constexpr double kR = 0.02625;  // m, the paper's ball radius
// Step cap for the hard cases: a thousand times the typical 5-30 steps.
constexpr int kStepCap = 20000;
// Input perturbation for the continuity check (m/s or rad/s): a rounding-sized nudge.
constexpr double kPerturbation = 1e-9;
// Output change allowed for that perturbation: the map is Lipschitz with constant
// of order 1-13 (measured: output changes 1e-9 to 1.3e-8 over these cases), plus
// the integrator's own noise from a changed step sequence (tolerance 1e-10 times
// the speed scale).
constexpr double kContinuityBound = 5e-8;  // m/s (spins compared as R w)
// The fixed-step scheme's error is first order: measured at most 0.08 V/N over
// these cases, and 1.44 V/N where the slip at A sticks under mu_bb = 0.5 (the
// scheme chatters around the stuck slip); V the speed scale.
constexpr int kFineSteps = 1'000'000;
constexpr double kFixedStepErrorPerStep = 2.0;  // times speed scale / N
// Energy may not rise; the allowance is rounding.
constexpr double kEnergyRoundingRel = 1e-12;

struct HardCase {
  std::string name;
  ImpactState in;
  BallBallParams contact;
  double mu_s = 0.21;
};

double MaxDiff(const ImpactState& a, const ImpactState& b) {
  return test::MaxDifference(a, b, kR);
}

bool AllFinite(const ImpactState& s) {
  return s.c.v.allFinite() && s.c.w.allFinite() && s.o.v.allFinite() && s.o.w.allFinite();
}

ImpulseSolverOptions Capped() {
  ImpulseSolverOptions o;
  o.max_steps = kStepCap;
  return o;
}

// The checks every hard case must pass; returns the result for case-specific checks.
ImpactResult CheckHardCase(const HardCase& hc) {
  SCOPED_TRACE(hc.name);
  const BallParams ball;
  const ImpactResult r = ResolveImpact(hc.in, ball, hc.contact, hc.mu_s, Capped());
  EXPECT_EQ(r.status, ImpactStatus::kOk);
  EXPECT_LT(r.work.steps + r.work.rejected_steps, kStepCap);
  EXPECT_TRUE(AllFinite(r.out));
  EXPECT_LE(KineticEnergy(r.out, ball), KineticEnergy(hc.in, ball) * (1 + kEnergyRoundingRel));

  // Continuity: nudge each of the twelve input components by 1e-9.
  double worst_jump = 0;
  for (int i = 0; i < 12; ++i) {
    ImpactState p = hc.in;
    Vec3& v = i < 3 ? p.c.v : i < 6 ? p.c.w : i < 9 ? p.o.v : p.o.w;
    v[i % 3] += kPerturbation;
    const ImpactResult rp = ResolveImpact(p, ball, hc.contact, hc.mu_s, Capped());
    if (rp.status != ImpactStatus::kOk) continue;  // e.g. nudged out of approach
    worst_jump = std::max(worst_jump, MaxDiff(rp.out, r.out));
  }
  EXPECT_LE(worst_jump, kContinuityBound);

  // Agreement with the paper's scheme run fine.
  ImpulseSolverOptions fine;
  fine.integrator = ImpulseIntegrator::kFixedStep;
  fine.steps = kFineSteps;
  fine.max_steps = 10 * kFineSteps;
  const ImpactResult f = ResolveImpact(hc.in, ball, hc.contact, hc.mu_s, fine);
  EXPECT_EQ(f.status, ImpactStatus::kOk);
  const double bound = kFixedStepErrorPerStep * SpeedScale(hc.in, kR) / kFineSteps;
  EXPECT_LE(MaxDiff(f.out, r.out), bound);
  return r;
}

ImpactState Rolling(double v0, double cut_deg) {
  return PaperIncidentState(v0, v0 / kR, 0.0, DegToRad(cut_deg));
}

TEST(HardCasesTest, CutAnglesFromFullBallToTheThinnestGraze) {
  for (double cut : {0.0, 60.0, 89.0, 89.9, 89.999}) {
    CheckHardCase({"cut " + std::to_string(cut), Rolling(1.5, cut), {}});
  }
}

TEST(HardCasesTest, ExtremeSpeeds) {
  for (double v0 : {1e-6, 20.0}) {
    CheckHardCase({"V0 " + std::to_string(v0), Rolling(v0, 30.0), {}});
  }
}

TEST(HardCasesTest, SpinsUpTo1000RadPerSecond) {
  CheckHardCase({"top 1000, side -1000", PaperIncidentState(2.0, 1000.0, -1000.0, 0.5), {}});
  CheckHardCase({"draw -1000, side 1000", PaperIncidentState(2.0, -1000.0, 1000.0, 0.2), {}});
  CheckHardCase({"side 1000, full ball", PaperIncidentState(0.5, 0.0, 1000.0, 0.0), {}});
}

TEST(HardCasesTest, RestitutionZeroHalfAndOne) {
  for (double e : {0.0, 0.5, 1.0}) {
    CheckHardCase({"e " + std::to_string(e), Rolling(1.539, 33.83), {.mu_bb = 0.05, .e = e}});
  }
}

TEST(HardCasesTest, BallBallFrictionZeroAndHalf) {
  for (double mu : {0.0, 0.5}) {
    CheckHardCase({"mu_bb " + std::to_string(mu), PaperIncidentState(1.5, 30.0, 20.0, 0.4),
                   {.mu_bb = mu, .e = 0.89}});
  }
}

TEST(HardCasesTest, ClothFrictionZeroAndOne) {
  for (double mu_s : {0.0, 1.0}) {
    CheckHardCase({"mu_s " + std::to_string(mu_s), PaperIncidentState(1.5, -30.0, 20.0, 0.4),
                   {}, mu_s});
  }
}

TEST(HardCasesTest, MarlowFriction) {
  CheckHardCase({"Marlow", PaperIncidentState(1.5, 57.0, 10.0, 0.6),
                 {.mu_bb = 0.05, .e = 0.89, .friction_law = BallBallFrictionLaw::kMarlow}});
}

// The object ball arrives with backspin, so its cloth slip points back towards the
// cue ball; the normal impulse drives it forwards through zero, where the cone
// cannot hold it (it needs 2/7 of the normal impulse, the cloth offers 0.21 * 0.05),
// and it slides on the other way.
TEST(HardCasesTest, ASlipThatReverses) {
  ImpactState in = Rolling(1.5, 0.0);
  in.o.v = Vec3(0.0, -0.3, 0.0);
  in.o.w = Vec3(-5.0, 0.0, 0.0);  // slip at B: -0.3 + R (-5) < 0
  const ImpactResult r = CheckHardCase({"reversal at B", in, {}});
  EXPECT_EQ(r.b.reverse, 1);
  EXPECT_EQ(r.b.stick, 0);
  EXPECT_GT(r.out.o.v.y() + kR * r.out.o.w.x(), 0.0);  // the slip now points forwards
}

// The slip at A reaches zero and sticks: a stun shot with a small cut (1-D slip).
TEST(HardCasesTest, TheSlipAtASticks) {
  const ImpactResult r = CheckHardCase({"stun, cut 0.2 rad", PaperIncidentState(1.5, 0, 0, 0.2), {}});
  EXPECT_EQ(r.a.stick, 1);
  EXPECT_NEAR(r.out.c.v.x() - kR * r.out.c.w.z() - r.out.o.v.x() - kR * r.out.o.w.z(), 0.0, 1e-9);
}

// A 2-D approach to a sticking zero at A (the slip turns as it shrinks).
TEST(HardCasesTest, TheSlipAtASticksAfterTurning) {
  const ImpactResult r = CheckHardCase({"draw and side", PaperIncidentState(1.2, -5.0, 20.0, 0.15), {}});
  EXPECT_EQ(r.a.stick, 1);
}

// Heavy topspin: the slip at A points down on the cue ball, friction lifts it and
// presses the object ball onto the cloth.
TEST(HardCasesTest, HeavyTopspinLiftsTheCueBall) {
  const ImpactResult r = CheckHardCase({"topspin 3 V/R", PaperIncidentState(1.0, 3.0 / kR, 0, 0.3), {}});
  EXPECT_EQ(r.c_liftoffs, 1);
  EXPECT_EQ(r.o_liftoffs, 0);
  EXPECT_GT(r.out.c.v.z(), 0.0);
  EXPECT_EQ(r.out.o.v.z(), 0.0);
}

// Heavy draw: the cue ball is pressed onto the cloth and the object ball lifts.
TEST(HardCasesTest, HeavyDrawPressesTheCueBallAndLiftsTheObjectBall) {
  const ImpactResult r = CheckHardCase({"draw -3 V/R", PaperIncidentState(1.0, -3.0 / kR, 0, 0.3), {}});
  EXPECT_EQ(r.o_liftoffs, 1);
  EXPECT_EQ(r.c_liftoffs, 0);
  EXPECT_GT(r.out.o.v.z(), 0.0);
  EXPECT_EQ(r.out.c.v.z(), 0.0);
}

// The most friction the parameters allow (mu_bb = mu_s = 1), many seeded shots:
// the regime where a cloth contact's cone almost holds and the slip direction is
// stiff (the slaved slide). Every shot must finish within the cap.
TEST(HardCasesTest, HighestFrictionFinishesWithinTheCap) {
  const BallParams ball;
  uint64_t state = 1;
  auto uniform = [&state] {  // a fixed LCG: the same shots on every platform
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  for (int i = 0; i < 500; ++i) {
    const double v0 = 0.5 + 3 * uniform();
    const ImpactState in = PaperIncidentState(v0, (2 * uniform() - 1) * 3 * v0 / kR,
                                              (2 * uniform() - 1) * 3 * v0 / kR, 1.55 * uniform());
    const ImpactResult r = ResolveImpact(in, ball, {.mu_bb = 1.0, .e = 0.89}, 1.0, Capped());
    ASSERT_EQ(r.status, ImpactStatus::kOk) << "shot " << i;
    ASSERT_TRUE(AllFinite(r.out));
    ASSERT_LE(KineticEnergy(r.out, ball), KineticEnergy(in, ball) * (1 + kEnergyRoundingRel));
  }
}

// Found by the ball-ball fuzzer: a 20 m/s impact at the friction corner (mu_bb and mu_s
// within 1e-8 of 1) lifts the object ball off the cloth (by 3e-12 m/s), and at the
// search tolerance the cue ball too (by a rounding's 1e-27 m/s: how far depends on the
// compiler's rounding, so it is not asserted); friction at A then draws its vertical
// slip to zero from both sides. The witness for that slip's sign, which decides which
// ball the cloth holds, switched at every step there (100 000 steps to the cap, 89 ms,
// at tolerances 1e-6 to 1e-8); with both balls off the cloth it decides nothing and is
// not watched. The answer agrees with the fine fixed-step scheme.
TEST(HardCasesTest, BothBallsOffTheClothWithTheVerticalSlipAtAHeldAtZero) {
  ImpactState in;
  in.c.v = Vec3(-12.070039923655878, 15.947229735642212, 0);
  in.c.w = Vec3(7.9626526029347558e-10, 6.0267229110532693e-10, -66.678468386623535);
  const BallBallParams contact{.mu_bb = 0.99999999999999756, .e = 0.46515258947995786};
  const ImpactResult r = CheckHardCase({"friction corner, 20 m/s", in, contact, 0.99999998842968596});
  for (double tolerance : {1e-6, 1e-8}) {
    const ImpactResult s =
        ResolveImpact(in, BallParams{}, contact, 0.99999998842968596, test::Adaptive(tolerance));
    EXPECT_EQ(s.status, ImpactStatus::kOk) << tolerance;
    EXPECT_LT(s.work.steps + s.work.rejected_steps, 100) << tolerance;
    EXPECT_LT(MaxDiff(s.out, r.out), 1e-5) << tolerance;
  }
}

// Why no contact sticks, slips and sticks again: at A a stuck slip stays stuck (with
// no friction at A there is no cloth reaction, and the normal impulse passes
// through both centres), and a cloth contact can stick only if the friction that
// holds its slip, (1 + 2.5 |f2|) / 3.5 per unit normal impulse at least, fits in
// its cone mu_s |f2| with |f2| <= mu_bb: mu_bb (3.5 mu_s - 2.5) >= 1, which the
// parameter ranges ([0, 1] each) allow only at their corner. Checked over the
// whole friction-direction circle and parameter grid.
TEST(HardCasesTest, ClothContactsCannotStickForValidFriction) {
  // The bound itself, over the friction-direction circle and the parameter grid.
  for (double mu_bb = 0.05; mu_bb < 1.0; mu_bb += 0.05) {
    for (double mu_s = 0.05; mu_s <= 1.0; mu_s += 0.05) {
      for (int k = 0; k < 360; ++k) {
        const double phi = DegToRad(k);
        const double f1 = -mu_bb * std::cos(phi), f2 = -mu_bb * std::sin(phi);
        const double need = std::hypot(f1, 1 + 2.5 * std::abs(f2)) / 3.5;
        EXPECT_GT(need, mu_s * std::abs(f2)) << mu_bb << " " << mu_s << " " << k;
      }
    }
  }
  // And the solver: over the same grid and shots whose cloth slips start at zero (a
  // rolling cue ball's D) or pass near it (any cut, heavy top, draw and side), it
  // never reports a cloth contact (D or B) stuck.
  int impacts = 0;
  for (double mu_bb = 0.05; mu_bb < 1.0; mu_bb += 0.1) {
    for (double mu_s = 0.05; mu_s <= 1.0; mu_s += 0.1) {
      for (double cut : {0.0, 0.4, 0.8, 1.2, 1.5}) {
        for (double spin : {-3.0, -1.0, 0.0, 1.0, 3.0}) {
          const ImpactState in = PaperIncidentState(2.0, spin * 2.0 / kR, -spin * 2.0 / kR, cut);
          const ImpactResult r = ResolveImpact(in, {}, {.mu_bb = mu_bb, .e = 0.89}, mu_s, Capped());
          ASSERT_EQ(r.status, ImpactStatus::kOk) << mu_bb << " " << mu_s << " " << cut << " " << spin;
          EXPECT_EQ(r.d.stick, 0) << mu_bb << " " << mu_s << " " << cut << " " << spin;
          EXPECT_EQ(r.b.stick, 0) << mu_bb << " " << mu_s << " " << cut << " " << spin;
          ++impacts;
        }
      }
    }
  }
  EXPECT_EQ(impacts, 10 * 10 * 5 * 5);
}

// Regression (found by the fuzzer): with e ~ 0 the end of restitution lies a hair
// after the end of compression; at a loose tolerance both fell in one step, the
// restitution guard started at e^2 W_c ~ 1e-20, rounding made it non-positive, it
// never "crossed", and the impact ran on to the step cap.
TEST(HardCasesTest, NearlyInelasticImpactEndsInTheStepOfItsCompression) {
  ImpactState in;
  in.c.v = Vec3(-19.8223, 2.658, 0);
  in.c.w = Vec3(-42.2159, -314.829, 317.647);
  for (double e : {4.00777e-10, 0.0, 1e-6}) {
    ImpulseSolverOptions o = Capped();
    o.tolerance = 0.1;
    const ImpactResult r = ResolveImpact(in, {}, {.mu_bb = 0.658824, .e = e}, 3.9e-8, o);
    EXPECT_EQ(r.status, ImpactStatus::kOk) << e;
    EXPECT_LT(r.work.steps, 20) << e;
    // Restitution lasts about e P_c in impulse (W falls by e^2 W_c, quadratically).
    EXPECT_NEAR(r.impulse_final, r.impulse_compression, (2 * e + 1e-9) * r.impulse_final) << e;
  }
}

TEST(HardCasesTest, BallsThatDoNotApproach) {
  const BallParams ball;
  std::vector<ImpactState> cases = {Rolling(1.0, 90.0), Rolling(1.0, 135.0), Rolling(1.0, 180.0),
                                    ImpactState{}};
  ImpactState receding;  // O runs away faster than C follows
  receding.c.v = Vec3(0, 1.0, 0);
  receding.o.v = Vec3(0, 1.5, 0);
  cases.push_back(receding);
  for (const ImpactState& in : cases) {
    const ImpactResult r = ResolveImpact(in, ball, {}, 0.21, Capped());
    EXPECT_EQ(r.status, ImpactStatus::kNotApproaching);
    EXPECT_EQ(MaxDiff(r.out, in), 0.0);
    EXPECT_EQ(r.work.rhs_evals, 0);
  }
}

}  // namespace
}  // namespace snooker::physics
