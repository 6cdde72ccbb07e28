// The command line as a client of a real server: `snooker simulate --server` and
// `snooker plan --server` print what the local commands print, and `snooker loadtest`
// sends bounded load to a loopback server only, checks every answer and reports
// errors by status code. The server runs in this process; the `snooker` binary
// connects to it.
#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <regex>
#include <string>

#include "cli/load_tables.h"
#include "physics/table/table.h"
#include "server/convert.h"
#include "tests/support/cli_support.h"
#include "tests/support/own_user.h"
#include "tests/service/server_support.h"
#include "tests/support/text.h"

namespace snooker {
namespace {

using cli_support::RunCli;
using cli_support::RunResult;
using cli_support::RunShell;
using cli_support::TempFile;
using server_support::TestServer;

constexpr const char* kServerTable = R"({"balls": [
    {"id": "cue", "kind": "CUE", "position": {"x": 0.9, "y": 0.6}},
    {"id": "red-1", "kind": "RED", "position": {"x": 0.9, "y": 1.6}},
    {"id": "black", "kind": "BLACK", "position": {"x": 0.0241, "y": 3.0}}]})";  // a hair past
constexpr const char* kServerShot = R"({"speed": 2.5, "headingDeg": 90.3, "topspin": 40, "sidespin": -5})";

TEST(SimulateServerTest, PrintsWhatTheLocalCommandPrints) {
  TestServer s;
  const std::string files =
      " --table " + TempFile("remote_t.json", kServerTable) + " --shot " + TempFile("remote_s.json", kServerShot);
  for (const char* format : {"", " --json"}) {
    const RunResult local = RunCli("simulate" + files + format);
    const RunResult remote = RunCli("simulate" + files + format + " --server " + s.target);
    ASSERT_EQ(local.exit_code, 0) << local.err;
    ASSERT_EQ(remote.exit_code, 0) << remote.err;
    EXPECT_EQ(remote.out, local.out);
    EXPECT_TRUE(Mentions(remote.out, "moved black by 0.272 mm")) << remote.out;
  }
}

TEST(SimulateServerTest, TheServersErrorsExitAsTheLocalOnes) {
  TestServer s;
  const RunResult bad = RunCli("simulate --server " + s.target + " --table " +
                               TempFile("remote_bad.json", kServerTable) + " --shot " +
                               TempFile("remote_bad_s.json", R"({"speed": -3})"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(Mentions(bad.err, "snooker simulate: INVALID_ARGUMENT from " + s.target +
                                    ": shot.speed = -3"))
      << bad.err;
  // The command names the call by the request id the server's log line has.
  std::smatch id;
  ASSERT_TRUE(std::regex_search(bad.err, id, std::regex("\\(request id ([0-9a-f]{16})\\)\n$"))) << bad.err;
  server_support::WaitUntilAnswered(*s.server, 0, std::chrono::seconds(20));
  EXPECT_TRUE(Mentions(s.log.str(), "request_id=" + id[1].str() + " status=INVALID_ARGUMENT")) << s.log.str();
  s.server->Shutdown(std::chrono::milliseconds(0));
  const RunResult gone = RunCli("simulate --server " + s.target + " --deadline-ms 3000 --table " +
                                TempFile("remote_t2.json", kServerTable) + " --shot " +
                                TempFile("remote_s2.json", kServerShot));
  EXPECT_EQ(gone.exit_code, 1);
  EXPECT_TRUE(Mentions(gone.err, "snooker simulate: UNAVAILABLE from ")) << gone.err;
  EXPECT_TRUE(Mentions(gone.err, "(request id ")) << gone.err;  // its own, though no server saw it
}

google::protobuf::Struct ParseJson(const std::string& text) {
  google::protobuf::Struct j;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(text, &j).ok()) << text;
  return j;
}

double NumberField(const google::protobuf::Struct& j, const std::string& name) {
  const auto it = j.fields().find(name);
  EXPECT_NE(it, j.fields().end()) << name;
  return it == j.fields().end() ? -1 : it->second.number_value();
}

TEST(LoadTestTest, SendsEveryCallAndChecksEveryAnswer) {
  TestServer s;
  const RunResult r =
      RunCli("loadtest --target " + s.target + " --concurrency 4 --requests 120 --json");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const google::protobuf::Struct j = ParseJson(r.out);
  EXPECT_EQ(NumberField(j, "completed"), 120);
  EXPECT_EQ(NumberField(j, "errors"), 0);
  EXPECT_EQ(NumberField(j, "badAnswers"), 0);
  EXPECT_GT(NumberField(j, "ballsMoved"), 0);  // every fourth table is repaired
  EXPECT_EQ(j.fields().at("statuses").struct_value().fields().at("OK").number_value(), 120);
  EXPECT_EQ(j.fields().at("healthBefore").string_value(), "SERVING");
  const auto& lat = j.fields().at("latencyMs").struct_value();
  EXPECT_LE(NumberField(lat, "p50"), NumberField(lat, "p90"));
  EXPECT_LE(NumberField(lat, "p90"), NumberField(lat, "p99"));
  EXPECT_LE(NumberField(lat, "p99"), NumberField(lat, "max"));
  EXPECT_GT(NumberField(lat, "p50"), 0);
  // The server saw them all.
  EXPECT_EQ(s.server->counts().with(grpc::StatusCode::OK), 120 + 1);  // and GetModel
}

// Half the tables are refused (two balls overlapping by 2 mm, beyond the tolerance):
// the run fails, and says how many calls ended with which status and why.
TEST(LoadTestTest, ErrorsAreCountedByStatusCodeAndFailTheRun) {
  TestServer s;
  const std::string dir = cli_support::TempPath("loadtest_errors");
  ASSERT_EQ(system(("mkdir -p " + dir).c_str()), 0);
  std::ofstream(dir + "/good.json") << kServerTable;
  std::ofstream(dir + "/overlap.json")
      << R"({"balls": [{"id": "cue", "kind": "CUE", "position": {"x": 0.5, "y": 0.5}},
                       {"id": "red", "kind": "RED", "position": {"x": 0.5505, "y": 0.5}}]})";
  const RunResult r = RunCli("loadtest --target " + s.target +
                             " --concurrency 3 --requests 10 --tables " + dir);
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_TRUE(Mentions(r.out, "completed 10 of 10")) << r.out;
  EXPECT_TRUE(Mentions(r.out, "statuses: INVALID_ARGUMENT 5 OK 5")) << r.out;
  EXPECT_TRUE(Mentions(r.out, "problem: call 1: INVALID_ARGUMENT: table.balls = positions")) << r.out;
}

// A system that will not start every client thread asked for (a process limit) ends
// the run with a message that names the thread, where the client aborted.
TEST(LoadTestTest, ClientThreadsTheSystemWillNotStartEndTheRunWithAMessage) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root, to run the command as a user of its own";
  // A user of its own, so that the limit counts this command's threads alone.
  const std::string uid = std::to_string(test_support::OwnUserId());
  const std::string as_user = "setpriv --reuid=" + uid + " --regid=" + uid + " --clear-groups ";
  const RunResult probe = RunShell(as_user + SNOOKER_CLI_PATH + " help");
  if (probe.exit_code != 0) GTEST_SKIP() << "cannot run the command as uid " << uid << ": " << probe.err;
  TestServer s;
  const RunResult r = RunShell(as_user + "prlimit --nproc=20 " + SNOOKER_CLI_PATH + " loadtest --target " +
                               s.target + " --concurrency 32 --requests 40");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(Mentions(r.err, "snooker loadtest: could not start client thread ")) << r.err;
  EXPECT_TRUE(Mentions(r.err, " of 32 (Resource temporarily unavailable)")) << r.err;
}

TEST(LoadTestTest, RefusesTargetsOffThisMachine) {
  for (const char* target : {"10.1.2.3:50051", "example.com:50051", "0.0.0.0:50051"}) {
    const RunResult r = RunCli(std::string("loadtest --target ") + target +
                               " --concurrency 1 --requests 1");
    EXPECT_EQ(r.exit_code, 2) << target;
    EXPECT_TRUE(Mentions(r.err, "refusing --target")) << r.err;
  }
}

TEST(LoadTestTest, CountAndConcurrencyAreBounded) {
  for (const char* flags : {"--concurrency 0 --requests 1", "--concurrency 257 --requests 1",
                            "--concurrency 1 --requests 0", "--concurrency 1 --requests 1000001",
                            "--concurrency 1 --requests 1 --max-seconds 3601",
                            "--concurrency 1 --requests 1 --method dance"}) {
    const RunResult r = RunCli(std::string("loadtest --target 127.0.0.1:1 ") + flags);
    EXPECT_EQ(r.exit_code, 2) << flags << ": " << r.err;
  }
}

TEST(LoadTestTest, TakesTablesFromAFolder) {
  TestServer s;
  const std::string dir = cli_support::TempPath("loadtest_tables");
  ASSERT_EQ(system(("mkdir -p " + dir).c_str()), 0);
  {
    std::ofstream(dir + "/a.json") << kServerTable;
    std::ofstream(dir + "/b.json")
        << R"({"balls": [{"id": "c", "kind": "CUE", "position": {"x": 0.5, "y": 0.5}},
                         {"id": "p", "kind": "PINK", "position": {"x": 1.0, "y": 2.5}}]})";
    std::ofstream(dir + "/notes.txt") << "not a table";
  }
  RunResult r = RunCli("loadtest --target " + s.target + " --concurrency 2 --requests 10 --tables " + dir);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(Mentions(r.out, "2 tables from " + dir)) << r.out;
  EXPECT_TRUE(Mentions(r.out, "balls moved by the vision repair: 5")) << r.out;  // the black, 5 times
  std::ofstream(dir + "/c.json") << "{broken";
  r = RunCli("loadtest --target " + s.target + " --concurrency 2 --requests 10 --tables " + dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Mentions(r.err, "c.json' is not a valid TableState JSON")) << r.err;
  // A table no server takes is refused before the run, not sent on every call.
  std::ofstream(dir + "/c.json")
      << R"({"balls": [{"id": "c", "kind": "CUE", "position": {"x": 0.5, "y": 0.5}},
                       {"id": "p", "kind": "PINK", "position": {"x": "NaN", "y": 2.5}}]})";
  r = RunCli("loadtest --target " + s.target + " --concurrency 2 --requests 10 --tables " + dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Mentions(r.err, "c.json' is not a table a server takes: table.balls[1].position")) << r.err;
  EXPECT_EQ(system(("rm -rf " + dir).c_str()), 0);
}

TEST(LoadTablesTest, BuiltInTablesAreValidVariedAndSeeded) {
  const auto tables = cli::VariedTables(7, 64, 0.3);
  ASSERT_EQ(tables.size(), 64u);
  int repaired = 0, most = 0, fewest = 100;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const server::TableCheck strict = server::CheckTable(tables[i], physics::DefaultTable(), 0);
    const server::TableCheck lenient = server::CheckTable(tables[i], physics::DefaultTable(), 1e-3);
    EXPECT_TRUE(lenient.errors.empty()) << i << ": " << server::Describe(lenient.errors);
    EXPECT_EQ(strict.errors.empty(), i % 4 != 3) << i;
    repaired += lenient.warnings.empty() ? 0 : 1;
    most = std::max(most, tables[i].balls_size());
    fewest = std::min(fewest, tables[i].balls_size());
  }
  EXPECT_EQ(repaired, 16);
  EXPECT_GE(most, 15);
  EXPECT_LE(fewest, 6);
  const auto again = cli::VariedTables(7, 64, 0.3);
  EXPECT_EQ(again[10].SerializeAsString(), tables[10].SerializeAsString());
  EXPECT_NE(cli::VariedTables(8, 64, 0.3)[10].SerializeAsString(), tables[10].SerializeAsString());
}

// Everything but the last line ("N simulations, ..., T ms": wall time differs).
std::string WithoutWorkLine(const std::string& text) {
  const std::size_t end = text.rfind('\n', text.size() >= 2 ? text.size() - 2 : 0);
  return end == std::string::npos ? text : text.substr(0, end + 1);
}

constexpr const char* kPlanFlags =
    "plan --table builtin:red --max-simulations 300 --samples 16 --budget-ms 5000 --seed 3";

TEST(PlanServerTest, PrintsWhatTheLocalCommandPrints) {
  TestServer s;
  const RunResult local = RunCli(std::string(kPlanFlags));
  const RunResult remote = RunCli(std::string(kPlanFlags) + " --server " + s.target);
  ASSERT_EQ(local.exit_code, 0) << local.err;
  ASSERT_EQ(remote.exit_code, 0) << remote.err;
  EXPECT_TRUE(Mentions(remote.out, "#1  red-1 into top-right")) << remote.out;
  EXPECT_EQ(WithoutWorkLine(remote.out), WithoutWorkLine(local.out));
  // The work line names the cap that repeats the answer, the server's as the command's.
  for (const RunResult* r : {&local, &remote}) {
    EXPECT_TRUE(Mentions(r->out, " simulations of 300, ")) << r->out;
    EXPECT_TRUE(Mentions(r->out, " ms; --max-simulations 300 repeats it\n")) << r->out;
  }
  // JSON: the same shots; and an SVG of them.
  const std::string svg = cli_support::TempPath("plan_remote.svg");
  const RunResult local_json = RunCli(std::string(kPlanFlags) + " --json");
  const RunResult remote_json = RunCli(std::string(kPlanFlags) + " --json --svg " + svg + " --server " + s.target);
  ASSERT_EQ(remote_json.exit_code, 0) << remote_json.err;
  const google::protobuf::Struct a = ParseJson(local_json.out), b = ParseJson(remote_json.out);
  EXPECT_EQ(a.fields().at("shots").DebugString(), b.fields().at("shots").DebugString());
  EXPECT_TRUE(b.fields().at("final").bool_value());
  std::ifstream f(svg);
  std::string head(5, '\0');
  f.read(head.data(), 5);
  EXPECT_EQ(head, "<svg ");
}

TEST(PlanServerTest, StreamPrintsProgressThenTheAnswer) {
  TestServer s;
  const RunResult r = RunCli(std::string(kPlanFlags) + " --stream --server " + s.target);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::size_t progress = r.out.find("progress ");
  const std::size_t answer = r.out.find("#1  red-1 into top-right");
  ASSERT_NE(progress, std::string::npos) << r.out;
  ASSERT_NE(answer, std::string::npos) << r.out;
  EXPECT_LT(progress, answer);
  EXPECT_TRUE(Mentions(r.out, "P(pot) estimate")) << r.out;
}

TEST(PlanServerTest, TheServersErrorsExitAsTheLocalOnes) {
  TestServer s;
  const RunResult bad = RunCli("plan --table builtin:red --budget-ms 20000 --server " + s.target);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(Mentions(bad.err, "snooker plan: INVALID_ARGUMENT from " + s.target +
                                    ": time_budget_ms = 20000 (must be in [1, 10000] ms"))
      << bad.err;
  // The request's values go to the server as given; its answer names each bad one.
  const RunResult limits = RunCli(
      "plan --table builtin:red --shots 50 --samples -1 --vision-tolerance-mm 5 --server " + s.target);
  EXPECT_EQ(limits.exit_code, 2);
  EXPECT_TRUE(Mentions(limits.err, "vision_tolerance_mm = 5 (must be in [0, 1] mm")) << limits.err;
  EXPECT_TRUE(Mentions(limits.err, "max_shots = 50 (must be in [1, 20])")) << limits.err;
  EXPECT_TRUE(Mentions(limits.err, "monte_carlo_samples = -1 (must be in [0, 100000])")) << limits.err;
  const RunResult unknown = RunCli("plan --table builtin:snooker --server " + s.target);
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_TRUE(Mentions(unknown.err, "no built-in table 'snooker' (there are: black, red, colours, break-off)"))
      << unknown.err;
}

TEST(LoadTestTest, PlansAreCheckedAgainstTheirLimits) {
  TestServer s;
  const RunResult r = RunCli("loadtest --target " + s.target +
                             " --method plan --budget-ms 20 --concurrency 4 --requests 40 --json");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const google::protobuf::Struct j = ParseJson(r.out);
  EXPECT_EQ(j.fields().at("method").string_value(), "plan");
  EXPECT_EQ(NumberField(j, "completed"), 40);
  EXPECT_EQ(NumberField(j, "errors"), 0);
  EXPECT_EQ(NumberField(j, "badAnswers"), 0);
  EXPECT_EQ(NumberField(j, "budgetMs"), 20);
  EXPECT_GT(NumberField(j, "plansWithShots"), 0);
  // The answers cut short by the clock, as the server counted them (each counted
  // before it is answered).
  EXPECT_EQ(NumberField(j, "plansCutShort"), static_cast<double>(s.server->counts().plans_cut_short));
  EXPECT_GT(NumberField(j, "ballsMoved"), 0);  // every fourth table is repaired
  EXPECT_EQ(j.fields().at("statuses").struct_value().fields().at("OK").number_value(), 40);
  EXPECT_EQ(s.server->counts().with(grpc::StatusCode::OK), 40 + 1);  // and GetModel
}

TEST(LoadTablesTest, BuiltInNamedTablesAreValid) {
  for (const char* name : {"black", "red", "colours", "break-off"}) {
    v1::TableState t;
    ASSERT_TRUE(cli::BuiltinTable(name, &t)) << name;
    const bool in_hand = server::CueIndex(t) < 0;  // the cue ball in hand: no CUE ball
    EXPECT_EQ(in_hand, std::string(name) == "break-off") << name;
    const server::TableCheck check = server::CheckTable(
        t, physics::DefaultTable(), 0, in_hand ? server::CueBall::kInHand : server::CueBall::kOnTable);
    EXPECT_TRUE(check.errors.empty()) << name << ": " << server::Describe(check.errors);
  }
  // The opening: 15 reds and the six colours, no cue ball.
  v1::TableState rack;
  ASSERT_TRUE(cli::BuiltinTable("break-off", &rack));
  EXPECT_EQ(rack.balls_size(), 21);
  int reds = 0;
  for (const v1::Ball& b : rack.balls()) reds += b.kind() == v1::RED ? 1 : 0;
  EXPECT_EQ(reds, 15);
  v1::TableState t;
  EXPECT_FALSE(cli::BuiltinTable("snooker", &t));
}

}  // namespace
}  // namespace snooker
