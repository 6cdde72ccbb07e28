// The numerical pieces of physics/ode/ against closed forms: the explicit Runge-Kutta
// steppers (Dormand-Prince 5(4) and 8(5,3)) - their order of accuracy, that of their
// dense output, that their error estimates track the true error; the step-size
// controller; the small LU factorisation of the Rosenbrock steps.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Core>
#include <Eigen/LU>

#include <random>

#include "physics/ode/ode_dop853.h"
#include "physics/ode/ode_dp54.h"
#include "physics/ode/ode_rosenbrock23.h"

namespace snooker::physics::ode {
namespace {

using Y = Eigen::Vector2d;

// y1' = 1 + y1^2 (y1 = tan t), y2' = -y1 y2 (y2 = cos t): nonlinear and coupled,
// with a closed form.
bool Rhs(const Y& y, Y* dy) {
  *dy = Y(1 + y[0] * y[0], -y[0] * y[1]);
  return true;
}
Y Exact(double t) { return Y(std::tan(t), std::cos(t)); }
const double kT0 = 0.3;

double Dp54Error(double h, double* estimate, double* dense_error) {
  const Y y0 = Exact(kT0);
  Y k1;
  Rhs(y0, &k1);
  Dp54Result<Y> r;
  Dp54Step(y0, k1, h, Rhs, [](const Y&) {}, &r);
  *estimate = r.err.cwiseAbs().maxCoeff();
  const Dp54Dense<Y> dense(y0, r);
  *dense_error = (dense.At(y0, 0.4) - Exact(kT0 + 0.4 * h)).cwiseAbs().maxCoeff();
  return (r.y1 - Exact(kT0 + h)).cwiseAbs().maxCoeff();
}

double Dop853Error(double h, double* estimate, double* dense_error) {
  const Y y0 = Exact(kT0);
  Y k1;
  Rhs(y0, &k1);
  Dop853Result<Y> r;
  Dop853Step(y0, k1, h, Rhs, [](const Y&) {}, &r);
  *estimate = ErrorNorm853(r.err5.cwiseAbs().maxCoeff(), r.err3.cwiseAbs().maxCoeff());
  const Dop853Dense<Y> dense(y0, r, Rhs);
  EXPECT_TRUE(dense.valid());
  *dense_error = (dense.At(y0, 0.4) - Exact(kT0 + 0.4 * h)).cwiseAbs().maxCoeff();
  return (r.y1 - Exact(kT0 + h)).cwiseAbs().maxCoeff();
}

// Observed order of a local error: log2 of e(h) / e(h/2).
double Order(double e_h, double e_half) { return std::log2(e_h / e_half); }

TEST(Dp54Stepper, LocalErrorIsSixthOrderAndDenseOutputFifth) {
  double est1, est2, d1, d2;
  const double e1 = Dp54Error(0.08, &est1, &d1);
  const double e2 = Dp54Error(0.04, &est2, &d2);
  EXPECT_NEAR(Order(e1, e2), 6.0, 0.5);  // local error O(h^6) of a 5th-order method
  EXPECT_NEAR(Order(d1, d2), 5.0, 0.6);  // 4th-order continuous extension
  // The embedded estimate (5th minus 4th order) is of the error's size or larger.
  EXPECT_GE(est1, e1);
  EXPECT_LT(est1, 1e4 * e1);
}

TEST(Dop853Stepper, LocalErrorIsNinthOrderAndDenseOutputEighth) {
  double est1, est2, d1, d2;
  const double e1 = Dop853Error(0.2, &est1, &d1);
  const double e2 = Dop853Error(0.1, &est2, &d2);
  ASSERT_GT(e2, 0.0);
  EXPECT_NEAR(Order(e1, e2), 9.0, 0.7);  // local error O(h^9) of an 8th-order method
  EXPECT_NEAR(Order(d1, d2), 8.0, 0.7);  // 7th-order continuous extension
  EXPECT_GE(est1, e1);
  EXPECT_LT(est1, 1e4 * e1);
  // At the ends the dense output is the step itself.
  const Y y0 = Exact(kT0);
  Y k1;
  Rhs(y0, &k1);
  Dop853Result<Y> r;
  Dop853Step(y0, k1, 0.2, Rhs, [](const Y&) {}, &r);
  const Dop853Dense<Y> dense(y0, r, Rhs);
  EXPECT_LT((dense.At(y0, 0.0) - y0).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((dense.At(y0, 1.0) - r.y1).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Dop853Stepper, IsMoreAccurateThanDp54ForTheSameEvaluations) {
  // Twelve evaluations: two Dormand-Prince 5(4) steps of h/2 against one DOP853 step of
  // h (FSAL on both: 6 and 12 new evaluations).
  const double h = 0.2;
  const Y y0 = Exact(kT0);
  Y k1;
  Rhs(y0, &k1);
  Dp54Result<Y> a, b;
  Dp54Step(y0, k1, h / 2, Rhs, [](const Y&) {}, &a);
  Dp54Step(a.y1, a.k7, h / 2, Rhs, [](const Y&) {}, &b);
  Dop853Result<Y> c;
  Dop853Step(y0, k1, h, Rhs, [](const Y&) {}, &c);
  const double e54 = (b.y1 - Exact(kT0 + h)).cwiseAbs().maxCoeff();
  const double e853 = (c.y1 - Exact(kT0 + h)).cwiseAbs().maxCoeff();
  EXPECT_LT(30 * e853, e54) << e853 << " vs " << e54;
}

TEST(Dop853Stepper, ReportsAnUndefinedDerivative) {
  const Y y0 = Exact(kT0);
  Y k1;
  Rhs(y0, &k1);
  int calls = 0;
  auto failing = [&](const Y& y, Y* dy) {
    Rhs(y, dy);
    return ++calls != 5;
  };
  Dop853Result<Y> r;
  Dop853Step(y0, k1, 0.1, failing, [](const Y&) {}, &r);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(calls, 12);
}

// Accepted steps whose error grows from step to step at a fixed length (a friction
// direction turning ever faster): the predictive factor extrapolates the trend and
// asks for a shorter step than the PI factor alone, so that the next step is not
// rejected; with a flat error history both agree.
TEST(PiStepControl, PredictsARisingErrorTrend) {
  PiStepControl flat(5), rising(5);
  const double h = 0.01;
  flat.Accepted(0.5, h);
  const double f_flat = flat.Accepted(0.5, h);
  rising.Accepted(0.25, h);
  const double f_rising = rising.Accepted(0.5, h);
  // With err 0.25 -> 0.5 at the same h, the error doubles a step: the next factor
  // is the PI one times (0.25 / 0.5)^(1/5).
  EXPECT_LT(f_rising, f_flat);
  EXPECT_NEAR(f_rising, 0.9 * std::pow(0.5, -0.2) * std::pow(0.5, 0.2), 1e-12);
  // Reset forgets the history: the predictive factor needs two accepted steps.
  rising.Reset();
  EXPECT_GT(rising.Accepted(0.5, h), f_rising);
  // A higher-order pair scales with the 8th root of the error.
  PiStepControl high(8);
  EXPECT_NEAR(high.Rejected(256.0), 0.9 * std::pow(256.0, -(1.0 / 8 - 0.75 * 0.04)), 1e-12);
}

// The LU of the Rosenbrock steps solves random 7x7 systems as Eigen's full-pivoting
// LU does, including ones that need row exchanges (a zero leading entry).
TEST(SmallLu, SolvesSmallSystemsLikeEigen) {
  using M = Eigen::Matrix<double, 7, 7>;
  using V = Eigen::Matrix<double, 7, 1>;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    M a;
    V b;
    for (int i = 0; i < 7; ++i) {
      b[i] = u(rng);
      for (int j = 0; j < 7; ++j) a(i, j) = u(rng);
    }
    if (trial % 2 == 0) a(0, 0) = 0;  // pivoting required
    const V x = SmallLu<M>(a).solve(b);
    const V y = a.fullPivLu().solve(b);
    EXPECT_LT((x - y).cwiseAbs().maxCoeff(), 1e-9 * (1 + y.cwiseAbs().maxCoeff())) << trial;
    EXPECT_LT((a * x - b).cwiseAbs().maxCoeff(), 1e-12) << trial;
  }
  // A singular matrix gives a non-finite answer, which the stepper rejects.
  M singular = M::Identity();
  singular(3, 3) = 0;
  EXPECT_FALSE(SmallLu<M>(singular).solve(V::Ones()).allFinite());
}

}  // namespace
}  // namespace snooker::physics::ode
