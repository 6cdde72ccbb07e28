// Whether the test is built with AddressSanitizer (CI's sanitizer build adds
// UndefinedBehaviorSanitizer with it): a few tests of limits the sanitizers' own
// runtime cannot live within skip there, saying why, and the longest seeded sweeps run
// a part of their cases there (SweepCases).
#pragma once

#if defined(__SANITIZE_ADDRESS__) || defined(__has_feature)
#if defined(__SANITIZE_ADDRESS__) || __has_feature(address_sanitizer)
#define SNOOKER_UNDER_ASAN 1
#endif
#endif

namespace snooker::sanitizers {

/// How many cases of a long seeded sweep to run: all of them in the plain build, the
/// first quarter under the sanitizers. Those look for memory errors and undefined
/// behaviour, which the paths of the first cases already take, and run each case many
/// times slower; the sweep's statistics are the plain build's.
constexpr int SweepCases(int all) {
#ifdef SNOOKER_UNDER_ASAN
  return all / 4;
#else
  return all;
#endif
}

}  // namespace snooker::sanitizers
