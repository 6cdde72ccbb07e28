// Fidelity tiers (physics/sim/fidelity.h): what each sets, and that the default
// keeps whole shots within the measured bound of a converged run.
#include "physics/sim/fidelity.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "tests/support/scenarios.h"

namespace snooker::physics {
namespace {

TEST(FidelityTest, TiersSetTheImpactSolvers) {
  const SimParams defaults;
  const SimParams d = FidelityParams(Fidelity::kDefault);
  EXPECT_EQ(d.ball_ball_solver.tolerance, defaults.ball_ball_solver.tolerance);
  EXPECT_EQ(d.cushion_solver.tolerance, SimParams::kShotTolerance);
  EXPECT_EQ(d.cushion_solver.fidelity, ImpulseFidelity::kExact);
  EXPECT_EQ(d.ball_ball_solver.method, defaults.ball_ball_solver.method);
  EXPECT_EQ(d.cushion_solver.method, defaults.cushion_solver.method);
  // The pairs measured cheaper at each tier (docs/impact-methods.md).
  EXPECT_EQ(defaults.ball_ball_solver.method, ImpulseMethod::kDormandPrince54);
  EXPECT_EQ(defaults.cushion_solver.method, ImpulseMethod::kDormandPrince54);
  const SimParams r = FidelityParams(Fidelity::kReference);
  EXPECT_EQ(r.ball_ball_solver.tolerance, 1e-12);
  EXPECT_EQ(r.cushion_solver.tolerance, 1e-12);
  EXPECT_EQ(r.ball_ball_solver.method, ImpulseMethod::kDormandPrince853);
  EXPECT_EQ(r.cushion_solver.method, ImpulseMethod::kDormandPrince853);
  const SimParams s = FidelityParams(Fidelity::kSearch);
  EXPECT_EQ(s.ball_ball_solver.fidelity, ImpulseFidelity::kSearch);
  EXPECT_EQ(s.cushion_solver.fidelity, ImpulseFidelity::kSearch);
  // The rest of the base is kept.
  SimParams base;
  base.max_events = 123;
  EXPECT_EQ(FidelityParams(Fidelity::kSearch, base).max_events, 123);
}

// On seeded planner-workload shots, the default's final positions (the solvers at
// the shot tolerance, rolling impacts from the impact tables) lie within 0.1 mm of a
// converged run (docs/shot-speed-vs-error.md measured 0.04 mm on 300 shots; 0.21 mm
// on the several-cushion shots, whose cushion impacts the tables answer most), on every shot that is well conditioned: one whose outcome a change of one
// part in 1e9 in the cue ball's speed, or of 1e-9 rad in its direction, does not move
// by more than 1 um at the reference's precision. The search tier stays within 1 mm
// there (measured 0.41 mm).
TEST(FidelityTest, DefaultStaysWithinTheMeasuredBoundOfTheReference) {
  constexpr double kDefaultBound = 0.1e-3, kSearchBound = 1e-3, kNudgeMoves = 1e-6;  // m
  std::mt19937_64 rng(77);
  Simulator ref(DefaultTable(), FidelityParams(Fidelity::kReference));
  Simulator nudged(DefaultTable(), FidelityParams(Fidelity::kReference));
  Simulator def(DefaultTable(), FidelityParams(Fidelity::kDefault));
  Simulator search(DefaultTable(), FidelityParams(Fidelity::kSearch));
  int well = 0;
  for (int shot = 0; shot < 60; ++shot) {
    const std::vector<BallState> balls = scenarios::PlannerWorkloadShot(rng);
    for (Simulator* s : {&ref, &def, &search}) {
      ASSERT_EQ(s->Run(balls, RunOptions::Lean()), SimStatus::kAtRest);
    }
    std::vector<BallState> faster = balls, turned = balls;
    faster[0].v *= 1 + 1e-9;
    const double a = 1e-9;
    const Vec3 v = balls[0].v;
    turned[0].v = Vec3(std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y(), 0);
    bool conditioned = true;
    for (const std::vector<BallState>* nudge : {&faster, &turned}) {
      ASSERT_EQ(nudged.Run(*nudge, RunOptions::Lean()), SimStatus::kAtRest);
      for (size_t i = 0; i < balls.size(); ++i) {
        conditioned &= nudged.pocket_of(static_cast<int>(i)) == ref.pocket_of(static_cast<int>(i)) &&
                       (nudged.final_balls()[i].r - ref.final_balls()[i].r).norm() <= kNudgeMoves;
      }
    }
    if (!conditioned) continue;
    ++well;
    for (size_t i = 0; i < balls.size(); ++i) {
      const int k = static_cast<int>(i);
      ASSERT_EQ(def.pocket_of(k), ref.pocket_of(k)) << "shot " << shot << " ball " << i;
      EXPECT_LE((def.final_balls()[i].r - ref.final_balls()[i].r).norm(), kDefaultBound)
          << "shot " << shot << " ball " << i;
      if (search.pocket_of(k) < 0 && ref.pocket_of(k) < 0) {
        EXPECT_LE((search.final_balls()[i].r - ref.final_balls()[i].r).norm(), kSearchBound)
            << "shot " << shot << " ball " << i;
      }
    }
  }
  // About four shots in five are well conditioned (docs/shot-speed-vs-error.md: 242 of 300).
  EXPECT_GE(well, 40);
}

}  // namespace
}  // namespace snooker::physics
