// Model files: the physical model as a document (physics_model.proto), read over the
// default, written back whole; the `snooker model` command; a server started with a
// model reports it and simulates with it.
#include <gtest/gtest.h>

#include <google/protobuf/util/json_util.h>

#include <string>

#include "physics/model/model.h"
#include "server/api.h"
#include "server/model_convert.h"
#include "tests/service/server_support.h"
#include "tests/support/cli_support.h"

namespace snooker::server {
namespace {

using cli_support::RunCli;
using cli_support::TempFile;
using server_support::TestServer;

physics::Model Calibrated() {
  physics::Model m;
  m.cloth.mu_s = 0.168;
  m.cloth.mu_r = 0.01024;
  m.ball_ball = physics::WithFrictionCurve(m.ball_ball, {0.021, 0.11, 1.3});
  m.cushion.restitution_curve.e[3] = 0.97;
  m.cue.end_mass = 0.009;
  return m;
}

TEST(ModelFileTest, WrittenWholeAndReadBackItIsTheSameModel) {
  v1::PhysicsModel file;
  ModelToProto(Calibrated(), &file);
  physics::Model back;
  ASSERT_EQ(ModelFromProto(file, &back), "");
  EXPECT_TRUE(physics::SameModel(back, Calibrated()));
  // And a model without a curve stays without one.
  physics::Model flat;
  flat.cushion.restitution_curve = {};
  ModelToProto(flat, &file);
  ASSERT_EQ(ModelFromProto(file, &back), "");
  EXPECT_TRUE(physics::SameModel(back, flat));
  // The law's impact-speed form is kept as such.
  physics::Model impact = Calibrated();
  impact.ball_ball = physics::WithFrictionCurve(impact.ball_ball, {0.0, 0.15, 0.53},
                                                physics::BallBallFrictionLaw::kExponentialImpactSpeed);
  ModelToProto(impact, &file);
  EXPECT_EQ(file.ball_ball().friction_law(), v1::BALL_BALL_FRICTION_LAW_EXPONENTIAL_IMPACT_SPEED);
  ASSERT_EQ(ModelFromProto(file, &back), "");
  EXPECT_TRUE(physics::SameModel(back, impact));
  EXPECT_FALSE(physics::SameModel(back, Calibrated()));
}

TEST(ModelFileTest, AFieldLeftOutKeepsTheDefault) {
  v1::PhysicsModel file;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(R"({"cloth": {"muR": 0.011}, "cue": {"endMassKg": 0.008}})",
                                                          &file)
                  .ok());
  physics::Model m;
  ASSERT_EQ(ModelFromProto(file, &m), "");
  physics::Model expected;
  expected.cloth.mu_r = 0.011;
  expected.cue.end_mass = 0.008;
  EXPECT_TRUE(physics::SameModel(m, expected));
  physics::Model empty;
  ASSERT_EQ(ModelFromProto(v1::PhysicsModel{}, &empty), "");
  EXPECT_TRUE(physics::SameModel(empty, physics::Model{}));
}

TEST(ModelFileTest, BadValuesAreNamed) {
  auto error = [](const std::string& json) {
    v1::PhysicsModel file;
    EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(json, &file).ok()) << json;
    physics::Model m;
    return ModelFromProto(file, &m);
  };
  EXPECT_NE(error(R"({"cloth": {"muS": -0.5}})").find("cloth.mu_s = -0.5"), std::string::npos);
  EXPECT_NE(error(R"({"cloth": {"muR": "NaN"}})").find("cloth.mu_r = nan"), std::string::npos);
  // A cloth that would never stop a ball: every simulation would end at its caps.
  EXPECT_NE(error(R"({"cloth": {"muS": 1e-300}})").find("cloth.mu_s = 1e-300 (must be in [0.01, 1])"),
            std::string::npos);
  EXPECT_NE(error(R"({"cloth": {"muR": 0}})").find("cloth.mu_r = 0 (must be in [0.001, 1])"), std::string::npos);
  EXPECT_NE(error(R"({"cloth": {"gravity": 1e-300}})").find("cloth.g = 1e-300 (must be in [0.1, 100] m/s^2)"),
            std::string::npos);
  EXPECT_NE(error(R"({"cloth": {"spinDecel": 1e9}})").find("cloth.spin_decel = 1e+09"), std::string::npos);
  EXPECT_NE(error(R"({"cue": {"endMassKg": 0}})").find("cue.end_mass = 0"), std::string::npos);
  EXPECT_NE(error(R"({"ballBall": {"frictionLaw": "BALL_BALL_FRICTION_LAW_EXPONENTIAL", "slipGain": 0.99}})")
                .find("slip_gain = 0.99"),
            std::string::npos);
  EXPECT_NE(
      error(R"({"ballBall": {"frictionLaw": "BALL_BALL_FRICTION_LAW_EXPONENTIAL_IMPACT_SPEED", "slipDecay": -2}})")
          .find("slip_decay = -2"),
      std::string::npos);
  EXPECT_NE(error(R"({"cushion": {"restitution": [0.9, 0.8], "restitutionSpeed": [1]}})")
                .find("cushion.restitution has 2 values and cushion.restitution_speed 1"),
            std::string::npos);
  EXPECT_NE(error(R"({"cushion": {"restitution": [0.9, 0.8], "restitutionSpeed": [2, 1]}})")
                .find("restitution_curve knot 1"),
            std::string::npos);
}

TEST(ModelCommandTest, JsonReadsBackAsTheSameModelAndTheDefaultStaysTheDefault) {
  const cli_support::RunResult plain = RunCli("model --json");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  v1::PhysicsModel file;
  ModelToProto(Calibrated(), &file);
  std::string json;
  ASSERT_TRUE(google::protobuf::util::MessageToJsonString(file, &json).ok());
  const std::string path = TempFile("calibrated_model.json", json);
  const cli_support::RunResult again = RunCli("model --json --model " + path);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  v1::PhysicsModel read;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(again.out, &read).ok()) << again.out;
  physics::Model m;
  ASSERT_EQ(ModelFromProto(read, &m), "");
  EXPECT_TRUE(physics::SameModel(m, Calibrated()));
  // Without --model: the default, whatever was read before.
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(plain.out, &read).ok());
  ASSERT_EQ(ModelFromProto(read, &m), "");
  EXPECT_TRUE(physics::SameModel(m, physics::Model{}));
  const cli_support::RunResult text = RunCli("model --model " + path);
  EXPECT_NE(text.out.find("exponential: mu(s) = 0.021 + 0.11 exp(-1.3 s)"), std::string::npos) << text.out;
}

TEST(ModelCommandTest, EveryCommandRefusesABadModelFileNamingTheField) {
  const std::string bad = TempFile("bad_model.json", R"({"cloth": {"muS": 2}})");
  const std::string broken = TempFile("broken_model.json", R"({"cloth": {"muS": )");
  for (const std::string& cmd :
       {std::string("model"), std::string("collide --speed 1"), std::string("plan --table builtin:mid-frame"),
        std::string("selfplay --frames 1 --seed 1"), std::string("match --frames 1 --seed 1"),
        std::string("serve --address 127.0.0.1:0")}) {
    const cli_support::RunResult r = RunCli(cmd + " --model " + bad);
    EXPECT_EQ(r.exit_code, 2) << cmd;
    EXPECT_NE(r.err.find("cloth.mu_s = 2 (must be in [0.01, 1])"), std::string::npos) << cmd << ": " << r.err;
    const cli_support::RunResult s = RunCli(cmd + " --model " + broken);
    EXPECT_EQ(s.exit_code, 2) << cmd;
    EXPECT_NE(s.err.find("line 1"), std::string::npos) << cmd << ": " << s.err;
  }
  const cli_support::RunResult w = RunCli("selfplay --frames 1 --seed 1 --world " + bad);
  EXPECT_EQ(w.exit_code, 2);
  EXPECT_NE(w.err.find("--world"), std::string::npos) << w.err;
}

TEST(ModelServerTest, AServerWithAModelReportsItAndSimulatesWithIt) {
  ServerOptions options;
  options.model = Calibrated();
  TestServer s(options);
  ASSERT_NE(s.stub, nullptr);
  v1::GetModelResponse model;
  {
    grpc::ClientContext ctx;
    ASSERT_TRUE(s.stub->GetModel(&ctx, {}, &model).ok());
  }
  physics::Model reported;
  ASSERT_EQ(ModelFromProto(model.physics(), &reported), "");
  EXPECT_TRUE(physics::SameModel(reported, Calibrated()));
  EXPECT_EQ(model.ball_ball().friction_law(), "exponential");
  EXPECT_DOUBLE_EQ(model.cloth().mu_s(), 0.168);
  EXPECT_DOUBLE_EQ(model.cue().end_mass_kg(), 0.009);
  // Collide with unset parameters takes the server's model: more throw than the
  // default's 2.86 deg on a 45 degree stun cut.
  v1::CollideRequest c;
  c.set_speed(1.0);
  c.set_cut_angle_deg(45);
  v1::CollideResponse with_model, with_default;
  {
    grpc::ClientContext ctx;
    ASSERT_TRUE(s.stub->Collide(&ctx, c, &with_model).ok());
  }
  ASSERT_TRUE(Collide(c, &with_default).ok());
  auto throw_deg = [](const v1::CollideResponse& r) {
    return std::atan2(r.object().velocity().x(), r.object().velocity().y()) * 180 / M_PI;
  };
  EXPECT_NEAR(throw_deg(with_default), 2.86, 0.01);
  EXPECT_GT(throw_deg(with_model), throw_deg(with_default) + 1.0);
}

TEST(ModelServerTest, ADefaultServerReportsTheDefaultModel) {
  TestServer s;
  ASSERT_NE(s.stub, nullptr);
  v1::GetModelResponse model;
  grpc::ClientContext ctx;
  ASSERT_TRUE(s.stub->GetModel(&ctx, {}, &model).ok());
  physics::Model reported;
  ASSERT_EQ(ModelFromProto(model.physics(), &reported), "");
  EXPECT_TRUE(physics::SameModel(reported, physics::Model{}));
}

}  // namespace
}  // namespace snooker::server
