// What the impact solvers' fuzz targets share: a broken law's report, the decoding of
// values (mostly physical, sometimes anything a double holds) and a bitwise comparison
// of ball motions that counts NaN as equal to NaN.
#pragma once

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "physics/core/types.h"

namespace snooker::fuzz {

/// Reports the broken law and aborts (libFuzzer then keeps the input as crash-*).
[[noreturn]] inline void Fail(const char* what, double a, double b) {
  std::fprintf(stderr, "law broken: %s (%.17g vs %.17g)\n", what, a, b);
  std::abort();
}

/// A value in [lo, hi], or one time in sixteen any double at all (NaN, inf, huge).
inline double Value(FuzzedDataProvider& in, double lo, double hi) {
  if (in.ConsumeIntegralInRange<int>(0, 15) == 0) return in.ConsumeFloatingPoint<double>();
  return in.ConsumeFloatingPointInRange<double>(lo, hi);
}

inline physics::Vec3 Vector(FuzzedDataProvider& in, double bound) {
  return physics::Vec3(Value(in, -bound, bound), Value(in, -bound, bound), Value(in, -bound, bound));
}

/// Equal bit for bit, NaN matching NaN: what "returned unchanged" means.
inline bool Same(const physics::BallMotion& a, const physics::BallMotion& b) {
  auto same = [](const physics::Vec3& x, const physics::Vec3& y) {
    for (int i = 0; i < 3; ++i) {
      if (!(x[i] == y[i] || (std::isnan(x[i]) && std::isnan(y[i])))) return false;
    }
    return true;
  };
  return same(a.v, b.v) && same(a.w, b.w);
}

}  // namespace snooker::fuzz
