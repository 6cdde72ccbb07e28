// The service's calls by method: how many ended with which status, and how long they
// took from arrival to answer (a histogram). Every call of either transport adds to
// them lock-free as it is answered; GET /metrics on the HTTP listener shows them,
// with the service's other counters, in Prometheus's text format (MetricsText).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace snooker::server {

/// The service's methods, in the order of their counts.
inline constexpr std::array<const char*, 6> kMethodNames{"Collide", "Simulate", "GetModel",
                                                         "Plan",    "PlanStream", "Calibrate"};
inline constexpr std::size_t kMethodCount = kMethodNames.size();
/// The histogram's upper bounds, s (a call of exactly a bound falls in its bucket);
/// the last bucket, past them all, is unbounded.
inline constexpr std::array<double, 12> kLatencyBoundsSeconds{0.001, 0.0025, 0.005, 0.01, 0.025, 0.05,
                                                              0.1,   0.25,   0.5,   1,    2.5,   10};
inline constexpr std::size_t kLatencyBuckets = kLatencyBoundsSeconds.size() + 1;
/// gRPC's status codes, 0 (OK) to 16 (UNAUTHENTICATED).
inline constexpr std::size_t kStatusCodeCount = 17;

/// A method's index in kMethodNames, or -1 for another name.
int MethodIndex(std::string_view name) noexcept;

/// One method's calls as read at one moment.
struct MethodCounts {
  std::array<std::int64_t, kStatusCodeCount> by_status{};  ///< answered calls by status code
  std::array<std::int64_t, kLatencyBuckets> latency{};      ///< calls per bucket (not cumulative)
  double latency_seconds = 0;                               ///< their latencies' sum
};

class MethodMetrics {
 public:
  /// Counts an answered call of `method` (MethodIndex; -1 is not counted) with gRPC
  /// status `code` that took `seconds`.
  void Observe(int method, int code, double seconds) noexcept;
  std::array<MethodCounts, kMethodCount> Read() const noexcept;

 private:
  struct Method {
    std::array<std::atomic<std::int64_t>, kStatusCodeCount> by_status{};
    std::array<std::atomic<std::int64_t>, kLatencyBuckets> latency{};
    std::atomic<std::int64_t> latency_ns{0};
  };
  std::array<Method, kMethodCount> methods_;
};

struct CallCounts;

/// `counts` in Prometheus's text format (version 0.0.4): the build, the calls received, in flight,
/// running and answered by method and status, the plans in the server, the progress
/// messages written and dropped, the plans cut short, the log lines lost, each method's latency
/// histogram (snooker_call_latency_seconds), and with TLS when the certificate served
/// expires (`certificate_expiry`, Unix s).
std::string MetricsText(const CallCounts& counts, std::optional<std::int64_t> certificate_expiry = std::nullopt);

}  // namespace snooker::server
