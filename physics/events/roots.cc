#include "physics/events/roots.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace snooker::physics {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();

// Horner's rule on a degree-4 polynomial errs by at most gamma_8 ~ 4 eps times
// sum |c_i| |t|^i; the derivative coefficients (3 c_3, 6 c_3, ...) carry one more
// rounding each. 16 eps covers both with a safety factor of about 3. A value this
// close to zero is zero as far as floating point can tell.
constexpr double kZeroBandFactor = 16.0 * kEps;

// Safeguarded Newton halves the bracket at least every other step, so 200 steps
// reach adjacent doubles from any finite bracket (2^-100 of its width) long
// before the cap; the cap only guards against a logic error.
constexpr int kMaxRefineIterations = 200;

// Working storage for one level of the derivative recursion. A level normally
// holds at most 4 roots; the spare room absorbs numerically flat polynomials,
// which are reported as kDegenerate.
constexpr int kBufferSize = 8;

// Cauchy's bound is exact in real arithmetic; the margin covers the rounding of
// the coefficient ratios.
constexpr double kRootBoundMargin = 1.0625;

struct Buffer {
  std::array<double, kBufferSize> t{};
  int count = 0;
  bool overflow = false;

  void Push(double x) {
    if (count < kBufferSize) {
      t[count++] = x;
    } else {
      overflow = true;
    }
  }
};

bool AllFinite(const Poly4& p) {
  return std::all_of(p.begin(), p.end(), [](double c) { return std::isfinite(c); });
}

bool AllZero(const Poly4& p) {
  return std::all_of(p.begin(), p.end(), [](double c) { return c == 0.0; });
}

// sum |c_i| |t|^i: the scale of the rounding error of EvaluatePoly(p, t).
double EvaluateAbs(const Poly4& p, double t) {
  const double a = std::abs(t);
  double s = std::abs(p[kMaxPolyDegree]);
  for (int i = kMaxPolyDegree - 1; i >= 0; --i) s = s * a + std::abs(p[i]);
  return s;
}

bool IsNumericallyZero(const Poly4& p, double t, double value) {
  return std::abs(value) <= kZeroBandFactor * EvaluateAbs(p, t);
}

// The root of q in [a, b], where q is monotone, q(a) has the sign `a_positive`
// and q(b) the other one. Newton's method from the midpoint; a Newton step that
// leaves the bracket or does not halve the previous step becomes a bisection.
double RefineRoot(const Poly4& q, const Poly4& dq, double a, double b, bool a_positive,
                  bool* capped) {
  double x = a + 0.5 * (b - a);
  double last_step = b - a;
  for (int i = 0; i < kMaxRefineIterations; ++i) {
    const double fx = EvaluatePoly(q, x);
    if (fx == 0.0) return x;
    if ((fx > 0.0) == a_positive) {
      a = x;
    } else {
      b = x;
    }
    const double mid = a + 0.5 * (b - a);
    if (mid <= a || mid >= b) return x;  // a and b are adjacent doubles
    double next = mid;
    const double dfx = EvaluatePoly(dq, x);
    if (dfx != 0.0) {
      const double newton = x - fx / dfx;
      if (newton > a && newton < b && std::abs(newton - x) <= 0.5 * last_step) next = newton;
    }
    if (next == x) return x;  // the Newton correction is below one ulp
    last_step = std::abs(next - x);
    x = next;
  }
  *capped = true;
  return a + 0.5 * (b - a);
}

// Roots of q on [lo, hi] given `crit`, the increasing roots of q' (any that are
// not strictly inside (lo, hi) are ignored). q is monotone between consecutive
// points of {lo, crit..., hi}: a point where q is numerically zero is a root, and
// a piece whose ends have opposite nonzero signs holds exactly one root.
void RootsOnPieces(const Poly4& q, const Poly4& dq, double lo, double hi, const Buffer& crit,
                   Buffer* out, bool* capped) {
  std::array<double, kBufferSize + 2> x{};
  int n = 0;
  x[n++] = lo;
  for (int i = 0; i < crit.count; ++i) {
    if (crit.t[i] > x[n - 1] && crit.t[i] < hi) x[n++] = crit.t[i];
  }
  if (hi > lo) x[n++] = hi;

  std::array<double, kBufferSize + 2> v{};
  std::array<bool, kBufferSize + 2> zero{};
  for (int i = 0; i < n; ++i) {
    v[i] = EvaluatePoly(q, x[i]);
    zero[i] = IsNumericallyZero(q, x[i], v[i]);
  }
  for (int i = 0; i < n; ++i) {
    if (zero[i]) out->Push(x[i]);
    if (i + 1 < n && !zero[i] && !zero[i + 1] && (v[i] > 0.0) != (v[i + 1] > 0.0)) {
      out->Push(RefineRoot(q, dq, x[i], x[i + 1], v[i] > 0.0, capped));
    }
  }
}

}  // namespace

const char* ToString(RootStatus s) {
  switch (s) {
    case RootStatus::kOk: return "ok";
    case RootStatus::kIdenticallyZero: return "identically zero";
    case RootStatus::kInvalidInput: return "invalid input";
    case RootStatus::kIterationCap: return "iteration cap reached";
    case RootStatus::kDegenerate: return "degenerate";
  }
  return "unknown";
}

double EvaluatePoly(const Poly4& p, double t) {
  double s = p[kMaxPolyDegree];
  for (int i = kMaxPolyDegree - 1; i >= 0; --i) s = s * t + p[i];
  return s;
}

Poly4 DifferentiatePoly(const Poly4& p) {
  Poly4 d{};
  for (int i = 1; i <= kMaxPolyDegree; ++i) d[i - 1] = static_cast<double>(i) * p[i];
  return d;
}

double RootBound(const Poly4& p) {
  int n = kMaxPolyDegree;
  while (n > 0 && p[n] == 0.0) --n;
  if (n == 0) return p[0] == 0.0 ? kInf : 0.0;
  double m = 0.0;
  for (int i = 0; i < n; ++i) m = std::max(m, std::abs(p[i] / p[n]));
  return (1.0 + m) * kRootBoundMargin;
}

RealRoots FindRealRoots(const Poly4& p, double lo, double hi) {
  RealRoots r;
  if (!AllFinite(p) || std::isnan(lo) || std::isnan(hi) || lo > hi) {
    r.status = RootStatus::kInvalidInput;
    return r;
  }
  if (AllZero(p)) {
    r.status = RootStatus::kIdenticallyZero;
    return r;
  }
  const double bound = RootBound(p);
  if (std::isinf(lo)) lo = -bound;
  if (std::isinf(hi)) hi = bound;
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    r.status = RootStatus::kInvalidInput;
    return r;
  }
  if (lo > hi) return r;  // an infinite end was clamped past the other: no root

  // d[k] is the k-th derivative; d[kMaxPolyDegree] is a constant with no root.
  std::array<Poly4, kMaxPolyDegree + 1> d{};
  d[0] = p;
  for (int k = 1; k <= kMaxPolyDegree; ++k) d[k] = DifferentiatePoly(d[k - 1]);

  bool capped = false;
  bool overflow = false;
  Buffer crit;  // roots of d[k + 1]
  for (int k = kMaxPolyDegree - 1; k >= 0; --k) {
    Buffer roots;
    // An identically zero derivative has no isolated roots: d[k - 1] is constant.
    if (!AllZero(d[k])) RootsOnPieces(d[k], d[k + 1], lo, hi, crit, &roots, &capped);
    overflow = overflow || roots.overflow;
    crit = roots;
  }

  r.count = std::min(crit.count, kMaxPolyDegree);
  for (int i = 0; i < r.count; ++i) r.t[i] = crit.t[i];
  if (crit.count > kMaxPolyDegree || overflow) {
    r.status = RootStatus::kDegenerate;
  } else if (capped) {
    r.status = RootStatus::kIterationCap;
  }
  return r;
}

namespace {

// FindFirstDownCrossing for p of degree <= 2 (p[3] = p[4] = 0) in closed form: the
// cushion gaps are quadratics in time, and this is most of the detectors' calls.
// The roots come from the cancellation-free formula (q = -(b + sign(b) sqrt(D)) / 2,
// roots q / a and c / q), accurate to a few ulps; a discriminant that rounding made
// negative at a vertex where |p| is within rounding of zero is a tangency, as in
// the general solver.
double FirstDownCrossingQuadratic(const Poly4& p, double lo, double hi) {
  const double c = p[0], b = p[1], a = p[2];
  auto in = [&](double r) { return r > lo && r <= hi; };
  if (a == 0.0) {
    if (!(b < 0.0)) return kInf;  // constant or rising: no down-crossing
    const double r = -c / b;
    return in(r) ? r : kInf;      // p > 0 just before r exactly when r > lo
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) {
    if (a < 0.0) return kInf;  // negative everywhere
    const double t = -b / (2.0 * a);
    const double value = c + t * (b + t * a);
    const double scale = std::abs(c) + std::abs(b * t) + std::abs(a * t * t);
    return in(t) && std::abs(value) <= kZeroBandFactor * scale ? t : kInf;
  }
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  double r1 = q / a, r2 = q != 0.0 ? c / q : r1;
  if (r1 > r2) std::swap(r1, r2);
  // Convex: positive before r1 (a down-crossing at r1, or a tangency when r1 = r2).
  // Concave: positive only between the roots (a down-crossing at r2, if p is
  // positive somewhere in (lo, r2)).
  if (a > 0.0) return in(r1) ? r1 : kInf;
  return in(r2) && r1 < r2 ? r2 : kInf;
}

// True when p is certainly positive on [lo, hi], beyond the band in which the
// general solver takes a value for zero: p's Bernstein coefficients on the interval
// bound it from below (the convex-hull property), so all of them above 4x that band
// prove there is no root and no tangency. About 40 flops, against ~1,500
// instructions for the roots; most quartic gaps that pass the detectors' culls have
// no contact, and the answer (+infinity) is the same either way.
bool CertainlyPositive(const Poly4& p, double lo, double hi) {
  const double h = hi - lo;
  // Taylor coefficients at lo, scaled to s in [0, 1]: p(lo + h s) = sum c_k s^k.
  std::array<double, kMaxPolyDegree + 1> c = p;
  for (int k = 0; k < kMaxPolyDegree; ++k) {  // synthetic division by (t - lo), repeated
    for (int i = kMaxPolyDegree - 1; i >= k; --i) c[i] += lo * c[i + 1];
  }
  double hk = 1.0;
  for (double& ck : c) {
    ck *= hk;
    hk *= h;
  }
  const double b[5] = {c[0], c[0] + c[1] / 4, c[0] + c[1] / 2 + c[2] / 6,
                       c[0] + 0.75 * c[1] + c[2] / 2 + c[3] / 4, c[0] + c[1] + c[2] + c[3] + c[4]};
  const double scale = EvaluateAbs(p, std::max(std::abs(lo), std::abs(hi)));
  const double floor = 4.0 * kZeroBandFactor * scale;
  for (double bi : b) {
    if (!(bi > floor)) return false;
  }
  return true;
}

}  // namespace

double FindFirstDownCrossing(const Poly4& p, double lo, double hi) {
  if (!std::isfinite(lo) || !(hi > lo)) return kInf;
  if (p[3] == 0.0 && p[4] == 0.0 && std::isfinite(p[0]) && std::isfinite(p[1]) &&
      std::isfinite(p[2]) && !std::isnan(hi)) {
    return FirstDownCrossingQuadratic(p, lo, hi);
  }
  if (std::isfinite(hi) && AllFinite(p) && CertainlyPositive(p, lo, hi)) return kInf;
  const RealRoots r = FindRealRoots(p, lo, hi);
  if (r.status == RootStatus::kInvalidInput || r.status == RootStatus::kIdenticallyZero) {
    return kInf;
  }
  // Between consecutive roots p keeps one sign; its value midway tells which.
  double prev = lo;
  for (int i = 0; i < r.count; ++i) {
    const double root = r.t[i];
    if (root <= lo) continue;
    if (EvaluatePoly(p, prev + 0.5 * (root - prev)) > 0.0) return root;
    prev = root;
  }
  return kInf;
}

}  // namespace snooker::physics
