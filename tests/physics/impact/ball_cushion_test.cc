// Tests of physics/impact/ball_cushion.h (Mathavan et al. 2010 cushion model) in the three
// layers of the ball-ball suite: published figures, closed forms and laws that hold
// whatever the inputs, and the contract of both integrators (statuses, hard cases).
#include "physics/impact/ball_cushion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "physics/impact/ball_cushion_impulse.h"
#include "physics/core/limits.h"
#include "physics/motion/slip_phase.h"
#include "tests/physics/impact/impact_test_support.h"

namespace snooker::physics {
namespace {

using test::Adaptive;
using test::FixedStep;
using test::kRoundingRel;

// The rebound of a rolling 1 m/s square-on ball read off the paper's plots is "about
// 0.91 m/s" (docs/physics-notes.md section 8); a plot read to its grid is good to
// about 0.01 m/s.
constexpr double kPlotReadingTol = 0.01;  // m/s
// The required agreement of the default tolerance with a very tight run. m/s (spins
// compared as R w).
constexpr double kDefaultVsTightTol = 1e-6;
// A "very tight" adaptive run: 1e-14 of the speed scale per step.
constexpr double kTightTolerance = 1e-14;
// The acceptance band around the measured fit. m/s.
constexpr double kFitBand = 0.05;
// The deviations from the measured fit reported in docs/cushion-model.md are quoted
// to 3 decimals; this pins them to that. m/s.
constexpr double kReportedFigureTol = 0.002;

const BallParams kBall;

// Kinetic energy of the ball, translational (horizontal: the model has zdot = 0) and
// rotational. J.
double Energy(const BallMotion& m) {
  return 0.5 * kBall.mass * (m.v.x() * m.v.x() + m.v.y() * m.v.y()) +
         0.5 * kBall.Inertia() * m.w.squaredNorm();
}

// Largest difference of two outcomes in velocity units: |dv| and R |dw|. m/s.
double Distance(const BallMotion& a, const BallMotion& b) {
  return test::MaxDifference(a, b, kBall.radius);
}

// A rolling ball square on at `speed` m/s.
BallMotion RollingSquareOn(double speed) {
  return CushionIncidentState(speed, kPi / 2, speed / kBall.radius, 0.0);
}

// The random inputs of the accuracy tests: V 0.05-5 m/s, angle 1-90 deg, topspin
// and sidespin within +-2.5 V/R.
struct RandomShots {
  std::mt19937_64 rng;
  explicit RandomShots(std::uint64_t seed) : rng(seed) {}
  double U(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
  BallMotion Next(double spin_range = 2.5) {
    const double v = U(0.05, 5.0);
    const double a = DegToRad(U(1.0, 90.0));
    return CushionIncidentState(v, a, U(-spin_range, spin_range) * v / kBall.radius,
                                U(-spin_range, spin_range) * v / kBall.radius);
  }
  // Any valid parameters: mu_w up to 0.4, mu_s and e_e in [0, 1], nose 1.05R-1.95R.
  CushionParams NextParams() {
    for (int i = 0; i < 1000; ++i) {
      CushionParams p;
      p.mu_w = U(0.0, 0.4);
      p.mu_s = U(0.0, 1.0);
      p.e_e = U(0.0, 1.0);
      p.contact_height = kBall.radius * U(1.05, 1.95);
      if (ValidateCushionParams(kBall, p).empty()) return p;
    }
    return CushionParams{};
  }
};

// ---------------------------------------------------------------------------
// Layer 1: published figures.

// The check of docs/physics-notes.md section 8. The model gives 0.9107 m/s
// (v = (0, -0.91066) m/s, wx = -8.96 rad/s).
TEST(CushionPaperCheck, RollingBallAtOneMetrePerSecondReboundsAtAbout091) {
  const CushionParams p;
  const CushionImpactResult a = ResolveCushionImpact(RollingSquareOn(1.0), kBall, p, Adaptive());
  ASSERT_EQ(a.status, ImpactStatus::kOk);
  EXPECT_NEAR(a.out.v.norm(), 0.91, kPlotReadingTol);
  EXPECT_LT(a.out.v.y(), 0.0);                      // it comes back
  EXPECT_NEAR(a.out.v.x(), 0.0, 1e-12);             // square on stays square on
  // The paper's own scheme agrees (its error is ~1e-5 m/s at N = 1e5, first order).
  const CushionImpactResult f =
      ResolveCushionImpact(RollingSquareOn(1.0), kBall, p, FixedStep(100000));
  ASSERT_EQ(f.status, ImpactStatus::kOk);
  EXPECT_NEAR(f.out.v.norm(), a.out.v.norm(), 1e-4);
}

// Mathavan et al. (2009), 31 rolling square-on snooker shots:
// v_out = -0.0877 v^2 + 1.131 v - 0.0953 for v in 0.3-3.5 m/s. Is that the speed
// right after the impact or after the ball's slip on the cloth (v - 2u/7)?
double MeasuredFit(double v) { return -0.0877 * v * v + 1.131 * v - 0.0953; }

struct FitDeviation {
  double after_impact = 0;  // max |model - fit|, speed right after the impact. m/s
  double after_slip = 0;    // max |model - fit|, speed at the end of the slip. m/s
  double after_impact_band_top = 0;  // largest v up to which after_impact <= kFitBand
  bool after_impact_closer_everywhere = true;
};

FitDeviation CompareWithMeasuredFit() {
  const CushionParams p;
  const ClothParams cloth;
  FitDeviation d;
  bool in_band = true;
  for (int i = 0; i <= 320; ++i) {  // v = 0.30, 0.31, ..., 3.50 m/s
    const double v = 0.3 + 0.01 * i;
    const CushionImpactResult r = ResolveCushionImpact(RollingSquareOn(v), kBall, p, Adaptive());
    EXPECT_EQ(r.status, ImpactStatus::kOk);
    const double impact = std::abs(r.out.v.norm() - MeasuredFit(v));
    const double slip = std::abs(SlipPhaseEnd(r.out, kBall, cloth).speed - MeasuredFit(v));
    d.after_impact = std::max(d.after_impact, impact);
    d.after_slip = std::max(d.after_slip, slip);
    d.after_impact_closer_everywhere &= impact < slip;
    in_band &= impact <= kFitBand;
    if (in_band) d.after_impact_band_top = v;
  }
  return d;
}

// The speed right after the impact is the one the fit describes (the slip phase
// removes about a third of it: 0.58 m/s at 1 m/s against the fit's 0.95).
TEST(CushionMeasuredFit, SpeedRightAfterImpactIsTheVariantThatMatches) {
  const FitDeviation d = CompareWithMeasuredFit();
  EXPECT_TRUE(d.after_impact_closer_everywhere);
  EXPECT_LT(d.after_impact, d.after_slip);
}

// Neither variant stays within 0.05 m/s over 0.3-3.5 m/s, so no test asserts that:
// the model is homogeneous of degree one in the velocities (v_out = 0.9107 v) while
// the measured ratio falls with speed. This pins the figures reported in
// docs/cushion-model.md: max deviation 0.398 m/s right after the impact (at 3.5
// m/s; within 0.05 m/s up to 2.28 m/s), 0.760 m/s after the slip (at 3.12 m/s).
TEST(CushionMeasuredFit, DeviationsAreTheReportedFigures) {
  const FitDeviation d = CompareWithMeasuredFit();
  EXPECT_NEAR(d.after_impact, 0.398, kReportedFigureTol);
  EXPECT_NEAR(d.after_slip, 0.760, kReportedFigureTol);
  EXPECT_NEAR(d.after_impact_band_top, 2.28, 0.01 + 1e-9);  // to the 0.01 m/s grid
  EXPECT_GT(d.after_impact, kFitBand);
}

// The model is linear in the incident speed (all its equations are homogeneous).
TEST(CushionMeasuredFit, ReboundRatioDoesNotDependOnSpeed) {
  const CushionParams p;
  const double ratio = ResolveCushionImpact(RollingSquareOn(1.0), kBall, p, Adaptive())
                           .out.v.norm();
  for (double v : {0.3, 2.0, 3.5}) {
    const CushionImpactResult r = ResolveCushionImpact(RollingSquareOn(v), kBall, p, Adaptive());
    EXPECT_NEAR(r.out.v.norm() / v, ratio, 1e-8);
  }
}

// ---------------------------------------------------------------------------
// Layer 2: closed forms and invariants.

// Without friction only ydot changes: by Stronge, ydot' = -e ydot; the normal impulse
// is P_c = M ydot / cos th at the end of compression, (1 + e) P_c at the end, and the
// work W_c = M ydot^2 / 2.
TEST(CushionFrictionless, ReboundHasTheClosedForm) {
  RandomShots shots(11);
  for (int i = 0; i < 50; ++i) {
    CushionParams p = shots.NextParams();
    p.mu_w = p.mu_s = 0;
    const BallMotion in = shots.Next();
    const double c = std::sqrt(1 - std::pow(CushionSinTheta(kBall, p), 2));
    for (const ImpulseSolverOptions& o : {Adaptive(), FixedStep(7)}) {
      const CushionImpactResult r = ResolveCushionImpact(in, kBall, p, o);
      ASSERT_EQ(r.status, ImpactStatus::kOk);
      const double scale = in.v.norm() + kBall.radius * in.w.norm();
      EXPECT_NEAR(r.out.v.x(), in.v.x(), kRoundingRel * scale);
      EXPECT_NEAR(r.out.v.y(), -p.e_e * in.v.y(), 1e-9 * scale);
      EXPECT_NEAR((r.out.w - in.w).norm(), 0.0, kRoundingRel * scale / kBall.radius);
      const double pc = kBall.mass * in.v.y() / c;
      EXPECT_NEAR(r.impulse_compression, pc, 1e-9 * pc);
      EXPECT_NEAR(r.impulse_final, (1 + p.e_e) * pc, 1e-9 * pc);
      EXPECT_NEAR(r.work_compression, 0.5 * kBall.mass * in.v.y() * in.v.y(),
                  1e-9 * Energy(in));
    }
  }
}

// e = 1 without friction: no energy is lost.
TEST(CushionFrictionless, ElasticImpactConservesEnergy) {
  RandomShots shots(12);
  CushionParams p;
  p.mu_w = p.mu_s = 0;
  p.e_e = 1;
  for (int i = 0; i < 50; ++i) {
    const BallMotion in = shots.Next();
    for (const ImpulseSolverOptions& o : {Adaptive(), FixedStep(1000)}) {
      const CushionImpactResult r = ResolveCushionImpact(in, kBall, p, o);
      ASSERT_EQ(r.status, ImpactStatus::kOk);
      EXPECT_NEAR(Energy(r.out), Energy(in), 1e-9 * Energy(in));
    }
  }
}

// Friction dissipates, the normal force returns at most what it took (e <= 1) and the
// cloth reaction does no work (zdot = 0): energy never rises. Both integrators, with
// the snooker parameters and with any valid ones.
TEST(CushionEnergy, NeverRisesForRandomInputs) {
  RandomShots shots(13);
  for (int i = 0; i < 400; ++i) {
    const CushionParams p = i % 2 == 0 ? CushionParams{} : shots.NextParams();
    const BallMotion in = shots.Next(i % 4 < 2 ? 2.5 : 10.0);
    for (const ImpulseSolverOptions& o : {Adaptive(), FixedStep(200)}) {
      const CushionImpactResult r = ResolveCushionImpact(in, kBall, p, o);
      ASSERT_EQ(r.status, ImpactStatus::kOk) << "shot " << i;
      EXPECT_LE(Energy(r.out), Energy(in) * (1 + kRoundingRel)) << "shot " << i;
    }
  }
}

// The paper's fixed-step scheme holds each step's friction to the step's end, so at a
// handful of steps a slip driven past zero does positive work: energy rises. The
// fuzzer (fuzz/ball_cushion_fuzz.cc) allows 10/N of it. Over these random impacts at
// 1-5 steps, any valid parameters and spins to 10 V/R, the largest rise is 1.2/N in the
// GCC build and 0.96/N in clang's (the overshoot at coarse steps is chaotic, and the
// compilers round differently): real, and within the allowance.
TEST(CushionEnergy, CoarseFixedStepsGainEnergyWithinTenOverN) {
  RandomShots shots(29);
  double worst = 0;  // largest (E_out / E_in - 1) N
  for (int i = 0; i < 50'000; ++i) {
    CushionParams p = shots.NextParams();
    if (i % 2 == 0) p.e_e = 1.0;
    const BallMotion in = shots.Next(10.0);
    const int n = 1 + i % 5;
    const CushionImpactResult r = ResolveCushionImpact(in, kBall, p, FixedStep(n));
    ASSERT_EQ(r.status, ImpactStatus::kOk) << "shot " << i;
    worst = std::max(worst, (Energy(r.out) / Energy(in) - 1) * n);
  }
  EXPECT_GT(worst, 0.5);   // the overshoot exists at coarse steps ...
  EXPECT_LT(worst, 10.0);  // ... and stays within the fuzzer's allowance
}

// At a loose tolerance one adaptive step can cover the whole impact with an error far
// beyond its estimate: this impact (found by the fuzzer) gained 59 % of its kinetic
// energy in one step at tolerance 0.0262. Tolerances looser than
// kLoosestCushionTolerance are solved at it, where energy holds to a few tolerances.
TEST(CushionEnergy, LooseTolerancesAreSolvedAtTheLoosestThatHolds) {
  BallMotion in;
  in.v = Vec3(2.4075469514934844, 0.67329418584315515, 0);
  in.w = Vec3(-13.39336548485327, 47.891630317461399, 50.980392175052657);
  const CushionParams p = MathavanCushionParams(kBall);
  const CushionImpactResult loosest = ResolveCushionImpact(in, kBall, p, Adaptive(kLoosestCushionTolerance));
  ASSERT_EQ(loosest.status, ImpactStatus::kOk);
  for (double tolerance : {0.0262, 0.1}) {
    const CushionImpactResult r = ResolveCushionImpact(in, kBall, p, Adaptive(tolerance));
    ASSERT_EQ(r.status, ImpactStatus::kOk) << tolerance;
    EXPECT_LE(Energy(r.out), Energy(in)) << tolerance;
    EXPECT_EQ(r.out.v, loosest.out.v) << tolerance;
    EXPECT_EQ(r.out.w, loosest.out.w) << tolerance;
  }
  // On random impacts: ZeroingASlipAtTheLoosestToleranceAddsNoEnergy.
}

// A slip within a few tens of tolerances of zero counts as zero and is zeroed by a
// change of spin; at the loosest tolerance that threshold is capped at 3.2e-3 of the
// speed, or zeroing would rewrite the spins: this impact gained 0.8 % of its kinetic
// energy at tolerance 1e-3 with the threshold uncapped (32 tolerances). Over random
// impacts at 1e-3 the energy rises by less than a tenth of the tolerance (measured:
// by less than 5e-6 of itself over 10^5) and the outgoing state stays within ten
// tolerances of a converged one at the 99th percentile (16.7 here uncapped), and
// within a hundred for every impact. A looser request (0.05) gives the same answer.
TEST(CushionEnergy, ZeroingASlipAtTheLoosestToleranceAddsNoEnergy) {
  const CushionParams p = MathavanCushionParams(kBall);
  const ImpulseSolverOptions loosest = Adaptive(kLoosestCushionTolerance);
  BallMotion in;
  in.v = Vec3(-1.2529202326479263, 0.19439601870363851, 0);
  in.w = Vec3(-5.6402233926692249, -57.35693870053683, -70.551614609606219);
  const CushionImpactResult found = ResolveCushionImpact(in, kBall, p, loosest);
  ASSERT_EQ(found.status, ImpactStatus::kOk);
  EXPECT_LE(Energy(found.out), Energy(in) * (1 + 0.1 * kLoosestCushionTolerance));

  RandomShots shots(37);
  std::vector<double> errors;  // in tolerances of the speed scale
  for (int i = 0; i < 4000; ++i) {
    const BallMotion shot = shots.Next(i % 2 == 0 ? 2.5 : 10.0);
    const CushionImpactResult r = ResolveCushionImpact(shot, kBall, p, loosest);
    const CushionImpactResult looser = ResolveCushionImpact(shot, kBall, p, Adaptive(0.05));
    const CushionImpactResult exact = ResolveCushionImpact(shot, kBall, p, Adaptive());
    ASSERT_EQ(r.status, ImpactStatus::kOk) << "shot " << i;
    ASSERT_EQ(looser.status, ImpactStatus::kOk) << "shot " << i;
    ASSERT_EQ(exact.status, ImpactStatus::kOk) << "shot " << i;
    EXPECT_EQ(looser.out.v, r.out.v) << "shot " << i;
    EXPECT_EQ(looser.out.w, r.out.w) << "shot " << i;
    // Within a tenth of a tolerance (uncapped: up to eight tolerances).
    EXPECT_LE(Energy(r.out), Energy(shot) * (1 + 0.1 * kLoosestCushionTolerance)) << "shot " << i;
    const double scale = CushionSpeedScale(shot, kBall.radius);
    EXPECT_LT((r.out.v - exact.out.v).norm(), 100 * kLoosestCushionTolerance * scale) << "shot " << i;
    errors.push_back(Distance(r.out, exact.out) / (kLoosestCushionTolerance * scale));
  }
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() * 99 / 100], 10.0);
}

// The stick friction derived in ball_cushion_impulse.h keeps the stuck contact's slip
// constant, whatever the state and the other contact's direction.
TEST(CushionStickFriction, HoldsTheStuckSlipConstant) {
  RandomShots shots(14);
  for (int i = 0; i < 200; ++i) {
    const CushionParams p = i % 2 == 0 ? CushionParams{} : shots.NextParams();
    const cushion::Model model(kBall, p);
    const cushion::State x = cushion::Pack(shots.Next());
    for (int stuck : {cushion::kI, cushion::kC}) {
      cushion::Mode m;
      m.law[stuck] = cushion::Law::kStick;
      cushion::State dx;
      cushion::Derivative(x, m, model, &dx);
      const Vec2 rate = cushion::Slip(stuck, dx, model);
      EXPECT_NEAR(rate.norm(), 0.0, 1e-12 * model.inv_mass) << "stuck " << stuck;
    }
  }
}

// ---------------------------------------------------------------------------
// Layer 3: the integrators.

// The paper's first-order scheme converges to the adaptive solution. Where no slip
// reaches zero the error is smooth in the step: each doubling of N halves it and the
// N -> 2N change shrinks.
TEST(CushionConvergence, FixedStepApproachesAdaptiveAtFirstOrder) {
  for (const BallMotion& in : {
           CushionIncidentState(1.0, DegToRad(45), 1.0 / kBall.radius, 0.0),  // rolling
           CushionIncidentState(2.0, DegToRad(30), 5.0 / kBall.radius, -5.0 / kBall.radius),
       }) {
    const CushionParams p;
    const CushionImpactResult ref = ResolveCushionImpact(in, kBall, p, Adaptive(kTightTolerance));
    ASSERT_EQ(ref.status, ImpactStatus::kOk);
    double prev_error = 0, prev_change = 0;
    BallMotion prev;
    for (int n = 1000; n <= 32000; n *= 2) {
      const CushionImpactResult f = ResolveCushionImpact(in, kBall, p, FixedStep(n));
      ASSERT_EQ(f.status, ImpactStatus::kOk);
      const double error = Distance(f.out, ref.out);
      if (n > 1000) {
        const double change = Distance(f.out, prev);
        if (n > 2000) {
          EXPECT_LT(change, prev_change) << "N = " << n;
        }
        EXPECT_NEAR(prev_error / error, 2.0, 0.1) << "N = " << n;  // measured 2.00
        prev_change = change;
      }
      prev_error = error;
      prev = f.out;
    }
  }
}

// Where a slip reaches zero (sticks, or reverses) Euler chatters around it and its
// error depends on where the zero falls in a step: it is still O(1/N) - measured
// error * N / V between 0.06 and 0.8 m/s for N = 1e3 - 2.56e5 - but the N -> 2N
// change does not shrink at every doubling. So the bound is tested, not monotony.
TEST(CushionConvergence, FixedStepErrorIsFirstOrderThroughStickAndReversal) {
  // Error * N / V allowed (dimensionless), above the measured 0.8.
  constexpr double kFirstOrderConstant = 1.0;
  CushionParams sticky;  // the cloth can hold the ball at C with mu_s = 0.8
  sticky.mu_s = 0.8;
  struct Shot {
    BallMotion in;
    CushionParams p;
  };
  for (const Shot& s : {
           Shot{CushionIncidentState(1.0, kPi / 2, 0.0, 0.0), {}},  // stun: I sticks
           Shot{RollingSquareOn(1.0), {}},                           // I reverses
           Shot{CushionIncidentState(1.0, DegToRad(15), 0.75 / kBall.radius, 0.0), sticky},
       }) {
    const CushionImpactResult ref = ResolveCushionImpact(s.in, kBall, s.p, Adaptive(kTightTolerance));
    ASSERT_EQ(ref.status, ImpactStatus::kOk);
    const double v = s.in.v.norm();
    for (int n = 1000; n <= 256000; n *= 2) {
      const CushionImpactResult f = ResolveCushionImpact(s.in, kBall, s.p, FixedStep(n));
      ASSERT_EQ(f.status, ImpactStatus::kOk);
      EXPECT_LT(Distance(f.out, ref.out) * n / v, kFirstOrderConstant) << "N = " << n;
    }
  }
}

// The default tolerance against a very tight run, for the random inputs.
TEST(CushionAdaptive, DefaultToleranceIsWithinOneMicrometrePerSecondOfTightRun) {
  RandomShots shots(15);
  double worst = 0;
  for (int i = 0; i < 300; ++i) {
    const BallMotion in = shots.Next();
    const CushionParams p;
    const CushionImpactResult d = ResolveCushionImpact(in, kBall, p, Adaptive());
    const CushionImpactResult t = ResolveCushionImpact(in, kBall, p, Adaptive(kTightTolerance));
    ASSERT_EQ(d.status, ImpactStatus::kOk) << "shot " << i;
    ASSERT_EQ(t.status, ImpactStatus::kOk) << "shot " << i;
    worst = std::max(worst, Distance(d.out, t.out));
  }
  EXPECT_LT(worst, kDefaultVsTightTol);
}

// Same, for any valid parameters (both contacts stick, unstick and leave zero in new
// directions here, often together).
TEST(CushionAdaptive, DefaultToleranceMatchesTightRunForAnyValidParameters) {
  RandomShots shots(16);
  for (int i = 0; i < 200; ++i) {
    const CushionParams p = shots.NextParams();
    const BallMotion in = shots.Next(3.0);
    const CushionImpactResult d = ResolveCushionImpact(in, kBall, p, Adaptive());
    const CushionImpactResult t = ResolveCushionImpact(in, kBall, p, Adaptive(kTightTolerance));
    ASSERT_EQ(d.status, ImpactStatus::kOk) << "shot " << i;
    ASSERT_EQ(t.status, ImpactStatus::kOk) << "shot " << i;
    EXPECT_LT(Distance(d.out, t.out), kDefaultVsTightTol) << "shot " << i;
  }
}

// Hard cases: each against the tight run and the paper's scheme at large N. Returns
// the default run; its status is checked here and again by callers that use it.
CushionImpactResult SolveAndCompare(const BallMotion& in, const CushionParams& p) {
  const CushionImpactResult d = ResolveCushionImpact(in, kBall, p, Adaptive());
  const CushionImpactResult t = ResolveCushionImpact(in, kBall, p, Adaptive(kTightTolerance));
  const CushionImpactResult f = ResolveCushionImpact(in, kBall, p, FixedStep(100000));
  EXPECT_EQ(d.status, ImpactStatus::kOk);
  EXPECT_EQ(t.status, ImpactStatus::kOk);
  EXPECT_EQ(f.status, ImpactStatus::kOk);
  EXPECT_LT(Distance(d.out, t.out), kDefaultVsTightTol);
  // Euler at N = 1e5: first-order error, a few 1e-5 of the speed scale (measured).
  const double scale = in.v.norm() + kBall.radius * in.w.norm();
  EXPECT_LT(Distance(f.out, t.out), 2e-4 * scale);
  EXPECT_LE(Energy(d.out), Energy(in) * (1 + kRoundingRel));
  return d;
}

TEST(CushionHardCases, GlancingIncidence) {
  for (double alpha_deg : {0.01, 0.1, 1.0}) {
    for (double topspin : {-1.0, 0.0, 1.0}) {
      const double v = 2.0;
      const BallMotion in =
          CushionIncidentState(v, DegToRad(alpha_deg), topspin * v / kBall.radius, 0.0);
      const CushionImpactResult r = SolveAndCompare(in, CushionParams{});
      ASSERT_EQ(r.status, ImpactStatus::kOk);
      // Friction acts almost along the cushion: the normal speed rebounds nearly as
      // without friction, -e ydot (measured within 0.2%).
      EXPECT_NEAR(r.out.v.y(), -0.98 * in.v.y(), 0.02 * in.v.y()) << alpha_deg << " deg";
    }
  }
}

TEST(CushionHardCases, HeavySpins) {
  for (double topspin : {-10.0, 10.0}) {
    for (double sidespin : {-10.0, 10.0}) {
      const double v = 1.5;
      const BallMotion in = CushionIncidentState(v, DegToRad(40), topspin * v / kBall.radius,
                                                 sidespin * v / kBall.radius);
      SolveAndCompare(in, CushionParams{});
    }
  }
}

// A stun shot square on: the slip at I reaches zero and sticks, then leaves its cone.
TEST(CushionHardCases, CushionContactSticksThenSlips) {
  const CushionImpactResult r =
      SolveAndCompare(CushionIncidentState(1.0, kPi / 2, 0.0, 0.0), CushionParams{});
  ASSERT_EQ(r.status, ImpactStatus::kOk);
  EXPECT_EQ(r.cushion.stick, 1);
  EXPECT_EQ(r.cushion.unstick, 1);
}

// With mu_s = 0.8 the cloth can hold the ball at C (with 0.212 it never can: the
// stick friction needed there exceeds mu_s n_c for every friction at I).
TEST(CushionHardCases, ClothContactSticks) {
  CushionParams p;
  p.mu_s = 0.8;
  const CushionImpactResult r =
      SolveAndCompare(CushionIncidentState(1.0, DegToRad(15), 0.75 / kBall.radius, 0.0), p);
  ASSERT_EQ(r.status, ImpactStatus::kOk);
  EXPECT_EQ(r.cloth.stick, 1);
}

// Regressions from random sweeps: both slips at zero together at the end of
// compression (each needs the other's friction to leave zero), a cone exit of C
// while I is followed to zero, and a cloth slip reaching zero under the tau clock.
// Both slips shrinking near zero, where each may be followed in tau = -ln|u|: when the
// cushion's tau clock failed the integrator tried the cloth's, when that failed the
// cushion's again, and so on without a step, to the cap (100 000 discarded steps at
// tolerances 1e-4 and 1e-6, the planner's search tier, returning the state it started
// from). A failed clock now waits for a step in P_I. Found by a seeded search of
// random impacts and parameters.
TEST(CushionHardCases, TwoSlipsDoNotHandTheTauClockBackAndForth) {
  BallMotion in;
  in.v = Vec3(-7.8232697783312108, 2.2524932063381295, 0);
  in.w = Vec3(-12.057300554554873, 62.696805915775336, -1.2280690136674877);
  CushionParams p;
  p.e_e = 0.64372083746427566;
  p.mu_w = 0.15291336583898074;
  p.mu_s = 0.23778644334101889;
  p.contact_height = kBall.radius * 1.7689631289458938;
  const CushionImpactResult tight = ResolveCushionImpact(in, kBall, p, Adaptive(1e-12));
  ASSERT_EQ(tight.status, ImpactStatus::kOk);
  const CushionImpactResult fine = ResolveCushionImpact(in, kBall, p, FixedStep(1'000'000));
  EXPECT_LT(Distance(fine.out, tight.out), 1e-5);
  for (double tolerance : {1e-4, 1e-6}) {
    const CushionImpactResult r = ResolveCushionImpact(in, kBall, p, Adaptive(tolerance));
    EXPECT_EQ(r.status, ImpactStatus::kOk) << tolerance;
    EXPECT_LT(r.work.steps + r.work.rejected_steps, 50) << tolerance;
    EXPECT_LT(Distance(r.out, tight.out), 1e-3) << tolerance;
  }
}

TEST(CushionHardCases, SlipsLeavingZeroTogetherAndStiffStretches) {
  struct Case {
    double v, alpha_deg, topspin, sidespin, mu_w, mu_s, e, h_over_r;
  };
  for (const Case& c : {
           Case{4.12980979, 75.9706756, 0.382866929, 0.49342274, 0.308097178, 0.389332231,
                0.886871595, 1.6404341},
           Case{4.30538928, 78.64324, -1.26517304, -0.260170178, 0.174032029, 0.901846855,
                0.742150217, 1.55965936},
           Case{4.20075312, 55.3788506, 0.802030084, 1.95149392, 0.384963261, 0.205868509,
                0.151706371, 1.82949115},
           Case{1.1219734, 37.5255465, -0.421683479, 0.640590341, 0.14, 0.212, 0.98, 1.4},
       }) {
    CushionParams p;
    p.mu_w = c.mu_w;
    p.mu_s = c.mu_s;
    p.e_e = c.e;
    p.contact_height = c.h_over_r * kBall.radius;
    ASSERT_EQ(ValidateCushionParams(kBall, p), "");
    const BallMotion in = CushionIncidentState(c.v, DegToRad(c.alpha_deg),
                                               c.topspin * c.v / kBall.radius,
                                               c.sidespin * c.v / kBall.radius);
    SolveAndCompare(in, p);
  }
}

// Square on, every slip keeps its direction: the slip at I lands on its zero in one
// step (held direction, located event) instead of creeping up to it, and reverses.
TEST(CushionAdaptive, SquareOnImpactLandsOnTheSlipZeroInOneStep) {
  const CushionImpactResult r =
      ResolveCushionImpact(RollingSquareOn(1.0), kBall, CushionParams{}, Adaptive());
  ASSERT_EQ(r.status, ImpactStatus::kOk);
  EXPECT_EQ(r.work.events, 3);  // end of compression, slip zero at I, end of impact
  EXPECT_EQ(r.cushion.reverse, 1);
  EXPECT_LE(r.work.steps, 8);  // measured 5
}

// e = 0: the impact ends where compression ends.
TEST(CushionAdaptive, PlasticImpactEndsAtCompression) {
  CushionParams p;
  p.e_e = 0;
  for (const ImpulseSolverOptions& o : {Adaptive(), FixedStep(1000)}) {
    const CushionImpactResult r = ResolveCushionImpact(RollingSquareOn(1.0), kBall, p, o);
    ASSERT_EQ(r.status, ImpactStatus::kOk);
    EXPECT_NEAR(r.impulse_final, r.impulse_compression, kRoundingRel * r.impulse_compression);
    EXPECT_NEAR(r.out.v.y(), 0.0, 1e-9);
  }
}

// ---------------------------------------------------------------------------
// Contract: inputs, statuses, messages.

TEST(CushionIncident, HelperBuildsTheNotesState) {
  const BallMotion m = CushionIncidentState(2.0, DegToRad(30), 50.0, -7.0);
  EXPECT_NEAR(m.v.x(), 2.0 * std::cos(DegToRad(30)), 1e-15);
  EXPECT_NEAR(m.v.y(), 2.0 * std::sin(DegToRad(30)), 1e-15);
  EXPECT_EQ(m.v.z(), 0.0);
  EXPECT_NEAR(m.w.x(), -50.0 * std::sin(DegToRad(30)), 1e-13);
  EXPECT_NEAR(m.w.y(), 50.0 * std::cos(DegToRad(30)), 1e-13);
  EXPECT_EQ(m.w.z(), -7.0);
  // Rolling: no slip on the cloth.
  const BallMotion r = CushionIncidentState(2.0, DegToRad(30), 2.0 / kBall.radius, 0.0);
  EXPECT_NEAR(ClothSlip(r, kBall.radius).norm(), 0.0, 1e-14);
  EXPECT_NEAR(CushionSinTheta(kBall, CushionParams{}), 0.4, 1e-12);
}

TEST(CushionStatus, NotApproachingLeavesTheBallAlone) {
  for (double vy : {0.0, -0.5}) {
    BallMotion in;
    in.v = Vec3(1.0, vy, 0.0);
    in.w = Vec3(3.0, -2.0, 1.0);
    for (const ImpulseSolverOptions& o : {Adaptive(), FixedStep(100)}) {
      const CushionImpactResult r = ResolveCushionImpact(in, kBall, CushionParams{}, o);
      EXPECT_EQ(r.status, ImpactStatus::kNotApproaching);
      EXPECT_EQ(r.out.v, in.v);
      EXPECT_EQ(r.out.w, in.w);
      EXPECT_EQ(r.work.rhs_evals, 0);
    }
  }
}

TEST(CushionStatus, NonFiniteInputIsInvalidAndNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  BallMotion bad_v = RollingSquareOn(1.0);
  bad_v.v.x() = nan;
  BallMotion bad_w = RollingSquareOn(1.0);
  bad_w.w.z() = inf;
  for (const ImpulseSolverOptions& o : {Adaptive(), FixedStep(100)}) {
    EXPECT_EQ(ResolveCushionImpact(bad_v, kBall, CushionParams{}, o).status,
              ImpactStatus::kInvalidInput);
    EXPECT_EQ(ResolveCushionImpact(bad_w, kBall, CushionParams{}, o).status,
              ImpactStatus::kInvalidInput);
  }
  EXPECT_NE(ValidateCushionImpact(bad_v, kBall, CushionParams{}, Adaptive()).find("velocity"),
            std::string::npos);
  EXPECT_NE(ValidateCushionImpact(bad_w, kBall, CushionParams{}, Adaptive())
                .find("angular velocity"),
            std::string::npos);
  EXPECT_EQ(ValidateCushionImpact(RollingSquareOn(1.0), kBall, CushionParams{}, Adaptive()), "");
}

// Spins whose squares overflow (an input the fuzzer found: accepted, it came back NaN)
// and anything beyond limits::kMaxImpactSpeedScale are rejected and named; the bound
// itself is solved.
TEST(CushionStatus, InputFasterThanTheSpeedScaleBoundIsInvalidAndNamed) {
  const double bound = limits::kMaxImpactSpeedScale;
  BallMotion huge = CushionIncidentState(2.5, 0.94, 0.0, 0.0);
  huge.w = Vec3(-1.4529211184382219e308, 1.058641030154852e308, -1.7976931348623093e308);
  BallMotion fast = RollingSquareOn(1.0);
  fast.w.z() = 1.01 * bound / kBall.radius;
  BallMotion fast_v = RollingSquareOn(1.0);
  fast_v.v.x() = 2 * bound;
  for (const ImpulseSolverOptions& o : {Adaptive(), FixedStep(100)}) {
    for (const BallMotion& in : {huge, fast, fast_v}) {
      const CushionImpactResult r = ResolveCushionImpact(in, kBall, CushionParams{}, o);
      EXPECT_EQ(r.status, ImpactStatus::kInvalidInput);
      EXPECT_EQ(r.out.w, in.w);
      EXPECT_NE(ValidateCushionImpact(in, kBall, CushionParams{}, o).find("speed scale = "),
                std::string::npos);
    }
    const BallMotion at = CushionIncidentState(0.999 * bound, kPi / 3, 0.0, 0.0);  // cos, sin round
    const CushionImpactResult r = ResolveCushionImpact(at, kBall, CushionParams{}, o);
    EXPECT_EQ(r.status, ImpactStatus::kOk);
    EXPECT_TRUE(r.out.v.allFinite() && r.out.w.allFinite());
    EXPECT_LE(Energy(r.out), Energy(at) * (1 + kRoundingRel));
    EXPECT_EQ(ValidateCushionImpact(at, kBall, CushionParams{}, o), "");
  }
  // A vertical velocity is not part of the model, and not of its speed scale.
  BallMotion up = RollingSquareOn(1.0);
  up.v.z() = 10 * bound;
  EXPECT_EQ(ResolveCushionImpact(up, kBall, CushionParams{}, Adaptive()).status, ImpactStatus::kOk);
}

TEST(CushionStatus, BadParametersAndOptionsAreInvalidAndNamed) {
  const BallMotion in = RollingSquareOn(1.0);
  struct Case {
    CushionParams p;
    ImpulseSolverOptions o;
    const char* named;
  };
  std::vector<Case> cases;
  auto add = [&](auto edit, const char* named, ImpulseSolverOptions o = Adaptive()) {
    CushionParams p;
    edit(p);
    cases.push_back({p, o, named});
  };
  add([](CushionParams& p) { p.e_e = 1.5; }, "e_e = 1.5");
  add([](CushionParams& p) { p.mu_w = -0.1; }, "mu_w = -0.1");
  add([](CushionParams& p) { p.mu_s = std::numeric_limits<double>::quiet_NaN(); }, "mu_s");
  add([](CushionParams& p) { p.contact_height = 0.02; }, "contact_height = 0.02");
  add([](CushionParams& p) { p.contact_height = 0.06; }, "contact_height = 0.06");
  add([](CushionParams& p) { p.mu_w = 0.5; }, "tan(theta)");  // lifts the ball
  add([](CushionParams& p) { p.mu_w = 0.4; p.mu_s = 1.0; p.contact_height = 0.0483; },
      "normal speed");  // friction can stall the normal speed
  ImpulseSolverOptions tol0 = Adaptive();
  tol0.tolerance = 0;
  add([](CushionParams&) {}, "tolerance = 0", tol0);
  add([](CushionParams&) {}, "steps = 0", FixedStep(0));
  ImpulseSolverOptions cap0 = Adaptive();
  cap0.max_steps = 0;
  add([](CushionParams&) {}, "max_steps = 0", cap0);
  for (const Case& c : cases) {
    const CushionImpactResult r = ResolveCushionImpact(in, kBall, c.p, c.o);
    EXPECT_EQ(r.status, ImpactStatus::kInvalidInput) << c.named;
    EXPECT_EQ(r.out.v, in.v) << c.named;
    const std::string msg = ValidateCushionImpact(in, kBall, c.p, c.o);
    EXPECT_NE(msg.find(c.named), std::string::npos) << msg;
  }
  // A mass outside limits::kBallMass: negative, or so large that M v overflows (an
  // input the fuzzer found came back infinite).
  for (double mass : {-1.0, 0.0, 11.0, 1.3e308}) {
    BallParams bad_ball;
    bad_ball.mass = mass;
    EXPECT_EQ(ResolveCushionImpact(in, bad_ball, CushionParams{}, Adaptive()).status,
              ImpactStatus::kInvalidInput)
        << mass;
    EXPECT_NE(ValidateCushionParams(bad_ball, CushionParams{}).find("mass = "), std::string::npos) << mass;
  }
}

TEST(CushionStatus, StepCapStopsBothIntegrators) {
  ImpulseSolverOptions a = Adaptive();
  a.max_steps = 1;  // the impact needs two at least: the slip at I reaches zero inside it
  ImpulseSolverOptions f = FixedStep(1000);
  f.max_steps = 3;
  for (const ImpulseSolverOptions& o : {a, f}) {
    const CushionImpactResult r = ResolveCushionImpact(RollingSquareOn(1.0), kBall, CushionParams{}, o);
    EXPECT_EQ(r.status, ImpactStatus::kStepLimit);
    EXPECT_TRUE(r.out.v.allFinite());
  }
}

// The vertical velocity is not part of the model: ignored on input, zero on output.
TEST(CushionContract, VerticalVelocityIsIgnored) {
  BallMotion in = CushionIncidentState(1.3, DegToRad(50), 20.0, 10.0);
  const CushionImpactResult flat = ResolveCushionImpact(in, kBall, CushionParams{}, Adaptive());
  in.v.z() = 0.3;
  const CushionImpactResult lifted = ResolveCushionImpact(in, kBall, CushionParams{}, Adaptive());
  EXPECT_EQ(lifted.out.v, flat.out.v);
  EXPECT_EQ(lifted.out.w, flat.out.w);
  EXPECT_EQ(lifted.out.v.z(), 0.0);
}

TEST(CushionContract, Deterministic) {
  const BallMotion in = CushionIncidentState(2.2, DegToRad(33), -30.0, 55.0);
  const CushionImpactResult a = ResolveCushionImpact(in, kBall, CushionParams{}, Adaptive());
  const CushionImpactResult b = ResolveCushionImpact(in, kBall, CushionParams{}, Adaptive());
  EXPECT_EQ(a.out.v, b.out.v);
  EXPECT_EQ(a.out.w, b.out.w);
  EXPECT_EQ(a.work.rhs_evals, b.work.rhs_evals);
}

// The restitution curve fitted to Mathavan et al. (2009)'s measured rebounds makes
// the model match their regression within 0.05 m/s over 0.3-3.5 m/s (rolling ball,
// square on), where the paper's constant e_e = 0.98 is up to 0.4 m/s off.
TEST(CushionRestitutionCurve, ReproducesTheMeasuredReboundFit) {
  constexpr double kTol = 0.05;  // m/s, the bound the table simulation needs
  const BallParams ball;
  CushionParams curve = MathavanCushionParams(ball);
  curve.restitution_curve = MeasuredReboundCurve();
  const CushionParams constant = MathavanCushionParams(ball);
  double worst_curve = 0, worst_constant = 0;
  for (double v = 0.3; v <= 3.5001; v += 0.05) {
    const double fit = -0.0877 * v * v + 1.131 * v - 0.0953;
    for (const auto& [params, worst] :
         {std::pair<const CushionParams*, double*>{&curve, &worst_curve},
          std::pair<const CushionParams*, double*>{&constant, &worst_constant}}) {
      const CushionImpactResult r =
          ResolveCushionImpact(CushionIncidentState(v, kPi / 2, v / ball.radius, 0), ball, *params, {});
      ASSERT_EQ(r.status, ImpactStatus::kOk);
      *worst = std::max(*worst, std::abs(Vec2(r.out.v.x(), r.out.v.y()).norm() - fit));
    }
  }
  EXPECT_LE(worst_curve, kTol);
  EXPECT_GT(worst_constant, 0.3);  // why the curve: the constant misses badly
}

TEST(CushionRestitutionCurve, InterpolatesAndHoldsBeyondItsEnds) {
  CushionParams p;
  p.restitution_curve = MeasuredReboundCurve();
  EXPECT_DOUBLE_EQ(CushionRestitution(p, 0.1), 0.839);
  EXPECT_DOUBLE_EQ(CushionRestitution(p, 1.0), 1.0);
  EXPECT_NEAR(CushionRestitution(p, 0.4), 0.5 * (0.839 + 0.964), 1e-12);
  EXPECT_DOUBLE_EQ(CushionRestitution(p, 9.0), 0.850);
  p.restitution_curve.points = 0;
  EXPECT_DOUBLE_EQ(CushionRestitution(p, 2.0), p.e_e);
}

TEST(CushionRestitutionCurve, BadKnotIsNamed) {
  const BallParams ball;
  CushionParams p = MathavanCushionParams(ball);
  p.restitution_curve = MeasuredReboundCurve();
  p.restitution_curve.e[2] = 1.5;
  EXPECT_NE(ValidateCushionParams(ball, p).find("restitution_curve knot 2"), std::string::npos);
  EXPECT_EQ(ResolveCushionImpact(CushionIncidentState(1, 1, 0, 0), ball, p, {}).status,
            ImpactStatus::kInvalidInput);
}

// A point count outside [0, kMaxPoints], below as well as above (-1 was once taken for
// "no bad knot" and accepted).
TEST(CushionRestitutionCurve, PointCountOutOfRangeIsNamed) {
  const BallParams ball;
  for (int points : {-1, -7, RestitutionCurve::kMaxPoints + 1}) {
    CushionParams p = MathavanCushionParams(ball);
    p.restitution_curve.points = points;
    EXPECT_NE(ValidateCushionParams(ball, p).find("restitution_curve.points = " + std::to_string(points)),
              std::string::npos)
        << points;
    EXPECT_EQ(ResolveCushionImpact(CushionIncidentState(1, 1, 0, 0), ball, p, {}).status,
              ImpactStatus::kInvalidInput)
        << points;
  }
}

// ---------------------------------------------------------------------------
// The search fidelity tier (ImpulseFidelity::kSearch).

// The documented accuracy of the tier, on the random inputs with spins up to
// 2.5 V/R: within 5e-5 of the speed scale of a converged answer (measured: 1.7e-5),
// for less than half the work of the default tolerance (measured: 65 against 196
// right-hand sides an impact).
TEST(CushionSearchFidelity, MeetsItsDocumentedAccuracyForLessWork) {
  constexpr double kSearchRelTol = 5e-5;  // of max(|v|, R|w|), velocity and R * spin
  RandomShots shots(17);
  double worst = 0;
  long search_work = 0, default_work = 0;
  for (int i = 0; i < 300; ++i) {
    const BallMotion in = shots.Next();
    const CushionImpactResult s = ResolveCushionImpact(in, kBall, {}, test::Search());
    const CushionImpactResult t = ResolveCushionImpact(in, kBall, {}, Adaptive(kTightTolerance));
    const CushionImpactResult d = ResolveCushionImpact(in, kBall, {}, Adaptive());
    ASSERT_EQ(s.status, ImpactStatus::kOk) << "shot " << i;
    ASSERT_EQ(t.status, ImpactStatus::kOk) << "shot " << i;
    const double scale = std::max(in.v.norm(), kBall.radius * in.w.norm());
    worst = std::max(worst, Distance(s.out, t.out) / scale);
    search_work += s.work.rhs_evals;
    default_work += d.work.rhs_evals;
  }
  EXPECT_LE(worst, kSearchRelTol);
  EXPECT_LT(2 * search_work, default_work);
}

// Both Runge-Kutta pairs converge to the same cushion impact: on the random
// inputs each at tolerance 1e-9 lies within 1e-7 of the speed scale of the other's
// answer at 1e-13.
TEST(CushionMethod, BothPairsConvergeToTheSameAnswer) {
  RandomShots shots(23);
  constexpr ImpulseMethod kDop853 = ImpulseMethod::kDormandPrince853;
  const ImpulseSolverOptions dp54 = Adaptive(1e-9), dop853 = Adaptive(1e-9, kDop853);
  const ImpulseSolverOptions ref54 = Adaptive(1e-13), ref853 = Adaptive(1e-13, kDop853);
  double worst54 = 0, worst853 = 0, refs = 0;
  for (int i = 0; i < 200; ++i) {
    const BallMotion in = shots.Next();
    const double scale = std::max(in.v.norm(), kBall.radius * in.w.norm());
    const CushionImpactResult a = ResolveCushionImpact(in, kBall, {}, dp54);
    const CushionImpactResult b = ResolveCushionImpact(in, kBall, {}, dop853);
    const CushionImpactResult ra = ResolveCushionImpact(in, kBall, {}, ref54);
    const CushionImpactResult rb = ResolveCushionImpact(in, kBall, {}, ref853);
    for (const CushionImpactResult* r : {&a, &b, &ra, &rb}) {
      ASSERT_EQ(r->status, ImpactStatus::kOk) << i;
    }
    worst54 = std::max(worst54, Distance(a.out, rb.out) / scale);
    worst853 = std::max(worst853, Distance(b.out, ra.out) / scale);
    refs = std::max(refs, Distance(ra.out, rb.out) / scale);
  }
  EXPECT_LT(refs, 1e-10);
  EXPECT_LT(worst54, 1e-7);
  EXPECT_LT(worst853, 1e-7);
}

TEST(CushionMethod, UnknownMethodIsRejectedWithItsName) {
  ImpulseSolverOptions o;
  o.method = static_cast<ImpulseMethod>(9);
  const BallMotion in = CushionIncidentState(1.0, 1.0, 0.0, 0.0);
  EXPECT_EQ(ResolveCushionImpact(in, kBall, {}, o).status, ImpactStatus::kInvalidInput);
  EXPECT_NE(ValidateCushionImpact(in, kBall, {}, o).find("method = 9"), std::string::npos);
}

TEST(CushionSearchFidelity, OverridesIntegratorAndToleranceAndRejectsUnknownTiers) {
  const BallMotion in = CushionIncidentState(1.7, DegToRad(70), 40.0, -20.0);
  ImpulseSolverOptions search = FixedStep(10);
  search.fidelity = ImpulseFidelity::kSearch;
  const CushionImpactResult a = ResolveCushionImpact(in, kBall, {}, search);
  const CushionImpactResult b = ResolveCushionImpact(in, kBall, {}, Adaptive(kSearchTolerance));
  ASSERT_EQ(a.status, ImpactStatus::kOk);
  EXPECT_EQ(Distance(a.out, b.out), 0.0);
  search.fidelity = static_cast<ImpulseFidelity>(9);
  EXPECT_EQ(ResolveCushionImpact(in, kBall, {}, search).status, ImpactStatus::kInvalidInput);
  EXPECT_NE(ValidateCushionImpact(in, kBall, {}, search).find("fidelity = 9"), std::string::npos);
}

}  // namespace
}  // namespace snooker::physics
