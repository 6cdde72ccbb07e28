#include "server/plan_convert.h"

#include <cmath>
#include <algorithm>
#include <sstream>

#include "physics/core/limits.h"

namespace snooker::server {
namespace {

std::string Num(double x) { return FormatNumber(x); }

// Adds an error when an optional double field is set and outside [lo, hi].
template <typename Msg, typename Has, typename Get>
void CheckRange(std::vector<FieldError>* errors, const Msg& m, Has has, Get get, const char* field,
                double lo, double hi, const char* unit) {
  if (!(m.*has)()) return;
  const double x = (m.*get)();
  if (std::isfinite(x) && x >= lo && x <= hi) return;
  errors->push_back({field, Num(x), "must be a number in [" + Num(lo) + ", " + Num(hi) + "]" + unit});
}

}  // namespace

planner::BallKind BallKindFrom(v1::BallKind kind) {
  switch (kind) {
    case v1::CUE: return planner::BallKind::kCue;
    case v1::YELLOW: return planner::BallKind::kYellow;
    case v1::GREEN: return planner::BallKind::kGreen;
    case v1::BROWN: return planner::BallKind::kBrown;
    case v1::BLUE: return planner::BallKind::kBlue;
    case v1::PINK: return planner::BallKind::kPink;
    case v1::BLACK: return planner::BallKind::kBlack;
    default: return planner::BallKind::kRed;
  }
}

v1::BallKind ToProto(planner::BallKind kind) {
  switch (kind) {
    case planner::BallKind::kCue: return v1::CUE;
    case planner::BallKind::kRed: return v1::RED;
    case planner::BallKind::kYellow: return v1::YELLOW;
    case planner::BallKind::kGreen: return v1::GREEN;
    case planner::BallKind::kBrown: return v1::BROWN;
    case planner::BallKind::kBlue: return v1::BLUE;
    case planner::BallKind::kPink: return v1::PINK;
    case planner::BallKind::kBlack: return v1::BLACK;
  }
  return v1::BALL_KIND_UNSPECIFIED;
}

std::optional<planner::BallOn> BallOnFrom(v1::BallOn on) {
  switch (on) {
    case v1::BALL_ON_RED: return planner::BallOn::kRed;
    case v1::BALL_ON_COLOUR: return planner::BallOn::kAnyColour;
    case v1::BALL_ON_YELLOW: return planner::BallOn::kYellow;
    case v1::BALL_ON_GREEN: return planner::BallOn::kGreen;
    case v1::BALL_ON_BROWN: return planner::BallOn::kBrown;
    case v1::BALL_ON_BLUE: return planner::BallOn::kBlue;
    case v1::BALL_ON_PINK: return planner::BallOn::kPink;
    case v1::BALL_ON_BLACK: return planner::BallOn::kBlack;
    default: return std::nullopt;
  }
}

std::vector<FieldError> ValidatePlanRequest(const v1::PlanRequest& r, const physics::TableModel& table) {
  return CheckPlanRequest(r, table, PlanBounds{}).errors;
}

PlanCheck CheckPlanRequest(const v1::PlanRequest& r, const physics::TableModel& table,
                           const PlanBounds& bounds) {
  PlanCheck result;
  // The table as Simulate checks it (ids, kinds, one cue ball, placement), with the
  // same vision repair. A bad tolerance is reported alone: the table is then
  // checked with the server's.
  std::vector<FieldError> tolerance_errors;
  const std::optional<double> tolerance = VisionTolerance(
      r.has_vision_tolerance_mm() ? std::optional<double>(r.vision_tolerance_mm()) : std::nullopt,
      bounds.vision_tolerance_mm, "vision_tolerance_mm", &tolerance_errors);
  TableCheck check = CheckTable(r.table(), table, tolerance.value_or(bounds.vision_tolerance_mm * 1e-3));
  std::vector<FieldError>& errors = result.errors;
  errors = std::move(check.errors);
  errors.insert(errors.end(), tolerance_errors.begin(), tolerance_errors.end());
  result.repaired = std::move(check.repaired);
  result.warnings = std::move(check.warnings);
  const v1::TableState& t = r.table();
  int reds = 0, colours[9] = {};
  for (const v1::Ball& b : t.balls()) {
    if (b.kind() == v1::RED) ++reds;
    if (b.kind() >= v1::YELLOW && b.kind() <= v1::BLACK) ++colours[b.kind()];
  }
  if (reds > physics::kRedCount) {
    errors.push_back({"table.balls", std::to_string(reds) + " RED balls", "at most 15"});
  }
  for (int k = v1::YELLOW; k <= v1::BLACK; ++k) {
    if (colours[k] > 1) {
      errors.push_back({"table.balls", std::to_string(colours[k]) + " " +
                                           v1::BallKind_Name(static_cast<v1::BallKind>(k)) + " balls",
                        "at most one of each colour"});
    }
  }
  if (!v1::BallOn_IsValid(r.ball_on())) {
    errors.push_back({"ball_on", std::to_string(r.ball_on()), "must be a BallOn value"});
  } else if (const auto on = BallOnFrom(r.ball_on())) {
    bool present = false;
    for (const v1::Ball& b : t.balls()) {
      if (b.kind() != v1::BALL_KIND_UNSPECIFIED && v1::BallKind_IsValid(b.kind())) {
        present = present || planner::IsLegalTarget(*on, BallKindFrom(b.kind()));
      }
    }
    if (!present) {
      errors.push_back({"ball_on", v1::BallOn_Name(r.ball_on()), "no such ball on the table"});
    }
  }
  using L = v1::RobotLimits;
  const L& l = r.limits();
  const double hi = physics::limits::kShotSpeed.hi;
  CheckRange(&errors, l, &L::has_min_speed, &L::min_speed, "limits.min_speed", 0, hi, " m/s");
  CheckRange(&errors, l, &L::has_max_speed, &L::max_speed, "limits.max_speed", 0.05, hi, " m/s");
  const planner::RobotLimits defaults;
  const double lo_speed = l.has_min_speed() ? l.min_speed() : defaults.min_speed;
  const double hi_speed = l.has_max_speed() ? l.max_speed() : defaults.max_speed;
  if (std::isfinite(lo_speed) && std::isfinite(hi_speed) && !(hi_speed > lo_speed)) {
    errors.push_back({"limits.max_speed", Num(hi_speed), "must exceed limits.min_speed (" + Num(lo_speed) + ")"});
  }
  CheckRange(&errors, l, &L::has_max_topspin_fraction, &L::max_topspin_fraction,
             "limits.max_topspin_fraction", 0, 3, " of the rolling spin");
  CheckRange(&errors, l, &L::has_max_sidespin_fraction, &L::max_sidespin_fraction,
             "limits.max_sidespin_fraction", 0, 3, " of the rolling spin");
  CheckRange(&errors, l, &L::has_cue_clearance_m, &L::cue_clearance_m, "limits.cue_clearance_m", 0, 2, " m");
  CheckRange(&errors, l, &L::has_cue_radius_m, &L::cue_radius_m, "limits.cue_radius_m", 0, 0.05, " m");
  using N = v1::NoiseModel;
  const N& n = r.noise();
  CheckRange(&errors, n, &N::has_heading_sigma_deg, &N::heading_sigma_deg, "noise.heading_sigma_deg", 0, 10, " deg");
  CheckRange(&errors, n, &N::has_speed_sigma_fraction, &N::speed_sigma_fraction, "noise.speed_sigma_fraction", 0, 0.5, "");
  CheckRange(&errors, n, &N::has_topspin_sigma, &N::topspin_sigma, "noise.topspin_sigma", 0, 100, " rad/s");
  CheckRange(&errors, n, &N::has_sidespin_sigma, &N::sidespin_sigma, "noise.sidespin_sigma", 0, 100, " rad/s");
  CheckRange(&errors, n, &N::has_position_sigma_mm, &N::position_sigma_mm, "noise.position_sigma_mm", 0, 50, " mm");
  for (const auto& [id, sigma] : n.ball_position_sigma_mm()) {
    bool known = false;
    for (const v1::Ball& b : t.balls()) known = known || b.id() == id;
    const std::string field = "noise.ball_position_sigma_mm[\"" + id + "\"]";
    if (!known) errors.push_back({field, Num(sigma), "names no ball of the table"});
    if (!(std::isfinite(sigma) && sigma >= 0 && sigma <= 50)) {
      errors.push_back({field, Num(sigma), "must be a number in [0, 50] mm"});
    }
  }
  if (r.has_time_budget_ms()) {
    const double budget = r.time_budget_ms();
    const double most = std::min(bounds.max_budget_ms, kMaxPlanBudgetMs);
    if (!(std::isfinite(budget) && budget >= 1 && budget <= most)) {
      errors.push_back({"time_budget_ms", Num(budget),
                        "must be in [1, " + Num(most) + "] ms: " + Num(most) +
                            " ms is the server's largest budget (--max-budget-ms)"});
    }
  }
  if (r.has_max_shots() && (r.max_shots() < 1 || r.max_shots() > 20)) {
    errors.push_back({"max_shots", std::to_string(r.max_shots()), "must be in [1, 20]"});
  }
  if (r.has_max_simulations() && (r.max_simulations() < 0 || r.max_simulations() > 100'000'000)) {
    errors.push_back({"max_simulations", std::to_string(r.max_simulations()), "must be in [0, 100000000]"});
  }
  if (r.has_monte_carlo_samples() && (r.monte_carlo_samples() < 0 || r.monte_carlo_samples() > 100'000)) {
    errors.push_back({"monte_carlo_samples", std::to_string(r.monte_carlo_samples()), "must be in [0, 100000]"});
  }
  return result;
}

planner::PlanRequest PlanRequestFrom(const v1::PlanRequest& r, std::optional<double> default_budget_ms) {
  planner::PlanRequest p;
  for (const v1::Ball& b : r.table().balls()) {
    p.table.balls.push_back({BallKindFrom(b.kind()), physics::Vec2(b.position().x(), b.position().y())});
  }
  p.ball_on = BallOnFrom(r.ball_on());
  const v1::RobotLimits& l = r.limits();
  if (l.has_min_speed()) p.limits.min_speed = l.min_speed();
  if (l.has_max_speed()) p.limits.max_speed = l.max_speed();
  if (l.has_max_topspin_fraction()) p.limits.max_topspin_fraction = l.max_topspin_fraction();
  if (l.has_max_sidespin_fraction()) p.limits.max_sidespin_fraction = l.max_sidespin_fraction();
  if (l.has_cue_clearance_m()) p.limits.cue.length = l.cue_clearance_m();
  if (l.has_cue_radius_m()) p.limits.cue.radius = l.cue_radius_m();
  const v1::NoiseModel& n = r.noise();
  if (n.has_heading_sigma_deg()) p.noise.heading = physics::DegToRad(n.heading_sigma_deg());
  if (n.has_speed_sigma_fraction()) p.noise.speed_fraction = n.speed_sigma_fraction();
  if (n.has_topspin_sigma()) p.noise.topspin = n.topspin_sigma();
  if (n.has_sidespin_sigma()) p.noise.sidespin = n.sidespin_sigma();
  if (n.has_position_sigma_mm()) p.noise.position = n.position_sigma_mm() * 1e-3;
  if (!n.ball_position_sigma_mm().empty()) {
    for (const v1::Ball& b : r.table().balls()) {
      const auto it = n.ball_position_sigma_mm().find(b.id());
      p.position_sigma.push_back(it == n.ball_position_sigma_mm().end() ? p.noise.position
                                                                        : it->second * 1e-3);
    }
  }
  if (r.has_time_budget_ms()) {
    p.time_budget = r.time_budget_ms() * 1e-3;
  } else if (default_budget_ms) {
    p.time_budget = *default_budget_ms * 1e-3;
  }
  if (r.has_max_shots()) p.max_shots = r.max_shots();
  if (r.has_seed()) p.seed = r.seed();
  if (r.has_position_play()) p.position_play = r.position_play();
  if (r.has_max_simulations()) p.max_simulations = r.max_simulations();
  if (r.has_monte_carlo_samples()) p.monte_carlo_samples = r.monte_carlo_samples();
  return p;
}

void ToProto(const planner::PlannedShot& s, const v1::TableState& table,
             const physics::TableModel& model, v1::PlannedShot* out) {
  auto id = [&](int i) -> const std::string& { return table.balls(i).id(); };
  out->set_speed(s.shot.speed);
  out->set_heading_deg(physics::RadToDeg(s.shot.heading));
  out->set_topspin(s.shot.topspin);
  out->set_sidespin(s.shot.sidespin);
  out->set_cut_deg(physics::RadToDeg(s.cut));
  out->set_object_ball(id(s.object_ball));
  out->set_pocket(physics::ToString(s.pocket));
  out->set_pot_probability(s.pot_probability);
  out->set_position_value(s.position_value);
  if (s.next_ball >= 0) out->set_next_ball(id(s.next_ball));
  ToProto(s.cue_ball_end, out->mutable_cue_ball_end());
  for (const physics::SimEvent& e : s.events) ToProto(e, table, model, out->add_events());
}

void ToProto(const planner::PlanAnswer& a, const v1::TableState& table,
             const physics::TableModel& model, v1::PlanResponse* out) {
  for (const planner::PlannedShot& s : a.shots) ToProto(s, table, model, out->add_shots());
  out->set_reason(a.reason);
  out->set_simulations(static_cast<std::int32_t>(std::min<std::int64_t>(a.simulations, INT32_MAX)));
  out->set_evaluations(static_cast<std::int32_t>(std::min<std::int64_t>(a.evaluations, INT32_MAX)));
  out->set_elapsed_ms(a.elapsed * 1e3);
}

}  // namespace snooker::server
