// Calibration behind the API: the Calibrate RPC through a real server (a fit that
// never changes the server's model, statuses that name the bad observation by its
// API path, a deadline that ends a fit), observations that survive the trip to
// API messages and back, and `snooker record` / `snooker calibrate` as a user runs
// them.
#include <gtest/gtest.h>

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <google/protobuf/util/message_differencer.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "calibration/datasets.h"
#include "calibration/record.h"
#include "physics/model/model.h"
#include "server/calibrate_api.h"
#include "server/model_convert.h"
#include "tests/service/server_support.h"
#include "tests/support/cli_support.h"

namespace snooker::server {
namespace {

using cli_support::RunCli;
using cli_support::TempFile;
using google::protobuf::util::MessageDifferencer;
using server_support::TestServer;

// Alciatore's stun-shot throw at a 45 deg cut (8 points) as API observations.
v1::Observations AlciatoreThrows() {
  calibration::Observations o;
  o.throws = calibration::AlciatoreStunThrow45();
  v1::Observations out;
  ObservationsToProto(o, &out);
  return out;
}

v1::CalibrateRequest ThrowFit() {
  v1::CalibrateRequest r;
  *r.mutable_observations() = AlciatoreThrows();
  r.add_fit("ball-ball");
  return r;
}

// A tracked shot made by hand: the cue ball struck towards a red, seen three times.
v1::TrackedShot HandTrackedShot() {
  v1::TrackedShot s;
  auto add_ball = [&](const char* id, v1::BallKind kind, double x, double y) {
    v1::Ball* b = s.mutable_table()->add_balls();
    b->set_id(id);
    b->set_kind(kind);
    b->mutable_position()->set_x(x);
    b->mutable_position()->set_y(y);
  };
  add_ball("cue", v1::CUE, 0.9, 1.0);
  add_ball("red", v1::RED, 0.9, 2.5);
  s.mutable_shot()->set_speed(1.0);
  s.mutable_shot()->set_heading_deg(90);
  for (int k = 1; k <= 3; ++k) {
    v1::Sighting* seen = s.add_sightings();
    seen->set_t_s(0.1 * k);
    for (const auto& [id, y] : {std::pair<const char*, double>{"cue", 1.0 + 0.09 * k}, {"red", 2.5}}) {
      v1::BallSighting* b = seen->add_balls();
      b->set_id(id);
      b->mutable_position()->set_x(0.9);
      b->mutable_position()->set_y(y);
    }
  }
  return s;
}

v1::CushionObservation Rebound(double speed, double angle_deg, double rebound_speed) {
  v1::CushionObservation c;
  c.set_speed(speed);
  c.set_angle_deg(angle_deg);
  c.set_topspin(speed / 0.02625);
  c.set_rebound_speed(rebound_speed);
  return c;
}

// The message of a request the API refuses; a test failure when it answers
// anything but INVALID_ARGUMENT.
std::string Refusal(const v1::CalibrateRequest& request) {
  v1::CalibrateResponse response;
  const ApiStatus st = Calibrate(request, &response);
  EXPECT_EQ(st.code, ApiStatus::Code::kInvalidArgument) << st.message;
  EXPECT_FALSE(st.message.empty());
  return st.message;
}

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

v1::GetModelResponse ModelOf(TestServer& s) {
  v1::GetModelResponse model;
  grpc::ClientContext ctx;
  EXPECT_TRUE(s.stub->GetModel(&ctx, {}, &model).ok());
  return model;
}

grpc::Status CallCalibrate(TestServer& s, const v1::CalibrateRequest& request, v1::CalibrateResponse* response) {
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
  return s.stub->Calibrate(&ctx, request, response);
}

TEST(CalibrateRpcTest, FitsAlciatoresThrowDataAndLeavesTheServersModelAlone) {
  TestServer s;
  ASSERT_NE(s.stub, nullptr);
  const v1::GetModelResponse before = ModelOf(s);
  v1::CalibrateResponse r;
  const grpc::Status st = CallCalibrate(s, ThrowFit(), &r);
  ASSERT_TRUE(st.ok()) << st.error_message();
  ASSERT_EQ(r.parameters_size(), 3);
  EXPECT_EQ(r.parameters(0).name(), "ball_ball.mu_bb");
  EXPECT_EQ(r.parameters(1).name(), "ball_ball.slip_gain");
  EXPECT_EQ(r.parameters(2).name(), "ball_ball.slip_decay");
  EXPECT_EQ(r.parameters(2).unit(), "s/m");
  for (const v1::FittedParameter& p : r.parameters()) {
    EXPECT_TRUE(std::isfinite(p.value())) << p.name();
    EXPECT_TRUE(std::isfinite(p.uncertainty()) && p.uncertainty() >= 0) << p.name() << " " << p.uncertainty();
  }
  ASSERT_EQ(r.residuals_size(), 1);
  EXPECT_EQ(r.residuals(0).kind(), "throw");
  EXPECT_EQ(r.residuals(0).unit(), "deg");
  EXPECT_EQ(r.residuals(0).count(), 8);
  EXPECT_LT(r.residuals(0).rms_after(), r.residuals(0).rms_before());
  EXPECT_GT(r.evaluations(), 0);
  physics::Model fitted;
  ASSERT_EQ(ModelFromProto(r.model(), &fitted), "");
  EXPECT_EQ(fitted.ball_ball.friction_law, physics::BallBallFrictionLaw::kExponential);
  EXPECT_DOUBLE_EQ(fitted.ball_ball.slip_gain, r.parameters(1).value());
  // Everything not fitted is the server's (default) model.
  EXPECT_DOUBLE_EQ(fitted.cloth.mu_s, physics::Model{}.cloth.mu_s);
  EXPECT_TRUE(MessageDifferencer::Equals(ModelOf(s), before));
}

TEST(CalibrateRpcTest, AServerWithAModelStartsTheFitFromItAndKeepsItsOwn) {
  ServerOptions options;
  options.model = calibration::SimToRealWorld();
  TestServer s(options);
  ASSERT_NE(s.stub, nullptr);
  const v1::GetModelResponse before = ModelOf(s);
  v1::CalibrateRequest request = ThrowFit();
  request.set_max_evaluations(30);
  v1::CalibrateResponse r;
  const grpc::Status st = CallCalibrate(s, request, &r);
  ASSERT_TRUE(st.ok()) << st.error_message();
  ASSERT_EQ(r.parameters_size(), 3);
  // The fit starts from the server's law, not the default's.
  EXPECT_DOUBLE_EQ(r.parameters(0).start(), calibration::kSimToRealThrowLaw.a);
  EXPECT_DOUBLE_EQ(r.parameters(1).start(), calibration::kSimToRealThrowLaw.b);
  EXPECT_DOUBLE_EQ(r.parameters(2).start(), calibration::kSimToRealThrowLaw.c);
  physics::Model fitted;
  ASSERT_EQ(ModelFromProto(r.model(), &fitted), "");
  EXPECT_DOUBLE_EQ(fitted.cloth.mu_s, calibration::SimToRealWorld().cloth.mu_s);
  EXPECT_DOUBLE_EQ(fitted.cue.end_mass, calibration::SimToRealWorld().cue.end_mass);
  EXPECT_TRUE(MessageDifferencer::Equals(ModelOf(s), before));
  physics::Model reported;
  ASSERT_EQ(ModelFromProto(ModelOf(s).physics(), &reported), "");
  EXPECT_TRUE(physics::SameModel(reported, calibration::SimToRealWorld()));
  // A refused call leaves it too, and is INVALID_ARGUMENT on the wire.
  request.mutable_observations()->mutable_throw_(1)->set_cut_deg(NAN);
  const grpc::Status bad = CallCalibrate(s, request, &r);
  EXPECT_EQ(bad.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(Has(bad.error_message(), "throw[1].cut_deg")) << bad.error_message();
  EXPECT_TRUE(MessageDifferencer::Equals(ModelOf(s), before));
}

TEST(CalibrateRpcTest, AClientDeadlineEndsATrackedShotFitPromptly) {
  calibration::Observations recorded;
  recorded.shots = calibration::Record(physics::Model{}, 120, 11, 1e-3);
  v1::CalibrateRequest request;
  ObservationsToProto(recorded, request.mutable_observations());
  for (const char* g : {"cloth", "ball-ball", "cue"}) request.add_fit(g);
  ServerOptions options;
  options.workers = 1;
  TestServer s(options);
  ASSERT_NE(s.stub, nullptr);
  const auto t0 = std::chrono::steady_clock::now();
  grpc::ClientContext ctx;
  // Long enough for the request to reach the method on a loaded machine (a call
  // whose deadline passes in transit never does), far shorter than the fit.
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(300));
  v1::CalibrateResponse r;
  const grpc::Status st = s.stub->Calibrate(&ctx, request, &r);
  EXPECT_EQ(st.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED) << st.error_message();
  // The client gives up at its deadline whatever the server does: the server's
  // own answer (its count of finished calls) shows that the fit stopped.
  const CallCounts c = server_support::WaitUntilAnswered(*s.server, 1, std::chrono::seconds(30));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(c.received, 1) << "the call did not reach the server";
  EXPECT_LT(seconds, 2.0) << "the fit went on after the deadline";
  EXPECT_EQ(c.with(grpc::StatusCode::DEADLINE_EXCEEDED), 1)
      << "finished " << c.finished << ", OK " << c.with(grpc::StatusCode::OK) << ", CANCELLED "
      << c.with(grpc::StatusCode::CANCELLED) << ", RESOURCE_EXHAUSTED " << c.with(grpc::StatusCode::RESOURCE_EXHAUSTED);
}

TEST(CalibrateApiTest, ADeadlineEndsEvenOneLongEvaluation) {
  // 30000 throws, each solved for the incident speed that gives its object ball's:
  // one evaluation of them all takes longer than the deadline (about 0.7 s), the
  // Jacobian at the start six of them.
  v1::CalibrateRequest request = ThrowFit();
  v1::Observations* o = request.mutable_observations();
  o->clear_throw_();
  for (int i = 0; i < 30000; ++i) {
    v1::ThrowObservation* t = o->add_throw_();
    t->set_cut_deg(20 + 0.002 * i);
    t->set_object_ball_speed(0.3 + 0.0001 * i);
    t->set_throw_deg(4);
  }
  CallLimits limits;
  const auto t0 = std::chrono::steady_clock::now();
  limits.interrupt.deadline = t0 + std::chrono::milliseconds(50);
  v1::CalibrateResponse response;
  const ApiStatus st = Calibrate(request, &response, limits);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(st.code, ApiStatus::Code::kDeadlineExceeded) << st.message;
  EXPECT_LT(seconds, 1.0);  // without the checks inside an evaluation: 8 s
  EXPECT_EQ(response.parameters_size(), 0);
}

TEST(CalibrateValidationTest, AThrowOutOfRangeIsNamedByItsApiPathInDegrees) {
  v1::CalibrateRequest r = ThrowFit();
  r.mutable_observations()->mutable_throw_(1)->set_cut_deg(NAN);
  std::string m = Refusal(r);
  EXPECT_TRUE(Has(m, "throw[1].cut_deg = nan")) << m;
  r.mutable_observations()->mutable_throw_(1)->set_cut_deg(95);
  m = Refusal(r);
  EXPECT_TRUE(Has(m, "throw[1].cut_deg = 95 (must be in [0, 89] deg)")) << m;
  r = ThrowFit();
  r.mutable_observations()->mutable_throw_(3)->set_throw_deg(50);
  m = Refusal(r);
  EXPECT_TRUE(Has(m, "throw[3].throw_deg = 50")) << m;
  r = ThrowFit();
  r.mutable_observations()->mutable_throw_(2)->set_object_ball_speed(-1);
  m = Refusal(r);
  EXPECT_TRUE(Has(m, "throw[2].object_ball_speed = -1")) << m;
}

TEST(CalibrateValidationTest, ASingleThrowIsRefused) {
  v1::CalibrateRequest r = ThrowFit();
  r.mutable_observations()->mutable_throw_()->DeleteSubrange(1, 7);
  const std::string m = Refusal(r);
  EXPECT_TRUE(Has(m, "throw: 1 observation")) << m;
}

TEST(CalibrateValidationTest, ContradictoryThrowsAreRefused) {
  v1::CalibrateRequest r = ThrowFit();
  *r.mutable_observations()->add_throw_() = r.observations().throw_(0);
  r.mutable_observations()->mutable_throw_(8)->set_throw_deg(r.observations().throw_(0).throw_deg() + 4);
  const std::string m = Refusal(r);
  EXPECT_TRUE(Has(m, "throw[0] and throw[8] contradict")) << m;
}

TEST(CalibrateValidationTest, ManyContradictoryThrowsAreRefusedQuicklyInAShortMessage) {
  // 4000 throws of one input, half measured 4 deg apart from the other half:
  // four million contradicting pairs, one message of a few lines.
  v1::CalibrateRequest r = ThrowFit();
  r.mutable_observations()->clear_throw_();
  for (int i = 0; i < 4000; ++i) {
    *r.mutable_observations()->add_throw_() = ThrowFit().observations().throw_(0);
    r.mutable_observations()->mutable_throw_(i)->set_throw_deg(i % 2 == 0 ? 3 : 7);
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::string m = Refusal(r);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
  EXPECT_TRUE(Has(m, "throw[0] and throw[1] contradict")) << m;
  EXPECT_LE(m.size(), 4096u);
}

TEST(CalibrateValidationTest, ASightingOfAnUnknownBallIsNamed) {
  v1::CalibrateRequest r;
  *r.mutable_observations()->add_tracked() = HandTrackedShot();
  r.add_fit("cloth");
  r.mutable_observations()->mutable_tracked(0)->mutable_sightings(2)->mutable_balls(1)->set_id("ghost");
  const std::string m = Refusal(r);
  EXPECT_TRUE(Has(m, "tracked[0].sightings[2].balls[1].id = \"ghost\" (must be a ball of the shot's table)")) << m;
}

TEST(CalibrateValidationTest, ATrackedShotWithoutAStrikeIsRefused) {
  v1::CalibrateRequest r;
  *r.mutable_observations()->add_tracked() = HandTrackedShot();
  r.add_fit("cloth");
  r.mutable_observations()->mutable_tracked(0)->clear_shot();
  const std::string m = Refusal(r);
  EXPECT_TRUE(Has(m, "tracked[0] = no strike")) << m;
}

TEST(CalibrateValidationTest, GroupsMustBeKnownAndAtLeastOne) {
  v1::CalibrateRequest r = ThrowFit();
  r.add_fit("fish");
  std::string m = Refusal(r);
  EXPECT_TRUE(Has(m, "fit = ball-ball,fish")) << m;
  EXPECT_TRUE(Has(m, "unknown group \"fish\"")) << m;
  r.clear_fit();
  m = Refusal(r);
  EXPECT_TRUE(Has(m, "fit = (none)")) << m;
}

TEST(CalibrateValidationTest, MaxEvaluationsOutsideItsRangeIsRefused) {
  v1::CalibrateRequest r = ThrowFit();
  r.set_max_evaluations(5);
  std::string m = Refusal(r);
  EXPECT_TRUE(Has(m, "max_evaluations = 5 (must be in [10, 100000])")) << m;
  r.set_max_evaluations(100001);
  m = Refusal(r);
  EXPECT_TRUE(Has(m, "max_evaluations = 100001")) << m;
}

TEST(CalibrateValidationTest, ABadStartModelIsNamed) {
  v1::CalibrateRequest r = ThrowFit();
  r.mutable_start()->mutable_cloth()->set_mu_s(2);
  const std::string m = Refusal(r);
  EXPECT_TRUE(Has(m, "start = not a valid model (cloth.mu_s = 2 (must be in [0.01, 1]))")) << m;
}

TEST(CalibrateValidationTest, TheClothFromThrowsAloneIsRefusedWithTheReason) {
  v1::CalibrateRequest r = ThrowFit();
  r.set_fit(0, "cloth");
  const std::string m = Refusal(r);
  EXPECT_TRUE(Has(m, "cloth: no tracked shots")) << m;
}

TEST(CalibrateValidationTest, TheLibrarysListNamesBecomeTheApis) {
  // A bad rebound and two that contradict: cushion[...], never rebound[...].
  v1::CalibrateRequest r;
  r.add_fit("cushion");
  *r.mutable_observations()->add_cushion() = Rebound(1.0, 60, 0.7);
  *r.mutable_observations()->add_cushion() = Rebound(-1.0, 60, 0.7);
  std::string m = Refusal(r);
  EXPECT_TRUE(Has(m, "cushion[1].speed = -1")) << m;
  EXPECT_FALSE(Has(m, "rebound[")) << m;
  *r.mutable_observations()->mutable_cushion(1) = Rebound(1.0, 60, 1.2);
  m = Refusal(r);
  EXPECT_TRUE(Has(m, "cushion[0] and cushion[1] contradict")) << m;
  EXPECT_FALSE(Has(m, "rebound[")) << m;
  r.mutable_observations()->mutable_cushion(1)->set_angle_deg(200);
  m = Refusal(r);
  EXPECT_TRUE(Has(m, "cushion[1].angle_deg = 200")) << m;
  r.mutable_observations()->clear_cushion();
  *r.mutable_observations()->add_cushion() = Rebound(1.0, 60, 0.7);
  m = Refusal(r);
  EXPECT_TRUE(Has(m, "cushion: 1 observation")) << m;
  // Tracked shots: tracked[...], never shot[...], and the API's field names.
  r.Clear();
  r.add_fit("cloth");
  *r.mutable_observations()->add_tracked() = HandTrackedShot();
  *r.mutable_observations()->add_tracked() = HandTrackedShot();
  r.mutable_observations()->mutable_tracked(1)->mutable_sightings(1)->set_t_s(0.05);
  m = Refusal(r);
  EXPECT_TRUE(Has(m, "tracked[1].sightings[1].t_s = 0.05")) << m;
  EXPECT_FALSE(Has(m, "shot[")) << m;
  r.mutable_observations()->mutable_tracked(1)->mutable_sightings(1)->set_t_s(0.2);
  r.mutable_observations()->mutable_tracked(1)->mutable_shot()->set_speed(11);
  m = Refusal(r);
  EXPECT_TRUE(Has(m, "tracked[1].shot.speed = 11")) << m;
  EXPECT_FALSE(Has(m, "shot[")) << m;
  // A strike in the cue's terms: its tip offsets are the API's tip_side, tip_height.
  v1::CueStrike* cue = r.mutable_observations()->mutable_tracked(1)->mutable_cue();
  cue->set_speed(2);
  cue->set_heading_deg(90);
  cue->set_tip_side(0.99);
  cue->set_tip_height(0.3);
  m = Refusal(r);
  EXPECT_TRUE(Has(m, "tracked[1].cue.tip_side = 0.99")) << m;
  r.mutable_observations()->mutable_tracked(1)->mutable_shot()->set_speed(1);
  r.mutable_observations()->mutable_tracked(1)->mutable_shot()->set_heading_deg(90);
  r.mutable_observations()->mutable_tracked(1)->mutable_table()->mutable_balls(1)->mutable_position()->set_y(1.01);
  m = Refusal(r);
  EXPECT_TRUE(Has(m, "tracked[1].table.balls")) << m;
  EXPECT_FALSE(Has(m, "shot[")) << m;
  r.mutable_observations()->mutable_tracked(1)->mutable_table()->mutable_balls(1)->mutable_position()->set_y(2.5);
  r.mutable_observations()->mutable_tracked(0)->mutable_sightings(2)->mutable_balls(1)->mutable_position()->set_x(
      -0.3);
  m = Refusal(r);
  EXPECT_TRUE(Has(m, "tracked[0].sightings[2].balls[1].position.x = -0.3")) << m;
  EXPECT_FALSE(Has(m, "shot[")) << m;
}

// Degrees of an angle that went to radians and back, compared on the circle.
double AngleDifference(double a, double b) { return std::remainder(a - b, 2 * physics::kPi); }

TEST(ObservationsRoundTripTest, ThrowsReboundsAndTrackedShotsComeBackAsTheyWere) {
  calibration::Observations in;
  in.throws = calibration::AlciatoreStunThrow45();
  calibration::ThrowObservation t;
  t.cut = 0.3;
  t.cue_ball_speed = 1.7;
  t.topspin = 12.5;
  t.sidespin = -30.25;
  t.measured_throw = -0.0123;
  in.throws.push_back(t);
  calibration::CushionObservation c;
  c.speed = 1.3;
  c.angle = 1.1;
  c.topspin = 49.5;
  c.sidespin = 7;
  c.rebound_speed = 0.9;
  in.rebounds.push_back(c);
  c.rebound_angle = 1.234;
  in.rebounds.push_back(c);
  in.shots = calibration::Record(physics::Model{}, 2, 3, 1e-3);
  // A shot struck as the cue ball's motion, with a ball not seen at its last sighting.
  calibration::TrackedShot shot = in.shots[0];
  shot.strike = physics::Shot{1.5, 4.0, 20, -10, 3};
  shot.sightings.back().positions.back() = physics::Vec2(NAN, NAN);
  in.shots.push_back(shot);

  v1::Observations proto;
  ObservationsToProto(in, &proto);
  std::vector<FieldError> errors;
  const calibration::Observations out = ObservationsFrom(proto, &errors);
  EXPECT_TRUE(errors.empty()) << Describe(errors);
  constexpr double kEps = 1e-12;
  ASSERT_EQ(out.throws.size(), in.throws.size());
  for (std::size_t i = 0; i < in.throws.size(); ++i) {
    const calibration::ThrowObservation &a = in.throws[i], &b = out.throws[i];
    EXPECT_NEAR(a.cut, b.cut, kEps) << i;
    EXPECT_EQ(a.cue_ball_speed.has_value(), b.cue_ball_speed.has_value()) << i;
    EXPECT_EQ(a.object_ball_speed.has_value(), b.object_ball_speed.has_value()) << i;
    EXPECT_NEAR(a.cue_ball_speed.value_or(0), b.cue_ball_speed.value_or(0), kEps) << i;
    EXPECT_NEAR(a.object_ball_speed.value_or(0), b.object_ball_speed.value_or(0), kEps) << i;
    EXPECT_NEAR(a.topspin, b.topspin, kEps) << i;
    EXPECT_NEAR(a.sidespin, b.sidespin, kEps) << i;
    EXPECT_NEAR(a.measured_throw, b.measured_throw, kEps) << i;
  }
  ASSERT_EQ(out.rebounds.size(), in.rebounds.size());
  for (std::size_t i = 0; i < in.rebounds.size(); ++i) {
    const calibration::CushionObservation &a = in.rebounds[i], &b = out.rebounds[i];
    EXPECT_NEAR(a.speed, b.speed, kEps) << i;
    EXPECT_NEAR(a.angle, b.angle, kEps) << i;
    EXPECT_NEAR(a.topspin, b.topspin, kEps) << i;
    EXPECT_NEAR(a.sidespin, b.sidespin, kEps) << i;
    EXPECT_NEAR(a.rebound_speed, b.rebound_speed, kEps) << i;
    ASSERT_EQ(a.rebound_angle.has_value(), b.rebound_angle.has_value()) << i;
    if (a.rebound_angle) {
      EXPECT_NEAR(*a.rebound_angle, *b.rebound_angle, kEps) << i;
    }
  }
  ASSERT_EQ(out.shots.size(), in.shots.size());
  for (std::size_t i = 0; i < in.shots.size(); ++i) {
    const calibration::TrackedShot &a = in.shots[i], &b = out.shots[i];
    EXPECT_EQ(a.cue_ball, b.cue_ball) << i;
    ASSERT_EQ(a.balls.size(), b.balls.size()) << i;
    for (std::size_t k = 0; k < a.balls.size(); ++k) EXPECT_LT((a.balls[k] - b.balls[k]).norm(), kEps) << i;
    ASSERT_EQ(a.strike.index(), b.strike.index()) << i;
    if (const auto* ka = std::get_if<physics::CueStrike>(&a.strike)) {
      const auto& kb = std::get<physics::CueStrike>(b.strike);
      EXPECT_NEAR(ka->speed, kb.speed, kEps) << i;
      EXPECT_NEAR(AngleDifference(ka->heading, kb.heading), 0, kEps) << i;
      EXPECT_NEAR(ka->side, kb.side, kEps) << i;
      EXPECT_NEAR(ka->height, kb.height, kEps) << i;
      EXPECT_NEAR(ka->elevation, kb.elevation, kEps) << i;
    } else {
      const auto &sa = std::get<physics::Shot>(a.strike), &sb = std::get<physics::Shot>(b.strike);
      EXPECT_NEAR(sa.speed, sb.speed, kEps) << i;
      EXPECT_NEAR(AngleDifference(sa.heading, sb.heading), 0, kEps) << i;
      EXPECT_NEAR(sa.topspin, sb.topspin, kEps) << i;
      EXPECT_NEAR(sa.sidespin, sb.sidespin, kEps) << i;
      EXPECT_NEAR(sa.swerve_spin, sb.swerve_spin, kEps) << i;
    }
    ASSERT_EQ(a.sightings.size(), b.sightings.size()) << i;
    for (std::size_t j = 0; j < a.sightings.size(); ++j) {
      EXPECT_NEAR(a.sightings[j].t, b.sightings[j].t, kEps) << i << " " << j;
      ASSERT_EQ(a.sightings[j].positions.size(), b.sightings[j].positions.size()) << i << " " << j;
      for (std::size_t k = 0; k < a.sightings[j].positions.size(); ++k) {
        const physics::Vec2 pa = a.sightings[j].positions[k], pb = b.sightings[j].positions[k];
        if (std::isnan(pa.x())) {
          EXPECT_TRUE(std::isnan(pb.x()) && std::isnan(pb.y())) << i << " " << j << " " << k;
        } else {
          EXPECT_LT((pa - pb).norm(), kEps) << i << " " << j << " " << k;
        }
      }
    }
  }
  // The unseen ball is left out of the message, not sent as NaN.
  const v1::Sighting& last = proto.tracked(2).sightings(proto.tracked(2).sightings_size() - 1);
  EXPECT_EQ(last.balls_size(), static_cast<int>(shot.balls.size()) - 1);
}

std::string ReadText(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string JsonOf(const google::protobuf::Message& m) {
  std::string json;
  EXPECT_TRUE(google::protobuf::util::MessageToJsonString(m, &json).ok());
  return json;
}

// The Alciatore throws split into two data files, and the whole set in one.
struct ThrowFiles {
  std::string whole, first, second;
};
ThrowFiles WriteThrowFiles() {
  const v1::Observations all = AlciatoreThrows();
  v1::Observations first, second;
  for (int i = 0; i < all.throw__size(); ++i) *(i < 4 ? first : second).add_throw_() = all.throw_(i);
  return {TempFile("throws_all.json", JsonOf(all)), TempFile("throws_first.json", JsonOf(first)),
          TempFile("throws_second.json", JsonOf(second))};
}

TEST(RecordCommandTest, TheSameArgumentsGiveTheSameFileAndAnotherSeedAnother) {
  const std::string a = cli_support::TempPath("record_a.json"), b = cli_support::TempPath("record_b.json"),
                    c = cli_support::TempPath("record_c.json"), d = cli_support::TempPath("record_d.json");
  const std::string args = "record --world default --shots 3 --vision-noise-mm 1 --seed ";
  const cli_support::RunResult ra = RunCli(args + "5 --out " + a);
  ASSERT_EQ(ra.exit_code, 0) << ra.err;
  EXPECT_TRUE(Has(ra.out, "recorded 3 tracked shots")) << ra.out;
  ASSERT_EQ(RunCli(args + "5 --out " + b).exit_code, 0);
  ASSERT_EQ(RunCli(args + "6 --out " + c).exit_code, 0);
  // Seeds take the whole unsigned range, as every command's --seed does.
  const cli_support::RunResult rd = RunCli(args + "18446744073709551615 --out " + d);
  ASSERT_EQ(rd.exit_code, 0) << rd.err;
  const std::string text = ReadText(a);
  EXPECT_FALSE(text.empty());
  EXPECT_EQ(text, ReadText(b));
  EXPECT_NE(text, ReadText(c));
  EXPECT_NE(text, ReadText(d));
  v1::Observations read;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(text, &read).ok());
  EXPECT_EQ(read.tracked_size(), 3);
}

TEST(RecordCommandTest, ABadWorldOrNoiseIsAUsageErrorNamingIt) {
  const std::string out = cli_support::TempPath("record_bad.json");
  const std::string bad = TempFile("bad_world.json", R"({"cloth": {"muS": 2}})");
  cli_support::RunResult r = RunCli("record --world " + bad + " --shots 1 --seed 1 --out " + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Has(r.err, "--world")) << r.err;
  EXPECT_TRUE(Has(r.err, "cloth.mu_s = 2")) << r.err;
  r = RunCli("record --world default --shots 1 --seed 1 --vision-noise-mm -1 --out " + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Has(r.err, "--vision-noise-mm -1")) << r.err;
}

TEST(CalibrateCommandTest, MergesDataFilesAndPrintsTheContractedJson) {
  const ThrowFiles files = WriteThrowFiles();
  const cli_support::RunResult whole = RunCli("calibrate --data " + files.whole + " --fit ball-ball --json");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const std::string model = cli_support::TempPath("calibrated_throw_model.json");
  const cli_support::RunResult split =
      RunCli("calibrate --data " + files.first + " " + files.second + " --fit ball-ball --json --out " + model);
  ASSERT_EQ(split.exit_code, 0) << split.err;
  EXPECT_EQ(split.out, whole.out);

  v1::CalibrateResponse answer;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(whole.out, &answer).ok()) << whole.out;
  ASSERT_EQ(answer.parameters_size(), 3);
  // The names tools outside the project read (the --help text's contract).
  google::protobuf::Struct json;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(whole.out, &json).ok());
  std::set<std::string> top, parameter;
  for (const auto& [name, value] : json.fields()) top.insert(name);
  for (const auto& [name, value] : json.fields().at("parameters").list_value().values(0).struct_value().fields()) {
    parameter.insert(name);
  }
  EXPECT_EQ(top, (std::set<std::string>{"model", "parameters", "residuals", "evaluations"}));
  EXPECT_EQ(parameter, (std::set<std::string>{"name", "unit", "start", "value", "uncertainty", "atBound"}));

  // --out wrote a model file that the other commands read, with the fitted law.
  const cli_support::RunResult read = RunCli("model --json --model " + model);
  ASSERT_EQ(read.exit_code, 0) << read.err;
  v1::PhysicsModel file;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(read.out, &file).ok()) << read.out;
  physics::Model m;
  ASSERT_EQ(ModelFromProto(file, &m), "");
  EXPECT_EQ(m.ball_ball.friction_law, physics::BallBallFrictionLaw::kExponential);
  EXPECT_DOUBLE_EQ(m.ball_ball.mu_bb, answer.parameters(0).value());
  EXPECT_DOUBLE_EQ(m.ball_ball.slip_gain, answer.parameters(1).value());
  EXPECT_DOUBLE_EQ(m.ball_ball.slip_decay, answer.parameters(2).value());
}

TEST(CalibrateCommandTest, ANanInADataFileIsAUsageErrorNamingTheThrow) {
  const std::string data = TempFile("nan_throws.json", R"({"throw": [
      {"cutDeg": 45, "objectBallSpeed": 0.5, "throwDeg": 6},
      {"cutDeg": 45, "objectBallSpeed": 1.0, "throwDeg": "NaN"}]})");
  const cli_support::RunResult r = RunCli("calibrate --data " + data + " --fit ball-ball");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Has(r.err, "throw[1].throw_deg = nan")) << r.err;
}

TEST(CalibrateCommandTest, MissingDataOrGroupsIsAUsageError) {
  const ThrowFiles files = WriteThrowFiles();
  cli_support::RunResult r = RunCli("calibrate --fit ball-ball");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Has(r.err, "--data")) << r.err;
  r = RunCli("calibrate --data " + files.whole);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Has(r.err, "--fit is required")) << r.err;
  r = RunCli("calibrate --data " + files.whole + " --fit fish");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Has(r.err, "unknown group \"fish\"")) << r.err;
}

}  // namespace
}  // namespace snooker::server
