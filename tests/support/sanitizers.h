// Whether the test is built with AddressSanitizer (CI's sanitizer build adds
// UndefinedBehaviorSanitizer with it): a few tests of limits the sanitizers' own
// runtime cannot live within skip there, saying why.
#pragma once

#if defined(__SANITIZE_ADDRESS__) || defined(__has_feature)
#if defined(__SANITIZE_ADDRESS__) || __has_feature(address_sanitizer)
#define SNOOKER_UNDER_ASAN 1
#endif
#endif
