#include "server/model_convert.h"

#include <cstddef>
#include <string>

namespace snooker::server {
namespace {

template <typename Msg, typename Has, typename Get>
void Take(const Msg& m, Has has, Get get, double* out) {
  if ((m.*has)()) *out = (m.*get)();
}

std::string CushionFrom(const v1::CushionParameters& c, physics::CushionParams* out) {
  using C = v1::CushionParameters;
  Take(c, &C::has_mu_w, &C::mu_w, &out->mu_w);
  Take(c, &C::has_mu_s, &C::mu_s, &out->mu_s);
  Take(c, &C::has_constant_restitution, &C::constant_restitution, &out->e_e);
  if (c.has_no_restitution_curve() && c.no_restitution_curve()) {
    if (c.restitution_size() > 0 || c.restitution_speed_size() > 0) {
      return "cushion.no_restitution_curve = true with a restitution curve given (must be one or the other)";
    }
    out->restitution_curve = physics::RestitutionCurve{};
    return "";
  }
  if (c.restitution_size() == 0 && c.restitution_speed_size() == 0) return "";
  if (c.restitution_size() != c.restitution_speed_size() ||
      c.restitution_size() > physics::RestitutionCurve::kMaxPoints) {
    return "cushion.restitution has " + std::to_string(c.restitution_size()) +
           " values and cushion.restitution_speed " + std::to_string(c.restitution_speed_size()) +
           " (must be as many, at most " + std::to_string(physics::RestitutionCurve::kMaxPoints) + ")";
  }
  physics::RestitutionCurve curve;
  curve.points = c.restitution_size();
  for (int i = 0; i < curve.points; ++i) {
    curve.speed[static_cast<std::size_t>(i)] = c.restitution_speed(i);
    curve.e[static_cast<std::size_t>(i)] = c.restitution(i);
  }
  out->restitution_curve = curve;
  return "";
}

}  // namespace

std::optional<physics::BallBallFrictionLaw> FrictionLawFromProto(int law) {
  switch (law) {
    case v1::BALL_BALL_FRICTION_LAW_CONSTANT: return physics::BallBallFrictionLaw::kConstant;
    case v1::BALL_BALL_FRICTION_LAW_MARLOW: return physics::BallBallFrictionLaw::kMarlow;
    case v1::BALL_BALL_FRICTION_LAW_EXPONENTIAL: return physics::BallBallFrictionLaw::kExponential;
    case v1::BALL_BALL_FRICTION_LAW_EXPONENTIAL_IMPACT_SPEED: return physics::BallBallFrictionLaw::kExponentialImpactSpeed;
    default: return std::nullopt;
  }
}

const char* FrictionLawName(physics::BallBallFrictionLaw law) {
  switch (law) {
    case physics::BallBallFrictionLaw::kMarlow: return "marlow";
    case physics::BallBallFrictionLaw::kExponential: return "exponential";
    case physics::BallBallFrictionLaw::kExponentialImpactSpeed: return "exponential-impact-speed";
    case physics::BallBallFrictionLaw::kConstant: break;
  }
  return "constant";
}

std::string ModelFromProto(const v1::PhysicsModel& f, physics::Model* m) {
  using B = v1::BallParameters;
  Take(f.ball(), &B::has_mass_kg, &B::mass_kg, &m->ball.mass);
  Take(f.ball(), &B::has_radius_m, &B::radius_m, &m->ball.radius);
  using L = v1::ClothParameters;
  Take(f.cloth(), &L::has_mu_s, &L::mu_s, &m->cloth.mu_s);
  Take(f.cloth(), &L::has_mu_r, &L::mu_r, &m->cloth.mu_r);
  Take(f.cloth(), &L::has_spin_decel, &L::spin_decel, &m->cloth.spin_decel);
  Take(f.cloth(), &L::has_gravity, &L::gravity, &m->cloth.g);
  using P = v1::BallBallParameters;
  const P& bb = f.ball_ball();
  if (const auto law = FrictionLawFromProto(bb.friction_law())) {
    m->ball_ball.friction_law = *law;
  } else if (bb.friction_law() != v1::BALL_BALL_FRICTION_LAW_UNSPECIFIED) {
    return "ball_ball.friction_law = " + std::to_string(bb.friction_law()) +
           " (must be CONSTANT, MARLOW, EXPONENTIAL or EXPONENTIAL_IMPACT_SPEED)";
  }
  Take(bb, &P::has_mu_bb, &P::mu_bb, &m->ball_ball.mu_bb);
  Take(bb, &P::has_slip_gain, &P::slip_gain, &m->ball_ball.slip_gain);
  Take(bb, &P::has_slip_decay, &P::slip_decay, &m->ball_ball.slip_decay);
  Take(bb, &P::has_restitution, &P::restitution, &m->ball_ball.e);
  if (std::string e = CushionFrom(f.cushion(), &m->cushion); !e.empty()) return e;
  using Q = v1::CueParameters;
  const Q& q = f.cue();
  Take(q, &Q::has_mass_kg, &Q::mass_kg, &m->cue.mass);
  Take(q, &Q::has_tip_radius_m, &Q::tip_radius_m, &m->cue.tip_radius);
  Take(q, &Q::has_tip_restitution, &Q::tip_restitution, &m->cue.tip_restitution);
  Take(q, &Q::has_tip_friction, &Q::tip_friction, &m->cue.tip_friction);
  Take(q, &Q::has_end_mass_kg, &Q::end_mass_kg, &m->cue.end_mass);
  Take(q, &Q::has_bed_restitution, &Q::bed_restitution, &m->cue.bed_restitution);
  Take(q, &Q::has_max_hop_m, &Q::max_hop_m, &m->cue.max_hop);
  return physics::ValidateModel(*m);
}

void ModelToProto(const physics::Model& m, v1::PhysicsModel* out) {
  out->Clear();
  out->mutable_ball()->set_mass_kg(m.ball.mass);
  out->mutable_ball()->set_radius_m(m.ball.radius);
  v1::ClothParameters* cloth = out->mutable_cloth();
  cloth->set_mu_s(m.cloth.mu_s);
  cloth->set_mu_r(m.cloth.mu_r);
  cloth->set_spin_decel(m.cloth.spin_decel);
  cloth->set_gravity(m.cloth.g);
  v1::BallBallParameters* bb = out->mutable_ball_ball();
  switch (m.ball_ball.friction_law) {
    case physics::BallBallFrictionLaw::kMarlow: bb->set_friction_law(v1::BALL_BALL_FRICTION_LAW_MARLOW); break;
    case physics::BallBallFrictionLaw::kExponential:
      bb->set_friction_law(v1::BALL_BALL_FRICTION_LAW_EXPONENTIAL);
      break;
    case physics::BallBallFrictionLaw::kExponentialImpactSpeed:
      bb->set_friction_law(v1::BALL_BALL_FRICTION_LAW_EXPONENTIAL_IMPACT_SPEED);
      break;
    case physics::BallBallFrictionLaw::kConstant: bb->set_friction_law(v1::BALL_BALL_FRICTION_LAW_CONSTANT); break;
  }
  bb->set_mu_bb(m.ball_ball.mu_bb);
  bb->set_slip_gain(m.ball_ball.slip_gain);
  bb->set_slip_decay(m.ball_ball.slip_decay);
  bb->set_restitution(m.ball_ball.e);
  v1::CushionParameters* c = out->mutable_cushion();
  c->set_mu_w(m.cushion.mu_w);
  c->set_mu_s(m.cushion.mu_s);
  c->set_constant_restitution(m.cushion.e_e);
  const physics::RestitutionCurve& curve = m.cushion.restitution_curve;
  if (curve.points <= 0) c->set_no_restitution_curve(true);
  for (int i = 0; i < curve.points && i < physics::RestitutionCurve::kMaxPoints; ++i) {
    c->add_restitution_speed(curve.speed[static_cast<std::size_t>(i)]);
    c->add_restitution(curve.e[static_cast<std::size_t>(i)]);
  }
  v1::CueParameters* q = out->mutable_cue();
  q->set_mass_kg(m.cue.mass);
  q->set_tip_radius_m(m.cue.tip_radius);
  q->set_tip_restitution(m.cue.tip_restitution);
  q->set_tip_friction(m.cue.tip_friction);
  q->set_end_mass_kg(m.cue.end_mass);
  q->set_bed_restitution(m.cue.bed_restitution);
  q->set_max_hop_m(m.cue.max_hop);
}

}  // namespace snooker::server
