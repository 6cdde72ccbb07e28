// Real roots of polynomials of degree <= 4 on a closed interval, for the event
// detectors (physics/events/detect.h).
//
// Why this method: closed-form quartic and cubic formulas lose most of their digits
// near double roots (a ball grazing another) and when the leading coefficient is
// tiny (a ball that barely decelerates), which are exactly the cases a simulator
// meets. Instead the roots are isolated by recursion on derivatives: the real roots
// of p' split [lo, hi] into pieces on which p is monotone, so each piece holds at
// most one root, found by Newton's method safeguarded by bisection (the bracket
// never grows, so it always converges) to full double precision. A zero or tiny
// leading coefficient needs no special case: the recursion then simply finds no
// critical point inside the interval.
//
// Double roots: a critical point where |p| lies within the rounding error of
// evaluating p there is reported as a root (once). So a tangency is found even
// though p may never change sign in floating point.
//
// Hot path: no allocation, no exception, no virtual call; every loop has a cap.
#pragma once

#include <array>
#include <cstdint>

namespace snooker::physics {

/// Highest polynomial degree handled.
inline constexpr int kMaxPolyDegree = 4;

/// Coefficients of p(t) = c[0] + c[1] t + c[2] t^2 + c[3] t^3 + c[4] t^4, lowest
/// degree first. Units are those of the caller (t in s for the detectors).
using Poly4 = std::array<double, kMaxPolyDegree + 1>;

enum class RootStatus : std::uint8_t {
  kOk,
  /// Every coefficient is zero: every t is a root; no root is listed.
  kIdenticallyZero,
  /// lo > hi, a NaN bound, or a coefficient that is not finite; no root is listed.
  kInvalidInput,
  /// A refinement reached its iteration cap; that root is the midpoint of its
  /// last bracket (still inside the right piece).
  kIterationCap,
  /// p is zero to rounding error at more points than its degree allows (it is
  /// numerically flat on the interval); the first kMaxPolyDegree are listed.
  kDegenerate,
};

const char* ToString(RootStatus s);

/// Real roots in increasing order. A multiple root is listed once, except where p
/// is flat to rounding error around it (a root of multiplicity 3 or 4 over a tiny
/// interval), which may list a few points of that flat stretch.
struct RealRoots {
  std::array<double, kMaxPolyDegree> t{};
  int count = 0;
  RootStatus status = RootStatus::kOk;
};

/// p(t) by Horner's rule.
double EvaluatePoly(const Poly4& p, double t);

/// The derivative p'(t), same layout (its c[4] is zero).
Poly4 DifferentiatePoly(const Poly4& p);

/// A bound B with every real root of p in [-B, B] (Cauchy's bound on the
/// polynomial without its zero leading coefficients). +infinity when p is
/// identically zero or its bound overflows; 0 when p is a nonzero constant.
double RootBound(const Poly4& p);

/// The real roots of p in the closed interval [lo, hi], increasing. An infinite
/// bound is replaced by RootBound(p). Roots at lo or hi are included.
RealRoots FindRealRoots(const Poly4& p, double lo, double hi);

/// The first time in (lo, hi] at which p goes from > 0 to <= 0: the smallest root
/// r in (lo, hi] such that p > 0 just before r (a sign change or a tangency from
/// above). lo itself is never returned: a caller that cares whether p is already
/// <= 0 at lo checks that itself. +infinity when there is none, when hi <= lo, or
/// on invalid input.
double FindFirstDownCrossing(const Poly4& p, double lo, double hi);

}  // namespace snooker::physics
