#include "server/request_id.h"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <random>

#include "physics/core/splitmix64.h"

namespace snooker::server {

bool IsPrintableRequestId(std::string_view id) {
  if (id.empty() || id.size() > kMaxRequestIdBytes) return false;
  for (const char c : id) {
    const bool alnum = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (!alnum && std::string_view("-_.:/+=@").find(c) == std::string_view::npos) return false;
  }
  return true;
}

namespace {
std::uint64_t RandomStart() noexcept {
  try {
    std::random_device device;
    return (static_cast<std::uint64_t>(device()) << 32) ^ device();
  } catch (...) {  // no entropy source: the clock still separates two processes
    return static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  }
}
}  // namespace

std::string NewRequestId() {
  static const std::uint64_t start = RandomStart();
  static std::atomic<std::uint64_t> next{0};
  // SplitMix64's step is a bijection of its state: distinct counters, distinct ids.
  std::uint64_t state = start + next.fetch_add(1, std::memory_order_relaxed);
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(physics::SplitMix64(state)));
  return text;
}

std::string RequestIdFor(std::string_view given) {
  return IsPrintableRequestId(given) ? std::string(given) : NewRequestId();
}

}  // namespace snooker::server
