// Test helpers: the demo's table (`snooker plan --table builtin:black`) as the
// planner takes it, and plans whose search estimate is checked against their own
// Monte Carlo.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>

#include "planner/builtin_tables.h"
#include "planner/planner.h"
#include "planner/rules.h"

namespace snooker::planner::testing_tables {

/// The cue ball, the black on its spot and three reds of the pack, in that order.
inline TableState DemoTable() { return TableOf(*BuiltinTable("black")); }

/// Calls check(shot, seed) with the best shot of `request` planned on seeds 1, 2 and
/// 3, capped at 4000 simulations (so that each plan is a function of its seed), the
/// shot's Monte Carlo at 200 samples: a binomial error of at most 0.035 on its pot
/// probability. A plan without a shot fails the test.
template <class Check>
void BestShotsOnThreeSeeds(PlanRequest request, Check check) {
  request.max_simulations = 4000;
  request.monte_carlo_samples = 200;
  request.max_shots = 1;
  for (const std::uint64_t seed : {1, 2, 3}) {
    request.seed = seed;
    const PlanAnswer a = Planner::Default().Plan(request);
    EXPECT_EQ(a.status, PlanStatus::kOk) << a.reason << ", seed " << seed;
    if (!a.shots.empty()) check(a.shots.front(), seed);
  }
}

}  // namespace snooker::planner::testing_tables
