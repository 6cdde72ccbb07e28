#include "physics/model/model.h"

#include <cmath>
#include <sstream>

namespace snooker::physics {
namespace {

void Add(std::ostringstream& out, const char* group, const std::string& message) {
  if (message.empty()) return;
  // Each message is "name = value (rule)[; name = value (rule)]": prefix every name.
  std::size_t start = 0;
  while (start < message.size()) {
    std::size_t end = message.find("; ", start);
    if (end == std::string::npos) end = message.size();
    if (out.tellp() > 0) out << "; ";
    out << group << '.' << message.substr(start, end - start);
    start = end + 2;
  }
}

bool Finite(double x) { return std::isfinite(x); }

std::string ValidateCue(const CueParams& c) {
  std::ostringstream out;
  auto check = [&](bool ok, const char* name, double v, const char* rule) {
    if (ok) return;
    if (out.tellp() > 0) out << "; ";
    out << name << " = " << v << " (must be " << rule << ")";
  };
  check(Finite(c.mass) && c.mass > 0 && c.mass <= 10, "mass", c.mass, "in (0, 10] kg");
  check(Finite(c.tip_radius) && c.tip_radius > 0 && c.tip_radius <= 0.1, "tip_radius", c.tip_radius,
        "in (0, 0.1] m");
  check(Finite(c.tip_restitution) && c.tip_restitution >= 0 && c.tip_restitution <= 1, "tip_restitution",
        c.tip_restitution, "in [0, 1]");
  check(Finite(c.tip_friction) && c.tip_friction > 0 && c.tip_friction <= 2, "tip_friction", c.tip_friction,
        "in (0, 2]");
  check(Finite(c.end_mass) && c.end_mass > 0 && c.end_mass <= 1, "end_mass", c.end_mass, "in (0, 1] kg");
  check(Finite(c.bed_restitution) && c.bed_restitution >= 0 && c.bed_restitution <= 1, "bed_restitution",
        c.bed_restitution, "in [0, 1]");
  check(Finite(c.max_hop) && c.max_hop >= 0 && c.max_hop <= 0.1, "max_hop", c.max_hop, "in [0, 0.1] m");
  return out.str();
}

bool Same(const RestitutionCurve& a, const RestitutionCurve& b) {
  if (a.points != b.points) return false;
  for (int i = 0; i < a.points && i < RestitutionCurve::kMaxPoints; ++i) {
    if (a.speed[i] != b.speed[i] || a.e[i] != b.e[i]) return false;
  }
  return true;
}

}  // namespace

SimParams Model::Apply(SimParams base) const {
  base.ball = ball;
  base.cloth = cloth;
  base.ball_ball = ball_ball;
  base.cushion = cushion;
  return base;
}

Model ModelOf(const SimParams& sim, const CueParams& cue) {
  Model m;
  m.ball = sim.ball;
  m.cloth = sim.cloth;
  m.ball_ball = sim.ball_ball;
  m.cushion = sim.cushion;
  m.cue = cue;
  return m;
}

bool SameModel(const Model& a, const Model& b) {
  const BallBallParams &p = a.ball_ball, &q = b.ball_ball;
  const CushionParams &c = a.cushion, &d = b.cushion;
  const CueParams &u = a.cue, &w = b.cue;
  return a.ball.mass == b.ball.mass && a.ball.radius == b.ball.radius &&
         a.cloth.mu_s == b.cloth.mu_s && a.cloth.mu_r == b.cloth.mu_r &&
         a.cloth.spin_decel == b.cloth.spin_decel && a.cloth.g == b.cloth.g && p.mu_bb == q.mu_bb &&
         p.e == q.e && p.friction_law == q.friction_law && p.slip_gain == q.slip_gain &&
         p.slip_decay == q.slip_decay && c.e_e == d.e_e && Same(c.restitution_curve, d.restitution_curve) &&
         c.mu_w == d.mu_w && c.mu_s == d.mu_s && c.contact_height == d.contact_height && u.mass == w.mass &&
         u.tip_radius == w.tip_radius && u.tip_restitution == w.tip_restitution &&
         u.tip_friction == w.tip_friction && u.end_mass == w.end_mass &&
         u.bed_restitution == w.bed_restitution && u.max_hop == w.max_hop;
}

std::string ValidateModel(const Model& m) {
  std::ostringstream out;
  Add(out, "ball", ValidateBallParams(m.ball));
  Add(out, "cloth", ValidateClothParams(m.cloth));
  Add(out, "ball_ball", ValidateBallBallParams(m.ball_ball));
  Add(out, "cushion", ValidateCushionParams(m.ball, m.cushion));
  Add(out, "cue", ValidateCue(m.cue));
  return out.str();
}

}  // namespace snooker::physics
