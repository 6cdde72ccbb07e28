#include "server/metrics.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "server/build_info.h"
#include "server/grpc_service.h"

namespace snooker::server {

int MethodIndex(std::string_view name) noexcept {
  for (std::size_t i = 0; i < kMethodCount; ++i) {
    if (name == kMethodNames[i]) return static_cast<int>(i);
  }
  return -1;
}

void MethodMetrics::Observe(int method, int code, double seconds) noexcept {
  if (method < 0 || static_cast<std::size_t>(method) >= kMethodCount) return;
  Method& m = methods_[static_cast<std::size_t>(method)];
  const std::size_t status = code >= 0 && static_cast<std::size_t>(code) < kStatusCodeCount
                                 ? static_cast<std::size_t>(code)
                                 : 2;  // UNKNOWN
  m.by_status[status].fetch_add(1, std::memory_order_relaxed);
  if (!(seconds >= 0)) seconds = 0;  // NaN or a clock that went back
  const std::size_t bucket = static_cast<std::size_t>(
      std::lower_bound(kLatencyBoundsSeconds.begin(), kLatencyBoundsSeconds.end(), seconds) -
      kLatencyBoundsSeconds.begin());
  m.latency[bucket].fetch_add(1, std::memory_order_relaxed);
  m.latency_ns.fetch_add(static_cast<std::int64_t>(std::min(seconds, 1e9) * 1e9), std::memory_order_relaxed);
}

std::array<MethodCounts, kMethodCount> MethodMetrics::Read() const noexcept {
  std::array<MethodCounts, kMethodCount> out;
  for (std::size_t i = 0; i < kMethodCount; ++i) {
    for (std::size_t c = 0; c < kStatusCodeCount; ++c) out[i].by_status[c] = methods_[i].by_status[c].load();
    for (std::size_t b = 0; b < kLatencyBuckets; ++b) out[i].latency[b] = methods_[i].latency[b].load();
    out[i].latency_seconds = static_cast<double>(methods_[i].latency_ns.load()) * 1e-9;
  }
  return out;
}

namespace {

// A metric's HELP and TYPE lines.
void Head(std::ostream& out, const char* name, const char* type, const char* help) {
  out << "# HELP " << name << ' ' << help << "\n# TYPE " << name << ' ' << type << '\n';
}

}  // namespace

std::string MetricsText(const CallCounts& counts, std::optional<std::int64_t> certificate_expiry) {
  std::ostringstream out;
  out.precision(9);  // the bounds as written, the sums to nine digits
  auto single = [&](const char* name, const char* type, const char* help, std::int64_t value) {
    Head(out, name, type, help);
    out << name << ' ' << value << '\n';
  };
  Head(out, "snooker_build_info", "gauge", "Which build serves: its version and commit (always 1).");
  out << "snooker_build_info{version=\"" << kBuildVersion << "\",commit=\"" << kBuildCommit << "\"} 1\n";
  single("snooker_calls_received_total", "counter", "Calls that reached a method.", counts.received);
  single("snooker_calls_in_flight", "gauge", "Calls received and not yet answered.", counts.in_flight());
  single("snooker_calls_running", "gauge", "Calls on a worker now.", counts.running);
  single("snooker_plans_in_server", "gauge", "Plan and PlanStream calls in the server now.", counts.plans);
  single("snooker_plan_progress_messages_total", "counter", "PlanStream progress messages written.",
         counts.progress_messages);
  single("snooker_plan_progress_dropped_total", "counter",
         "PlanStream progress messages replaced by a newer one before they were written.",
         counts.progress_dropped);
  single("snooker_plans_cut_short_total", "counter",
         "Plans the clock (budget or deadline) or a cancel stopped before their simulation cap: "
         "answered cut_short, or refused as their deadline passed before they started.",
         counts.plans_cut_short);
  single("snooker_log_lines_lost_total", "counter", "Call log lines the log refused (the calls were answered).",
         counts.log_lines_lost);
  if (certificate_expiry) {
    single("snooker_tls_certificate_expiry_timestamp_seconds", "gauge",
           "When the TLS certificate that new connections are presented expires (its notAfter), "
           "in s since the Unix epoch.",
           *certificate_expiry);
  }
  Head(out, "snooker_calls_total", "counter", "Calls answered, by method and gRPC status.");
  for (std::size_t m = 0; m < kMethodCount; ++m) {
    for (std::size_t c = 0; c < kStatusCodeCount; ++c) {
      const std::int64_t n = counts.methods[m].by_status[c];
      if (n == 0 && c != 0) continue;  // OK always, other statuses once seen
      out << "snooker_calls_total{method=\"" << kMethodNames[m] << "\",code=\""
          << StatusCodeName(static_cast<grpc::StatusCode>(c)) << "\"} " << n << '\n';
    }
  }
  Head(out, "snooker_call_latency_seconds", "histogram", "Time from a call's arrival to its answer, by method.");
  for (std::size_t m = 0; m < kMethodCount; ++m) {
    const MethodCounts& mc = counts.methods[m];
    std::int64_t cumulative = 0;
    for (std::size_t b = 0; b < kLatencyBuckets; ++b) {
      cumulative += mc.latency[b];
      out << "snooker_call_latency_seconds_bucket{method=\"" << kMethodNames[m] << "\",le=\"";
      if (b < kLatencyBoundsSeconds.size()) {
        out << kLatencyBoundsSeconds[b];
      } else {
        out << "+Inf";
      }
      out << "\"} " << cumulative << '\n';
    }
    out << "snooker_call_latency_seconds_sum{method=\"" << kMethodNames[m] << "\"} " << mc.latency_seconds << '\n';
    out << "snooker_call_latency_seconds_count{method=\"" << kMethodNames[m] << "\"} " << cumulative << '\n';
  }
  return out.str();
}

}  // namespace snooker::server
