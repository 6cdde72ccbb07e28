#include "physics/events/roots.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace snooker::physics {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Simple roots at least kMinSeparation apart with O(1) coefficients: |p'| at a root
// is >= kMinSeparation^3 ~ 1e-4, so rounding (~1e-16) moves a root by ~1e-12.
constexpr double kSimpleRootTol = 1e-10;
constexpr double kMinSeparation = 0.05;
// A double root is fixed only to the square root of the evaluation precision.
constexpr double kDoubleRootTol = 1e-7;
// A quadruple root is fixed only to the fourth root of it (~1.2e-4).
constexpr double kQuadrupleRootTol = 1e-3;

// Coefficients of scale * prod (t - r_i), lowest degree first.
Poly4 FromRoots(const std::vector<double>& roots, double scale) {
  Poly4 p{};
  p[0] = scale;
  for (double r : roots) {
    Poly4 q{};
    for (int i = 0; i < kMaxPolyDegree; ++i) {
      q[i + 1] += p[i];
      q[i] -= r * p[i];
    }
    p = q;
  }
  return p;
}

TEST(RootsTest, ProductsOfLinearFactorsRandom) {
  std::mt19937_64 rng(20240601);
  std::uniform_real_distribution<double> root(-2.0, 2.0);
  std::uniform_real_distribution<double> log_scale(-6.0, 6.0);
  for (int trial = 0; trial < 4000; ++trial) {
    const int degree = 1 + trial % kMaxPolyDegree;
    std::vector<double> roots;
    while (static_cast<int>(roots.size()) < degree) {
      const double r = root(rng);
      const bool apart = std::all_of(roots.begin(), roots.end(),
                                     [r](double s) { return std::abs(r - s) >= kMinSeparation; });
      if (apart) roots.push_back(r);
    }
    std::sort(roots.begin(), roots.end());
    const double scale = std::pow(10.0, log_scale(rng)) * (trial % 2 ? 1.0 : -1.0);
    const RealRoots found = FindRealRoots(FromRoots(roots, scale), -3.0, 3.0);
    ASSERT_EQ(found.status, RootStatus::kOk);
    ASSERT_EQ(found.count, degree) << "trial " << trial;
    for (int i = 0; i < degree; ++i) EXPECT_NEAR(found.t[i], roots[i], kSimpleRootTol);
  }
}

TEST(RootsTest, OnlyRootsInsideTheIntervalAreListed) {
  const Poly4 p = FromRoots({-1.5, -0.5, 0.5, 1.5}, 1.0);
  const RealRoots r = FindRealRoots(p, -1.0, 1.0);
  ASSERT_EQ(r.count, 2);
  EXPECT_NEAR(r.t[0], -0.5, kSimpleRootTol);
  EXPECT_NEAR(r.t[1], 0.5, kSimpleRootTol);
}

TEST(RootsTest, RootsAtTheIntervalEndsAreIncluded) {
  const RealRoots r = FindRealRoots(FromRoots({0.0, 1.0}, 1.0), 0.0, 1.0);
  ASSERT_EQ(r.count, 2);
  EXPECT_EQ(r.t[0], 0.0);
  EXPECT_EQ(r.t[1], 1.0);
  // A single-point interval that is a root.
  const RealRoots point = FindRealRoots(FromRoots({0.25, 3.0}, 1.0), 0.25, 0.25);
  ASSERT_EQ(point.count, 1);
  EXPECT_EQ(point.t[0], 0.25);
}

TEST(RootsTest, DoubleRootIsReportedOnce) {
  // (t - 1/3)^2 (t + 1)(t - 1.7): 1/3 is not a double, so p never reaches 0 exactly.
  const Poly4 p = FromRoots({1.0 / 3.0, 1.0 / 3.0, -1.0, 1.7}, 2.5);
  const RealRoots r = FindRealRoots(p, -2.0, 2.0);
  ASSERT_EQ(r.count, 3);
  EXPECT_NEAR(r.t[0], -1.0, kSimpleRootTol);
  EXPECT_NEAR(r.t[1], 1.0 / 3.0, kDoubleRootTol);
  EXPECT_NEAR(r.t[2], 1.7, kSimpleRootTol);
}

TEST(RootsTest, TwoDoubleRoots) {
  const Poly4 p = FromRoots({-0.7, -0.7, 0.9, 0.9}, 1.0);
  const RealRoots r = FindRealRoots(p, -1.0, 1.0);
  ASSERT_EQ(r.count, 2);
  EXPECT_NEAR(r.t[0], -0.7, kDoubleRootTol);
  EXPECT_NEAR(r.t[1], 0.9, kDoubleRootTol);
}

TEST(RootsTest, QuadrupleRoot) {
  const RealRoots r = FindRealRoots(FromRoots({0.3, 0.3, 0.3, 0.3}, 1.0), -1.0, 1.0);
  ASSERT_GE(r.count, 1);
  for (int i = 0; i < r.count; ++i) EXPECT_NEAR(r.t[i], 0.3, kQuadrupleRootTol);
}

TEST(RootsTest, TangentQuadraticFromRandomDoubleRoots) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> root(-1.0, 1.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const double a = root(rng);
    const RealRoots r = FindRealRoots(FromRoots({a, a}, 1.0 + trial), -2.0, 2.0);
    ASSERT_EQ(r.count, 1) << "a = " << a;
    EXPECT_NEAR(r.t[0], a, kDoubleRootTol);
  }
}

TEST(RootsTest, DegenerateDegrees) {
  EXPECT_EQ(FindRealRoots(Poly4{}, -1.0, 1.0).status, RootStatus::kIdenticallyZero);
  EXPECT_EQ(FindRealRoots(Poly4{}, -1.0, 1.0).count, 0);
  EXPECT_EQ(FindRealRoots(Poly4{3.0}, -1.0, 1.0).count, 0);  // nonzero constant

  const RealRoots linear = FindRealRoots(Poly4{-1.0, 2.0}, -1.0, 1.0);
  ASSERT_EQ(linear.count, 1);
  EXPECT_EQ(linear.t[0], 0.5);

  // Exact zero leading coefficients at every degree: a quadratic stored as degree 4.
  const RealRoots quad = FindRealRoots(Poly4{-2.0, 0.0, 1.0, 0.0, 0.0}, 0.0, 2.0);
  ASSERT_EQ(quad.count, 1);
  EXPECT_NEAR(quad.t[0], std::sqrt(2.0), kSimpleRootTol);

  // A tiny leading coefficient: its other root (-1e20) is far outside.
  const RealRoots tiny = FindRealRoots(Poly4{-0.5, 1.0, 1e-20, 0.0, 1e-30}, -10.0, 10.0);
  ASSERT_EQ(tiny.count, 1);
  EXPECT_NEAR(tiny.t[0], 0.5, kSimpleRootTol);
}

TEST(RootsTest, ScaleInvariantOverHugeDynamicRange) {
  for (double scale : {1e-300, 1e-150, 1.0, 1e150, 1e290}) {
    const RealRoots r = FindRealRoots(FromRoots({0.25, 0.75}, scale), 0.0, 1.0);
    ASSERT_EQ(r.count, 2) << scale;
    EXPECT_NEAR(r.t[0], 0.25, kSimpleRootTol);
    EXPECT_NEAR(r.t[1], 0.75, kSimpleRootTol);
  }
  // Roots twelve orders of magnitude apart, each to full relative precision.
  const RealRoots wide = FindRealRoots(FromRoots({1e-6, 1e6}, 1.0), 0.0, 2e6);
  ASSERT_EQ(wide.count, 2);
  EXPECT_NEAR(wide.t[0] / 1e-6, 1.0, 1e-12);
  EXPECT_NEAR(wide.t[1] / 1e6, 1.0, 1e-12);
}

TEST(RootsTest, InfiniteBoundsUseTheRootBound) {
  const Poly4 p = FromRoots({-5.0, 3.0, 100.0}, 0.5);
  const RealRoots r = FindRealRoots(p, -kInf, kInf);
  ASSERT_EQ(r.count, 3);
  EXPECT_NEAR(r.t[0], -5.0, 1e-9);
  EXPECT_NEAR(r.t[1], 3.0, 1e-9);
  EXPECT_NEAR(r.t[2], 100.0, 1e-9);
  EXPECT_LE(100.0, RootBound(p));
  EXPECT_EQ(RootBound(Poly4{}), kInf);
  EXPECT_EQ(RootBound(Poly4{2.0}), 0.0);
}

TEST(RootsTest, InvalidInput) {
  EXPECT_EQ(FindRealRoots(Poly4{1.0, NAN}, 0.0, 1.0).status, RootStatus::kInvalidInput);
  EXPECT_EQ(FindRealRoots(Poly4{1.0, kInf}, 0.0, 1.0).status, RootStatus::kInvalidInput);
  EXPECT_EQ(FindRealRoots(Poly4{1.0, 1.0}, 1.0, 0.0).status, RootStatus::kInvalidInput);
  EXPECT_EQ(FindRealRoots(Poly4{1.0, 1.0}, NAN, 0.0).status, RootStatus::kInvalidInput);
}

// Every sign change seen by a fine scan brackets a listed root, and every listed
// root is a zero of p to rounding error.
TEST(RootsTest, AgreesWithBruteForceSignScan) {
  constexpr int kSamples = 20000;
  std::mt19937_64 rng(424242);
  std::uniform_real_distribution<double> coef(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    Poly4 p{};
    for (double& c : p) c = coef(rng);
    const double lo = -2.0, hi = 2.0;
    const RealRoots r = FindRealRoots(p, lo, hi);
    ASSERT_EQ(r.status, RootStatus::kOk);
    int changes = 0;
    double t0 = lo, v0 = EvaluatePoly(p, lo);
    for (int i = 1; i <= kSamples; ++i) {
      const double t1 = lo + (hi - lo) * i / kSamples;
      const double v1 = EvaluatePoly(p, t1);
      if ((v0 > 0) != (v1 > 0)) {
        ++changes;
        const bool bracketed = std::any_of(r.t.begin(), r.t.begin() + r.count,
                                           [&](double x) { return x >= t0 && x <= t1; });
        EXPECT_TRUE(bracketed) << "trial " << trial << " sign change in [" << t0 << ", " << t1
                               << "]";
      }
      t0 = t1;
      v0 = v1;
    }
    EXPECT_EQ(r.count, changes) << "trial " << trial;
    for (int i = 0; i < r.count; ++i) {
      const double t = r.t[i];
      const double scale = 1 + std::abs(t) + t * t + std::abs(t * t * t) + t * t * t * t;
      EXPECT_LE(std::abs(EvaluatePoly(p, t)), 1e-14 * scale);
    }
  }
}

TEST(RootsTest, FirstDownCrossingCases) {
  // > 0 before 1, < 0 on (1, 2).
  EXPECT_NEAR(FindFirstDownCrossing(FromRoots({1.0, 2.0}, 1.0), 0.0, 3.0), 1.0, kSimpleRootTol);
  // < 0 before 1, > 0 on (1, 2): the crossing from above is the second root.
  EXPECT_NEAR(FindFirstDownCrossing(FromRoots({1.0, 2.0}, -1.0), 0.0, 3.0), 2.0, kSimpleRootTol);
  // < 0, > 0, < 0, > 0: the crossing from above is the second root.
  EXPECT_NEAR(FindFirstDownCrossing(FromRoots({0.5, 1.0, 2.0}, 1.0), 0.0, 3.0), 1.0,
              kSimpleRootTol);
  // < 0 before 0.5 and > 0 after 2: no crossing from above at all.
  EXPECT_EQ(FindFirstDownCrossing(FromRoots({0.5, 0.5, 2.0}, 1.0), 0.0, 3.0), kInf);
  // A tangency from above counts; from below it does not.
  EXPECT_NEAR(FindFirstDownCrossing(FromRoots({1.0, 1.0}, 1.0), 0.0, 3.0), 1.0, kDoubleRootTol);
  EXPECT_EQ(FindFirstDownCrossing(FromRoots({1.0, 1.0}, -1.0), 0.0, 3.0), kInf);
  // lo itself is never returned: zero at lo then negative then positive.
  EXPECT_EQ(FindFirstDownCrossing(FromRoots({0.0, 1.0}, 1.0), 0.0, 2.0), kInf);
  // Positive on (0, 1) after a zero at lo: the crossing is at 1.
  EXPECT_NEAR(FindFirstDownCrossing(FromRoots({0.0, 1.0}, -1.0), 0.0, 2.0), 1.0, kSimpleRootTol);
  // A root exactly at hi is included.
  EXPECT_EQ(FindFirstDownCrossing(FromRoots({1.0, 3.0}, 1.0), 0.0, 1.0), 1.0);
  // Degenerate intervals and polynomials.
  EXPECT_EQ(FindFirstDownCrossing(FromRoots({1.0}, -1.0), 1.0, 1.0), kInf);
  EXPECT_EQ(FindFirstDownCrossing(Poly4{}, 0.0, 1.0), kInf);
  EXPECT_EQ(FindFirstDownCrossing(Poly4{1.0}, 0.0, 1.0), kInf);
  EXPECT_EQ(FindFirstDownCrossing(Poly4{1.0, 1.0}, 0.0, NAN), kInf);
}

// Quadratics (every cushion gap) take a closed-form path in FindFirstDownCrossing;
// it must agree with the general solver (FindRealRoots, derivative recursion and
// Newton refinement) on random quadratics over a wide range of scales, tangencies
// and nearly linear ones included.
// The first down-crossing in (lo, hi] read off the general solver's full root list
// (p's sign midway between consecutive roots): what FindFirstDownCrossing's fast
// paths must reproduce.
double FirstDownCrossingOfAllRoots(const Poly4& p, double lo, double hi) {
  const RealRoots r = FindRealRoots(p, lo, hi);
  double prev = lo;
  for (int i = 0; i < r.count; ++i) {
    if (r.t[i] <= lo) continue;
    if (EvaluatePoly(p, prev + 0.5 * (r.t[i] - prev)) > 0.0) return r.t[i];
    prev = r.t[i];
  }
  return kInf;
}

TEST(RootsTest, QuadraticFastPathAgreesWithTheGeneralSolver) {
  std::mt19937_64 rng(1234);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int crossings = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double scale = std::pow(10.0, 6 * u(rng));
    Poly4 p{u(rng), u(rng) * scale, u(rng) * scale * scale, 0, 0};
    if (trial % 4 == 1) p[0] = p[1] * p[1] / (4 * p[2]);  // a double root
    if (trial % 4 == 2) p[2] *= 1e-12;                    // nearly linear
    const double lo = 0.0, hi = 2.0 / scale;
    const double expected = FirstDownCrossingOfAllRoots(p, lo, hi);
    const double found = FindFirstDownCrossing(p, lo, hi);
    if (expected == kInf) {
      // Only a tangency within rounding may be found where the general solver saw none.
      if (found != kInf) {
        EXPECT_LE(std::abs(EvaluatePoly(p, found)), 1e-12) << "trial " << trial;
      }
      continue;
    }
    ++crossings;
    // Simple roots agree to a few ulps; a double root only to sqrt(eps) of its position.
    const double tol = (trial % 4 == 1 ? 1e-7 : 1e-12) * hi;
    EXPECT_NEAR(found, expected, tol) << "trial " << trial;
  }
  EXPECT_GT(crossings, 2000);
}

// The first sample at which p <= 0 after a sample at which p > 0, from a fine scan;
// the crossing must lie in the sample step that ends there (a brief dip between
// samples may be found earlier, but then p really is ~0 there).
TEST(RootsTest, FirstDownCrossingAgreesWithBruteForceScan) {
  constexpr int kSamples = 20000;
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> coef(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    Poly4 p{};
    for (double& c : p) c = coef(rng);
    const double lo = 0.0, hi = 2.0;
    const double found = FindFirstDownCrossing(p, lo, hi);
    double scan = kInf;
    double t_prev = lo;
    bool prev_positive = EvaluatePoly(p, lo) > 0;
    for (int i = 1; i <= kSamples && scan == kInf; ++i) {
      const double t = lo + (hi - lo) * i / kSamples;
      const bool positive = EvaluatePoly(p, t) > 0;
      if (prev_positive && !positive) scan = t;
      if (scan == kInf) t_prev = t;
      prev_positive = positive;
    }
    if (scan == kInf) {
      if (found != kInf) {
        EXPECT_LE(std::abs(EvaluatePoly(p, found)), 1e-12) << trial;
      }
      continue;
    }
    EXPECT_LE(found, scan) << "trial " << trial;
    if (found < t_prev) {
      EXPECT_LE(std::abs(EvaluatePoly(p, found)), 1e-12) << "trial " << trial;
    }
  }
}

// FindFirstDownCrossing answers "no crossing" for a quartic its Bernstein bound
// proves positive, without the root finder. The answer must be the general solver's
// in every case: random quartics positive at lo, many of them grazing zero (a double
// root shifted up or down by a hair), on intervals that do not start at 0.
TEST(RootsTest, PositiveQuarticCullChangesNoAnswer) {
  std::mt19937_64 rng(2029);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int culled_kind = 0, crossings = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double r = 1.0 + u(rng), s = 1.0 + u(rng), q = u(rng);
    // (t - r)^2 ((t - s)^2 + q^2) + shift: touches, misses or crosses zero near r.
    const double shift = trial % 3 == 0 ? 0.0 : std::pow(10.0, -14 + 13 * (u(rng) + 1) / 2) * (trial % 3 == 1 ? 1 : -1);
    Poly4 p = FromRoots({r, r}, 1.0);
    const Poly4 f = FromRoots({s, s}, 1.0);
    Poly4 prod{};
    for (int i = 0; i <= 2; ++i) {
      for (int j = 0; j <= 2; ++j) prod[i + j] += p[i] * (f[j] + (j == 0 ? q * q : 0.0));
    }
    prod[0] += shift;
    const double lo = 0.25 * (u(rng) + 1), hi = lo + 2.0 * (u(rng) + 1.05);
    const double expected = FirstDownCrossingOfAllRoots(prod, lo, hi);
    const double found = FindFirstDownCrossing(prod, lo, hi);
    if (expected == kInf) {
      ++culled_kind;
      EXPECT_EQ(found, kInf) << "trial " << trial;
    } else {
      ++crossings;
      EXPECT_EQ(found, expected) << "trial " << trial;
    }
  }
  EXPECT_GT(culled_kind, 2000);
  EXPECT_GT(crossings, 2000);
}

}  // namespace
}  // namespace snooker::physics
