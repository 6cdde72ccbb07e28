// What the impact solvers' fuzz targets share: a broken law's report, the decoding of
// values (mostly physical, sometimes anything a double holds), the validator's law and
// a bitwise comparison of ball motions that counts NaN as equal to NaN.
#pragma once

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "physics/core/types.h"
#include "physics/impact/impulse_solver.h"

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

/// The law every solver's validator keeps: it names a bad value (`validation` is not
/// empty) exactly when the solver rejects the input.
inline void CheckValidatorAgrees(const std::string& validation, physics::ImpactStatus status) {
  const bool named = !validation.empty();
  if (named != (status == physics::ImpactStatus::kInvalidInput)) {
    Fail("validator names a bad value exactly when the solver rejects", named, static_cast<double>(status));
  }
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
