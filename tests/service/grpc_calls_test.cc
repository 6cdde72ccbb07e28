// The gRPC service's bounds on calls: bytes that do not
// parse, wall time from the client's deadline and the server's maximum, cancellation,
// a full queue, shutdown, and the per-call log, through an in-process server and
// real stubs.
//
// No test here asserts a duration tighter than a generous sanity bound: where a test
// shows that the server stopped working early, the work it was given would take at
// least call_support::kWork (from one call's measured cost), and the bound is half that.
#include <arpa/inet.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <sstream>
#include <regex>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "server/api.h"
#include "server/server.h"
#include "snooker/v1/service.grpc.pb.h"
#include "tests/service/call_support.h"
#include "tests/service/requests.h"
#include "tests/service/server_support.h"
#include "tests/support/text.h"

namespace snooker::server {
namespace {

namespace req = testing_requests;
using call_support::Batch;
using call_support::HeavyCallsForTheWork;
using call_support::kWork;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

class CallsTest : public testing::Test {
 protected:
  void StartServer(ServerOptions options) {
    options.address = "127.0.0.1:0";
    options.log = &log_;
    std::string error;
    server_ = Server::Start(options, &error);
    ASSERT_NE(server_, nullptr) << error;
    channel_ = grpc::CreateChannel("127.0.0.1:" + std::to_string(server_->port()),
                                   grpc::InsecureChannelCredentials());
    stub_ = v1::ShotPlanner::NewStub(channel_);
  }
  void TearDown() override {
    if (server_) server_->Shutdown(milliseconds(0));
  }

  // Waits (at most 30 s) until the server has answered every call it received.
  // Returns how long that took from `since`.
  Clock::duration WaitUntilIdle(Clock::time_point since) {
    EXPECT_EQ(server_support::WaitUntilAnswered(*server_, 0, std::chrono::seconds(30)).in_flight(), 0);
    return Clock::now() - since;
  }

  // Waits (at most 20 s) until the server has received n calls.
  bool WaitUntilReceived(std::int64_t n) {
    const auto give_up = Clock::now() + std::chrono::seconds(20);
    while (server_->counts().received < n && Clock::now() < give_up) {
      std::this_thread::sleep_for(milliseconds(1));
    }
    return server_->counts().received >= n;
  }

  // One call, so the channel is connected before a batch is timed.
  void WarmUp() {
    v1::CollideResponse resp;
    grpc::ClientContext ctx;
    ASSERT_TRUE(stub_->Collide(&ctx, req::PaperCollide(), &resp).ok());
  }

  std::ostringstream log_;  // written under the service's lock; read after calls end
  std::unique_ptr<Server> server_;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::ShotPlanner::Stub> stub_;
};

TEST_F(CallsTest, BytesThatDoNotParseAreInvalidArgumentWithAReason) {
  StartServer({});
  grpc::GenericStub generic(channel_);
  const std::string garbage("\x00\x01\x02\x03", 4);
  grpc::Slice slice(garbage);
  grpc::ByteBuffer request(&slice, 1), response;
  grpc::ClientContext ctx;
  std::promise<grpc::Status> done;
  generic.UnaryCall(&ctx, "/snooker.v1.ShotPlanner/Simulate", grpc::StubOptions(), &request,
                    &response, [&](grpc::Status s) { done.set_value(std::move(s)); });
  const grpc::Status st = done.get_future().get();
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(Mentions(st.error_message(), "not a valid snooker.v1.SimulateRequest (4 bytes)"))
      << st.error_message();
}

TEST_F(CallsTest, CollideSpeedsOutOfRangeAreInvalidArgument) {
  StartServer({});
  for (const double speed : {1e308, 1e-300}) {
    v1::CollideRequest r = req::PaperCollide();
    r.set_speed(speed);
    v1::CollideResponse resp;
    grpc::ClientContext ctx;
    const grpc::Status st = stub_->Collide(&ctx, r, &resp);
    EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << speed;
    EXPECT_TRUE(Mentions(st.error_message(), "speed = ")) << st.error_message();
  }
}

TEST_F(CallsTest, UnknownEnumValuesAreInvalidArgument) {
  StartServer({});
  v1::CollideRequest r = req::PaperCollide();
  r.mutable_solver()->set_integrator(v1::ImpulseIntegrator(7));
  v1::CollideResponse resp;
  grpc::ClientContext ctx;
  const grpc::Status st = stub_->Collide(&ctx, r, &resp);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(Mentions(st.error_message(), "solver.integrator = 7")) << st.error_message();
}

TEST_F(CallsTest, StepsBeyondTheCapAreInvalidArgument) {
  StartServer({});
  v1::CollideRequest r = req::PaperCollide();
  r.mutable_solver()->set_integrator(v1::IMPULSE_INTEGRATOR_FIXED_STEP);
  r.mutable_solver()->set_steps(536'870'911);  // ran 10 s before
  v1::CollideResponse resp;
  grpc::ClientContext ctx;
  const grpc::Status st = stub_->Collide(&ctx, r, &resp);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(Mentions(st.error_message(), "solver.steps = 536870911")) << st.error_message();
}

TEST_F(CallsTest, TenThousandBallsAreRefusedWithAShortMessage) {
  StartServer({});
  v1::SimulateRequest r;
  for (int i = 0; i < 10'000; ++i) {
    req::AddBall(&r, i == 0 ? "cue" : "red-" + std::to_string(i), i == 0 ? v1::CUE : v1::RED, 0.9, 1.0);
  }
  r.mutable_shot()->set_speed(1);
  v1::SimulateResponse resp;
  grpc::ClientContext ctx;
  const grpc::Status st = stub_->Simulate(&ctx, r, &resp);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(Mentions(st.error_message(), "10000 balls")) << st.error_message();
  EXPECT_LT(st.error_message().size(), 100u);
}

TEST_F(CallsTest, AOneMegabyteIdIsRefusedWithAShortMessage) {
  StartServer({});
  v1::SimulateRequest r = req::BreakOff(1, 0, 0);
  r.mutable_table()->mutable_balls(0)->set_id(std::string(1 << 20, 'c'));
  v1::SimulateResponse resp;
  grpc::ClientContext ctx;
  const grpc::Status st = stub_->Simulate(&ctx, r, &resp);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(Mentions(st.error_message(), "(1048576 bytes)")) << st.error_message().substr(0, 300);
  EXPECT_LT(st.error_message().size(), 300u);
}

// Heavy calls with a 100 ms client deadline, far more than one worker can do in that
// time: each is answered DEADLINE_EXCEEDED, the server stopped every call it did not
// finish in time, and it is idle again long before the work would have ended.
TEST_F(CallsTest, HeavyCallsWithA100msDeadlineAreAnsweredDeadlineExceeded) {
  ServerOptions options;
  options.workers = 1;
  options.max_queued = 10'000;
  StartServer(options);
  WarmUp();
  const int n = HeavyCallsForTheWork();
  const v1::SimulateRequest heavy = req::Heavy();
  const auto t0 = Clock::now();
  Batch batch(stub_.get(), heavy, n, milliseconds(100));
  const std::vector<int> by_code = batch.Wait();
  const auto answered_after = Clock::now() - t0;
  const auto idle_after = WaitUntilIdle(t0);
  const int late = by_code[grpc::StatusCode::DEADLINE_EXCEEDED];
  EXPECT_EQ(late + by_code[grpc::StatusCode::OK], n);
  EXPECT_GT(late, n / 2);
  EXPECT_LT(answered_after, kWork / 2);
  const CallCounts c = server_->counts();
  // The server answers DEADLINE_EXCEEDED, or CANCELLED when the client's own timer
  // (its deadline less the time in transit) cancelled the call first.
  const std::int64_t stopped =
      c.with(grpc::StatusCode::DEADLINE_EXCEEDED) + c.with(grpc::StatusCode::CANCELLED);
  EXPECT_EQ(stopped + c.with(grpc::StatusCode::OK), c.received);
  EXPECT_GT(stopped, c.received / 2);
  EXPECT_LT(idle_after, kWork / 2);
}

// The same without a client deadline, ended by the server's maximum: every call
// reaches the server, and its own DEADLINE_EXCEEDED comes back to the client.
TEST_F(CallsTest, HeavyCallsPastTheServerMaximumAreAnsweredDeadlineExceeded) {
  ServerOptions options;
  options.workers = 1;
  options.max_queued = 10'000;
  options.max_call = milliseconds(100);
  StartServer(options);
  const int n = HeavyCallsForTheWork();
  const v1::SimulateRequest heavy = req::Heavy();
  const auto t0 = Clock::now();
  Batch batch(stub_.get(), heavy, n, std::nullopt);
  const std::vector<int> by_code = batch.Wait();
  const auto idle_after = WaitUntilIdle(t0);
  const int late = by_code[grpc::StatusCode::DEADLINE_EXCEEDED];
  EXPECT_EQ(late + by_code[grpc::StatusCode::OK], n);
  EXPECT_GT(late, n / 2);
  EXPECT_EQ(server_->counts().with(grpc::StatusCode::DEADLINE_EXCEEDED), late);
  for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
    if (batch.status(i).error_code() == grpc::StatusCode::DEADLINE_EXCEEDED) {
      EXPECT_TRUE(Mentions(batch.status(i).error_message(), "the call's deadline passed"))
          << batch.status(i).error_message();
    }
  }
  EXPECT_LT(idle_after, kWork / 2);
}

// A call without a deadline still ends at the server's maximum, inside its run.
TEST_F(CallsTest, TheServerMaximumEndsACallWithoutADeadline) {
  ServerOptions options;
  options.max_call = milliseconds(1);
  StartServer(options);
  v1::SimulateResponse resp;
  grpc::ClientContext ctx;
  const grpc::Status st = stub_->Simulate(&ctx, req::Heavy(), &resp);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  EXPECT_TRUE(Mentions(st.error_message(), "the call's deadline passed")) << st.error_message();
}

// Cancelled calls stop: with all of them received (kWork queued), the server answers
// them CANCELLED and is idle long before the work would have ended.
TEST_F(CallsTest, CancelledCallsStopWorking) {
  ServerOptions options;
  options.workers = 1;
  options.max_queued = 10'000;
  StartServer(options);
  const int n = HeavyCallsForTheWork();
  const v1::SimulateRequest heavy = req::Heavy();
  Batch batch(stub_.get(), heavy, n, std::nullopt);
  ASSERT_TRUE(WaitUntilReceived(n));
  const auto t1 = Clock::now();
  batch.CancelAll();
  const std::vector<int> by_code = batch.Wait();
  const auto idle_after = WaitUntilIdle(t1);
  EXPECT_GT(by_code[grpc::StatusCode::CANCELLED], n / 2);
  const CallCounts c = server_->counts();
  EXPECT_EQ(c.with(grpc::StatusCode::CANCELLED) + c.with(grpc::StatusCode::OK), n);
  EXPECT_GT(c.with(grpc::StatusCode::CANCELLED), n / 2);
  EXPECT_LT(idle_after, kWork / 2);
}

// One worker, no queue: calls beyond the one running are refused at once.
TEST_F(CallsTest, ABusyServerRefusesCallsBeyondItsQueue) {
  ServerOptions options;
  options.workers = 1;
  options.max_queued = 0;
  StartServer(options);
  Batch batch(stub_.get(), req::Heavy(), 10, std::nullopt);
  const std::vector<int> by_code = batch.Wait();
  EXPECT_GE(by_code[grpc::StatusCode::OK], 1);
  EXPECT_GE(by_code[grpc::StatusCode::RESOURCE_EXHAUSTED], 1);
  EXPECT_EQ(by_code[grpc::StatusCode::OK] + by_code[grpc::StatusCode::RESOURCE_EXHAUSTED], 10);
  for (size_t i = 0; i < 10; ++i) {
    if (batch.status(i).error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED) {
      EXPECT_TRUE(Mentions(batch.status(i).error_message(), "the server is busy"));
    }
  }
}

TEST_F(CallsTest, EveryCallIsLoggedOnOneLine) {
  StartServer({});
  v1::CollideResponse ok;
  grpc::ClientContext ctx1;
  ASSERT_TRUE(stub_->Collide(&ctx1, req::PaperCollide(), &ok).ok());
  v1::SimulateResponse bad;
  grpc::ClientContext ctx2;
  ASSERT_FALSE(stub_->Simulate(&ctx2, v1::SimulateRequest(), &bad).ok());
  WaitUntilIdle(Clock::now());
  server_->Shutdown(milliseconds(0));
  const std::string log = log_.str();
  EXPECT_TRUE(Mentions(log, "snooker: call method=Collide peer=ipv4:127.0.0.1:")) << log;
  EXPECT_TRUE(Mentions(log, "status=OK latency_ms=")) << log;
  EXPECT_TRUE(Mentions(log, "method=Simulate")) << log;
  EXPECT_TRUE(Mentions(log, "status=INVALID_ARGUMENT")) << log;
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 2) << log;
}

// A call goes by the client's request id, or one the server makes: in its log line
// and in the answer's initial metadata, for calls answered on a gRPC thread and on a
// worker, OK or not.
TEST_F(CallsTest, EachCallIsNamedByItsRequestIdInTheLogAndTheAnswer) {
  StartServer({});
  auto id_sent_back = [](const grpc::ClientContext& ctx) {
    const auto& md = ctx.GetServerInitialMetadata();
    const auto it = md.find("x-request-id");
    return it == md.end() ? std::string("(none)") : std::string(it->second.data(), it->second.size());
  };
  grpc::ClientContext given;
  given.AddMetadata("x-request-id", "robot-3:shot-412");
  v1::CollideResponse collide;
  ASSERT_TRUE(stub_->Collide(&given, req::PaperCollide(), &collide).ok());
  EXPECT_EQ(id_sent_back(given), "robot-3:shot-412");

  grpc::ClientContext none;  // a refused call, without an id
  v1::SimulateResponse simulate;
  ASSERT_FALSE(stub_->Simulate(&none, v1::SimulateRequest(), &simulate).ok());
  const std::string made = id_sent_back(none);
  EXPECT_TRUE(std::regex_match(made, std::regex("[0-9a-f]{16}"))) << made;

  grpc::ClientContext unprintable;  // an id the log could not carry is replaced
  unprintable.AddMetadata("x-request-id", "shot 412");
  v1::GetModelResponse model;
  ASSERT_TRUE(stub_->GetModel(&unprintable, v1::GetModelRequest(), &model).ok());
  const std::string replaced = id_sent_back(unprintable);
  EXPECT_TRUE(std::regex_match(replaced, std::regex("[0-9a-f]{16}"))) << replaced;
  EXPECT_NE(replaced, made);

  grpc::ClientContext plan;  // the plans' own path
  plan.AddMetadata("x-request-id", "plan-1");
  v1::PlanResponse planned;
  EXPECT_EQ(stub_->Plan(&plan, v1::PlanRequest(), &planned).error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(id_sent_back(plan), "plan-1");
  grpc::ClientContext stream;
  stream.AddMetadata("x-request-id", "stream-1");
  auto reader = stub_->PlanStream(&stream, v1::PlanRequest());
  while (reader->Read(&planned)) {
  }
  EXPECT_EQ(reader->Finish().error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(id_sent_back(stream), "stream-1");

  WaitUntilIdle(Clock::now());
  server_->Shutdown(milliseconds(0));
  const std::string log = log_.str();
  for (const char* line : {"method=Collide peer=ipv4:127.0.0.1:", "request_id=robot-3:shot-412 status=OK"}) {
    EXPECT_TRUE(Mentions(log, line)) << log;
  }
  for (const std::string& id : {made, replaced, std::string("plan-1"), std::string("stream-1")}) {
    EXPECT_TRUE(Mentions(log, "request_id=" + id + " status=")) << id << "\n" << log;
  }
  EXPECT_FALSE(Mentions(log, "shot 412")) << log;
}

// Shutdown lets calls in flight finish for its grace, then cancels the rest.
TEST_F(CallsTest, ShutdownCancelsWhatIsLeftAfterItsGrace) {
  ServerOptions options;
  options.workers = 1;
  options.max_queued = 10'000;
  StartServer(options);
  const int n = HeavyCallsForTheWork();
  const v1::SimulateRequest heavy = req::Heavy();
  Batch batch(stub_.get(), heavy, n, std::nullopt);
  ASSERT_TRUE(WaitUntilReceived(n));
  const auto t1 = Clock::now();
  server_->Shutdown(milliseconds(100));
  const auto shutdown_took = Clock::now() - t1;
  const std::vector<int> by_code = batch.Wait();
  // The server answers CANCELLED; the client of a call cut by the shutdown sees
  // gRPC's UNAVAILABLE.
  EXPECT_GT(server_->counts().with(grpc::StatusCode::CANCELLED), n / 2);
  EXPECT_EQ(by_code[grpc::StatusCode::OK] + by_code[grpc::StatusCode::CANCELLED] +
                by_code[grpc::StatusCode::UNAVAILABLE],
            n);
  EXPECT_GE(shutdown_took, milliseconds(100));  // the grace was given
  EXPECT_LT(shutdown_took, kWork / 2);
  EXPECT_EQ(server_->counts().in_flight(), 0);
}

// A peer that opens an HTTP/2 connection to `port` and then answers nothing, though
// it reads what comes (a client that vanished without closing: a robot that lost
// power or its network). How long the server took to close the connection, or
// nullopt when it was still open after `wait`.
std::optional<Clock::duration> SilentPeerClosedAfter(int port, Clock::duration wait) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return Clock::duration::zero();
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(port));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const auto start = Clock::now();
  std::optional<Clock::duration> closed = Clock::duration::zero();
  // The client's connection preface, then an empty SETTINGS frame.
  static constexpr char kHello[] = "PRI * HTTP/2.0\r\n\r\nSM\r\n\r\n\0\0\0\x04\0\0\0\0\0";
  if (connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof(to)) == 0 &&
      write(fd, kHello, sizeof(kHello) - 1) == static_cast<ssize_t>(sizeof(kHello) - 1)) {
    closed.reset();
    char buf[4096];
    for (auto left = wait; left > Clock::duration::zero(); left = wait - (Clock::now() - start)) {
      pollfd p{fd, POLLIN, 0};
      const auto ms = std::chrono::duration_cast<milliseconds>(left).count() + 1;
      if (poll(&p, 1, static_cast<int>(ms)) <= 0) continue;
      if (read(fd, buf, sizeof(buf)) <= 0) {
        closed = Clock::now() - start;
        break;
      }
    }
  }
  close(fd);
  return closed;
}

// The server pings a quiet connection and closes it when the ping goes unanswered; a
// client that answers keeps its connection. With gRPC's own defaults the silent
// peer would hold its connection (and a descriptor) for over two hours.
TEST_F(CallsTest, AConnectionThatStopsAnsweringIsClosedByTheKeepalive) {
  ServerOptions options;
  options.keepalive = milliseconds(200);
  options.keepalive_timeout = milliseconds(200);
  StartServer(options);
  const std::optional<Clock::duration> closed = SilentPeerClosedAfter(server_->port(), std::chrono::seconds(20));
  ASSERT_TRUE(closed.has_value()) << "the silent connection was still open after 20 s";
  // A ping, then its timeout: 400 ms, less what gRPC's timers, kept in whole
  // milliseconds, may fire early (seen: 399.8 ms).
  EXPECT_GE(*closed, milliseconds(395));
  // A client that answers the pings keeps its connection through many of them.
  WarmUp();
  std::this_thread::sleep_for(milliseconds(1500));
  EXPECT_EQ(channel_->GetState(false), GRPC_CHANNEL_READY);
  WarmUp();
}

TEST_F(CallsTest, WithTheDefaultKeepaliveASilentConnectionIsLeftForNow) {
  StartServer({});
  EXPECT_FALSE(SilentPeerClosedAfter(server_->port(), std::chrono::seconds(2)).has_value());
}

TEST(KeepaliveTest, OutOfRangeSettingsAreRefusedByName) {
  for (const auto& [keepalive, timeout, message] :
       {std::tuple{0, 20'000, "keepalive 0 ms is outside [1, 86400000] ms"},
        std::tuple{60'000, -1, "keepalive_timeout -1 ms is outside [1, 86400000] ms"},
        std::tuple{86'400'001, 20'000, "keepalive 86400001 ms is outside [1, 86400000] ms"}}) {
    ServerOptions options;
    options.address = "127.0.0.1:0";
    options.keepalive = milliseconds(keepalive);
    options.keepalive_timeout = milliseconds(timeout);
    std::string error;
    EXPECT_EQ(Server::Start(options, &error), nullptr) << message;
    EXPECT_EQ(error, message);
  }
}

}  // namespace
}  // namespace snooker::server
