// GetModel through a real server and stub: the model a client can draw and check
// against is the one the server simulates with, and the bounds it reports are the
// server's own options.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "physics/core/limits.h"
#include "physics/table/table.h"
#include "planner/builtin_tables.h"
#include "server/api.h"
#include "server/plan_convert.h"
#include "tests/service/requests.h"
#include "tests/service/server_support.h"

namespace snooker::server {
namespace {

using server_support::TestServer;

v1::GetModelResponse Model(TestServer& s) {
  v1::GetModelResponse model;
  grpc::ClientContext ctx;
  const grpc::Status st = s.stub->GetModel(&ctx, {}, &model);
  EXPECT_TRUE(st.ok()) << st.error_message();
  return model;
}

// Every double of a message, recursively, is finite.
void ExpectFinite(const google::protobuf::Message& m) {
  using google::protobuf::FieldDescriptor;
  const google::protobuf::Reflection* r = m.GetReflection();
  std::vector<const FieldDescriptor*> fields;
  r->ListFields(m, &fields);
  for (const FieldDescriptor* f : fields) {
    const int n = f->is_repeated() ? r->FieldSize(m, f) : 1;
    for (int i = 0; i < n; ++i) {
      if (f->cpp_type() == FieldDescriptor::CPPTYPE_DOUBLE) {
        const double x = f->is_repeated() ? r->GetRepeatedDouble(m, f, i) : r->GetDouble(m, f);
        EXPECT_TRUE(std::isfinite(x)) << f->full_name();
      } else if (f->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) {
        ExpectFinite(f->is_repeated() ? r->GetRepeatedMessage(m, f, i) : r->GetMessage(m, f));
      }
    }
  }
}

TEST(GetModelTest, DescribesTheTableTheServerSimulatesOn) {
  TestServer s;
  ASSERT_NE(s.stub, nullptr);
  const v1::GetModelResponse m = Model(s);
  ExpectFinite(m);
  const v1::TableGeometry& g = m.table();
  EXPECT_DOUBLE_EQ(g.width_m(), 1.778);
  EXPECT_DOUBLE_EQ(g.length_m(), 3.569);
  EXPECT_DOUBLE_EQ(g.cushion_contact_distance_m(),
                   physics::DefaultTable().cushion_contact_distance());
  EXPECT_EQ(g.segments_size(), physics::TableModel::kSegmentCount);
  EXPECT_EQ(g.knuckles_size(), physics::TableModel::kJawCount);
  ASSERT_EQ(g.pockets_size(), 6);
  EXPECT_EQ(g.spots_size(), 6);
  EXPECT_EQ(g.red_triangle_size(), 15);
  EXPECT_EQ(g.segments(0).kind(), "cushion");
  EXPECT_EQ(g.segments(6).kind(), "jaw wall");
  for (const v1::CushionSegment& seg : g.segments()) {
    EXPECT_NEAR(std::hypot(seg.normal().x(), seg.normal().y()), 1.0, 1e-12) << seg.name();
  }
  EXPECT_DOUBLE_EQ(m.ball().radius_m(), 0.02625);
  EXPECT_DOUBLE_EQ(m.ball().mass_kg(), 0.1406);
  EXPECT_NEAR(m.ball().inertia_kg_m2(), 0.4 * 0.1406 * 0.02625 * 0.02625, 1e-15);
  EXPECT_DOUBLE_EQ(m.cloth().mu_s(), 0.21);
  EXPECT_DOUBLE_EQ(m.ball_ball().restitution(), 0.89);
  EXPECT_EQ(m.ball_ball().friction_law(), "constant");
  EXPECT_GT(m.cushion().restitution_speed_size(), 1);
  EXPECT_EQ(m.cushion().restitution_speed_size(), m.cushion().restitution_size());
  EXPECT_EQ(m.simulation().max_events(), 5000);
  EXPECT_DOUBLE_EQ(m.simulation().path_sample_s(), 0.02);
  EXPECT_DOUBLE_EQ(m.simulation().tolerance(), physics::SimParams::kShotTolerance);
  EXPECT_TRUE(m.simulation().impact_tables());

  // The pocket names are those a Simulate answer uses: pot the black and look.
  std::set<std::string> pockets;
  for (const v1::Pocket& p : g.pockets()) pockets.insert(p.name());
  v1::SimulateResponse sim;
  grpc::ClientContext ctx;
  v1::SimulateRequest r = testing_requests::BreakOff(8, 0, 0);
  ASSERT_TRUE(s.stub->Simulate(&ctx, r, &sim).ok());
  for (const v1::FinalBall& b : sim.final_balls()) {
    if (b.pocketed()) {
      EXPECT_EQ(pockets.count(b.pocket()), 1u) << b.pocket();
    }
  }
  for (const v1::Event& e : sim.events()) {
    if (!e.pocket().empty()) {
      EXPECT_EQ(pockets.count(e.pocket()), 1u) << e.pocket();
    }
  }
}

// The built-in tables a client offers are the command line's, ball for ball, and a
// Plan takes each as it is (the break-off's with the cue ball in hand).
TEST(GetModelTest, ListsTheBuiltInTablesThatAPlanAccepts) {
  TestServer s;
  ASSERT_NE(s.stub, nullptr);
  const v1::GetModelResponse m = Model(s);
  const std::vector<planner::BuiltinTableEntry> list = planner::BuiltinTableList();
  ASSERT_EQ(m.builtin_tables_size(), static_cast<int>(list.size()));
  for (int t = 0; t < m.builtin_tables_size(); ++t) {
    const v1::BuiltinTable& table = m.builtin_tables(t);
    EXPECT_EQ(table.name(), list[static_cast<std::size_t>(t)].name);
    EXPECT_FALSE(table.description().empty()) << table.name();
    const auto balls = planner::BuiltinTable(table.name());
    ASSERT_TRUE(balls.has_value()) << table.name();
    ASSERT_EQ(table.state().balls_size(), static_cast<int>(balls->size())) << table.name();
    bool has_cue = false;
    for (int i = 0; i < table.state().balls_size(); ++i) {
      const v1::Ball& b = table.state().balls(i);
      const planner::NamedBall& want = (*balls)[static_cast<std::size_t>(i)];
      EXPECT_EQ(b.id(), want.id) << table.name();
      EXPECT_EQ(b.kind(), ToProto(want.ball.kind)) << table.name() << " " << b.id();
      EXPECT_EQ(b.position().x(), want.ball.position.x()) << table.name() << " " << b.id();
      EXPECT_EQ(b.position().y(), want.ball.position.y()) << table.name() << " " << b.id();
      has_cue = has_cue || b.kind() == v1::CUE;
    }
    EXPECT_EQ(has_cue, table.name() != "break-off") << table.name();

    v1::PlanRequest r;
    *r.mutable_table() = table.state();
    r.set_cue_in_hand(!has_cue);
    r.set_max_simulations(300);
    r.set_monte_carlo_samples(16);
    r.set_time_budget_ms(10'000);
    r.set_max_shots(1);
    r.set_seed(1);
    v1::PlanResponse answer;
    grpc::ClientContext ctx;
    const grpc::Status st = s.stub->Plan(&ctx, r, &answer);
    EXPECT_TRUE(st.ok()) << table.name() << ": " << st.error_message();
    EXPECT_EQ(answer.shots_size(), 1) << table.name();
  }
  // The demonstration's table first, as the page draws it on load.
  EXPECT_EQ(m.builtin_tables(0).name(), "black");
}

TEST(GetModelTest, ReportsTheServersOwnBounds) {
  ServerOptions options;
  options.vision_tolerance_mm = 0.5;
  options.workers = 3;
  options.max_queued = 7;
  options.max_plans = 9;
  options.max_call = std::chrono::milliseconds(1234);
  options.default_plan_budget_ms = 50;
  options.max_plan_budget_ms = 2000;
  TestServer s(options);
  ASSERT_NE(s.stub, nullptr);
  const v1::ServiceLimits l = Model(s).service();
  EXPECT_EQ(l.vision_tolerance_mm(), 0.5);
  EXPECT_EQ(l.workers(), 3);
  EXPECT_EQ(l.max_queued(), 7);
  EXPECT_EQ(l.max_plans(), 9);
  EXPECT_EQ(l.max_call_ms(), 1234);
  EXPECT_EQ(l.default_plan_budget_ms(), 50);
  EXPECT_EQ(l.max_plan_budget_ms(), 2000);
  EXPECT_EQ(l.max_request_bytes(), static_cast<std::int64_t>(limits::kMaxRequestBytes));
  EXPECT_EQ(l.max_balls(), physics::limits::kMaxBalls);
  EXPECT_EQ(l.max_id_bytes(), 64);
  EXPECT_EQ(l.max_shot_speed(), 20);
}

TEST(GetModelTest, BadServerOptionsAreRefusedNamingTheOption) {
  struct Case {
    void (*spoil)(ServerOptions*);
    const char* must_mention;
  };
  const Case cases[] = {
      {[](ServerOptions* o) { o->vision_tolerance_mm = 11; }, "vision_tolerance_mm 11"},
      {[](ServerOptions* o) { o->vision_tolerance_mm = NAN; }, "vision_tolerance_mm nan"},
      {[](ServerOptions* o) { o->max_plans = 0; }, "max_plans 0"},
      {[](ServerOptions* o) { o->max_plan_budget_ms = 0; }, "max_plan_budget_ms 0"},
      {[](ServerOptions* o) { o->default_plan_budget_ms = 500, o->max_plan_budget_ms = 100; },
       "default_plan_budget_ms 500"},
  };
  for (const Case& c : cases) {
    ServerOptions o;
    o.address = "127.0.0.1:0";
    c.spoil(&o);
    std::string error;
    EXPECT_EQ(Server::Start(o, &error), nullptr) << c.must_mention;
    EXPECT_NE(error.find(c.must_mention), std::string::npos) << error;
  }
}

}  // namespace
}  // namespace snooker::server
