// The gRPC service through an in-process server on a free loopback port and a real
// client stub.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "health.grpc.pb.h"
#include "server/build_info.h"
#include "server/grpc_service.h"
#include "server/server.h"
#include "snooker/v1/service.grpc.pb.h"
#include "tests/support/cli_support.h"

namespace snooker::server {
namespace {

class GrpcServiceTest : public testing::Test {
 protected:
  void SetUp() override {
    std::string error;
    server_ = Server::Start("127.0.0.1:0", &error);
    ASSERT_NE(server_, nullptr) << error;
    channel_ = grpc::CreateChannel("127.0.0.1:" + std::to_string(server_->port()),
                                   grpc::InsecureChannelCredentials());
    stub_ = v1::ShotPlanner::NewStub(channel_);
  }
  void TearDown() override {
    if (server_) server_->Shutdown();
  }
  std::unique_ptr<Server> server_;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::ShotPlanner::Stub> stub_;
};

// Each API code has its gRPC code and keeps its message. The mapping cannot throw: a
// call must always be finished, and a message that cannot be copied is lost alone.
TEST(ToGrpcStatusTest, EachCodeMapsWithItsMessageAndNothingCanThrow) {
  const ApiStatus ok = ApiStatus::Ok();
  static_assert(noexcept(ToGrpcStatus(ok)));
  const std::pair<ApiStatus::Code, grpc::StatusCode> codes[] = {
      {ApiStatus::Code::kInvalidArgument, grpc::StatusCode::INVALID_ARGUMENT},
      {ApiStatus::Code::kResourceExhausted, grpc::StatusCode::RESOURCE_EXHAUSTED},
      {ApiStatus::Code::kDeadlineExceeded, grpc::StatusCode::DEADLINE_EXCEEDED},
      {ApiStatus::Code::kCancelled, grpc::StatusCode::CANCELLED},
      {ApiStatus::Code::kInternal, grpc::StatusCode::INTERNAL}};
  for (const auto& [api, grpc_code] : codes) {
    const grpc::Status s = ToGrpcStatus({api, "the reason"});
    EXPECT_EQ(s.error_code(), grpc_code) << StatusCodeName(grpc_code);
    EXPECT_EQ(s.error_message(), "the reason") << StatusCodeName(grpc_code);
  }
  EXPECT_TRUE(ToGrpcStatus(ok).ok());
}

TEST_F(GrpcServiceTest, HealthReportsServing) {
  auto health = grpc::health::v1::Health::NewStub(channel_);
  grpc::health::v1::HealthCheckRequest req;
  req.set_service(kServiceName);
  grpc::health::v1::HealthCheckResponse resp;
  grpc::ClientContext ctx;
  ASSERT_TRUE(health->Check(&ctx, req, &resp).ok());
  EXPECT_EQ(resp.status(), grpc::health::v1::HealthCheckResponse::SERVING);
}

// GetModel says which build answers: the project's version and the commit of the
// checkout it was built from (with "-dirty" for changes), as git tells it.
TEST_F(GrpcServiceTest, GetModelSaysWhichBuildAnswers) {
  v1::GetModelResponse model;
  grpc::ClientContext ctx;
  ASSERT_TRUE(stub_->GetModel(&ctx, v1::GetModelRequest(), &model).ok());
  EXPECT_EQ(model.build().version(), SNOOKER_VERSION);
  const std::string& commit = model.build().commit();
  EXPECT_TRUE(std::regex_match(commit, std::regex("[0-9a-f]{12}(-dirty)?|unknown"))) << commit;
  const cli_support::RunResult head =
      cli_support::RunShell("git -C '" SNOOKER_SOURCE_DIR "' rev-parse --short=12 HEAD 2>/dev/null");
  if (head.exit_code != 0) GTEST_SKIP() << "not a git checkout: the commit is " << commit;
  EXPECT_EQ(commit.substr(0, 12), head.out.substr(0, 12)) << "built from another commit: build again";
}

// A service the server does not know is NOT_FOUND (gRPC's health semantics); the
// server as a whole ("") is SERVING.
TEST_F(GrpcServiceTest, HealthKnowsOnlyItsServices) {
  auto health = grpc::health::v1::Health::NewStub(channel_);
  grpc::health::v1::HealthCheckRequest req;
  grpc::health::v1::HealthCheckResponse resp;
  {
    grpc::ClientContext ctx;
    req.set_service("");
    ASSERT_TRUE(health->Check(&ctx, req, &resp).ok());
    EXPECT_EQ(resp.status(), grpc::health::v1::HealthCheckResponse::SERVING);
  }
  {
    grpc::ClientContext ctx;
    req.set_service("snooker.v1.NoSuchService");
    EXPECT_EQ(health->Check(&ctx, req, &resp).error_code(), grpc::StatusCode::NOT_FOUND);
  }
}

TEST_F(GrpcServiceTest, CollideAnswersThePapersFirstShot) {
  v1::CollideRequest req;
  req.set_speed(1.539);
  req.set_topspin(1.539 / 0.02625);
  req.set_cut_angle_deg(33.83);
  v1::CollideResponse resp;
  grpc::ClientContext ctx;
  const grpc::Status st = stub_->Collide(&ctx, req, &resp);
  ASSERT_TRUE(st.ok()) << st.error_message();
  EXPECT_NEAR(resp.cue().slip_end().speed(), 0.914, 0.005);
  EXPECT_NEAR(resp.cue().slip_end().exit_angle_deg(), 31.93, 0.05);
}

TEST_F(GrpcServiceTest, BadRequestIsInvalidArgumentNamingTheField) {
  v1::CollideRequest req;
  req.set_speed(std::nan(""));
  v1::CollideResponse resp;
  grpc::ClientContext ctx;
  const grpc::Status st = stub_->Collide(&ctx, req, &resp);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(st.error_message().find("speed = nan"), std::string::npos) << st.error_message();
}

TEST_F(GrpcServiceTest, SimulateAnswersThroughTheStub) {
  v1::SimulateRequest req;
  v1::Ball* cue = req.mutable_table()->add_balls();
  cue->set_id("cue");
  cue->set_kind(v1::CUE);
  cue->mutable_position()->set_x(0.9);
  cue->mutable_position()->set_y(1.0);
  req.mutable_shot()->set_speed(1.0);
  req.mutable_shot()->set_heading_deg(90);
  v1::SimulateResponse resp;
  grpc::ClientContext ctx;
  const grpc::Status st = stub_->Simulate(&ctx, req, &resp);
  ASSERT_TRUE(st.ok()) << st.error_message();
  EXPECT_EQ(resp.status(), "at rest");
  ASSERT_EQ(resp.final_balls_size(), 1);
  EXPECT_GT(resp.final_balls(0).position().y(), 1.0);  // it rolled up the table
}

TEST_F(GrpcServiceTest, SimulateWithoutCueBallIsInvalidArgument) {
  v1::SimulateRequest req;
  v1::Ball* red = req.mutable_table()->add_balls();
  red->set_id("red-1");
  red->set_kind(v1::RED);
  red->mutable_position()->set_x(0.9);
  red->mutable_position()->set_y(1.0);
  v1::SimulateResponse resp;
  grpc::ClientContext ctx;
  const grpc::Status st = stub_->Simulate(&ctx, req, &resp);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(st.error_message().find("0 CUE balls"), std::string::npos) << st.error_message();
}

}  // namespace
}  // namespace snooker::server
