// The phase-end location of the paper's fixed-step scheme (physics/ode/
// fixed_step_integrator.h) against closed forms, at every scale of the step.
#include "physics/ode/fixed_step_integrator.h"

#include <gtest/gtest.h>

#include <cmath>

namespace snooker::physics::ode {
namespace {

// a + b t: the crossing at -a / b, inside the bracket or not.
TEST(FirstDownCrossingTest, LinearCrossingIsExactOrNone) {
  EXPECT_DOUBLE_EQ(FirstDownCrossing(2.0, -4.0, 0.0, 0.0, 1.0), 0.5);
  EXPECT_EQ(FirstDownCrossing(-1.0, -4.0, 0.0, 0.0, 1.0), 0.0);  // already down at lo
  EXPECT_GT(FirstDownCrossing(2.0, -1.0, 0.0, 0.0, 1.0), 1.0);   // crosses at 2
}

// A concave quadratic positive at lo: its larger root, 3 for 3 + 2t - t^2.
TEST(FirstDownCrossingTest, ConcaveCrossingIsTheLargerRoot) {
  EXPECT_DOUBLE_EQ(FirstDownCrossing(3.0, 2.0, -1.0, 0.0, 4.0), 3.0);
  EXPECT_GT(FirstDownCrossing(3.0, 2.0, -1.0, 0.0, 2.0), 2.0);
}

// "No crossing" must compare above the bracket at any scale: hi + 1 rounds to hi once
// hi passes 2^53, and then read as a crossing at hi (an impact solved at 1e20 m/s
// ended after one step that way).
TEST(FirstDownCrossingTest, NoCrossingStaysAboveTheBracketBeyondTwoToThe53) {
  for (double hi : {1.0, 0x1p52, 0x1p53, 1e17, 1e200}) {
    EXPECT_GT(FirstDownCrossing(hi, -0.5, 0.0, 0.0, hi), hi) << hi;
    EXPECT_GT(FirstDownCrossing(hi, 0.0, -0.5 / hi, 0.0, hi), hi) << hi;
  }
}

// Compression (normal speed y0 + y1 t) and restitution (work back to (1 - e^2) W_c)
// located in the step, at unit scale and at 2^60 times it (a power of two: exact).
TEST(EulerPhaseEndsTest, PhaseEndsScaleWithTheStep) {
  for (double k : {1.0, 0x1p60}) {
    EulerPhaseEnds phases(1.0);
    // Step 1: speed 1 - t over [0, 0.5]: still compressing.
    EXPECT_GT(phases.Step(0.0, 0.5 * k, 1.0 * k, -1.0, 0.0), 0.5 * k) << k;
    // Step 2: from P = 0.5: speed 0.5 - t, W_c reached at t = 0.5 (W_c = 0.5 k^2); e = 1
    // ends the impact where W is back to 0: 0.5 k^2 + 0 - t^2 / 2 = 0 -> 1 past it.
    const double w0 = 0.5 * k * (1.0 * k) - 0.5 * 0.25 * k * k;  // W after step 1
    const double t = phases.Step(0.5 * k, 2.0 * k, 0.5 * k, -1.0, w0);
    EXPECT_NEAR(t / k, 1.5, 1e-12) << k;
  }
}

}  // namespace
}  // namespace snooker::physics::ode
