// The service over HTTP with the Connect protocol (server/http_server.h,
// server/connect.h), through an in-process server and cpp-httplib's client: the
// answers equal gRPC's, errors carry Connect's codes and HTTP statuses, a stream
// sends enveloped progress and ends with its end-of-stream message, the client's
// timeout ends a plan, and the listener's security: plaintext only on loopback,
// HTTPS with the TLS flags, CORS only for a named origin, the page with its headers.
#include <google/protobuf/util/json_util.h>
#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <future>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "cli/load_tables.h"
#include "server/build_info.h"
#include "server/connect.h"
#include "server/request_id.h"
#include "server/server.h"
#include "server/tls_context.h"
#include "server/web_files.h"
#include "tests/service/requests.h"
#include "tests/service/server_support.h"
#include "tests/support/cli_support.h"
#include "tests/support/text.h"

// Last: through <resolv.h> it defines the macro _res, a name Eigen's headers use.
#include <httplib.h>

namespace snooker::server {
namespace {

using Clock = std::chrono::steady_clock;
using server_support::ShotsOf;

std::string Json(const google::protobuf::Message& m) {
  std::string out;
  EXPECT_TRUE(google::protobuf::util::MessageToJsonString(m, &out).ok());
  return out;
}

template <typename Message>
Message FromJson(const std::string& json) {
  Message m;
  const auto st = google::protobuf::util::JsonStringToMessage(json, &m);
  EXPECT_TRUE(st.ok()) << st.message() << ": " << json.substr(0, 300);
  return m;
}

// A plan of the built-in table "black" capped in simulations: the same answer for
// the same seed.
v1::PlanRequest BlackPlan() {
  v1::PlanRequest r;
  EXPECT_TRUE(cli::BuiltinTable("black", r.mutable_table()));
  r.set_max_simulations(300);
  r.set_monte_carlo_samples(16);
  r.set_time_budget_ms(10'000);
  r.set_seed(1);
  return r;
}

// A plan that would take its whole 10 s budget: 15 reds, no simulation cap.
v1::PlanRequest LongPlan() {
  v1::PlanRequest r;
  testing_requests::AddBall(&r, "cue", v1::CUE, 0.889, 1.2);
  for (int i = 0; i < 15; ++i) {
    testing_requests::AddBall(&r, "red-" + std::to_string(i + 1), v1::RED, 0.3 + 0.59 * (i % 3),
                              1.6 + 0.35 * (i / 3));
  }
  r.set_time_budget_ms(10'000);
  r.set_max_simulations(100'000'000);
  r.set_monte_carlo_samples(100'000);
  return r;
}

// LongPlan(), kept for a call in flight.
const v1::PlanRequest& LongPlanRequest() {
  static const v1::PlanRequest r = LongPlan();
  return r;
}

// The envelopes of a streaming answer: (flags, message).
std::vector<std::pair<int, std::string>> Envelopes(const std::string& body) {
  std::vector<std::pair<int, std::string>> out;
  std::size_t at = 0;
  while (at + 5 <= body.size()) {
    std::size_t n = 0;
    for (std::size_t i = 1; i < 5; ++i) n = (n << 8) | static_cast<unsigned char>(body[at + i]);
    if (at + 5 + n > body.size()) break;
    out.emplace_back(static_cast<unsigned char>(body[at]), body.substr(at + 5, n));
    at += 5 + n;
  }
  EXPECT_EQ(at, body.size()) << "bytes after the last whole envelope";
  return out;
}

// A socket connected to the server at `port` on loopback, or -1.
int ConnectLoopback(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return -1;
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(port));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&to), sizeof(to)) == 0) return fd;
  close(fd);
  return -1;
}

bool WriteAll(int fd, std::string_view bytes) {
  return write(fd, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size());
}

// What arrives on `fd` until the peer closes it, or until 20 s have passed.
std::string ReadUntilClosed(int fd) {
  std::string answer;
  const auto end = Clock::now() + std::chrono::seconds(20);
  char buf[4096];
  for (int i = 0; i < 10'000 && Clock::now() < end; ++i) {
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, 100) <= 0) continue;
    const ssize_t n = read(fd, buf, sizeof(buf));
    if (n <= 0) break;
    answer.append(buf, static_cast<std::size_t>(n));
  }
  return answer;
}

// What the server at `port` answers to the raw bytes `request` (which should ask it to
// close the connection), read until it closes, or "" when it does not within 20 s.
std::string RawExchange(int port, const std::string& request) {
  const int fd = ConnectLoopback(port);
  if (fd < 0) return "";
  std::string answer;
  if (WriteAll(fd, request)) answer = ReadUntilClosed(fd);
  close(fd);
  return answer;
}

class HttpTest : public testing::Test {
 protected:
  void StartServer(ServerOptions options = {}) {
    if (options.http_address.empty()) options.http_address = "127.0.0.1:0";
    test_server_ = std::make_unique<server_support::TestServer>(options);
    ASSERT_NE(test_server_->server, nullptr);
    port_ = test_server_->server->http_port();
    ASSERT_GT(port_, 0);
  }
  httplib::Client Client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(60, 0);
    return c;
  }
  httplib::Result Call(const std::string& method, const std::string& body,
                       const std::string& type = "application/json", const httplib::Headers& headers = {}) {
    return Client().Post(("/snooker.v1.ShotPlanner/" + method).c_str(), headers, body, type.c_str());
  }
  // The server's log once every call it received has its answer.
  std::string Log() {
    server_support::WaitUntilAnswered(*test_server_->server, 0, std::chrono::seconds(20));
    return test_server_->log.str();
  }

  std::unique_ptr<server_support::TestServer> test_server_;
  int port_ = 0;
};

TEST_F(HttpTest, PlanOfABuiltinTableEqualsTheGrpcAnswer) {
  StartServer();
  const v1::PlanRequest request = BlackPlan();
  v1::PlanResponse grpc_answer;
  grpc::ClientContext ctx;
  const grpc::Status st = test_server_->stub->Plan(&ctx, request, &grpc_answer);
  ASSERT_TRUE(st.ok()) << st.error_message();
  ASSERT_GT(grpc_answer.shots_size(), 0) << grpc_answer.reason();

  const auto res = Call("Plan", Json(request));
  ASSERT_TRUE(res) << httplib::to_string(res.error());
  ASSERT_EQ(res->status, 200) << res->body;
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/json");
  const auto http_answer = FromJson<v1::PlanResponse>(res->body);
  EXPECT_EQ(ShotsOf(http_answer), ShotsOf(grpc_answer));
  EXPECT_EQ(http_answer.simulations(), grpc_answer.simulations());
  EXPECT_TRUE(http_answer.final());
  EXPECT_EQ(http_answer.simulation_cap(), 300);
  EXPECT_FALSE(http_answer.cut_short());
  EXPECT_TRUE(Mentions(res->body, "\"headingDeg\"")) << "lowerCamelCase names";
  EXPECT_TRUE(Mentions(res->body, "\"cutShort\"")) << "every field, false ones too";

  // The binary form gives the same answer.
  const auto binary = Call("Plan", request.SerializeAsString(), "application/proto");
  ASSERT_TRUE(binary);
  ASSERT_EQ(binary->status, 200);
  v1::PlanResponse from_binary;
  ASSERT_TRUE(from_binary.ParseFromString(binary->body));
  EXPECT_EQ(ShotsOf(from_binary), ShotsOf(grpc_answer));

  const std::string log = Log();
  EXPECT_TRUE(Mentions(log, "method=Plan peer=ipv4:127.0.0.1:")) << log;
  EXPECT_TRUE(Mentions(log, "transport=http")) << log;
}

// A log stream that throws on every line (the access log's and the call's alike)
// loses the lines and answers the calls.
TEST_F(HttpTest, ALogThatRefusesItsLinesLosesThemAndNotTheCalls) {
  StartServer();
  std::ostream& log = test_server_->log;
  server_support::RefusingBuffer refusing;
  std::streambuf* const kept = log.rdbuf(&refusing);
  log.exceptions(std::ios::badbit);
  for (int call = 0; call < 2; ++call) {
    const auto res = Call("Plan", Json(BlackPlan()));
    ASSERT_TRUE(res) << httplib::to_string(res.error());
    EXPECT_EQ(res->status, 200) << res->body;
    EXPECT_GT(FromJson<v1::PlanResponse>(res->body).shots_size(), 0);
  }
  const server::CallCounts counts =
      server_support::WaitUntilAnswered(*test_server_->server, 2, std::chrono::seconds(20));
  EXPECT_EQ(counts.in_flight(), 0);
  EXPECT_EQ(counts.log_lines_lost, 2);
  log.exceptions(std::ios::goodbit);
  log.clear();
  log.rdbuf(kept);
}

TEST_F(HttpTest, GetModelAnswersTheServersModelInJson) {
  StartServer();
  v1::GetModelResponse grpc_answer;
  grpc::ClientContext ctx;
  ASSERT_TRUE(test_server_->stub->GetModel(&ctx, v1::GetModelRequest(), &grpc_answer).ok());
  for (const char* body : {"{}", ""}) {
    const auto res = Call("GetModel", body);
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200) << res->body;
    EXPECT_TRUE(google::protobuf::util::MessageDifferencer::Equals(FromJson<v1::GetModelResponse>(res->body),
                                                                   grpc_answer));
  }
}

// GET /metrics counts the calls of both transports by method and status, and times
// them; it is not itself a call.
TEST_F(HttpTest, MetricsCountTheCallsOfBothTransports) {
  StartServer();
  v1::CollideResponse grpc_answer;
  grpc::ClientContext ctx;
  ASSERT_TRUE(test_server_->stub->Collide(&ctx, testing_requests::PaperCollide(), &grpc_answer).ok());
  ASSERT_EQ(Call("Collide", Json(testing_requests::PaperCollide()))->status, 200);
  v1::CollideRequest bad = testing_requests::PaperCollide();
  bad.set_speed(-1);
  ASSERT_EQ(Call("Collide", Json(bad))->status, 400);
  Log();  // every call answered
  const auto res = Client().Get("/metrics");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(res->get_header_value("Content-Type"), "text/plain; version=0.0.4; charset=utf-8");
  EXPECT_EQ(res->get_header_value("Cache-Control"), "no-store");
  const std::string& text = res->body;
  EXPECT_TRUE(Mentions(text, std::string("\nsnooker_build_info{version=\"") + kBuildVersion + "\",commit=\"" +
                                 kBuildCommit + "\"} 1\n"))
      << text;
  EXPECT_TRUE(Mentions(text, "\nsnooker_calls_received_total 3\n")) << text;
  EXPECT_TRUE(Mentions(text, "\nsnooker_calls_in_flight 0\n")) << text;
  EXPECT_TRUE(Mentions(text, "\nsnooker_calls_total{method=\"Collide\",code=\"OK\"} 2\n")) << text;
  EXPECT_TRUE(Mentions(text, "\nsnooker_calls_total{method=\"Collide\",code=\"INVALID_ARGUMENT\"} 1\n")) << text;
  EXPECT_TRUE(Mentions(text, "\nsnooker_call_latency_seconds_count{method=\"Collide\"} 3\n")) << text;
  EXPECT_TRUE(Mentions(text, "\nsnooker_call_latency_seconds_count{method=\"Plan\"} 0\n")) << text;
  EXPECT_TRUE(Mentions(text, "\nsnooker_plans_cut_short_total 0\n")) << text;
  EXPECT_FALSE(Mentions(text, "snooker_tls_certificate_expiry")) << "no TLS, no certificate: " << text;
  // Scraping is not a call: the count stands.
  EXPECT_TRUE(Mentions(Client().Get("/metrics")->body, "\nsnooker_calls_received_total 3\n"));
  EXPECT_EQ(Client().Post("/metrics", "", "text/plain")->status, 405);
}

TEST_F(HttpTest, ABadValueIsInvalidArgumentNamingTheField) {
  StartServer();
  v1::CollideRequest request = testing_requests::PaperCollide();
  request.set_speed(-1);
  const auto res = Call("Collide", Json(request));
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400);
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/json");
  EXPECT_TRUE(Mentions(res->body, "\"code\": \"invalid_argument\"")) << res->body;
  EXPECT_TRUE(Mentions(res->body, "speed")) << res->body;
}

TEST_F(HttpTest, BadJsonIsInvalidArgumentSayingWhere) {
  StartServer();
  auto res = Call("Collide", "{\"speed\": 1.5,\n \"cutAngleDeg\": }");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400);
  EXPECT_TRUE(Mentions(res->body, "invalid_argument")) << res->body;
  EXPECT_TRUE(Mentions(res->body, "line 2, column")) << res->body;
  res = Call("Collide", R"({"speed": 1.5, "sped": 2})");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400);
  EXPECT_TRUE(Mentions(res->body, "sped")) << res->body;
  res = Call("Simulate", R"({"table": {"balls": [{"id": "cue", "position": {"x": "left"}}]}})");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400);
  EXPECT_TRUE(Mentions(res->body, "position.x")) << res->body;
  // Bytes that are not a message in the binary form.
  res = Call("Collide", "\xff\xff\xff", "application/proto");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400);
  EXPECT_TRUE(Mentions(res->body, "invalid_argument")) << res->body;
}

TEST_F(HttpTest, WhatIsNotAProcedureOrNotThisWayIsRefused) {
  StartServer();
  auto res = Call("Teleport", "{}");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 404);
  EXPECT_TRUE(Mentions(res->body, "\"code\": \"unimplemented\"")) << res->body;
  EXPECT_TRUE(Mentions(res->body, "Teleport")) << res->body;

  res = Client().Get("/snooker.v1.ShotPlanner/Plan");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 405);
  EXPECT_TRUE(Mentions(res->get_header_value("Allow"), "POST"));

  res = Call("GetModel", "{}", "text/plain");  // what a page may send without asking
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 415);
  res = Call("PlanStream", "{}", "application/json");  // a stream, asked for as unary
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 415);
  res = Call("GetModel", "{}", "application/json", {{"Connect-Timeout-Ms", "soon"}});
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400);
  EXPECT_TRUE(Mentions(res->body, "Connect-Timeout-Ms")) << res->body;
}

TEST_F(HttpTest, AnOversizedBodyIsRefused) {
  StartServer();
  const std::string body(limits::kMaxRequestBytes + 100, ' ');
  const auto res = Call("Simulate", body);
  ASSERT_TRUE(res) << httplib::to_string(res.error());
  EXPECT_EQ(res->status, 429);
  EXPECT_TRUE(Mentions(res->body, "\"code\": \"resource_exhausted\"")) << res->body;
  EXPECT_TRUE(Mentions(res->body, "larger than")) << res->body;
  // The server goes on.
  const auto after = Call("GetModel", "{}");
  ASSERT_TRUE(after);
  EXPECT_EQ(after->status, 200);
}

// A POST without Content-Length or Transfer-Encoding has no body (RFC 9112, 6.3):
// GetModel answers it at once, where the server used to wait for a body until its
// read timeout. A length given twice, or not in digits, is refused, naming it.
TEST_F(HttpTest, ABodysFramingIsReadAsHttpSaysOrRefused) {
  StartServer();
  const std::string head = "POST /snooker.v1.ShotPlanner/GetModel HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                           "Content-Type: application/json\r\nConnection: close\r\n";
  const std::string none = RawExchange(port_, head + "\r\n");
  EXPECT_EQ(none.rfind("HTTP/1.1 200 ", 0), 0u) << none;
  EXPECT_TRUE(Mentions(none, "\"cue\"")) << none;
  struct Case {
    const char* headers;
    const char* status;
    const char* mention;
  };
  for (const Case& c : {Case{"Content-Length: abc\r\n", "400", "Content-Length 'abc' is not a whole number of bytes"},
                        Case{"Content-Length: -5\r\n", "400", "Content-Length '-5'"},
                        Case{"Content-Length: 2\r\nContent-Length: 5\r\n", "400", "Content-Length is given 2 times"},
                        Case{"Content-Length: 2\r\n", "200", "\"cue\""}}) {  // one length of digits, as before
    const std::string answer = RawExchange(port_, head + c.headers + "\r\n{}");
    EXPECT_EQ(answer.rfind(std::string("HTTP/1.1 ") + c.status + " ", 0), 0u) << c.headers << answer;
    EXPECT_TRUE(Mentions(answer, c.mention)) << c.headers << answer;
  }
}

// What cpp-httplib refuses before any handler of ours runs is answered with a body
// that says what was refused: a Connect error on the service's paths, text elsewhere.
TEST_F(HttpTest, RefusalsBeforeRoutingSayWhatWasRefused) {
  StartServer();
  const std::string tail = " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
  struct Case {
    std::string request_line;
    const char* status;
    std::vector<const char*> mentions;
  };
  const std::string long_path = "/" + std::string(CPPHTTPLIB_REQUEST_URI_MAX_LENGTH + 10, 'a');
  for (const Case& c : {Case{"TRACE /", "400", {"method TRACE is not served", "text/plain", "Connection: close"}},
                        Case{"TRACE /snooker.v1.ShotPlanner/Plan", "400",
                             {"\"code\": \"invalid_argument\"", "method TRACE", "application/json"}},
                        Case{"GET " + long_path, "414", {"longer than 8192 bytes", "Connection: close"}}}) {
    const std::string answer = RawExchange(port_, c.request_line + tail);
    const std::string shown = c.request_line.substr(0, 60);
    EXPECT_EQ(answer.rfind(std::string("HTTP/1.1 ") + c.status + " ", 0), 0u) << shown << "\n" << answer;
    for (const char* mention : c.mentions) EXPECT_TRUE(Mentions(answer, mention)) << shown << "\n" << answer;
  }
  // Answers of the server's own keep their bodies.
  const auto res = Client().Get("/nothing-here");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 404);
  EXPECT_EQ(res->body, "not found\n");
}

TEST_F(HttpTest, AOneMillisecondTimeoutEndsABigPlanAsGrpcsDeadlineDoes) {
  StartServer();
  const auto start = Clock::now();
  const auto res = Call("Plan", Json(LongPlan()), "application/json", {{"Connect-Timeout-Ms", "1"}});
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  ASSERT_TRUE(res);
  EXPECT_LT(seconds, 5.0);
  if (res->status == 200) {  // OK only with the shots verified by then
    EXPECT_GT(FromJson<v1::PlanResponse>(res->body).shots_size(), 0);
    EXPECT_TRUE(FromJson<v1::PlanResponse>(res->body).cut_short());
  } else {
    EXPECT_EQ(res->status, 504) << res->body;
    EXPECT_TRUE(Mentions(res->body, "\"code\": \"deadline_exceeded\"")) << res->body;
  }
  // Either way the clock stopped its work: the log line and the metrics say so.
  const std::string log = Log();
  EXPECT_TRUE(Mentions(log, "cut_short=1")) << log;
  EXPECT_TRUE(Mentions(Client().Get("/metrics")->body, "\nsnooker_plans_cut_short_total 1\n"));
}

TEST_F(HttpTest, PlansOverHttpAndGrpcShareOneAdmission) {
  ServerOptions options;
  options.max_plans = 1;
  StartServer(options);
  // A gRPC plan holds the one place ...
  grpc::ClientContext ctx;
  v1::PlanResponse held;
  std::promise<grpc::Status> held_done;
  test_server_->stub->async()->Plan(&ctx, &LongPlanRequest(), &held,
                                    [&](grpc::Status st) { held_done.set_value(std::move(st)); });
  const auto give_up = Clock::now() + std::chrono::seconds(20);
  while (test_server_->server->counts().plans < 1 && Clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_EQ(test_server_->server->counts().plans, 1);
  // ... so an HTTP plan is refused at once.
  const auto res = Call("Plan", Json(BlackPlan()));
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 429);
  EXPECT_TRUE(Mentions(res->body, "--max-plans")) << res->body;
  ctx.TryCancel();
  EXPECT_EQ(held_done.get_future().get().error_code(), grpc::StatusCode::CANCELLED);
}

TEST_F(HttpTest, AShutdownCancelsAnHttpPlanAfterItsGrace) {
  StartServer();
  std::promise<httplib::Result> answer;
  std::thread client([&] { answer.set_value(Call("Plan", Json(LongPlan()))); });
  const auto give_up = Clock::now() + std::chrono::seconds(20);
  while (test_server_->server->counts().running < 1 && Clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  const auto start = Clock::now();
  test_server_->server->Shutdown(std::chrono::milliseconds(100));
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  client.join();
  const httplib::Result res = answer.get_future().get();
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 499) << res->body;
  EXPECT_TRUE(Mentions(res->body, "\"code\": \"canceled\"")) << res->body;
  EXPECT_LT(seconds, 5.0);
  EXPECT_TRUE(Mentions(test_server_->log.str(), "method=Plan")) << test_server_->log.str();
}

// A client that sends its request a byte a second outlives the shutdown's wait for
// connections (the keep-alive and I/O timeouts). The server and its service are
// destroyed while it trickles; its request, once whole, is refused as the shutdown's,
// where the handlers used to run on the freed listener and service.
TEST_F(HttpTest, AConnectionThatOutlivesTheShutdownIsRefusedWithoutTheService) {
  StartServer();
  const int fd = ConnectLoopback(port_);
  ASSERT_GE(fd, 0);
  constexpr int kBodyBytes = 64;
  ASSERT_TRUE(WriteAll(fd, "POST /snooker.v1.ShotPlanner/GetModel HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                           "Content-Type: application/json\r\nConnection: close\r\nContent-Length: " +
                               std::to_string(kBodyBytes) + "\r\n\r\n{"));
  std::atomic<bool> destroyed{false};
  std::thread trickle([&] {
    int sent = 1;
    for (; sent < kBodyBytes - 1 && !destroyed.load(); ++sent) {
      if (!WriteAll(fd, " ")) return;
      std::this_thread::sleep_for(std::chrono::seconds(1));
    }
    WriteAll(fd, std::string(static_cast<std::size_t>(kBodyBytes - 1 - sent), ' ') + "}");
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // the request is being read
  const auto start = Clock::now();
  test_server_.reset();  // the shutdown gives up on the connection, the service goes
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  destroyed.store(true);
  trickle.join();
  const std::string answer = ReadUntilClosed(fd);
  close(fd);
  EXPECT_GT(seconds, limits::kHttpKeepAliveSeconds + limits::kHttpIoTimeoutSeconds - 1.0);  // it waited first
  EXPECT_EQ(answer.rfind("HTTP/1.1 503 ", 0), 0u) << answer;
  EXPECT_TRUE(Mentions(answer, "the server is shutting down")) << answer;
}

TEST_F(HttpTest, PlanStreamSendsProgressThenPlansAnswerThenTheEnd) {
  StartServer();
  const v1::PlanRequest request = BlackPlan();
  const auto unary = Call("Plan", Json(request));
  ASSERT_TRUE(unary);
  ASSERT_EQ(unary->status, 200) << unary->body;
  const auto plan = FromJson<v1::PlanResponse>(unary->body);

  const auto res = Call("PlanStream", connect::Envelope(0, Json(request)), "application/connect+json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200);
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/connect+json");
  const auto envelopes = Envelopes(res->body);
  ASSERT_GE(envelopes.size(), 3u) << "progress, the final answer, the end";
  for (std::size_t i = 0; i + 2 < envelopes.size(); ++i) {
    EXPECT_EQ(envelopes[i].first, 0);
    const auto progress = FromJson<v1::PlanResponse>(envelopes[i].second);
    EXPECT_FALSE(progress.final());
    EXPECT_EQ(progress.shots_size(), 1);
  }
  const auto& last = envelopes[envelopes.size() - 2];
  EXPECT_EQ(last.first, 0);
  const auto answer = FromJson<v1::PlanResponse>(last.second);
  EXPECT_TRUE(answer.final());
  EXPECT_EQ(ShotsOf(answer), ShotsOf(plan));
  EXPECT_EQ(envelopes.back().first, connect::kEndStreamFlag);
  EXPECT_EQ(envelopes.back().second, "{}");
  EXPECT_GE(test_server_->server->counts().progress_messages, 1);

  // A request that is not one envelope ends the stream with the error.
  const auto bad = Call("PlanStream", Json(request), "application/connect+json");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 200);
  const auto bad_envelopes = Envelopes(bad->body);
  ASSERT_EQ(bad_envelopes.size(), 1u);
  EXPECT_EQ(bad_envelopes[0].first, connect::kEndStreamFlag);
  EXPECT_TRUE(Mentions(bad_envelopes[0].second, "{\"error\": {\"code\": \"invalid_argument\""))
      << bad_envelopes[0].second;
}

TEST_F(HttpTest, ThePageTheHealthCheckAndNoCorsByDefault) {
  StartServer();
  auto res = Client().Get("/");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(res->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_EQ(res->get_header_value("Content-Security-Policy"), "default-src 'self'");
  EXPECT_EQ(res->get_header_value("X-Content-Type-Options"), "nosniff");
  EXPECT_EQ(res->get_header_value("Cache-Control"), "no-cache");
  ASSERT_NE(FindWebFile("index.html"), nullptr);
  EXPECT_EQ(res->body, std::string(FindWebFile("index.html")->bytes));
  for (const WebFile& f : WebFiles()) {
    res = Client().Get(("/" + std::string(f.name)).c_str());
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200) << f.name;
    EXPECT_EQ(res->get_header_value("Content-Type"), f.content_type) << f.name;
  }
  res = Client().Get("/no-such-file.js");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 404);
  res = Client().Get("/nested/index.html");  // the page's files are all at the top
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 404);
  // What GET serves is refused other ways with what it allows; anything else is not there.
  for (const std::string path : {"/", "/index.html", "/healthz", "/metrics"}) {
    res = Client().Post(path.c_str(), "", "text/plain");
    ASSERT_TRUE(res) << path;
    EXPECT_EQ(res->status, 405) << path;
    EXPECT_EQ(res->get_header_value("Allow"), "GET, HEAD, OPTIONS") << path;
  }
  res = Client().Post("/no-such-file.js", "", "text/plain");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 404);
  res = Client().Get("/healthz");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(res->body, "SERVING\n");

  res = Call("GetModel", "{}", "application/json", {{"Origin", "https://elsewhere.example"}});
  ASSERT_TRUE(res);
  EXPECT_FALSE(res->has_header("Access-Control-Allow-Origin"));
  res = Client().Options("/snooker.v1.ShotPlanner/Plan",
                         {{"Origin", "https://elsewhere.example"}, {"Access-Control-Request-Method", "POST"}});
  ASSERT_TRUE(res);
  EXPECT_FALSE(res->has_header("Access-Control-Allow-Origin"));
  EXPECT_FALSE(res->has_header("Access-Control-Allow-Methods"));
}

// As over gRPC: a call goes by the client's X-Request-Id or one the server makes, in
// its log line and in the answer's header; so does a request of the page.
TEST_F(HttpTest, EachRequestIsNamedByItsRequestIdInTheLogAndTheAnswer) {
  StartServer();
  auto res = Call("GetModel", "{}", "application/json", {{"x-request-id", "trainer-9"}});  // any case
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(res->get_header_value("X-Request-Id"), "trainer-9");
  res = Call("Simulate", "{\"table\": 1}", "application/json", {{"X-Request-Id", "bad id"}});
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400);
  const std::string made = res->get_header_value("X-Request-Id");
  EXPECT_TRUE(IsPrintableRequestId(made) && made.size() == 16 && made != "bad id") << made;
  // A request of the page is logged after its answer is sent; a call on the same
  // connection is read only once that line is written, and Log() waits for calls.
  httplib::Client probe = Client();
  probe.set_keep_alive(true);
  res = probe.Get("/healthz", {{"X-Request-Id", "probe-1"}});
  ASSERT_TRUE(res);
  EXPECT_EQ(res->get_header_value("X-Request-Id"), "probe-1");
  ASSERT_TRUE(probe.Post("/snooker.v1.ShotPlanner/GetModel", "{}", "application/json"));
  const std::string log = Log();
  EXPECT_TRUE(Mentions(log, "method=GetModel peer=ipv4:127.0.0.1:")) << log;
  EXPECT_TRUE(Mentions(log, "request_id=trainer-9 status=OK")) << log;
  EXPECT_TRUE(Mentions(log, "request_id=" + made + " status=INVALID_ARGUMENT")) << log;
  EXPECT_TRUE(Mentions(log, "path=/healthz peer=ipv4:127.0.0.1:")) << log;
  EXPECT_TRUE(Mentions(log, "request_id=probe-1 status=200")) << log;
}

TEST_F(HttpTest, CorsNamesTheOneOriginGiven) {
  ServerOptions options;
  options.cors_origin = "https://planner.example:8443";
  StartServer(options);
  auto res = Call("GetModel", "{}", "application/json", {{"Origin", "https://planner.example:8443"}});
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(res->get_header_value("Access-Control-Allow-Origin"), "https://planner.example:8443");
  res = Client().Options("/snooker.v1.ShotPlanner/Plan",
                         {{"Origin", "https://planner.example:8443"},
                          {"Access-Control-Request-Method", "POST"},
                          {"Access-Control-Request-Headers", "content-type,connect-protocol-version"}});
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 204);
  EXPECT_EQ(res->get_header_value("Access-Control-Allow-Origin"), "https://planner.example:8443");
  EXPECT_EQ(res->get_header_value("Access-Control-Allow-Methods"), "POST");
  EXPECT_TRUE(Mentions(res->get_header_value("Access-Control-Allow-Headers"), "Connect-Timeout-Ms"));
  // The page of that origin may send a request id and read the one it gets back.
  EXPECT_TRUE(Mentions(res->get_header_value("Access-Control-Allow-Headers"), "X-Request-Id"));
  EXPECT_EQ(res->get_header_value("Access-Control-Expose-Headers"), "X-Request-Id");

  // What is not one origin is refused.
  for (const char* bad : {"*", "planner.example", "https://planner.example/app", "https://a.example\r\nX: 1"}) {
    EXPECT_FALSE(CheckCorsOrigin(bad).empty()) << bad;
  }
}

// A scraper's listener beside gRPC, without the HTTP API: /metrics counts the gRPC
// calls, /healthz answers, and nothing else is served there.
TEST(MetricsListenerTest, ServesMetricsAndHealthAndNothingElse) {
  ServerOptions options;
  options.metrics_address = "127.0.0.1:0";
  server_support::TestServer t(options);
  ASSERT_NE(t.server, nullptr);
  EXPECT_EQ(t.server->http_port(), 0);
  ASSERT_GT(t.server->metrics_port(), 0);
  EXPECT_STREQ(t.server->metrics_scheme(), "http");
  grpc::ClientContext ctx;
  v1::GetModelResponse model;
  ASSERT_TRUE(t.stub->GetModel(&ctx, v1::GetModelRequest(), &model).ok());
  server_support::WaitUntilAnswered(*t.server, 0, std::chrono::seconds(20));
  httplib::Client c("127.0.0.1", t.server->metrics_port());
  const auto metrics = c.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_EQ(metrics->status, 200);
  EXPECT_TRUE(Mentions(metrics->body, "\nsnooker_calls_total{method=\"GetModel\",code=\"OK\"} 1\n")) << metrics->body;
  const auto health = c.Get("/healthz");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
  EXPECT_EQ(health->body, "SERVING\n");
  for (const char* path : {"/", "/index.html", "/snooker.v1.ShotPlanner/GetModel"}) {
    const auto res = c.Get(path);
    ASSERT_TRUE(res) << path;
    EXPECT_EQ(res->status, 404) << path;
    EXPECT_TRUE(Mentions(res->body, "serves GET /metrics and /healthz only")) << path << ": " << res->body;
  }
  const auto call = c.Post("/snooker.v1.ShotPlanner/GetModel", "{}", "application/json");
  ASSERT_TRUE(call);
  EXPECT_EQ(call->status, 404);
  const auto post = c.Post("/metrics", "", "text/plain");
  ASSERT_TRUE(post);
  EXPECT_EQ(post->status, 405);
  EXPECT_EQ(post->get_header_value("Allow"), "GET, HEAD");
  // A request's line is written after its answer: read the log once the listener has
  // stopped.
  t.server->Shutdown(std::chrono::milliseconds(0));
  EXPECT_TRUE(Mentions(t.log.str(), "snooker: http method=GET path=/metrics")) << t.log.str();
}

TEST(HttpCommandTest, PlainHttpOffLoopbackIsRefused) {
  const cli_support::RunResult r = cli_support::RunCli("serve --http 0.0.0.0:0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Mentions(r.err, "refusing to serve HTTP on 0.0.0.0:0 in plaintext")) << r.err;
  EXPECT_TRUE(Mentions(r.err, "--insecure")) << r.err;
  const cli_support::RunResult cors = cli_support::RunCli("serve --cors-origin https://a.example");
  EXPECT_EQ(cors.exit_code, 2);
  EXPECT_TRUE(Mentions(cors.err, "--cors-origin needs --http")) << cors.err;
  const cli_support::RunResult metrics = cli_support::RunCli("serve --metrics 0.0.0.0:0");
  EXPECT_EQ(metrics.exit_code, 2);
  EXPECT_TRUE(Mentions(metrics.err, "refusing to serve metrics on 0.0.0.0:0 in plaintext")) << metrics.err;
  const cli_support::RunResult help = cli_support::RunCli("serve --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_TRUE(Mentions(help.out, "--http HOST:PORT")) << help.out;
  EXPECT_TRUE(Mentions(help.out, "--metrics HOST:PORT")) << help.out;
  EXPECT_TRUE(Mentions(help.out, "--cors-origin ORIGIN")) << help.out;
}

TEST(ConnectTest, EnvelopesTimeoutsAndCodes) {
  std::string_view message;  // a view into the envelope: the envelope must outlive it
  const std::string envelope = connect::Envelope(0, "{}");
  EXPECT_TRUE(connect::OpenEnvelope(envelope, &message).ok());
  EXPECT_EQ(message, "{}");
  EXPECT_FALSE(connect::OpenEnvelope("{}", &message).ok());
  EXPECT_FALSE(connect::OpenEnvelope(connect::Envelope(connect::kCompressedFlag, "{}"), &message).ok());
  EXPECT_FALSE(connect::OpenEnvelope(connect::Envelope(0, "{}") + "x", &message).ok());
  std::chrono::milliseconds ms{};
  EXPECT_TRUE(connect::ParseTimeout("2500", &ms).ok());
  EXPECT_EQ(ms.count(), 2500);
  for (const char* bad : {"", "0", "-1", "1.5", "12345678901", "1 "}) {
    EXPECT_FALSE(connect::ParseTimeout(bad, &ms).ok()) << bad;
  }
  const std::pair<ApiStatus::Code, int> statuses[] = {
      {ApiStatus::Code::kInvalidArgument, 400}, {ApiStatus::Code::kResourceExhausted, 429},
      {ApiStatus::Code::kDeadlineExceeded, 504}, {ApiStatus::Code::kCancelled, 499},
      {ApiStatus::Code::kInternal, 500}};
  for (const auto& [code, http] : statuses) EXPECT_EQ(connect::ErrorOf({code, "m"}).http_status, http);
  EXPECT_EQ(connect::ErrorJson(connect::ErrorOf(ApiStatus::Invalid("ball \"a\"\n"))),
            "{\"code\": \"invalid_argument\", \"message\": \"ball \\\"a\\\"\\u000a\"}");
}

class HttpTlsTest : public HttpTest {
 protected:
  static void SetUpTestSuite() {
    dir_ = cli_support::TempPath("snooker_http_certs");
    const std::string cmd = std::string(SNOOKER_DEV_CERTS) + " " + dir_ + " >/dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  static std::string Path(const std::string& name) { return dir_ + "/" + name; }
  static std::string Pem(const std::string& name) {
    std::ifstream f(Path(name));
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
  }
  /// The line of the certificate expiry gauge that /metrics should show for the
  /// certificate `name`: its notAfter as openssl prints it, read by date(1).
  static std::string ExpiryLine(const std::string& name) {
    const cli_support::RunResult r =
        cli_support::RunShell("date -u -d \"$(openssl x509 -noout -enddate -in " + Path(name) + " | cut -d= -f2)\" +%s");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return "\nsnooker_tls_certificate_expiry_timestamp_seconds " + r.out;  // r.out ends with its newline
  }
  static inline std::string dir_;
};

TEST_F(HttpTlsTest, HttpsServesWithTheTlsFlagsAndPlainHttpFails) {
  ServerOptions options;
  TlsOptions tls;
  tls.cert_chain_pem = Pem("server.pem");
  tls.private_key_pem = Pem("server.key");
  tls.client_ca_pem = Pem("ca.pem");
  options.tls = tls;
  options.http_address = "127.0.0.1:0";
  StartServer(options);

  httplib::SSLClient with_certificate("localhost", port_, Path("client.pem"), Path("client.key"));
  with_certificate.set_ca_cert_path(Path("ca.pem"));
  with_certificate.enable_server_certificate_verification(true);
  auto res = with_certificate.Post("/snooker.v1.ShotPlanner/GetModel", "{}", "application/json");
  ASSERT_TRUE(res) << httplib::to_string(res.error());
  EXPECT_EQ(res->status, 200);
  const auto metrics = with_certificate.Get("/metrics");
  ASSERT_TRUE(metrics);
  EXPECT_TRUE(Mentions(metrics->body, ExpiryLine("server.pem"))) << ExpiryLine("server.pem") << metrics->body;

  httplib::SSLClient without_certificate("localhost", port_);
  without_certificate.set_ca_cert_path(Path("ca.pem"));
  without_certificate.enable_server_certificate_verification(true);
  EXPECT_FALSE(without_certificate.Get("/healthz"));

  httplib::SSLClient stranger("localhost", port_, Path("other-client.pem"), Path("other-client.key"));
  stranger.set_ca_cert_path(Path("ca.pem"));
  stranger.enable_server_certificate_verification(true);
  EXPECT_FALSE(stranger.Get("/healthz"));

  httplib::Client plain("127.0.0.1", port_);
  plain.set_read_timeout(5, 0);
  const auto plain_res = plain.Get("/healthz");
  EXPECT_TRUE(!plain_res || plain_res->status != 200);
}

// The leaf's expiry, read from its PEM text; none from text that is not a certificate.
TEST_F(HttpTlsTest, ACertificatesExpiryIsItsLeafs) {
  const auto expiry = CertificateExpiry(Pem("server.pem") + Pem("other-server.pem"));
  ASSERT_TRUE(expiry);
  EXPECT_EQ("\nsnooker_tls_certificate_expiry_timestamp_seconds " + std::to_string(*expiry) + "\n",
            ExpiryLine("server.pem"));
  EXPECT_FALSE(CertificateExpiry(""));
  EXPECT_FALSE(CertificateExpiry(Pem("server.key")));
  EXPECT_FALSE(CertificateExpiry("-----BEGIN CERTIFICATE-----\nnot base64\n-----END CERTIFICATE-----\n"));
}

TEST_F(HttpTlsTest, ARotatedCertificateIsServedWithoutARestartAndABrokenSetIsNot) {
  server_support::RotatingCertificates certs(cli_support::TempPath("snooker_http_rotation"));
  certs.Serve(Path("server.pem"), Path("server.key"), Path("ca.pem"));
  ServerOptions options;
  TlsOptions tls;
  tls.cert_chain_pem = Pem("server.pem");
  tls.private_key_pem = Pem("server.key");
  tls.client_ca_pem = Pem("ca.pem");
  tls.reload_interval = std::chrono::seconds(1);
  tls.cert_chain_file = certs.File("cert.pem");
  tls.private_key_file = certs.File("key.pem");
  tls.client_ca_file = certs.File("ca.pem");
  options.tls = tls;
  StartServer(options);
  // Whether a client that trusts `ca`, with the certificate `client`, is answered.
  auto answered = [&](const std::string& ca, const std::string& client) {
    httplib::SSLClient c("localhost", port_, Path(client + ".pem"), Path(client + ".key"));
    c.set_ca_cert_path(Path(ca));
    c.enable_server_certificate_verification(true);
    const auto res = c.Get("/healthz");
    return res && res->status == 200;
  };
  // The expiry of the certificate served, on /metrics.
  auto metrics = [&](const std::string& ca, const std::string& client) {
    httplib::SSLClient c("localhost", port_, Path(client + ".pem"), Path(client + ".key"));
    c.set_ca_cert_path(Path(ca));
    c.enable_server_certificate_verification(true);
    const auto res = c.Get("/metrics");
    return res ? res->body : "no answer: " + httplib::to_string(res.error());
  };
  ASSERT_NE(ExpiryLine("server.pem"), ExpiryLine("other-server.pem")) << "scripts/dev-certs gives them different lives";
  EXPECT_TRUE(answered("ca.pem", "client"));
  EXPECT_FALSE(answered("other-ca.pem", "other-client"));
  EXPECT_TRUE(Mentions(metrics("ca.pem", "client"), ExpiryLine("server.pem")));

  // The server's certificate and the CA of its clients both rotated to another CA.
  certs.Serve(Path("other-server.pem"), Path("other-server.key"), Path("other-ca.pem"));
  EXPECT_TRUE(server_support::Eventually(std::chrono::seconds(15), [&] { return answered("other-ca.pem", "other-client"); }));
  EXPECT_FALSE(answered("ca.pem", "client"));
  EXPECT_FALSE(answered("other-ca.pem", "client"));

  // A set whose key is not its certificate's is refused and said once; the set in use
  // goes on serving.
  certs.Serve(Path("server.pem"), Path("other-server.key"), Path("ca.pem"));
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(answered("other-ca.pem", "other-client"));
  EXPECT_TRUE(Mentions(metrics("other-ca.pem", "other-client"), ExpiryLine("other-server.pem")));
  const std::string log = Log();
  EXPECT_TRUE(Mentions(log, "tls serves the certificate read again from " + certs.File("cert.pem"))) << log;
  EXPECT_EQ(Occurrences(log, "tls kept the certificate in use; its files changed but the key does not match the certificate"), 1)
      << log;
  // HTTPS and gRPC share one reader of the files: each set is read and said once.
  EXPECT_EQ(Occurrences(log, "the certificate read again from"), 1) << log;
  EXPECT_EQ(Occurrences(log, "kept the certificate in use"), 1) << log;
}

// A key file replaced by a FIFO that nobody writes is refused, not waited on: the
// handshakes go on with the set in use. The HTTP listener alone, since gRPC's own
// watcher would open the FIFO and wait (operations.md, on rotating certificates).
TEST_F(HttpTlsTest, AFifoInPlaceOfAKeyIsRefusedNotWaitedOn) {
  server_support::RotatingCertificates certs(cli_support::TempPath("snooker_http_fifo"));
  certs.Serve(Path("server.pem"), Path("server.key"));
  TlsOptions tls;
  tls.cert_chain_pem = Pem("server.pem");
  tls.private_key_pem = Pem("server.key");
  tls.reload_interval = std::chrono::seconds(1);
  tls.cert_chain_file = certs.File("cert.pem");
  tls.private_key_file = certs.File("key.pem");
  ShotPlannerService service{ServiceOptions{}};
  std::ostringstream log;
  HttpOptions options;
  options.address = "127.0.0.1:0";
  options.tls = &tls;
  options.log = &log;
  std::string error;
  auto http = HttpServer::Start(&service, options, &error);
  ASSERT_NE(http, nullptr) << error;
  auto answered = [&] {
    httplib::SSLClient c("localhost", http->port());
    c.set_ca_cert_path(Path("ca.pem"));
    c.enable_server_certificate_verification(true);
    c.set_read_timeout(5, 0);
    const auto res = c.Get("/healthz");
    return res && res->status == 200;
  };
  EXPECT_TRUE(answered());
  ASSERT_EQ(std::remove(certs.File("key.pem").c_str()), 0);
  ASSERT_EQ(mkfifo(certs.File("key.pem").c_str(), 0600), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(answered());
  http->Finish(Clock::now());
  EXPECT_TRUE(Mentions(log.str(), "tls kept the certificate in use; its files changed but cannot read '" +
                                      certs.File("key.pem") + "': is a FIFO (named pipe), not a regular file"))
      << log.str();
}

}  // namespace
}  // namespace snooker::server
