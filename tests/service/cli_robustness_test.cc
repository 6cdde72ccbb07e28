// The `snooker` command under hostile input (and the service's shutdown): input
// files that are not regular files or are too large, JSON with mistakes in it, a table
// of 3000 stacked balls, memory running out, and SIGTERM with calls in flight.
#include <fcntl.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "cli/load_tables.h"
#include "snooker/v1/service.grpc.pb.h"
#include "tests/service/call_support.h"
#include "tests/support/cli_support.h"
#include "tests/support/sanitizers.h"
#include "tests/service/requests.h"
#include "tests/support/text.h"

namespace snooker {
namespace {

using cli_support::RunCli;
using cli_support::RunResult;
using cli_support::RunShell;
using cli_support::TempFile;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

constexpr const char* kPlainShot = R"({"speed": 1.5, "headingDeg": 90})";

// `simulate --table PATH` with a good shot file; at most 10 s (a FIFO hung forever).
RunResult SimulateTable(const std::string& path) {
  return RunShell("timeout 10 " + std::string(SNOOKER_CLI_PATH) + " simulate --table '" + path +
                  "' --shot " + TempFile("robust_shot.json", kPlainShot));
}

void ExpectRefused(const RunResult& r, const std::string& path, const std::string& why) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(Mentions(r.err, "cannot read '" + path + "': " + why)) << r.err;
  EXPECT_LT(r.err.size(), 200u) << r.err;
}

// /dev/zero was read until memory ran out, and the command aborted.
TEST(CliInputFileTest, ADeviceIsRefused) {
  ExpectRefused(SimulateTable("/dev/zero"), "/dev/zero", "is a character device, not a regular file");
}

// A directory gave "Unexpected end of string".
TEST(CliInputFileTest, ADirectoryIsRefused) {
  const std::string dir = testing::TempDir();
  ExpectRefused(SimulateTable(dir), dir, "is a directory");
}

// A FIFO hung.
TEST(CliInputFileTest, AFifoIsRefusedWithoutWaiting) {
  const std::string fifo = cli_support::TempPath("table.fifo");
  std::remove(fifo.c_str());
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  ExpectRefused(SimulateTable(fifo), fifo, "is a FIFO (named pipe), not a regular file");
  std::remove(fifo.c_str());
}

TEST(CliInputFileTest, AFileOverSixteenMegabytesIsRefusedUnread) {
  const std::string big = cli_support::TempPath("big.json");
  {
    std::ofstream f(big);
  }
  ASSERT_EQ(truncate(big.c_str(), 17 << 20), 0);  // sparse: nothing written
  ExpectRefused(SimulateTable(big), big, "is 17825792 bytes; at most 16777216 (16 MB) are read");
  std::remove(big.c_str());
}

TEST(CliInputFileTest, AMissingFileSaysSo) {
  ExpectRefused(SimulateTable("/nonexistent/table.json"), "/nonexistent/table.json",
                "No such file or directory");
}

TEST(CliInputFileTest, AnUnreadableFileSaysSo) {
  if (geteuid() == 0) GTEST_SKIP() << "root reads any file";
  const std::string path = TempFile("unreadable.json", "{}");
  ASSERT_EQ(chmod(path.c_str(), 0), 0);
  ExpectRefused(SimulateTable(path), path, "Permission denied");
}

// 3000 stacked balls took 17 s and printed a 388 MB error.
TEST(CliInputFileTest, ThreeThousandStackedBallsAreRefusedWithAShortMessage) {
  std::string table = R"({"balls": [{"id": "cue", "kind": "CUE", "position": {"x": 0.9, "y": 1}})";
  for (int i = 1; i < 3000; ++i) {
    table += R"(, {"id": "red-)" + std::to_string(i) + R"(", "kind": "RED", "position": {"x": 0.9, "y": 1}})";
  }
  table += "]}";
  const RunResult r = SimulateTable(TempFile("stacked.json", table));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Mentions(r.err, "table.balls = 3000 balls (at most 32)")) << r.err.substr(0, 300);
  EXPECT_LT(r.err.size(), 100u);
}

// JSON input that a person got wrong, read by each command that reads table files:
// where a syntax error is (line and column), kinds in any case, and an unknown kind
// named with its ball and the kinds there are.
struct TableReader {
  const char* name;
  const char* args;  // TABLE: the table file; SHOT: a good shot file
};

// gtest prints a parameter with this (not as bytes).
void PrintTo(const TableReader& c, std::ostream* os) { *os << "snooker " << c.args; }

class CliJsonInputTest : public testing::TestWithParam<TableReader> {
 protected:
  RunResult Run(const std::string& table_text) {
    std::string args = GetParam().args;
    const std::string path = TempFile(std::string(GetParam().name) + "_table.json", table_text);
    args.replace(args.find("TABLE"), 5, path);
    if (const std::size_t shot = args.find("SHOT"); shot != std::string::npos) {
      args.replace(shot, 4, TempFile("json_input_shot.json", kPlainShot));
    }
    const RunResult r = RunShell("timeout 60 " + std::string(SNOOKER_CLI_PATH) + " " + args);
    path_ = path;
    return r;
  }
  std::string path_;
};

TEST_P(CliJsonInputTest, ASyntaxErrorIsGivenByLineAndColumn) {
  // No comma after the first ball.
  const RunResult r = Run(R"({"balls": [
  {"id": "cue", "kind": "CUE", "position": {"x": 0.9, "y": 0.6}}
  {"id": "red-1", "kind": "RED", "position": {"x": 0.9, "y": 1.6}}
]})");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(Mentions(r.err, "'" + path_ + "' is not a valid TableState JSON: line 3, column 3: expected "
                              "',' or ']' after an element of an array, found '{'"))
      << r.err;
}

TEST_P(CliJsonInputTest, KindsAreTakenInAnyCase) {
  const RunResult r = Run(R"({"balls": [{"id": "cue", "kind": "cue", "position": {"x": 0.9, "y": 0.6}},
      {"id": "red-1", "kind": "Red", "position": {"x": 0.9, "y": 1.6}}]})");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST_P(CliJsonInputTest, AnUnknownKindNamesTheBallAndTheKinds) {
  const RunResult r = Run(R"({"balls": [{"id": "cue", "kind": "CUE", "position": {"x": 0.9, "y": 0.6}},
      {"id": "red-1", "kind": "crimson", "position": {"x": 0.9, "y": 1.6}}]})");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(Mentions(r.err, "ball \"red-1\" has kind \"crimson\", which is not one of CUE, RED, YELLOW, "
                              "GREEN, BROWN, BLUE, PINK, BLACK (in any case)"))
      << r.err;
}

INSTANTIATE_TEST_SUITE_P(
    Commands, CliJsonInputTest,
    testing::Values(TableReader{"simulate", "simulate --table TABLE --shot SHOT"},
                    TableReader{"plan",
                                "plan --table TABLE --max-simulations 50 --samples 4 --budget-ms 5000"}),
    [](const testing::TestParamInfo<TableReader>& p) { return std::string(p.param.name); });

TEST(CliJsonInputTest, AShotFilesSyntaxErrorIsGivenByLineAndColumn) {
  const std::string shot = TempFile("json_input_bad_shot.json", "{\"speed\": 1.5\n \"headingDeg\": 90}");
  const RunResult r = RunCli("simulate --table " + TempFile("json_input_t.json", R"({"balls": [
      {"id": "cue", "kind": "cue", "position": {"x": 0.9, "y": 0.6}}]})") + " --shot " + shot);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(Mentions(r.err, "'" + shot + "' is not a valid Shot JSON: line 2, column 2: expected ',' or "
                              "'}' after a member of an object, found '\"'"))
      << r.err;
}

// The load test's folder of tables is read the same way.
TEST(CliJsonInputTest, AFolderOfTablesIsReadTheSameWay) {
  const std::string dir = cli_support::TempPath("json_input_tables");
  ASSERT_EQ(system(("rm -rf " + dir + " && mkdir -p " + dir).c_str()), 0);
  std::ofstream(dir + "/a.json") << R"({"balls": [
      {"id": "cue", "kind": "Cue", "position": {"x": 0.9, "y": 0.6}},
      {"id": "p", "kind": "pink", "position": {"x": 0.9, "y": 1.6}}]})";
  std::vector<v1::TableState> tables;
  std::string why;
  ASSERT_TRUE(cli::ReadTables(dir, &tables, &why)) << why;
  ASSERT_EQ(tables.size(), 1u);
  EXPECT_EQ(tables[0].balls(1).kind(), v1::PINK);
  std::ofstream(dir + "/b.json") << R"({"balls": [{"id": "cue", "kind": "CUE"}, {"kind": "violet"}]})";
  tables.clear();
  EXPECT_FALSE(cli::ReadTables(dir, &tables, &why));
  EXPECT_TRUE(Mentions(why, "b.json' is not a valid TableState JSON: line 1, column 51: ball 1 (counting "
                            "from 0; it has no id) has kind \"violet\", which is not one of CUE, RED"))
      << why;
  std::ofstream(dir + "/b.json") << "{\"balls\": [}";
  EXPECT_FALSE(cli::ReadTables(dir, &tables, &why));
  EXPECT_TRUE(Mentions(why, "b.json' is not a valid TableState JSON: line 1, column 12: expected a value"))
      << why;
  EXPECT_EQ(system(("rm -rf " + dir).c_str()), 0);
}


// Output that cannot be written (here to /dev/full, a device always full) fails the
// command with the system's reason. The file writers had checked their stream before
// its buffer was flushed (a short file on a full disk passed), the demo's SVG was not
// checked, nor was standard output: each said exit 0.
TEST(CliOutputTest, AFullDeviceFailsTheCommandWithTheReason) {
  if (access("/dev/full", W_OK) != 0) GTEST_SKIP() << "this machine has no /dev/full";
  const std::string cli = SNOOKER_CLI_PATH;
  const std::string table = TempFile(
      "output_table.json", R"({"balls": [{"id": "cue", "kind": "CUE", "position": {"x": 0.9, "y": 0.6}},
                                         {"id": "red-1", "kind": "RED", "position": {"x": 0.9, "y": 1.6}}]})");
  const std::string shot = TempFile("output_shot.json", kPlainShot);
  struct Case {
    std::string command, says;
  };
  const std::string full = "cannot write '/dev/full': No space left on device";
  for (const Case& c : {
           Case{"collide --speed 2 --json > /dev/full", "snooker collide: cannot write the standard output"},
           Case{"model > /dev/full", "snooker model: cannot write the standard output"},
           Case{"simulate --table " + table + " --shot " + shot + " --json > /dev/full",
                "snooker simulate: cannot write the standard output"},
           Case{"simulate --table " + table + " --shot " + shot + " --svg /dev/full > /dev/null",
                "snooker simulate: " + full},
           Case{"plan --table builtin:black --max-simulations 200 --svg /dev/full > /dev/null",
                "snooker plan: " + full},
           Case{"selfplay --frames 1 --seed 1 --max-simulations 200 --records /dev/full > /dev/null",
                "snooker selfplay: " + full},
           Case{"record --world default --shots 1 --seed 5 --out /dev/full", "snooker record: " + full},
           Case{"demo --svg /dev/full > /dev/null", "snooker demo: " + full},
       }) {
    SCOPED_TRACE(c.command);
    const RunResult r = RunShell("timeout 120 " + cli + " " + c.command);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(Mentions(r.err, c.says)) << r.err;
  }
}

// An allocation failure is reported, never an abort: a 15 MB id under a 60 MB
// address-space limit (the command itself needs about 30 MB).
TEST(CliInputFileTest, RunningOutOfMemoryIsReportedNotAnAbort) {
#ifdef SNOOKER_UNDER_ASAN
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: no ulimit -v";
#endif
  const std::string path = TempFile(
      "hugeid.json", R"({"balls": [{"id": ")" + std::string(15'000'000, 'c') +
                         R"(", "kind": "CUE", "position": {"x": 0.9, "y": 1}}]})");
  const RunResult r =
      RunShell("ulimit -v 60000; " + std::string(SNOOKER_CLI_PATH) + " simulate --table " + path +
               " --shot " + TempFile("oom_shot.json", kPlainShot));
  EXPECT_EQ(r.exit_code, 1) << r.err.substr(0, 300);  // not -1: no abort
  EXPECT_TRUE(Mentions(r.err, "out of memory")) << r.err.substr(0, 300);
  std::remove(path.c_str());
}

TEST(CliServeTest, BadFlagsAreUsageErrors) {
  for (const auto& [flags, text] :
       {std::pair{"--max-call-ms 0", "--max-call-ms 0 is out of range"},
        std::pair{"--shutdown-grace-ms -1", "--shutdown-grace-ms -1 is out of range"},
        std::pair{"--workers 0", "--workers 0 is out of range"},
        std::pair{"--max-queued lots", "--max-queued 'lots' is not a whole number"}}) {
    const RunResult r = RunCli(std::string("serve ") + flags);
    EXPECT_EQ(r.exit_code, 2) << flags;
    EXPECT_TRUE(Mentions(r.err, text)) << r.err;
  }
}

// `snooker serve` as a subprocess: stdout to a pipe (the port is printed there),
// stderr (the call log) to a file, or to a pipe whose reader is gone.
class ServeProcess {
 public:
  enum class Log { kToFile, kToAPipeWithoutReader };
  explicit ServeProcess(const std::vector<std::string>& flags, Log log = Log::kToFile) {
    err_path_ = cli_support::TempPath("serve_stderr.txt");
    std::vector<std::string> args = {SNOOKER_CLI_PATH, "serve", "--address", "127.0.0.1:0"};
    args.insert(args.end(), flags.begin(), flags.end());
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    int out[2];
    if (pipe(out) != 0) return;
    int err = -1;
    if (log == Log::kToFile) {
      err = open(err_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    } else {
      int log_pipe[2];
      if (pipe(log_pipe) != 0) return;
      close(log_pipe[0]);  // no reader: a write raises SIGPIPE, or fails where that is ignored
      err = log_pipe[1];
    }
    pid_ = fork();
    if (pid_ == 0) {  // the child: only async-signal-safe calls until exec
      dup2(out[1], 1);
      dup2(err, 2);
      execv(argv[0], argv.data());
      _exit(127);
    }
    close(out[1]);
    close(err);
    out_ = fdopen(out[0], "r");
  }
  ~ServeProcess() {
    if (pid_ > 0 && !exited_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    if (out_ != nullptr) fclose(out_);
    std::remove(err_path_.c_str());
  }
  /// The next line on its stdout ("" at the end).
  std::string Line() {
    char buf[512];
    return out_ != nullptr && fgets(buf, sizeof buf, out_) != nullptr ? std::string(buf) : "";
  }
  /// Waits up to `limit` for the process to exit; its exit code, or -1.
  int Wait(std::chrono::seconds limit) {
    const auto give_up = Clock::now() + limit;
    int status = 0;
    while (Clock::now() < give_up) {
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        exited_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      }
      std::this_thread::sleep_for(milliseconds(2));
    }
    return -1;
  }
  pid_t pid() const { return pid_; }
  std::string Stderr() const { return cli_support::ReadText(err_path_); }

 private:
  pid_t pid_ = -1;
  FILE* out_ = nullptr;
  bool exited_ = false;
  std::string err_path_;
};

// On the server's side of a shutdown grace, the work given would take kWork: the
// process must exit within the grace and a generous margin, well before that.
TEST(CliServeTest, SigtermWithCallsInFlightExitsWithinTheGrace) {
  constexpr auto kGrace = milliseconds(200);
  const int n = call_support::HeavyCallsForTheWork();
  ServeProcess serve({"--workers", "1", "--max-queued", "10000", "--shutdown-grace-ms",
                      std::to_string(kGrace.count())});
  ASSERT_GT(serve.pid(), 0);
  const std::string first = serve.Line();
  const auto at = first.find("on port ");
  ASSERT_NE(at, std::string::npos) << first;
  const int port = std::stoi(first.substr(at + 8));
  auto channel = grpc::CreateChannel("127.0.0.1:" + std::to_string(port),
                                     grpc::InsecureChannelCredentials());
  auto stub = v1::ShotPlanner::NewStub(channel);
  const v1::SimulateRequest heavy = testing_requests::Heavy();
  call_support::Batch batch(stub.get(), heavy, n, std::nullopt);
  // Work is under way once the first call is answered; the rest are in flight.
  const auto t0 = Clock::now();
  while (batch.done() == 0 && Clock::now() - t0 < std::chrono::seconds(20)) {
    std::this_thread::sleep_for(milliseconds(1));
  }
  ASSERT_GT(batch.done(), 0u);
  ASSERT_LT(batch.done(), static_cast<size_t>(n));
  const auto signalled = Clock::now();
  ASSERT_EQ(kill(serve.pid(), SIGTERM), 0);
  const int code = serve.Wait(std::chrono::seconds(30));
  const auto took = Clock::now() - signalled;
  EXPECT_EQ(code, 0) << serve.Stderr().substr(0, 2000);
  EXPECT_LT(took, kGrace + std::chrono::seconds(3));  // the work left would take seconds more
  const std::string shutting_down = serve.Line();
  EXPECT_TRUE(Mentions(shutting_down, "signal 15, shutting down:")) << shutting_down;
  EXPECT_TRUE(Mentions(shutting_down, "may finish for up to 200 ms")) << shutting_down;
  const std::string stopped = serve.Line();
  EXPECT_TRUE(Mentions(stopped, "snooker: stopped after")) << stopped;
  const std::vector<int> by_code = batch.Wait();
  EXPECT_GT(by_code[grpc::StatusCode::UNAVAILABLE] + by_code[grpc::StatusCode::CANCELLED], n / 2);
  EXPECT_TRUE(Mentions(serve.Stderr(), "status=CANCELLED")) << serve.Stderr().substr(0, 2000);
}

// A server whose log reader has gone away (stderr a pipe nobody reads) goes on
// serving: each call's line is lost and counted, the call answered.
TEST(CliServeTest, AServerWhoseLogReaderIsGoneGoesOnServing) {
  ServeProcess serve({}, ServeProcess::Log::kToAPipeWithoutReader);
  ASSERT_GT(serve.pid(), 0);
  const std::string first = serve.Line();
  const auto at = first.find("on port ");
  ASSERT_NE(at, std::string::npos) << first;
  auto stub = v1::ShotPlanner::NewStub(grpc::CreateChannel(
      "127.0.0.1:" + std::to_string(std::stoi(first.substr(at + 8))), grpc::InsecureChannelCredentials()));
  for (int call = 0; call < 3; ++call) {
    grpc::ClientContext ctx;
    ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(20));
    v1::CollideResponse response;
    const grpc::Status status = stub->Collide(&ctx, testing_requests::PaperCollide(), &response);
    ASSERT_TRUE(status.ok()) << "call " << call << ": " << status.error_message();
  }
  ASSERT_EQ(kill(serve.pid(), SIGTERM), 0);
  EXPECT_EQ(serve.Wait(std::chrono::seconds(30)), 0);
  EXPECT_TRUE(Mentions(serve.Line(), "signal 15, shutting down:"));
  const std::string stopped = serve.Line();
  EXPECT_TRUE(Mentions(stopped, "stopped after 3 calls (3 OK, 0 cancelled); 3 of their log lines were lost"))
      << stopped;
}

}  // namespace
}  // namespace snooker
