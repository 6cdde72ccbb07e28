// The service's metrics: each call counted by method and status, its latency in the
// histogram's right bucket, and the whole in Prometheus's text format (server/metrics.h).
#include "server/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "server/connect.h"
#include "server/grpc_service.h"
#include "tests/support/text.h"

namespace snooker::server {
namespace {

constexpr int kOk = 0, kInvalidArgument = 3;

TEST(MethodMetricsTest, ACallFallsInTheFirstBucketWhoseBoundHoldsIt) {
  MethodMetrics m;
  const int plan = MethodIndex("Plan");
  ASSERT_EQ(plan, 3);
  m.Observe(plan, kOk, 0.001);    // on a bound: that bucket
  m.Observe(plan, kOk, 0.0011);   // just past it: the next
  m.Observe(plan, kOk, 10);       // the last bound
  m.Observe(plan, kOk, 11);       // past every bound
  m.Observe(plan, kInvalidArgument, std::numeric_limits<double>::quiet_NaN());  // as 0
  m.Observe(plan, kOk, -1);       // a clock that went back: as 0
  const MethodCounts c = m.Read()[3];
  EXPECT_EQ(c.latency[0], 3);
  EXPECT_EQ(c.latency[1], 1);
  EXPECT_EQ(c.latency[kLatencyBuckets - 2], 1);
  EXPECT_EQ(c.latency[kLatencyBuckets - 1], 1);
  EXPECT_EQ(c.by_status[kOk], 5);
  EXPECT_EQ(c.by_status[kInvalidArgument], 1);
  EXPECT_NEAR(c.latency_seconds, 0.001 + 0.0011 + 10 + 11, 1e-9);
}

TEST(MethodMetricsTest, AnotherMethodOrStatusIsNotLostInAnother) {
  MethodMetrics m;
  EXPECT_EQ(MethodIndex("Dance"), -1);
  m.Observe(MethodIndex("Dance"), kOk, 0.01);  // not counted anywhere
  m.Observe(MethodIndex("Collide"), 99, 0.01);  // a status out of range: UNKNOWN (2)
  const auto all = m.Read();
  std::int64_t calls = 0;
  for (const MethodCounts& c : all) {
    for (const std::int64_t n : c.by_status) calls += n;
  }
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(all[0].by_status[2], 1);
}

// The methods counted are the service's own, in its order (proto/ is the API's one
// source): a method added there and not here would go uncounted. The HTTP side names
// the same list to a client that asks for another procedure.
TEST(MethodMetricsTest, TheMethodsAreTheServicesOwn) {
  std::ifstream proto(SNOOKER_SOURCE_DIR "/proto/snooker/v1/service.proto");
  ASSERT_TRUE(proto) << "cannot read service.proto";
  const std::string text((std::istreambuf_iterator<char>(proto)), std::istreambuf_iterator<char>());
  std::vector<std::string> rpcs;
  const std::regex rpc(R"(\n\s*rpc\s+(\w+)\s*\()");
  for (auto m = std::sregex_iterator(text.begin(), text.end(), rpc); m != std::sregex_iterator(); ++m) {
    rpcs.push_back((*m)[1].str());
  }
  ASSERT_EQ(rpcs.size(), kMethodCount);
  std::string listed;
  for (std::size_t i = 0; i < kMethodCount; ++i) {
    EXPECT_EQ(rpcs[i], kMethodNames[i]);
    EXPECT_EQ(MethodIndex(kMethodNames[i]), static_cast<int>(i));
    listed += (i == 0 ? "" : ", ") + std::string(kMethodNames[i]);
  }
  EXPECT_EQ(MethodIndex("Teleport"), -1);
  EXPECT_EQ(connect::ProcedureNames(), listed);
}

// Every line is a comment or `name{labels} value`; each metric has its HELP and TYPE;
// a histogram's buckets never fall and its +Inf bucket is its count.
TEST(MetricsTextTest, IsPrometheusTextWithCumulativeBuckets) {
  MethodMetrics m;
  m.Observe(MethodIndex("Simulate"), kOk, 0.004);
  m.Observe(MethodIndex("Simulate"), kOk, 0.2);
  m.Observe(MethodIndex("Simulate"), kInvalidArgument, 0.0001);
  CallCounts counts;
  counts.received = 4;
  counts.finished = 3;
  counts.methods = m.Read();
  constexpr std::int64_t kExpiry = 1796083200;  // 2026-12-01T00:00:00Z
  const std::string text = MetricsText(counts, kExpiry);
  EXPECT_FALSE(Mentions(MetricsText(counts), "snooker_tls_certificate_expiry")) << "without TLS";

  const std::regex sample(R"(^([a-z_]+)(\{[a-zA-Z_]+="[^"]*"(,[a-zA-Z_]+="[^"]*")*\})? (-?[0-9.e+-]+)$)");
  const std::regex comment(R"(^# (HELP|TYPE) ([a-z_]+) .+$)");
  std::map<std::string, int> typed;
  std::map<std::string, double> value;  // a sample's value by its name and labels
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::smatch s;
    if (std::regex_match(line, s, comment)) {
      if (s[1] == "TYPE") typed[s[2]] += 1;
      continue;
    }
    ASSERT_TRUE(std::regex_match(line, s, sample)) << line;
    std::string family = s[1];
    for (const char* suffix : {"_bucket", "_sum", "_count"}) {
      if (family.ends_with(suffix) && typed.count(family.substr(0, family.size() - std::strlen(suffix)))) {
        family = family.substr(0, family.size() - std::strlen(suffix));
      }
    }
    EXPECT_EQ(typed[family], 1) << "no TYPE before " << line;
    value[std::string(s[1]) + std::string(s[2])] = std::stod(s[4]);
  }
  EXPECT_EQ(value["snooker_calls_received_total"], 4);
  EXPECT_EQ(value["snooker_tls_certificate_expiry_timestamp_seconds"], kExpiry);
  EXPECT_EQ(value["snooker_calls_in_flight"], 1);
  EXPECT_EQ(value[R"(snooker_calls_total{method="Simulate",code="OK"})"], 2);
  EXPECT_EQ(value[R"(snooker_calls_total{method="Simulate",code="INVALID_ARGUMENT"})"], 1);
  EXPECT_EQ(value.count(R"(snooker_calls_total{method="Plan",code="INVALID_ARGUMENT"})"), 0u);
  for (const char* method : kMethodNames) {
    const std::string labels = std::string("{method=\"") + method + "\"";
    double previous = 0;
    for (std::size_t b = 0; b < kLatencyBuckets; ++b) {
      std::ostringstream le;
      le << ",le=\"";
      if (b + 1 < kLatencyBuckets) {
        le << kLatencyBoundsSeconds[b];
      } else {
        le << "+Inf";
      }
      const std::string key = "snooker_call_latency_seconds_bucket" + labels + le.str() + "\"}";
      ASSERT_TRUE(value.count(key)) << key;
      EXPECT_GE(value[key], previous) << key;
      previous = value[key];
    }
    EXPECT_EQ(previous, value["snooker_call_latency_seconds_count" + labels + "}"]) << method;
  }
  EXPECT_EQ(value[R"(snooker_call_latency_seconds_bucket{method="Simulate",le="0.001"})"], 1);
  EXPECT_EQ(value[R"(snooker_call_latency_seconds_bucket{method="Simulate",le="0.005"})"], 2);
  EXPECT_EQ(value[R"(snooker_call_latency_seconds_bucket{method="Simulate",le="0.1"})"], 2);
  EXPECT_EQ(value[R"(snooker_call_latency_seconds_bucket{method="Simulate",le="0.25"})"], 3);
  EXPECT_NEAR(value[R"(snooker_call_latency_seconds_sum{method="Simulate"})"], 0.2041, 1e-8);
}

}  // namespace
}  // namespace snooker::server
