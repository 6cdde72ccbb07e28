#include "server/api.h"

#include <cmath>

#include "physics/ball_ball.h"
#include "physics/slip_phase.h"
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

}  // namespace snooker::server
