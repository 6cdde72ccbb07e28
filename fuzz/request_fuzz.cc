// libFuzzer target for the service's request path: bytes -> decoding (server/decode.h)
// -> validation and conversion (server/convert.h) -> a bounded library call
// (server/api.h), as the gRPC service runs it. The first input byte picks the method
// (low bits) and the mode (high bit): the rest is either the request's wire bytes
// as they are (random bytes, and the seeds of fuzz/seeds/request mutated) or drives a
// builder that makes a structured request near the bounds, serialised and decoded
// like any other. For every input:
//  * no crash, hang or unbounded memory (libFuzzer's -timeout and -rss_limit_mb);
//  * a status that is not OK has a reason, every message is within
//    limits::kMaxMessageBytes, and no input is INTERNAL (a broken invariant, e.g. an
//    event before the current time);
//  * an answer has only finite numbers and fits limits::kMaxResponseBytes;
//  * a vision repair moved each ball at most the tolerance, and what it left is a
//    valid placement.
// A broken property aborts (libFuzzer then saves the input as a crash-* file).
//
// A method is one entry of kMethods (0 Collide, 1 Simulate, 2 GetModel, 3 Plan,
// 4 Calibrate). Plans run with a tiny budget (at most kPlanBudgetMs, and a cap on
// simulations and samples) so that thousands of inputs run a minute; their answers
// must be final, inside the request's limits, with probabilities in [0, 1] and the
// vision repair within its tolerance. Calibrations run capped too (kCalibrateEvaluations,
// a few observations of each kind, at most 2 tracked shots): each fitted value
// within its bound, each uncertainty >= 0 or the documented -1, the model a
// valid model file.
#include <fuzzer/FuzzedDataProvider.h>
#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>
#include <google/protobuf/stubs/logging.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <string_view>

#include "physics/core/limits.h"
#include "physics/table/table.h"
#include "calibration/fit.h"
#include "server/api.h"
#include "server/calibrate_api.h"
#include "server/decode.h"
#include "server/limits.h"
#include "server/model_convert.h"
#include "server/plan_api.h"
#include "planner/planner.h"

namespace {

using namespace snooker;
using server::ApiStatus;

[[noreturn]] void Fail(const std::string& what) {
  std::fprintf(stderr, "property broken: %s\n", what.c_str());
  std::abort();
}

void CheckStatus(const ApiStatus& st, const char* method) {
  if (st.message.size() > server::limits::kMaxMessageBytes) {
    Fail(std::string(method) + ": a message of " + std::to_string(st.message.size()) + " bytes");
  }
  if (!st.ok() && st.message.empty()) Fail(std::string(method) + ": a status without a reason");
  if (st.code == ApiStatus::Code::kInternal) Fail(std::string(method) + ": INTERNAL: " + st.message);
}

// Every double in a message (recursively) is finite.
void CheckFinite(const google::protobuf::Message& m) {
  using google::protobuf::FieldDescriptor;
  const google::protobuf::Reflection* r = m.GetReflection();
  std::vector<const FieldDescriptor*> fields;
  r->ListFields(m, &fields);
  for (const FieldDescriptor* f : fields) {
    const bool repeated = f->is_repeated();
    const int n = repeated ? r->FieldSize(m, f) : 1;
    for (int i = 0; i < n; ++i) {
      if (f->cpp_type() == FieldDescriptor::CPPTYPE_DOUBLE) {
        const double x = repeated ? r->GetRepeatedDouble(m, f, i) : r->GetDouble(m, f);
        if (!std::isfinite(x)) Fail("a non-finite number in the answer: " + f->full_name());
      } else if (f->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) {
        CheckFinite(repeated ? r->GetRepeatedMessage(m, f, i) : r->GetMessage(m, f));
      }
    }
  }
}

// The bounds let a valid request run up to a second or so (10^6 events, 10^7 fixed
// steps; the service tests cover those). Here valid requests are capped lower so that
// the fuzzer tries thousands of inputs a second; invalid values are left for
// validation to refuse.
void Tame(v1::SimulateRequest* r) {
  v1::SimulationOptions* o = r->mutable_options();
  if (!o->has_max_events() || (o->max_events() > 3000 && o->max_events() <= physics::limits::kMaxEvents)) {
    o->set_max_events(3000);
  }
}
void Tame(v1::GetModelRequest*) {}
// A plan's budget here, ms, and its caps on work.
constexpr double kPlanBudgetMs = 5;
void Tame(v1::PlanRequest* r) {
  if (r->has_time_budget_ms() && r->time_budget_ms() > kPlanBudgetMs &&
      r->time_budget_ms() <= server::limits::kDefaultMaxPlanBudgetMs) {
    r->set_time_budget_ms(kPlanBudgetMs);
  }
  if (!r->has_max_simulations() || (r->max_simulations() > 400 && r->max_simulations() <= 100'000'000) ||
      r->max_simulations() == 0) {
    r->set_max_simulations(400);
  }
  if (r->has_monte_carlo_samples() && r->monte_carlo_samples() > 16 &&
      r->monte_carlo_samples() <= 100'000) {
    r->set_monte_carlo_samples(16);
  } else if (!r->has_monte_carlo_samples()) {
    r->set_monte_carlo_samples(16);
  }
}
void Tame(v1::CollideRequest* r) {
  v1::ImpulseSolverOptions* s = r->mutable_solver();
  if (s->has_steps() && s->steps() > 20'000 && s->steps() <= physics::limits::kMaxFixedSteps) {
    s->set_steps(20'000);
  }
}

// A calibration's caps here: its evaluations, and the observations of each kind
// (a fit evaluates every observation some tens of times).
constexpr int kCalibrateEvaluations = 20;
constexpr int kCalibrateObservations = 12;
constexpr int kCalibrateTracked = 2;
constexpr int kCalibrateSightings = 8;
void Tame(v1::CalibrateRequest* r) {
  if (!r->has_max_evaluations() ||
      (r->max_evaluations() > kCalibrateEvaluations && r->max_evaluations() <= 100'000)) {
    r->set_max_evaluations(kCalibrateEvaluations);
  }
  v1::Observations* o = r->mutable_observations();
  if (o->throw__size() > kCalibrateObservations) {
    o->mutable_throw_()->DeleteSubrange(kCalibrateObservations, o->throw__size() - kCalibrateObservations);
  }
  if (o->cushion_size() > kCalibrateObservations) {
    o->mutable_cushion()->DeleteSubrange(kCalibrateObservations, o->cushion_size() - kCalibrateObservations);
  }
  if (o->tracked_size() > kCalibrateTracked) {
    o->mutable_tracked()->DeleteSubrange(kCalibrateTracked, o->tracked_size() - kCalibrateTracked);
  }
  for (v1::TrackedShot& s : *o->mutable_tracked()) {
    if (s.sightings_size() > kCalibrateSightings) {
      s.mutable_sightings()->DeleteSubrange(kCalibrateSightings, s.sightings_size() - kCalibrateSightings);
    }
  }
}

// Method-specific properties of an answer.
void CheckAnswer(const v1::CollideRequest&, const v1::CollideResponse&) {}
void CheckAnswer(const v1::GetModelRequest&, const v1::GetModelResponse&) {}

// A fit's answer: its parameters are the groups', each within its bound, with an
// uncertainty >= 0 or -1 (undetermined); its model reads back as a valid model file.
void CheckAnswer(const v1::CalibrateRequest& request, const v1::CalibrateResponse& response) {
  physics::Model start;
  if (!server::ModelFromProto(request.start(), &start).empty()) Fail("Calibrate: a bad start model answered");
  std::string groups_text;
  for (const std::string& g : request.fit()) groups_text += (groups_text.empty() ? "" : ",") + g;
  const calibration::ParsedGroups groups = calibration::ParseGroups(groups_text);
  std::vector<server::FieldError> errors;
  const calibration::Observations observations = server::ObservationsFrom(request.observations(), &errors);
  const std::vector<calibration::ParameterSpec> specs =
      calibration::FittedParameters(groups.groups, observations, start);
  if (!groups.error.empty() || !errors.empty()) Fail("Calibrate: a request with bad groups or observations answered");
  if (response.parameters_size() != static_cast<int>(specs.size()) || specs.empty()) {
    Fail("Calibrate: " + std::to_string(response.parameters_size()) + " parameters for " +
         std::to_string(specs.size()));
  }
  for (int i = 0; i < response.parameters_size(); ++i) {
    const v1::FittedParameter& p = response.parameters(i);
    const calibration::ParameterSpec& spec = specs[static_cast<std::size_t>(i)];
    if (p.name() != spec.name) Fail("Calibrate: parameter " + p.name() + " where " + spec.name + " was due");
    if (!(p.value() >= spec.lo && p.value() <= spec.hi)) Fail("Calibrate: " + p.name() + " outside its bounds");
    if (!(p.uncertainty() >= 0 || p.uncertainty() == -1)) Fail("Calibrate: " + p.name() + "'s uncertainty < 0");
  }
  physics::Model fitted;
  if (const std::string bad = server::ModelFromProto(response.model(), &fitted); !bad.empty()) {
    Fail("Calibrate: the fitted model is not a valid model file: " + bad);
  }
  if (response.evaluations() <= 0) Fail("Calibrate: no evaluations");
  for (const v1::ResidualSummary& r : response.residuals()) {
    if (r.count() <= 0 || !(r.rms_before() >= 0) || !(r.rms_after() >= 0)) Fail("Calibrate: a bad residual summary");
  }
}
// The vision repair moved each ball at most the tolerance, and left a valid table.
template <typename Request, typename Response>
void CheckRepair(const Request& request, const Response& response) {
  const double tolerance_mm = request.has_vision_tolerance_mm()
                                  ? request.vision_tolerance_mm()
                                  : server::limits::kDefaultVisionToleranceMm;
  // Where every ball started after the repair.
  std::vector<v1::Ball> balls(request.table().balls().begin(), request.table().balls().end());
  for (const v1::Warning& w : response.warnings()) {
    if (!(w.moved_mm() > 0 && w.moved_mm() <= tolerance_mm * (1 + 1e-9) + 1e-9)) {
      Fail("a ball moved " + std::to_string(w.moved_mm()) + " mm, tolerance " +
           std::to_string(tolerance_mm) + " mm");
    }
    if (w.message().empty()) Fail("a warning without a message");
    for (v1::Ball& b : balls) {
      if (b.id() == w.ball_id()) *b.mutable_position() = w.to();
    }
  }
  std::vector<physics::BallPlacement> placed;
  for (const v1::Ball& b : balls) {
    placed.push_back({b.id(), physics::Vec2(b.position().x(), b.position().y())});
  }
  const std::string bad = physics::DefaultTable().ValidatePlacement(placed);
  if (!bad.empty()) Fail("the repaired table is not valid: " + bad);
}

void CheckAnswer(const v1::SimulateRequest& request, const v1::SimulateResponse& response) {
  CheckRepair(request, response);
}

void CheckAnswer(const v1::PlanRequest& request, const v1::PlanResponse& response) {
  CheckRepair(request, response);
  if (!response.final()) Fail("a plan not marked final");
  const planner::RobotLimits defaults;
  const v1::RobotLimits& l = request.limits();
  const double lo = l.has_min_speed() ? l.min_speed() : defaults.min_speed;
  const double hi = l.has_max_speed() ? l.max_speed() : defaults.max_speed;
  const double top = l.has_max_topspin_fraction() ? l.max_topspin_fraction() : defaults.max_topspin_fraction;
  const double side =
      l.has_max_sidespin_fraction() ? l.max_sidespin_fraction() : defaults.max_sidespin_fraction;
  const int most = request.has_max_shots() ? request.max_shots() : 3;
  if (response.shots_size() > most) Fail("more shots than max_shots");
  const double radius = physics::BallParams{}.radius;
  for (const v1::PlannedShot& s : response.shots()) {
    const double rolling = s.speed() / radius;
    if (!(s.speed() >= lo * (1 - 1e-9) && s.speed() <= hi * (1 + 1e-9))) {
      Fail("a planned speed of " + std::to_string(s.speed()) + " m/s outside the limits");
    }
    if (std::abs(s.topspin()) > top * rolling * (1 + 1e-9) + 1e-12 ||
        std::abs(s.sidespin()) > side * rolling * (1 + 1e-9) + 1e-12) {
      Fail("a planned spin beyond the limits");
    }
    if (!(s.pot_probability() >= 0 && s.pot_probability() <= 1)) Fail("a probability outside [0, 1]");
    bool known = false;
    for (const v1::Ball& b : request.table().balls()) known = known || b.id() == s.object_ball();
    if (!known) Fail("a shot names an object ball not on the table");
  }
}

// Plan with the service's bounds and a tiny default budget (Tame caps a set one).
ApiStatus PlanOperation(const v1::PlanRequest& request, v1::PlanResponse* response,
                        const server::CallLimits& limits) {
  server::PlanControl control;
  control.deadline = limits.interrupt.deadline;
  control.vision_tolerance_mm = limits.vision_tolerance_mm;
  control.default_budget_ms = kPlanBudgetMs;
  control.max_budget_ms = limits.max_plan_budget_ms;
  return server::Plan(request, response, control);
}

template <typename Request, typename Response,
          ApiStatus (*Operation)(const Request&, Response*, const server::CallLimits&)>
void Exercise(std::string_view bytes, const char* method) {
  Request request;
  const ApiStatus parsed = server::ParseRequest(bytes, &request);
  CheckStatus(parsed, method);
  if (!parsed.ok()) {
    if (parsed.code != ApiStatus::Code::kInvalidArgument) Fail("undecodable bytes not INVALID_ARGUMENT");
    return;
  }
  Tame(&request);
  server::CallLimits limits;  // a backstop; -timeout catches a hang
  limits.interrupt.deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  Response response;
  const ApiStatus st = Operation(request, &response, limits);
  CheckStatus(st, method);
  if (!st.ok()) return;
  CheckFinite(response);
  if (response.ByteSizeLong() > limits.max_response_bytes) Fail("an answer above the response limit");
  CheckAnswer(request, response);
}

// Mostly values inside or near the bounds, sometimes anything (NaN, inf, huge, tiny).
double Value(FuzzedDataProvider& in, double lo, double hi) {
  switch (in.ConsumeIntegralInRange<int>(0, 15)) {
    case 0: return in.ConsumeFloatingPoint<double>();
    case 1: return std::numeric_limits<double>::quiet_NaN();
    case 2: return in.ConsumeBool() ? lo : hi;
    default: return in.ConsumeFloatingPointInRange<double>(lo, hi);
  }
}

std::string Serialized(const google::protobuf::Message& m) {
  std::string bytes;
  m.SerializePartialToString(&bytes);
  return bytes;
}

std::string BuildCollide(FuzzedDataProvider& in) {
  v1::CollideRequest r;
  r.set_speed(Value(in, 0, 30));
  r.set_topspin(Value(in, -1100, 1100));
  r.set_sidespin(Value(in, -1100, 1100));
  r.set_cut_angle_deg(Value(in, -91, 91));
  v1::CollisionParameters* p = r.mutable_parameters();
  if (in.ConsumeBool()) p->set_mu_bb(Value(in, -0.1, 1.1));
  if (in.ConsumeBool()) p->set_restitution(Value(in, -0.1, 1.1));
  if (in.ConsumeBool()) p->set_mu_s(Value(in, -0.1, 1.1));
  if (in.ConsumeBool()) p->set_mass_kg(Value(in, 0, 11));
  if (in.ConsumeBool()) p->set_radius_m(Value(in, 0, 1.1));
  if (in.ConsumeBool()) p->set_gravity(Value(in, 0, 110));
  if (in.ConsumeBool()) p->set_spin_decel(Value(in, -1, 1.1e4));
  p->set_friction_law(v1::BallBallFrictionLaw(in.ConsumeIntegralInRange<int>(-2, 10)));
  v1::ImpulseSolverOptions* s = r.mutable_solver();
  s->set_integrator(v1::ImpulseIntegrator(in.ConsumeIntegralInRange<int>(-2, 10)));
  if (in.ConsumeBool()) s->set_steps(in.ConsumeIntegral<std::int32_t>());
  if (in.ConsumeBool()) s->set_tolerance(Value(in, 1e-16, 0.2));
  return Serialized(r);
}

std::string Id(FuzzedDataProvider& in, int i) {
  switch (in.ConsumeIntegralInRange<int>(0, 7)) {
    case 0: return "";
    case 1: return std::string(in.ConsumeIntegralInRange<std::size_t>(60, 200), 'x');
    case 2: return in.ConsumeRandomLengthString(80);  // maybe not UTF-8: decoding refuses it
    case 3: return "red-1";                           // maybe a duplicate
    default: return "ball-" + std::to_string(i);
  }
}

// A coordinate on or near the table, sometimes anything.
double Coordinate(FuzzedDataProvider& in, double length) { return Value(in, -0.1, length + 0.1); }

// A ball's position: anywhere near the table, or in a resting contact: its
// centre exactly the cushion contact distance from a cushion, or exactly 2R from the
// previous ball (touching it), which the engine must handle as ordinary states; or,
// as vision reports them, a little past a cushion or into the previous ball (up to
// 1.5 mm: within the vision repair's tolerance or just beyond it).
physics::Vec2 Position(FuzzedDataProvider& in, const physics::Vec2* previous) {
  const physics::TableModel& table = physics::DefaultTable();
  const double w = table.spec().width, l = table.spec().length;
  const double vision_error = in.ConsumeBool() ? in.ConsumeFloatingPointInRange<double>(0, 1.5e-3) : 0;
  const double c = table.cushion_contact_distance() - vision_error;
  switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 1: {  // frozen to a cushion (or a hair past it)
      const double along = in.ConsumeProbability<double>();
      switch (in.ConsumeIntegralInRange<int>(0, 3)) {
        case 0: return {c, along * l};
        case 1: return {w - c, along * l};
        case 2: return {along * w, c};
        default: return {along * w, l - c};
      }
    }
    case 2:  // touching the previous ball (or overlapping it a little)
      if (previous != nullptr) {
        const double a = 2 * physics::kPi * in.ConsumeProbability<double>();
        return *previous +
               (2 * table.ball_radius() - vision_error) * physics::Vec2(std::cos(a), std::sin(a));
      }
      [[fallthrough]];
    default: return {Coordinate(in, w), Coordinate(in, l)};
  }
}

std::string BuildSimulate(FuzzedDataProvider& in) {
  v1::SimulateRequest r;
  const int n = in.ConsumeBool() ? in.ConsumeIntegralInRange<int>(0, 8)
                                 : in.ConsumeIntegralInRange<int>(0, 40);
  physics::Vec2 previous;
  for (int i = 0; i < n; ++i) {
    v1::Ball* b = r.mutable_table()->add_balls();
    b->set_id(i == 0 ? "cue" : Id(in, i));
    b->set_kind(i == 0 ? v1::CUE : v1::BallKind(in.ConsumeIntegralInRange<int>(-1, 10)));
    previous = Position(in, i > 0 ? &previous : nullptr);
    b->mutable_position()->set_x(previous.x());
    b->mutable_position()->set_y(previous.y());
  }
  v1::Shot* shot = r.mutable_shot();
  shot->set_speed(Value(in, 0, 21));
  shot->set_heading_deg(Value(in, -4000, 4000));
  shot->set_topspin(Value(in, -1100, 1100));
  shot->set_sidespin(Value(in, -1100, 1100));
  v1::SimulationOptions* o = r.mutable_options();
  if (in.ConsumeBool()) o->set_max_events(in.ConsumeIntegral<std::int32_t>());
  if (in.ConsumeBool()) o->set_max_time_s(Value(in, 0, 4000));
  if (in.ConsumeBool()) o->set_tolerance(Value(in, 1e-16, 0.2));
  o->set_include_paths(in.ConsumeBool());
  if (in.ConsumeBool()) o->set_path_sample_s(Value(in, 1e-5, 2));
  if (in.ConsumeBool()) r.set_vision_tolerance_mm(Value(in, -0.1, 1.2));
  return Serialized(r);
}

std::string BuildPlan(FuzzedDataProvider& in) {
  // The table as for Simulate, the rest of a plan request around its bounds.
  v1::SimulateRequest sim;
  sim.ParseFromString(BuildSimulate(in));
  v1::PlanRequest r;
  *r.mutable_table() = sim.table();
  if (sim.has_vision_tolerance_mm()) r.set_vision_tolerance_mm(sim.vision_tolerance_mm());
  r.set_ball_on(v1::BallOn(in.ConsumeIntegralInRange<int>(-1, 10)));
  v1::RobotLimits* l = r.mutable_limits();
  if (in.ConsumeBool()) l->set_min_speed(Value(in, -0.1, 21));
  if (in.ConsumeBool()) l->set_max_speed(Value(in, -0.1, 21));
  if (in.ConsumeBool()) l->set_max_topspin_fraction(Value(in, -0.1, 3.1));
  if (in.ConsumeBool()) l->set_max_sidespin_fraction(Value(in, -0.1, 3.1));
  if (in.ConsumeBool()) l->set_cue_clearance_m(Value(in, -0.1, 2.1));
  if (in.ConsumeBool()) l->set_cue_radius_m(Value(in, -0.01, 0.06));
  v1::NoiseModel* n = r.mutable_noise();
  if (in.ConsumeBool()) n->set_heading_sigma_deg(Value(in, -0.1, 11));
  if (in.ConsumeBool()) n->set_speed_sigma_fraction(Value(in, -0.1, 0.6));
  if (in.ConsumeBool()) n->set_topspin_sigma(Value(in, -1, 110));
  if (in.ConsumeBool()) n->set_sidespin_sigma(Value(in, -1, 110));
  if (in.ConsumeBool()) n->set_position_sigma_mm(Value(in, -1, 60));
  if (in.ConsumeBool() && r.table().balls_size() > 0) {
    (*n->mutable_ball_position_sigma_mm())[in.ConsumeBool() ? r.table().balls(0).id() : "nobody"] =
        Value(in, -1, 60);
  }
  if (in.ConsumeBool()) r.set_time_budget_ms(Value(in, -1, 12'000));
  if (in.ConsumeBool()) r.set_max_shots(in.ConsumeIntegralInRange<int>(-1, 25));
  if (in.ConsumeBool()) r.set_seed(in.ConsumeIntegral<std::uint64_t>());
  if (in.ConsumeBool()) r.set_position_play(in.ConsumeBool());
  if (in.ConsumeBool()) r.set_max_simulations(in.ConsumeIntegral<std::int32_t>());
  if (in.ConsumeBool()) r.set_monte_carlo_samples(in.ConsumeIntegral<std::int32_t>());
  return Serialized(r);
}

// Observations near and beyond their ranges, sometimes an input repeated with
// another measurement (contradictions); now and then one or two tiny tracked shots.
void AddThrows(FuzzedDataProvider& in, v1::Observations* o) {
  const int n = in.ConsumeIntegralInRange<int>(0, 6);
  for (int i = 0; i < n; ++i) {
    v1::ThrowObservation* t = o->add_throw_();
    if (i > 0 && in.ConsumeIntegralInRange<int>(0, 5) == 0) {
      *t = o->throw_(i - 1);
      t->set_throw_deg(Value(in, -50, 50));
      continue;
    }
    t->set_cut_deg(Value(in, -1, 91));
    switch (in.ConsumeIntegralInRange<int>(0, 5)) {
      case 0: break;  // no speed
      case 1:
        t->set_cue_ball_speed(Value(in, 0, 11));
        t->set_object_ball_speed(Value(in, 0, 11));
        break;
      case 2:
      case 3: t->set_cue_ball_speed(Value(in, 0, 11)); break;
      default: t->set_object_ball_speed(Value(in, 0, 11));
    }
    if (in.ConsumeBool()) t->set_topspin(Value(in, -1100, 1100));
    if (in.ConsumeBool()) t->set_sidespin(Value(in, -1100, 1100));
    t->set_throw_deg(Value(in, -50, 50));
  }
}

void AddRebounds(FuzzedDataProvider& in, v1::Observations* o) {
  const int n = in.ConsumeIntegralInRange<int>(0, 6);
  for (int i = 0; i < n; ++i) {
    v1::CushionObservation* c = o->add_cushion();
    if (i > 0 && in.ConsumeIntegralInRange<int>(0, 5) == 0) {
      *c = o->cushion(i - 1);
      c->set_rebound_speed(Value(in, -0.1, 11));
      continue;
    }
    c->set_speed(Value(in, 0, 11));
    c->set_angle_deg(Value(in, -1, 181));
    if (in.ConsumeBool()) c->set_topspin(Value(in, -1100, 1100));
    if (in.ConsumeBool()) c->set_sidespin(Value(in, -1100, 1100));
    c->set_rebound_speed(Value(in, -0.1, 11));
    if (in.ConsumeBool()) c->set_rebound_angle_deg(Value(in, -1, 181));
  }
}

void AddTrackedShot(FuzzedDataProvider& in, v1::Observations* o) {
  v1::TrackedShot* s = o->add_tracked();
  const int balls = in.ConsumeIntegralInRange<int>(0, 3);
  physics::Vec2 previous;
  for (int i = 0; i < balls; ++i) {
    v1::Ball* b = s->mutable_table()->add_balls();
    b->set_id(i == 0 ? "cue" : Id(in, i));
    b->set_kind(i == 0 || in.ConsumeIntegralInRange<int>(0, 7) == 0 ? v1::CUE : v1::RED);
    previous = Position(in, i > 0 ? &previous : nullptr);
    b->mutable_position()->set_x(previous.x());
    b->mutable_position()->set_y(previous.y());
  }
  switch (in.ConsumeIntegralInRange<int>(0, 4)) {
    case 0: break;  // no strike
    case 1:
    case 2: {
      v1::CueStrike* k = s->mutable_cue();
      k->set_speed(Value(in, 0, 11));
      k->set_heading_deg(Value(in, -4000, 4000));
      k->set_tip_side(Value(in, -1, 1));
      k->set_tip_height(Value(in, -1, 1));
      if (in.ConsumeBool()) k->set_elevation_deg(Value(in, -1, 91));
      break;
    }
    default: {
      v1::Shot* shot = s->mutable_shot();
      shot->set_speed(Value(in, 0, 11));
      shot->set_heading_deg(Value(in, -4000, 4000));
      if (in.ConsumeBool()) shot->set_topspin(Value(in, -1100, 1100));
      if (in.ConsumeBool()) shot->set_sidespin(Value(in, -1100, 1100));
      if (in.ConsumeBool()) shot->set_swerve_spin(Value(in, -1100, 1100));
    }
  }
  const int sightings = in.ConsumeIntegralInRange<int>(0, 4);
  double t = 0;
  for (int k = 0; k < sightings; ++k) {
    v1::Sighting* g = s->add_sightings();
    t += Value(in, -0.1, 1.0);
    g->set_t_s(t);
    for (int i = 0; i < balls; ++i) {
      if (in.ConsumeIntegralInRange<int>(0, 3) == 0) continue;  // not seen
      const v1::Ball& ball = s->table().balls(i);
      v1::BallSighting* b = g->add_balls();
      b->set_id(in.ConsumeIntegralInRange<int>(0, 9) == 0 ? "ghost" : ball.id());
      const double dx = Value(in, -0.5, 0.5), dy = Value(in, -0.5, 0.5);
      b->mutable_position()->set_x(ball.position().x() + dx);
      b->mutable_position()->set_y(ball.position().y() + dy);
    }
  }
}

std::string BuildCalibrate(FuzzedDataProvider& in) {
  v1::CalibrateRequest r;
  AddThrows(in, r.mutable_observations());
  AddRebounds(in, r.mutable_observations());
  if (in.ConsumeIntegralInRange<int>(0, 3) == 0) {
    const int tracked = in.ConsumeIntegralInRange<int>(1, 2);
    for (int i = 0; i < tracked; ++i) AddTrackedShot(in, r.mutable_observations());
  }
  static const char* const kWords[] = {"ball-ball", "cushion", "cloth", "cue", "", "fish",
                                       "ball-ball,cushion", " cue ", "Ball-Ball", ",", "cloth,cloth"};
  const int groups = in.ConsumeIntegralInRange<int>(0, 7) == 0 ? 0 : in.ConsumeIntegralInRange<int>(1, 3);
  for (int i = 0; i < groups; ++i) {
    r.add_fit(kWords[in.ConsumeIntegralInRange<std::size_t>(0, std::size(kWords) - 1)]);
  }
  v1::PhysicsModel* start = r.mutable_start();
  if (in.ConsumeBool()) {
    start->mutable_ball_ball()->set_friction_law(v1::BallBallFrictionLaw(in.ConsumeIntegralInRange<int>(-1, 4)));
  }
  if (in.ConsumeIntegralInRange<int>(0, 3) == 0) start->mutable_ball_ball()->set_mu_bb(Value(in, -0.1, 1.1));
  if (in.ConsumeIntegralInRange<int>(0, 3) == 0) start->mutable_ball_ball()->set_slip_gain(Value(in, -0.1, 1.1));
  if (in.ConsumeIntegralInRange<int>(0, 3) == 0) start->mutable_ball_ball()->set_slip_decay(Value(in, -1, 110));
  if (in.ConsumeIntegralInRange<int>(0, 3) == 0) start->mutable_cloth()->set_mu_s(Value(in, -0.1, 1.1));
  if (in.ConsumeIntegralInRange<int>(0, 3) == 0) start->mutable_cushion()->set_no_restitution_curve(in.ConsumeBool());
  if (in.ConsumeIntegralInRange<int>(0, 3) == 0) start->mutable_cue()->set_end_mass_kg(Value(in, -0.1, 1.1));
  if (in.ConsumeBool()) r.set_max_evaluations(in.ConsumeIntegralInRange<std::int32_t>(-5, 200'000));
  return Serialized(r);
}

std::string BuildGetModel(FuzzedDataProvider& in) {
  return in.ConsumeRandomLengthString(64);  // unknown fields, or bytes that do not parse
}

struct Method {
  const char* name;
  void (*run)(std::string_view bytes, const char* name);
  std::string (*build)(FuzzedDataProvider& in);
};

const Method kMethods[] = {
    {"Collide", &Exercise<v1::CollideRequest, v1::CollideResponse, &server::Collide>, &BuildCollide},
    {"Simulate", &Exercise<v1::SimulateRequest, v1::SimulateResponse, &server::Simulate>, &BuildSimulate},
    {"GetModel", &Exercise<v1::GetModelRequest, v1::GetModelResponse, &server::GetModel>, &BuildGetModel},
    {"Plan", &Exercise<v1::PlanRequest, v1::PlanResponse, &PlanOperation>, &BuildPlan},
    {"Calibrate", &Exercise<v1::CalibrateRequest, v1::CalibrateResponse, &server::Calibrate>, &BuildCalibrate},
};

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  google::protobuf::SetLogHandler(nullptr);  // decoding errors are expected here
  // The planner's pocket and throw tables, built once per process: here, not inside
  // the first Plan input's time limit.
  (void)planner::Planner::Default();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const Method& method = kMethods[(data[0] & 0x7F) % std::size(kMethods)];
  const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  if ((data[0] & 0x80) != 0) {
    FuzzedDataProvider in(data + 1, size - 1);
    method.run(method.build(in), method.name);
  } else {
    method.run(rest, method.name);
  }
  return 0;
}
