#include "server/api.h"

#include <algorithm>
#include <cmath>

#include "physics/impact/ball_ball.h"
#include "physics/sim/simulate.h"
#include "physics/motion/slip_phase.h"
#include "server/convert.h"

namespace snooker::server {
namespace {

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

ApiStatus Collide(const v1::CollideRequest& request, v1::CollideResponse* response) {
  const std::vector<FieldError> errors = ValidateCollideRequest(request);
  if (!errors.empty()) return ApiStatus::Invalid(Describe(errors));

  const physics::BallParams ball = BallParamsFrom(request.parameters());
  const physics::ClothParams cloth = ClothParamsFrom(request.parameters());
  const physics::BallBallParams contact = BallBallParamsFrom(request.parameters());
  const physics::ImpulseSolverOptions options = SolverOptionsFrom(request.solver());
  const double cut = physics::DegToRad(request.cut_angle_deg());
  const physics::ImpactState in = physics::PaperIncidentState(
      request.speed(), request.topspin(), request.sidespin(), cut);

  const physics::ImpactResult r = physics::ResolveImpact(in, ball, contact, cloth.mu_s, options);
  switch (r.status) {
    case physics::ImpactStatus::kOk: break;
    case physics::ImpactStatus::kInvalidInput:
    case physics::ImpactStatus::kNotApproaching:
      return ApiStatus::Invalid(std::string(physics::ToString(r.status)) + ": " +
                                physics::ValidateImpact(in, ball, contact, cloth.mu_s, options));
    case physics::ImpactStatus::kStepLimit:
      return {ApiStatus::Code::kResourceExhausted,
              "the impulse integrator reached its step cap of " +
                  std::to_string(options.max_steps) + " steps"};
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

v1::EventKind EventKindToProto(physics::EventKind k) {
  switch (k) {
    case physics::EventKind::kBallBall: return v1::BALL_BALL;
    case physics::EventKind::kCushion: return v1::CUSHION;
    case physics::EventKind::kJawWall: return v1::JAW_WALL;
    case physics::EventKind::kKnuckle: return v1::KNUCKLE;
    case physics::EventKind::kPocket: return v1::POCKET;
    case physics::EventKind::kTransition: return v1::MOTION_CHANGE;
  }
  return v1::EVENT_KIND_UNSPECIFIED;
}

}  // namespace

ApiStatus Simulate(const v1::SimulateRequest& request, v1::SimulateResponse* response) {
  const physics::TableModel& table = physics::DefaultTable();
  const std::vector<FieldError> errors = ValidateSimulateRequest(request, table);
  if (!errors.empty()) return ApiStatus::Invalid(Describe(errors));
  const v1::TableState& state = request.table();
  const std::vector<physics::BallState> balls = BallStatesFrom(state, request.shot());
  physics::Simulator sim(table, SimParamsFrom(request.options()));
  const physics::SimStatus status = sim.Run(balls);
  if (status == physics::SimStatus::kInvalidInput) {
    return {ApiStatus::Code::kInternal, "simulation rejected a validated table"};
  }
  if (status == physics::SimStatus::kSolverFailure) {
    return {ApiStatus::Code::kResourceExhausted, "an impact solver reached its step cap"};
  }
  response->set_status(physics::ToString(status));
  response->set_duration_s(sim.end_time());
  auto id = [&](int i) -> const std::string& { return state.balls(i).id(); };
  for (const physics::SimEvent& e : sim.events()) {
    v1::Event* out = response->add_events();
    out->set_time(e.time);
    out->set_kind(EventKindToProto(e.kind));
    out->add_balls(id(e.ball));
    if (e.other >= 0) out->add_balls(id(e.other));
    out->set_motion(physics::ToString(e.state_after));
    switch (e.kind) {
      case physics::EventKind::kCushion:
        out->set_cushion(table.segments()[static_cast<size_t>(e.where)].name);
        break;
      case physics::EventKind::kJawWall:
        out->set_cushion(table.segments()[static_cast<size_t>(e.where)].name);
        out->set_pocket(physics::ToString(table.segments()[static_cast<size_t>(e.where)].pocket));
        break;
      case physics::EventKind::kKnuckle:
        out->set_pocket(physics::ToString(table.jaws()[static_cast<size_t>(e.where)].pocket));
        break;
      case physics::EventKind::kPocket:
        out->set_pocket(physics::ToString(table.pockets()[static_cast<size_t>(e.where)].id));
        break;
      default: break;
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
  }
  if (request.options().include_paths()) {
    constexpr double kMaxPointsPerPath = 20000;  // bounds the response size
    const double asked =
        request.options().has_path_sample_s() ? request.options().path_sample_s() : 0.02;
    const double dt = std::max(asked, sim.end_time() / kMaxPointsPerPath);
    for (int i = 0; i < state.balls_size(); ++i) {
      v1::BallPath* path = response->add_paths();
      path->set_id(id(i));
      auto add = [&](double t) {
        path->add_t(t);
        ToProto(sim.PositionAt(i, t), path->add_points());
      };
      const auto knots = sim.path(i);
      const double end = sim.pocket_of(i) >= 0 ? knots.back().t : sim.end_time();
      for (size_t k = 0; k < knots.size(); ++k) {  // every knot, samples in between
        const double t1 = k + 1 < knots.size() ? knots[k + 1].t : end;
        for (double t = knots[k].t; t < t1; t += dt) add(t);
      }
      add(end);
    }
  }
  return ApiStatus::Ok();
}

}  // namespace snooker::server
