// The `snooker` command as a user (or a tool outside the project) runs it: the JSON
// field names are a contract, bad input gets a message naming the value and a
// non-zero exit.
#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "server/build_info.h"
#include "tests/physics/impact/paper_shots.h"
#include "tests/support/cli_support.h"
#include "tests/support/sanitizers.h"

namespace snooker {
namespace {

using cli_support::RunCli;
using cli_support::RunResult;
using cli_support::TempFile;

using google::protobuf::Struct;
using google::protobuf::Value;

const Value& Field(const Struct& s, const std::string& name) {
  static const Value kMissing;
  const auto it = s.fields().find(name);
  EXPECT_NE(it, s.fields().end()) << "missing JSON field '" << name << "'";
  return it == s.fields().end() ? kMissing : it->second;
}

double Number(const Struct& s, const std::string& name) {
  const Value& v = Field(s, name);
  EXPECT_EQ(v.kind_case(), Value::kNumberValue) << name;
  return v.number_value();
}

const Struct& Object(const Struct& s, const std::string& name) {
  const Value& v = Field(s, name);
  EXPECT_EQ(v.kind_case(), Value::kStructValue) << name;
  return v.struct_value();
}

// The field names the issue spells out, checked on one ball.
void ExpectBallContract(const Struct& ball) {
  for (const char* vec : {"velocity", "angularVelocity"}) {
    const Struct& v = Object(ball, vec);
    for (const char* c : {"x", "y", "z"}) EXPECT_TRUE(std::isfinite(Number(v, c))) << vec << c;
  }
  const Struct& slip = Object(ball, "slipEnd");
  const Struct& v = Object(slip, "velocity");
  EXPECT_TRUE(std::isfinite(Number(v, "x")));
  EXPECT_TRUE(std::isfinite(Number(v, "y")));
  for (const char* f : {"speed", "exitAngleDeg", "time"}) {
    EXPECT_TRUE(std::isfinite(Number(slip, f))) << f;
  }
}

TEST(CliCollideTest, JsonReproducesThePapersTablesWithTheContractedNames) {
  for (const physics::PaperShot& s : physics::kPaperShots) {
    std::ostringstream args;
    args.precision(17);
    args << "collide --speed " << s.speed << " --topspin " << s.speed / 0.02625 << " --cut-deg "
         << s.cut_deg << " --json";
    const RunResult r = RunCli(args.str());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    Struct json;
    ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &json).ok()) << r.out;
    ExpectBallContract(Object(json, "cue"));
    ExpectBallContract(Object(json, "object"));
    EXPECT_GT(Number(json, "impulseSteps"), 0);
    EXPECT_GT(Number(json, "rhsEvaluations"), 0);
    const Struct& cue = Object(Object(json, "cue"), "slipEnd");
    const Struct& obj = Object(Object(json, "object"), "slipEnd");
    EXPECT_NEAR(Number(cue, "speed"), s.predicted_cue_speed, 0.005);
    EXPECT_NEAR(Number(obj, "speed"), s.predicted_object_speed, 0.005);
    EXPECT_NEAR(Number(cue, "exitAngleDeg"), s.predicted_cue_exit_deg, 0.05);
    EXPECT_NEAR(Number(obj, "exitAngleDeg"), s.predicted_object_exit_deg, 0.05);
  }
}

TEST(CliCollideTest, FixedStepSchemeThroughTheCommandLine) {
  const RunResult r = RunCli("collide --speed 1.539 --topspin 58.6286 --cut-deg 33.83 --steps 10000 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Struct json;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &json).ok());
  EXPECT_NEAR(Number(Object(Object(json, "cue"), "slipEnd"), "exitAngleDeg"), 31.93, 0.05);
  EXPECT_NEAR(Number(json, "impulseSteps"), 5000, 100);
}

TEST(CliCollideTest, ReadableTableByDefault) {
  const RunResult r = RunCli("collide --speed 1.539 --topspin 58.6286 --cut-deg 33.83");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("exit angle (deg)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("31.92"), std::string::npos) << r.out;
}

struct BadInput {
  const char* name;  // the test's name in ctest
  const char* args;
  const char* must_mention;
};

// gtest prints a parameter with this (not as bytes).
void PrintTo(const BadInput& b, std::ostream* os) { *os << "collide " << b.args; }

class CliBadInputTest : public testing::TestWithParam<BadInput> {};

TEST_P(CliBadInputTest, ExitsNonZeroNamingTheValue) {
  const RunResult r = RunCli(std::string("collide ") + GetParam().args);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(GetParam().must_mention), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CliBadInputTest,
    testing::Values(BadInput{"SpeedNotANumber", "--speed fast", "--speed 'fast' is not a number"},
                    BadInput{"CutWithTrailingText", "--speed 1 --cut-deg 12x", "--cut-deg '12x'"},
                    BadInput{"SpeedNaN", "--speed nan", "--speed 'nan' is not a finite number"},
                    BadInput{"SpeedInfinite", "--speed inf", "--speed 'inf'"},
                    BadInput{"SpeedNegative", "--speed -2", "--speed -2"},
                    BadInput{"SpeedZero", "--speed 0", "--speed 0"},
                    BadInput{"SpeedTooLarge", "--speed 1e308", "--speed 1e+308"},
                    BadInput{"SpeedTooSmall", "--speed 1e-300", "--speed 1e-300"},
                    BadInput{"Cut90", "--speed 1 --cut-deg 90", "--cut-deg 90"},
                    BadInput{"Cut120", "--speed 1 --cut-deg 120", "--cut-deg 120"},
                    BadInput{"CutMinus95", "--speed 1 --cut-deg -95", "--cut-deg -95"},
                    BadInput{"StepsZero", "--speed 1 --steps 0", "--steps 0"},
                    BadInput{"StepsFraction", "--speed 1 --steps 2.5", "--steps '2.5'"},
                    BadInput{"StepsBeyondTheCap", "--speed 1 --steps 536870911",
                             "--steps 536870911 is out of range [1, 10000000]"},
                    BadInput{"FrictionAboveOne", "--speed 1 --mu-bb 3", "--mu-bb 3"},
                    BadInput{"RestitutionAboveOne", "--speed 1 --restitution 1.2", "--restitution 1.2"},
                    BadInput{"ToleranceZero", "--speed 1 --tolerance 0", "--tolerance 0"},
                    BadInput{"SpeedMissing", "--cut-deg 10", "--speed is required"},
                    BadInput{"UnknownOption", "--speed 1 --spin 3", "unknown option --spin"},
                    BadInput{"SpeedWithoutValue", "--speed", "--speed needs a value"},
                    BadInput{"SpeedEmpty", "--speed ''", "--speed needs a value; it was given an empty one"},
                    BadInput{"MuSBelowTheCloths", "--speed 1 --mu-s 1e-320", "--mu-s 1e-320: must be in [0.01, 1]"}),
    [](const testing::TestParamInfo<BadInput>& p) { return std::string(p.param.name); });

TEST(CliCollideTest, HelpExplainsEveryOptionWithItsUnit) {
  const RunResult r = RunCli("collide --help");
  ASSERT_EQ(r.exit_code, 0);
  for (const char* s : {"--speed V0", "m/s", "--topspin wT", "rad/s", "--sidespin wS",
                        "--cut-deg THETA", "degrees", "--steps N", "--tolerance X", "--mu-bb X",
                        "--restitution E", "--mu-s X", "--json"}) {
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
  }
}

TEST(CliTest, VersionNamesTheBuildsVersionAndCommit) {
  for (const char* flag : {"--version", "version"}) {
    const RunResult r = RunCli(flag);
    EXPECT_EQ(r.exit_code, 0) << flag;
    EXPECT_EQ(r.out, std::string("snooker ") + SNOOKER_VERSION + " (commit " + server::kBuildCommit + ")\n") << flag;
  }
}

TEST(CliTest, UnknownCommandIsAUsageError) {
  const RunResult r = RunCli("collied");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown command 'collied'"), std::string::npos);
}

// The demo starts the service and, as a gRPC client, reproduces the paper's first
// shot and pots the black on a built-in table.
TEST(CliTest, DemoUsesTheServiceOnBuiltInExamples) {
  const RunResult r = RunCli("demo");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("started on 127.0.0.1:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cue ball   0.914 m/s at 31.92"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("black   pocketed (top-left)"), std::string::npos) << r.out;
}

TEST(CliTest, ServeRunsUntilSigtermAndShutsDownCleanly) {
  const RunResult r = RunCli(
      "serve --address 127.0.0.1:0 & pid=$!; sleep 1; kill -TERM $pid; wait $pid; echo rc=$?");
  EXPECT_NE(r.out.find("serving snooker.v1.ShotPlanner on port"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("shutting down"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rc=0"), std::string::npos) << r.out;
}

// Each connection takes a descriptor: serve raises its soft open-file limit to the
// hard one, and warns of a hard limit too low for a busy server.
TEST(CliTest, ServeRaisesItsOpenFileLimitAndWarnsOfALowOne) {
  const std::string out = cli_support::TempPath("serve_limit_out.txt");
  for (const auto& [limits, soft, warns] : {std::tuple{"512:8192", "8192", false},
                                            std::tuple{"256:1024", "1024", true}}) {
    SCOPED_TRACE(limits);
    const RunResult r = cli_support::RunShell(
        std::string("{ prlimit --nofile=") + limits + " " + SNOOKER_CLI_PATH +
        " serve --address 127.0.0.1:0 > " + out + " & pid=$!; " + cli_support::kWaitForPort(out) +
        "awk '/Max open files/ {print \"soft=\" $4}' /proc/$pid/limits; kill -TERM $pid; wait $pid; "
        "echo rc=$?; }");
    EXPECT_TRUE(Mentions(r.out, std::string("soft=") + soft + "\n")) << r.out;
    EXPECT_TRUE(Mentions(r.out, "rc=0")) << r.out;
    EXPECT_EQ(Mentions(r.err, "snooker serve: warning: only 1024 open files allowed"), warns) << r.err;
  }
  std::remove(out.c_str());
}

// gRPC stops accepting connections for good once accept4 fails for want of a
// descriptor: serve then stops, exit 1, saying why, where it stayed up unreachable.
TEST(CliTest, ServeStopsWhenGrpcStopsAcceptingConnections) {
#ifdef SNOOKER_UNDER_ASAN
  GTEST_SKIP() << "the sanitizers' runtime needs descriptors of its own (UBSan's vptr check opens a pipe to "
                  "test memory), so with none left it reports errors that are not there";
#endif
  const std::string cli = SNOOKER_CLI_PATH;
  const std::string out = cli_support::TempPath("serve_accept_out.txt");
  const std::string err = cli_support::TempPath("serve_accept_err.txt");
  // 64 connections at once where 40 descriptors are allowed in all.
  const RunResult r = cli_support::RunShell(
      "{ prlimit --nofile=40 " + cli + " serve --address 127.0.0.1:0 > " + out + " 2> " + err +
      " & pid=$!; " + cli_support::kWaitForPort(out) + cli +
      " loadtest --target 127.0.0.1:$port --concurrency 64 --requests 200 --deadline-ms 5000 > /dev/null "
      "2>&1; for i in $(seq 300); do kill -0 $pid 2>/dev/null || break; sleep 0.1; done; "
      "if kill -0 $pid 2>/dev/null; then echo still-serving; kill -9 $pid; fi; wait $pid; echo rc=$?; }");
  EXPECT_FALSE(Mentions(r.out, "still-serving")) << r.out;
  EXPECT_TRUE(Mentions(r.out, "rc=1")) << r.out;
  const std::string said = cli_support::ReadText(out);
  const std::string log = cli_support::ReadText(err);
  EXPECT_TRUE(Mentions(said, "snooker: the gRPC port stopped accepting connections, shutting down:")) << said;
  EXPECT_TRUE(Mentions(log, "Failed accept4: Too many open files")) << log.substr(0, 2000);
  EXPECT_TRUE(Mentions(log, "snooker serve: gRPC stopped accepting connections on its port")) << log.substr(0, 2000);
  std::remove(out.c_str());
  std::remove(err.c_str());
}

TEST(CliTest, ServeOnABadAddressFails) {
  const RunResult r = RunCli("serve --insecure --address not-an-address:99999");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("port '99999' of 'not-an-address:99999' is not in [0, 65535]"),
            std::string::npos)
      << r.err;
  const RunResult unknown = RunCli("serve --insecure --address not-an-address:9999");
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.err.find("cannot listen on not-an-address:9999"), std::string::npos) << unknown.err;
}

// The issue's own example formats.
constexpr const char* kTable =
    R"({"balls": [{"id": "cue", "kind": "CUE", "position": {"x": 0.9, "y": 0.6}},
                  {"id": "red-1", "kind": "RED", "position": {"x": 0.9, "y": 1.6}}]})";
constexpr const char* kRollingShot = R"({"speed": 1.5, "headingDeg": 90, "topspin": 57.1, "sidespin": 0})";

TEST(CliSimulateTest, JsonHasTheContractedFields) {
  const RunResult r = RunCli("simulate --table " + TempFile("t.json", kTable) + " --shot " +
                             TempFile("s.json", kRollingShot) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Struct json;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &json).ok()) << r.out;
  const Value& events = Field(json, "events");
  ASSERT_EQ(events.kind_case(), Value::kListValue);
  ASSERT_GT(events.list_value().values_size(), 0);
  const Struct& first = events.list_value().values(0).struct_value();
  EXPECT_TRUE(std::isfinite(Number(first, "time")));
  EXPECT_EQ(Field(first, "kind").kind_case(), Value::kStringValue);
  const Value& finals = Field(json, "finalBalls");
  ASSERT_EQ(finals.list_value().values_size(), 2);
  for (const Value& v : finals.list_value().values()) {
    const Struct& b = v.struct_value();
    EXPECT_EQ(Field(b, "id").kind_case(), Value::kStringValue);
    EXPECT_TRUE(std::isfinite(Number(Object(b, "position"), "x")));
    EXPECT_EQ(Field(b, "pocketed").kind_case(), Value::kBoolValue);
    EXPECT_EQ(Field(b, "pocket").kind_case(), Value::kStringValue);
  }
  // The cue ball rolled into the red, which moved up the table.
  EXPECT_GT(Number(Object(finals.list_value().values(1).struct_value(), "position"), "y"), 1.6);
}

// --no-impact-tables integrates every impact: the cue ball's impact on the red (it
// rolls by then) is no longer looked up, so the answer differs by rounding-level
// amounts and agrees within 0.1 mm.
TEST(CliSimulateTest, NoImpactTablesIntegratesEveryImpact) {
  auto red_y = [](const RunResult& r) {
    Struct json;
    EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &json).ok()) << r.out;
    const Value& finals = Field(json, "finalBalls");
    return Number(Object(finals.list_value().values(1).struct_value(), "position"), "y");
  };
  const std::string files =
      " --table " + TempFile("t3.json", kTable) + " --shot " + TempFile("s3.json", kRollingShot) + " --json";
  const RunResult tables = RunCli("simulate" + files);
  const RunResult integrated = RunCli("simulate --no-impact-tables" + files);
  ASSERT_EQ(tables.exit_code, 0) << tables.err;
  ASSERT_EQ(integrated.exit_code, 0) << integrated.err;
  const double a = red_y(tables), b = red_y(integrated);
  EXPECT_NE(a, b);
  EXPECT_NEAR(a, b, 1e-4);
  EXPECT_NE(RunCli("simulate --help").out.find("--no-impact-tables"), std::string::npos);
}

TEST(CliSimulateTest, SvgDrawsTheTableAndPaths) {
  const std::string svg = cli_support::TempPath("shot.svg");
  const RunResult r = RunCli("simulate --table " + TempFile("t2.json", kTable) + " --shot " +
                             TempFile("s2.json", kRollingShot) + " --svg " + svg);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream f(svg);
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_EQ(ss.str().rfind("<svg", 0), 0u);
  EXPECT_NE(ss.str().find("<polyline"), std::string::npos);  // the paths
  EXPECT_NE(r.out.find("final positions"), std::string::npos);  // the readable report
}

TEST(CliSimulateTest, BadFilesAndTablesExitNonZeroNamingTheProblem) {
  struct Case {
    std::string table, shot, must_mention;
  };
  const std::vector<Case> cases = {
      {"{not json", kRollingShot, "is not a valid TableState JSON"},
      {R"({"balls": [{"id": "cue", "kind": "CUE", "position": {"x": 0.9, "y": 0.6}},
                     {"id": "red-1", "kind": "RED", "position": {"x": 0.91, "y": 0.6}}]})",
       kRollingShot, "cue and red-1 overlap by 0.0425 m"},
      {R"({"balls": [{"id": "cue", "kind": "CUE", "position": {"x": 2.5, "y": 0.6}}]})", kRollingShot,
       "cue"},
      {R"({"balls": [{"id": "cue", "kind": "PURPLE", "position": {"x": 0.9, "y": 0.6}}]})", kRollingShot,
       "TableState"},
      {kTable, R"({"speed": -3, "headingDeg": 90})", "shot.speed = -3"},
  };
  int i = 0;
  for (const Case& c : cases) {
    const RunResult r = RunCli("simulate --table " + TempFile("bad" + std::to_string(i) + ".json", c.table) +
                               " --shot " + TempFile("bads" + std::to_string(i) + ".json", c.shot));
    ++i;
    EXPECT_EQ(r.exit_code, 2) << c.must_mention << ": " << r.err;
    EXPECT_NE(r.err.find(c.must_mention), std::string::npos) << r.err;
  }
  const RunResult missing = RunCli("simulate --table /nonexistent.json --shot /nonexistent.json");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("cannot read '/nonexistent.json'"), std::string::npos);
}

}  // namespace
}  // namespace snooker
