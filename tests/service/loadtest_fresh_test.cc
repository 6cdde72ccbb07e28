// `snooker loadtest` against freshly started servers, several times over: a fresh
// `snooker serve` process and a fresh client process each run, so that what a
// process does once (its start, its first connections, made by 8 client threads at
// once) happens in every run. Every call of every run must be answered OK: a client
// connection taken for failed while it was being made (cli/client.cc,
// SetUpBeforeTheFirstConnection) shows here as UNAVAILABLE calls. Each run is bounded
// in time (`timeout`, and the load test's --max-seconds).
#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <string>

#include "tests/support/cli_support.h"

namespace snooker {
namespace {

using cli_support::RunResult;
using cli_support::RunShell;

struct FreshRun {
  const char* method;
  int requests;  ///< calls per run
};

// gtest prints a parameter with this (not as bytes).
void PrintTo(const FreshRun& c, std::ostream* os) { *os << c.method << ", " << c.requests << " calls a run"; }

constexpr int kRuns = 4;
constexpr int kConcurrency = 8;

// One run: a server on a free loopback port, the load test against it (its JSON
// answer on stdout), SIGTERM to the server; then "exits: LOADTEST SERVER".
RunResult OneFreshRun(const FreshRun& run, int index) {
  const std::string cli = SNOOKER_CLI_PATH;
  const std::string dir =
      cli_support::TempPath(std::string("loadtest_fresh_") + run.method + "_" + std::to_string(index));
  return RunShell(
      "rm -rf " + dir + " && mkdir -p " + dir + " && "
      "timeout -s KILL 120 " + cli + " serve --address 127.0.0.1:0 >" + dir + "/serve.out 2>" + dir +
      "/serve.log & pid=$!; " + cli_support::kWaitForPort(dir + "/serve.out") +
      "timeout -s KILL 90 " + cli + " loadtest --target 127.0.0.1:$port --method " + run.method +
      " --concurrency " + std::to_string(kConcurrency) + " --requests " + std::to_string(run.requests) +
      " --max-seconds 60 --json; rc=$?; kill -TERM $pid; wait $pid; src=$?; "
      "echo \"exits: $rc $src\"; rm -rf " + dir);
}

class LoadTestFreshServerTest : public testing::TestWithParam<FreshRun> {};

TEST_P(LoadTestFreshServerTest, EveryCallOfEveryRunIsAnsweredOk) {
  const FreshRun run = GetParam();
  for (int i = 1; i <= kRuns; ++i) {
    SCOPED_TRACE("run " + std::to_string(i) + " of " + std::to_string(kRuns));
    const RunResult r = OneFreshRun(run, i);
    const std::size_t exits = r.out.rfind("exits: ");
    ASSERT_NE(exits, std::string::npos) << r.out << r.err;
    EXPECT_EQ(r.out.substr(exits), "exits: 0 0\n") << r.out << r.err;
    google::protobuf::Struct j;
    ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out.substr(0, exits), &j).ok()) << r.out;
    const auto& f = j.fields();
    for (const char* name : {"completed", "errors", "badAnswers", "statuses", "healthBefore", "healthAfter"}) {
      ASSERT_TRUE(f.count(name)) << name << " missing: " << r.out;
    }
    EXPECT_EQ(f.at("completed").number_value(), run.requests) << r.out;
    EXPECT_EQ(f.at("errors").number_value(), 0) << r.out;
    EXPECT_EQ(f.at("badAnswers").number_value(), 0) << r.out;
    const auto& statuses = f.at("statuses").struct_value().fields();
    EXPECT_EQ(statuses.size(), 1u) << r.out;  // OK only
    EXPECT_EQ(statuses.count("OK") ? statuses.at("OK").number_value() : 0, run.requests) << r.out;
    EXPECT_EQ(f.at("healthBefore").string_value(), "SERVING");
    EXPECT_EQ(f.at("healthAfter").string_value(), "SERVING");
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, LoadTestFreshServerTest,
                         testing::Values(FreshRun{"simulate", 300}, FreshRun{"plan", 120}),
                         [](const testing::TestParamInfo<FreshRun>& p) {
                           return std::string(p.param.method);
                         });

}  // namespace
}  // namespace snooker
