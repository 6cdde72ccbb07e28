#include "server/api.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <thread>
#include <utility>

#include "physics/impact/ball_ball.h"
#include "physics/motion/slip_phase.h"
#include "physics/sim/paths.h"
#include "server/build_info.h"
#include "server/convert.h"
#include "server/plan_convert.h"

namespace snooker::server {

const char* ToString(ApiStatus::Code code) {
  switch (code) {
    case ApiStatus::Code::kOk: return "OK";
    case ApiStatus::Code::kInvalidArgument: return "INVALID_ARGUMENT";
    case ApiStatus::Code::kResourceExhausted: return "RESOURCE_EXHAUSTED";
    case ApiStatus::Code::kDeadlineExceeded: return "DEADLINE_EXCEEDED";
    case ApiStatus::Code::kCancelled: return "CANCELLED";
    case ApiStatus::Code::kInternal: return "INTERNAL";
  }
  return "UNKNOWN";
}

namespace {

// Sampling interval of paths when a request sets none, s (simulate.proto).
constexpr double kDefaultPathSampleS = 0.02;

std::string Num(double x, int digits = 6) {
  std::ostringstream s;
  s.precision(digits);
  s << x;
  return s.str();
}

// The status of a call that `interrupt` stopped: DEADLINE_EXCEEDED once its deadline
// has passed (whatever else happened), otherwise CANCELLED. `progress` says how far
// the work got ("after 32 events ...").
ApiStatus Stopped(const physics::Interrupt& interrupt, const std::string& progress) {
  const bool late = interrupt.deadline != std::chrono::steady_clock::time_point::max() &&
                    std::chrono::steady_clock::now() >= interrupt.deadline;
  if (late) return {ApiStatus::Code::kDeadlineExceeded, "the call's deadline passed " + progress};
  return {ApiStatus::Code::kCancelled, "the call was cancelled " + progress};
}

// Running estimate of a message's size on the wire against a budget. Each added
// sub-message costs its own size plus its tag and length (at most 6 bytes).
class ByteBudget {
 public:
  explicit ByteBudget(std::size_t limit) : limit_(limit) {}
  bool Add(std::size_t bytes) {
    used_ += bytes + 6;
    return used_ <= limit_;
  }
  std::size_t limit() const { return limit_; }

 private:
  std::size_t limit_;
  std::size_t used_ = 0;
};

void FillBall(const physics::BallMotion& m, const physics::Vec2& incoming,
              const physics::BallParams& ball, const physics::ClothParams& cloth,
              v1::BallAfterImpact* out) {
  ToProto(m.v, out->mutable_velocity());
  ToProto(m.w, out->mutable_angular_velocity());
  const physics::SlipEnd end = physics::SlipPhaseEnd(m, ball, cloth);
  v1::SlipEnd* s = out->mutable_slip_end();
  ToProto(end.velocity, s->mutable_velocity());
  s->set_speed(end.speed);
  s->set_exit_angle_deg(physics::RadToDeg(physics::AngleBetween(end.velocity, incoming)));
  s->set_time(end.time);
  s->set_sidespin(end.sidespin);
}

}  // namespace

ApiStatus Collide(const v1::CollideRequest& request, v1::CollideResponse* response,
                  const CallLimits& limits) {
  const std::vector<FieldError> errors = ValidateCollideRequest(request);
  if (!errors.empty()) return ApiStatus::Invalid(Describe(errors));

  const physics::Model& model = limits.physics_model();
  const physics::BallParams ball = BallParamsFrom(request.parameters(), model);
  const physics::ClothParams cloth = ClothParamsFrom(request.parameters(), model);
  const physics::BallBallParams contact = BallBallParamsFrom(request.parameters(), model);
  const physics::ImpulseSolverOptions options = SolverOptionsFrom(request.solver());
  const double cut = physics::DegToRad(request.cut_angle_deg());
  const physics::ImpactState in = physics::PaperIncidentState(
      request.speed(), request.topspin(), request.sidespin(), cut);

  const physics::ImpactResult r = physics::ResolveImpact(in, ball, contact, cloth.mu_s, options);
  switch (r.status) {
    case physics::ImpactStatus::kOk: break;
    case physics::ImpactStatus::kInvalidInput: {
      const std::string why = physics::ValidateImpact(in, ball, contact, cloth.mu_s, options);
      return ApiStatus::Invalid(BoundMessage(
          "invalid input: " + (why.empty() ? std::string("rejected by the impact solver") : why)));
    }
    case physics::ImpactStatus::kNotApproaching:
      // Validated input approaches unless the approach is negligible against the
      // speed scale (a cut within a hair of 90 deg, or spin far above the speed).
      return ApiStatus::Invalid(
          "not approaching: speed = " + FormatNumber(request.speed()) + " m/s at cut_angle_deg = " +
          FormatNumber(request.cut_angle_deg()) + " gives an approach speed of " +
          Num(request.speed() * std::cos(cut)) +
          " m/s along the line of centres, too small against the speed and spin to resolve "
          "an impact (the balls graze)");
    case physics::ImpactStatus::kStepLimit:
      return {ApiStatus::Code::kResourceExhausted,
              "the impulse integrator reached its step cap of " + std::to_string(options.max_steps) +
                  " steps (" + std::to_string(r.work.steps) + " accepted)"};
  }
  if (limits.interrupt.Due()) {
    return Stopped(limits.interrupt, "while the collision was resolved");
  }
  const physics::Vec2 incoming(std::sin(cut), std::cos(cut));  // cue ball's direction
  FillBall(r.out.c, incoming, ball, cloth, response->mutable_cue());
  FillBall(r.out.o, incoming, ball, cloth, response->mutable_object());
  response->set_impulse_steps(r.work.steps);
  response->set_rhs_evaluations(r.work.rhs_evals);
  response->set_rejected_steps(r.work.rejected_steps);
  response->set_events(r.work.events);
  response->set_impulse_compression(r.impulse_compression);
  response->set_impulse_final(r.impulse_final);
  return ApiStatus::Ok();
}

namespace {

std::string Progress(const physics::Simulator& sim) {
  return "after " + std::to_string(sim.event_count()) + " events (" + Num(sim.end_time()) +
         " s of the shot simulated)";
}

ApiStatus TooLarge(std::size_t limit, const std::string& what, v1::SimulateResponse* response) {
  response->Clear();
  return {ApiStatus::Code::kResourceExhausted,
          "the response would be larger than " + std::to_string(limit) + " bytes (" + what +
              "); ask for fewer events (options.max_events), shorter ball ids, or fewer path "
              "points (a larger options.path_sample_s, or no paths)"};
}

}  // namespace

ApiStatus Simulate(const v1::SimulateRequest& request, v1::SimulateResponse* response,
                   const CallLimits& limits) {
  const physics::TableModel& table = physics::DefaultTable();
  std::vector<FieldError> errors;
  const std::optional<double> tolerance = VisionTolerance(
      request.has_vision_tolerance_mm() ? std::optional<double>(request.vision_tolerance_mm())
                                        : std::nullopt,
      limits.vision_tolerance_mm, "vision_tolerance_mm", &errors);
  // A bad tolerance is reported alone: the table is checked with the server's.
  TableCheck check = CheckTable(request.table(), table,
                                tolerance.value_or(limits.vision_tolerance_mm * 1e-3));
  errors.insert(errors.begin(), check.errors.begin(), check.errors.end());
  const std::vector<FieldError> more = ValidateShotAndOptions(request);
  errors.insert(errors.end(), more.begin(), more.end());
  // A stroke in the robot's terms is struck into the cue ball's shot first.
  v1::Shot shot = request.shot();
  if (request.has_cue() && errors.empty()) {
    if (const auto struck = ShotFromCue(request.cue(), &errors, limits.physics_model())) ToProto(*struck, &shot);
  }
  if (!errors.empty()) return ApiStatus::Invalid(Describe(errors));
  const v1::TableState& state = check.repaired ? *check.repaired : request.table();
  const bool paths = request.options().include_paths();
  const std::vector<physics::BallState> balls = BallStatesFrom(state, shot);
  physics::Simulator sim(table, SimParamsFrom(request.options(), limits.physics_model()));
  physics::RunOptions run;
  run.record_events = true;
  run.record_paths = paths;
  run.interrupt = limits.interrupt;
  const physics::SimStatus status = sim.Run(balls, run);
  switch (status) {
    case physics::SimStatus::kAtRest:
    case physics::SimStatus::kEventLimit:
    case physics::SimStatus::kTimeLimit: break;
    case physics::SimStatus::kInterrupted: return Stopped(limits.interrupt, Progress(sim));
    case physics::SimStatus::kSolverFailure:
      return {ApiStatus::Code::kResourceExhausted,
              "an impact solver reached its step cap " + Progress(sim) +
                  "; a looser options.tolerance needs fewer steps"};
    case physics::SimStatus::kInvalidInput:
      return {ApiStatus::Code::kInternal, "the simulator rejected a validated table (a bug)"};
    case physics::SimStatus::kEventOrder:
    case physics::SimStatus::kRunning:
      return {ApiStatus::Code::kInternal,
              std::string("the simulation stopped on a broken invariant: ") +
                  physics::ToString(status) + ", " + Progress(sim)};
  }

  ByteBudget budget(limits.max_response_bytes);
  for (v1::Warning& w : check.warnings) {
    budget.Add(w.ByteSizeLong());
    *response->add_warnings() = std::move(w);
  }
  response->set_status(physics::ToString(status));
  response->set_duration_s(sim.end_time());
  auto id = [&](int i) -> const std::string& { return state.balls(i).id(); };
  for (const physics::SimEvent& e : sim.events()) {
    v1::Event* out = response->add_events();
    ToProto(e, state, table, out);
    if (!budget.Add(out->ByteSizeLong())) {
      return TooLarge(budget.limit(), std::to_string(sim.events().size()) + " events", response);
    }
  }
  for (int i = 0; i < state.balls_size(); ++i) {
    v1::FinalBall* out = response->add_final_balls();
    out->set_id(id(i));
    out->set_kind(state.balls(i).kind());
    ToProto(sim.final_balls()[static_cast<size_t>(i)].r, out->mutable_position());
    const int pocket = sim.pocket_of(i);
    out->set_pocketed(pocket >= 0);
    if (pocket >= 0) out->set_pocket(physics::ToString(table.pockets()[static_cast<size_t>(pocket)].id));
    budget.Add(out->ByteSizeLong());
  }
  if (paths) {
    // Every path sampled at the asked interval, grown so that the samples of all balls
    // stay within limits::kMaxPathPoints, knots apart (physics/sim/paths.h).
    const double asked =
        request.options().has_path_sample_s() ? request.options().path_sample_s() : kDefaultPathSampleS;
    const double dt = physics::PathSampleInterval(asked, sim.end_time(), state.balls_size(),
                                                  limits::kMaxPathPoints);
    constexpr std::size_t kPointBytes = 2 * 9 + 2 + 8;  // x, y with tags and length; t
    std::int64_t points = 0;
    std::vector<physics::PathSample> samples;
    for (int i = 0; i < state.balls_size(); ++i) {
      v1::BallPath* path = response->add_paths();
      path->set_id(id(i));
      bool fits = budget.Add(path->ByteSizeLong());
      auto add = [&](const physics::PathSample& p) {
        path->add_t(p.t);
        ToProto(p.r, path->add_points());
        ++points;
        fits = fits && budget.Add(kPointBytes);
      };
      physics::SamplePath(sim, i, dt, &samples);
      for (std::size_t k = 0; k + 1 < samples.size() && fits; ++k) add(samples[k]);
      add(samples.back());  // the final point
      if (!fits) {
        return TooLarge(budget.limit(),
                        std::to_string(sim.events().size()) + " events and more than " +
                            std::to_string(points) + " path points",
                        response);
      }
    }
  }
  if (limits.interrupt.Due()) {  // no answer after the deadline (paths take a while)
    response->Clear();
    return Stopped(limits.interrupt, Progress(sim) + ", while the answer was built");
  }
  if (response->ByteSizeLong() > limits.max_response_bytes) {  // the exact size
    return TooLarge(limits.max_response_bytes,
                    std::to_string(response->ByteSizeLong()) + " bytes", response);
  }
  return ApiStatus::Ok();
}

v1::ServiceLimits DefaultServiceLimits(const CallLimits& limits) {
  v1::ServiceLimits out;
  out.set_vision_tolerance_mm(limits.vision_tolerance_mm);
  out.set_max_call_ms(limits::kDefaultMaxCall.count());
  out.set_default_plan_budget_ms(limits.default_plan_budget_ms);
  out.set_max_plan_budget_ms(limits.max_plan_budget_ms);
  out.set_max_plans(limits::kDefaultMaxPlans);
  out.set_workers(static_cast<std::int32_t>(std::max(1u, std::thread::hardware_concurrency())));
  out.set_max_queued(limits::kDefaultMaxQueued);
  out.set_max_request_bytes(static_cast<std::int64_t>(limits::kMaxRequestBytes));
  out.set_max_response_bytes(static_cast<std::int64_t>(limits.max_response_bytes));
  out.set_max_balls(physics::limits::kMaxBalls);
  out.set_max_id_bytes(static_cast<std::int32_t>(physics::limits::kMaxIdBytes));
  out.set_max_shot_speed(physics::limits::kShotSpeed.hi);
  out.set_max_spin(physics::limits::kMaxSpin);
  return out;
}

ApiStatus GetModel(const v1::GetModelRequest& /*request*/, v1::GetModelResponse* response,
                   const CallLimits& limits) {
  const physics::TableModel& table = physics::DefaultTable();
  ToProto(table, response->mutable_table());
  ModelToProto(limits.physics_model(), table, kDefaultPathSampleS, response);  // what Simulate uses for unset options
  BuiltinTablesToProto(response);
  response->mutable_build()->set_version(kBuildVersion);
  response->mutable_build()->set_commit(kBuildCommit);
  *response->mutable_service() =
      limits.service != nullptr ? *limits.service : DefaultServiceLimits(limits);
  return ApiStatus::Ok();
}

}  // namespace snooker::server
