#include "server/plan_convert.h"

#include <google/protobuf/descriptor.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "planner/validate.h"

namespace snooker::server {
namespace {

// A planner field's API name, and the factor from its SI unit to the API's unit.
struct ApiField {
  const char* planner;
  const char* api;
  double scale;
  const char* unit;
};

constexpr ApiField kApiFields[] = {
    {"limits.min_speed", "limits.min_speed", 1, "m/s"},
    {"limits.max_speed", "limits.max_speed", 1, "m/s"},
    {"limits.max_topspin_fraction", "limits.max_topspin_fraction", 1, "of the rolling spin"},
    {"limits.max_sidespin_fraction", "limits.max_sidespin_fraction", 1, "of the rolling spin"},
    {"limits.cue.length", "limits.cue_clearance_m", 1, "m"},
    {"limits.cue.radius", "limits.cue_radius_m", 1, "m"},
    {"limits.cue.max_elevation", "limits.max_elevation_deg", 180 / physics::kPi, "deg"},
    {"limits.min_cue_speed", "limits.min_cue_speed", 1, "m/s"},
    {"limits.max_cue_speed", "limits.max_cue_speed", 1, "m/s"},
    {"noise.aim", "noise.aim_sigma_deg", 180 / physics::kPi, "deg"},
    {"noise.cue_speed_fraction", "noise.cue_speed_sigma_fraction", 1, ""},
    {"noise.tip_offset", "noise.tip_offset_sigma_mm", 1e3, "mm"},
    {"noise.elevation", "noise.elevation_sigma_deg", 180 / physics::kPi, "deg"},
    {"noise.squirt_fraction", "noise.squirt_sigma_fraction", 1, ""},
    {"noise.throw_fraction", "noise.throw_sigma_fraction", 1, ""},
    {"noise.heading", "noise.heading_sigma_deg", 180 / physics::kPi, "deg"},
    {"noise.speed_fraction", "noise.speed_sigma_fraction", 1, ""},
    {"noise.topspin", "noise.topspin_sigma", 1, "rad/s"},
    {"noise.sidespin", "noise.sidespin_sigma", 1, "rad/s"},
    {"noise.position", "noise.position_sigma_mm", 1e3, "mm"},
    {"position_sigma", "noise.ball_position_sigma_mm", 1e3, "mm"},
    {"time_budget", "time_budget_ms", 1e3, "ms"},
    {"max_shots", "max_shots", 1, ""},
    {"max_simulations", "max_simulations", 1, ""},
    {"monte_carlo_samples", "monte_carlo_samples", 1, ""},
    {"break_value", "break_value", 1, "points"},
    {"position_spread", "position_spread", 1, ""},
    {"table.balls", "table.balls", 1, ""},
    {"ball_on", "ball_on", 1, ""},
};

// x in the API's unit, without the last bits a unit conversion leaves (0.05 deg,
// not 0.050000000000000003).
std::string Converted(double x) {
  if (!std::isfinite(x)) return FormatNumber(x);
  char text[32];
  if (x == std::trunc(x) && std::abs(x) < 1e15) {  // a count, or a whole number of units: 100000, not 1e+05
    std::snprintf(text, sizeof text, "%.0f", x);
    return text;
  }
  std::snprintf(text, sizeof text, "%.12g", x);
  return FormatNumber(std::strtod(text, nullptr));
}

const ApiField* ApiFieldOf(const std::string& planner_field) {
  for (const ApiField& f : kApiFields) {
    if (planner_field == f.planner) return &f;
  }
  return nullptr;
}

// One planner error in the API's terms: its field name, the table's ids and the API's
// units. nullopt when the API has reported the field already in its own terms (a
// per-ball sigma that is the request's default, a budget over the server's bound).
std::optional<FieldError> ToApiError(const planner::FieldError& e, const v1::PlanRequest& r) {
  const ApiField* f = ApiFieldOf(e.field);
  if (f == nullptr) {
    // A field the API does not have (threads): the server set it, so it is a bug.
    return FieldError{e.field, e.value ? Converted(*e.value) : e.value_text,
                      "the server set an invalid value: " + e.rule};
  }
  FieldError out{f->api, e.value ? Converted(*e.value * f->scale) : e.value_text, e.rule};
  if (e.ball >= 0 && e.ball < r.table().balls_size()) {
    const v1::Ball& b = r.table().balls(e.ball);
    if (e.field == "position_sigma") {
      if (!r.noise().ball_position_sigma_mm().contains(b.id())) return std::nullopt;
      out.field += "[\"" + b.id() + "\"]";
    } else {
      out.field += "[" + std::to_string(e.ball) + "]";
      out.value = "(" + FormatNumber(b.position().x()) + ", " + FormatNumber(b.position().y()) +
                  ") (ball " + QuoteId(b.id()) + ")";
    }
  }
  if (e.field == "ball_on") out.value = v1::BallOn_Name(r.ball_on());
  if (e.range) {
    out.rule = "must be in [" + Converted(e.range->lo * f->scale) + ", " + Converted(e.range->hi * f->scale) +
               "]" + (f->unit[0] != '\0' ? std::string(" ") + f->unit : std::string());
  }
  return out;
}

// An enum field's value as its name, or as the number when it names no value.
std::string EnumText(const google::protobuf::EnumDescriptor* type, int value) {
  const google::protobuf::EnumValueDescriptor* v = type->FindValueByNumber(value);
  return v != nullptr ? std::string(v->name()) : std::to_string(value);
}

// The planner's value of E (kCount of them) whose API value is `value` (ToProto's
// inverse); nullopt for *_UNSPECIFIED or a number that names no value.
template <typename E, int kCount>
std::optional<E> FromApi(int value) {
  for (int k = 0; k < kCount; ++k) {
    if (static_cast<int>(ToProto(static_cast<E>(k))) == value) return static_cast<E>(k);
  }
  return std::nullopt;
}

// An error for each entry of a repeated enum field (kinds, routes) that names no
// planner value: "kinds[1] = SHOT_KIND_UNSPECIFIED (must be POT, ... or FOUL)".
template <typename E, int kCount>
void CheckEnumList(const std::string& field, const google::protobuf::RepeatedField<int>& values,
                   const google::protobuf::EnumDescriptor* type, std::vector<FieldError>* errors) {
  std::string rule = "must be ";
  for (int k = 0; k < kCount; ++k) {
    rule += std::string(k == 0 ? "" : k + 1 == kCount ? " or " : ", ") + planner::ToString(static_cast<E>(k));
  }
  for (int i = 0; i < values.size(); ++i) {
    if (!FromApi<E, kCount>(values[i])) {
      errors->push_back({field + "[" + std::to_string(i) + "]", EnumText(type, values[i]), rule});
    }
  }
}

// A repeated enum field as the planner's set: empty is every value.
template <typename E, int kCount>
planner::EnumSet<E, kCount> SetFromApi(const google::protobuf::RepeatedField<int>& values) {
  if (values.empty()) return {};
  auto set = planner::EnumSet<E, kCount>::None();
  for (const int v : values) {
    if (const auto e = FromApi<E, kCount>(v)) set = set.With(*e);
  }
  return set;
}

// What only the API has: its enum values, the ids of the per-ball sigmas, and the
// server's largest budget (--max-budget-ms, within the planner's range).
void CheckApiFields(const v1::PlanRequest& r, const PlanBounds& bounds, std::vector<FieldError>* errors) {
  if (!v1::BallOn_IsValid(r.ball_on())) {
    errors->push_back({"ball_on", std::to_string(r.ball_on()), "must be a BallOn value"});
  }
  for (const auto& [id, sigma] : r.noise().ball_position_sigma_mm()) {
    bool known = false;
    for (const v1::Ball& b : r.table().balls()) known = known || b.id() == id;
    if (!known) {
      errors->push_back({"noise.ball_position_sigma_mm[" + QuoteId(id) + "]", FormatNumber(sigma),
                         "names no ball of the table"});
    }
  }
  CheckEnumList<planner::ShotKind, planner::kShotKindCount>("kinds", r.kinds(), v1::ShotKind_descriptor(), errors);
  CheckEnumList<planner::PotRoute, planner::kPotRouteCount>("routes", r.routes(), v1::PotRoute_descriptor(), errors);
  if (r.cue_in_hand()) {
    // The answer names the placed cue ball "cue": no ball of the table may.
    for (int i = 0; i < r.table().balls_size(); ++i) {
      const v1::Ball& b = r.table().balls(i);
      if (b.id() != kPlacedCueId) continue;
      errors->push_back({"table.balls[" + std::to_string(i) + "].id",
                         QuoteId(b.id()) + " (a " + v1::BallKind_Name(b.kind()) + " ball)",
                         "is taken with cue_in_hand: the answer names the cue ball placed from hand \"" +
                             std::string(kPlacedCueId) + "\""});
    }
  }
  if (r.has_time_budget_ms()) {
    const physics::Range allowed{limits::kPlanBudgetMs.lo, bounds.max_budget_ms};
    if (!allowed.Contains(r.time_budget_ms())) {
      errors->push_back({"time_budget_ms", FormatNumber(r.time_budget_ms()),
                         "must be in [" + FormatNumber(allowed.lo) + ", " + FormatNumber(allowed.hi) +
                             "] ms: " + FormatNumber(allowed.hi) +
                             " ms is the server's largest budget (--max-budget-ms)"});
    }
  }
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
  // same vision repair; with the cue ball in hand, no cue ball. A bad tolerance is
  // reported alone: the table is then checked with the server's.
  std::vector<FieldError> tolerance_errors;
  const std::optional<double> tolerance = VisionTolerance(
      r.has_vision_tolerance_mm() ? std::optional<double>(r.vision_tolerance_mm()) : std::nullopt,
      bounds.vision_tolerance_mm, "vision_tolerance_mm", &tolerance_errors);
  TableCheck check = CheckTable(r.table(), table, tolerance.value_or(bounds.vision_tolerance_mm * 1e-3),
                                r.cue_in_hand() ? CueBall::kInHand : CueBall::kOnTableUnlessInHand);
  std::vector<FieldError>& errors = result.errors;
  errors = std::move(check.errors);
  const bool table_ok = errors.empty();
  errors.insert(errors.end(), tolerance_errors.begin(), tolerance_errors.end());
  result.repaired = std::move(check.repaired);
  result.warnings = std::move(check.warnings);
  CheckApiFields(r, bounds, &errors);
  // The planner's own rules (snooker's counts, the ball on, every range), renamed.
  // Its table checks only once the table is one: a bad table has been reported.
  const v1::PlanRequest* checked = &r;
  v1::PlanRequest repaired;
  if (result.repaired) {
    repaired = r;
    *repaired.mutable_table() = *result.repaired;
    checked = &repaired;
  }
  const planner::PlanRequest p = PlanRequestFrom(*checked);
  std::vector<planner::FieldError> rules = planner::ValidateSettings(p);
  if (table_ok) {
    std::vector<planner::FieldError> more = planner::ValidateTable(p.table, p.cue_in_hand, p.ball_on, table);
    rules.insert(rules.begin(), more.begin(), more.end());
  }
  const auto api_end = static_cast<std::ptrdiff_t>(errors.size());
  for (const planner::FieldError& e : rules) {
    std::optional<FieldError> api = ToApiError(e, *checked);
    if (!api) continue;
    const bool reported = std::any_of(errors.begin(), errors.begin() + api_end,
                                      [&](const FieldError& x) { return x.field == api->field; });
    if (!reported) errors.push_back(std::move(*api));
  }
  return result;
}

planner::PlanRequest PlanRequestFrom(const v1::PlanRequest& r, std::optional<double> default_budget_ms) {
  planner::PlanRequest p;
  for (const v1::Ball& b : r.table().balls()) {
    p.table.balls.push_back({BallKindFrom(b.kind()), physics::Vec2(b.position().x(), b.position().y())});
  }
  p.cue_in_hand = r.cue_in_hand();
  p.ball_on = BallOnFrom(r.ball_on());
  const v1::RobotLimits& l = r.limits();
  if (l.has_min_speed()) p.limits.min_speed = l.min_speed();
  if (l.has_max_speed()) p.limits.max_speed = l.max_speed();
  if (l.has_max_topspin_fraction()) p.limits.max_topspin_fraction = l.max_topspin_fraction();
  if (l.has_max_sidespin_fraction()) p.limits.max_sidespin_fraction = l.max_sidespin_fraction();
  if (l.has_cue_clearance_m()) p.limits.cue.length = l.cue_clearance_m();
  if (l.has_cue_radius_m()) p.limits.cue.radius = l.cue_radius_m();
  if (l.has_max_elevation_deg()) p.limits.cue.max_elevation = physics::DegToRad(l.max_elevation_deg());
  if (l.has_min_cue_speed()) p.limits.min_cue_speed = l.min_cue_speed();
  if (l.has_max_cue_speed()) p.limits.max_cue_speed = l.max_cue_speed();
  const v1::NoiseModel& n = r.noise();
  if (n.has_heading_sigma_deg()) p.noise.heading = physics::DegToRad(n.heading_sigma_deg());
  if (n.has_speed_sigma_fraction()) p.noise.speed_fraction = n.speed_sigma_fraction();
  if (n.has_topspin_sigma()) p.noise.topspin = n.topspin_sigma();
  if (n.has_sidespin_sigma()) p.noise.sidespin = n.sidespin_sigma();
  if (n.has_position_sigma_mm()) p.noise.position = n.position_sigma_mm() * 1e-3;
  if (n.has_aim_sigma_deg()) p.noise.aim = physics::DegToRad(n.aim_sigma_deg());
  if (n.has_cue_speed_sigma_fraction()) p.noise.cue_speed_fraction = n.cue_speed_sigma_fraction();
  if (n.has_tip_offset_sigma_mm()) p.noise.tip_offset = n.tip_offset_sigma_mm() * 1e-3;
  if (n.has_elevation_sigma_deg()) p.noise.elevation = physics::DegToRad(n.elevation_sigma_deg());
  if (n.has_squirt_sigma_fraction()) p.noise.squirt_fraction = n.squirt_sigma_fraction();
  if (n.has_throw_sigma_fraction()) p.noise.throw_fraction = n.throw_sigma_fraction();
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
  if (r.has_break_value()) p.break_value = r.break_value();
  if (r.has_position_spread()) p.position_spread = r.position_spread();
  p.kinds = SetFromApi<planner::ShotKind, planner::kShotKindCount>(r.kinds());
  p.routes = SetFromApi<planner::PotRoute, planner::kPotRouteCount>(r.routes());
  if (r.has_lookahead()) p.lookahead = r.lookahead();
  if (r.has_thin_break_off()) p.thin_break_off = r.thin_break_off();
  return p;
}

std::optional<planner::ShotKind> ShotKindFrom(v1::ShotKind kind) {
  return FromApi<planner::ShotKind, planner::kShotKindCount>(kind);
}

std::optional<planner::PotRoute> PotRouteFrom(v1::PotRoute route) {
  return FromApi<planner::PotRoute, planner::kPotRouteCount>(route);
}

v1::ShotKind ToProto(planner::ShotKind kind) {
  switch (kind) {
    case planner::ShotKind::kPot: return v1::POT;
    case planner::ShotKind::kSafety: return v1::SAFETY;
    case planner::ShotKind::kEscape: return v1::ESCAPE;
    case planner::ShotKind::kBreakOff: return v1::BREAK_OFF;
    case planner::ShotKind::kFoul: return v1::FOUL;
  }
  return v1::SHOT_KIND_UNSPECIFIED;
}

v1::PotRoute ToProto(planner::PotRoute route) {
  switch (route) {
    case planner::PotRoute::kDirect: return v1::DIRECT;
    case planner::PotRoute::kPlant: return v1::PLANT;
    case planner::PotRoute::kDouble: return v1::DOUBLE;
    case planner::PotRoute::kKick: return v1::KICK;
  }
  return v1::POT_ROUTE_UNSPECIFIED;
}

namespace {

// The balls a shot's indices name: `table`'s, or, when the shot placed the cue ball
// from hand (or names a ball past the table's), `table` with the placed cue ball
// "cue" after its balls (at cue_start), kept in `with_cue`. Every index past the
// table's balls names the placed cue ball.
const v1::TableState& BallsOf(const planner::PlannedShot& s, const v1::TableState& table,
                              v1::TableState* with_cue) {
  int last = std::max({s.object_ball, s.first_ball, s.next_ball, static_cast<int>(s.balls_end.size()) - 1});
  for (const physics::SimEvent& e : s.events) {
    last = std::max({last, static_cast<int>(e.ball), static_cast<int>(e.other)});
  }
  if (!s.cue_start && last < table.balls_size()) return table;
  *with_cue = table;
  do {
    v1::Ball* cue = with_cue->add_balls();
    cue->set_id(kPlacedCueId);
    cue->set_kind(v1::CUE);
    ToProto(s.cue_start.value_or(physics::Vec2::Zero()), cue->mutable_position());
  } while (with_cue->balls_size() <= last);
  return *with_cue;
}

}  // namespace

void ToProto(const planner::PlannedShot& s, const v1::TableState& table,
             const physics::TableModel& model, v1::PlannedShot* out) {
  v1::TableState with_cue;
  const v1::TableState& balls = BallsOf(s, table, &with_cue);
  auto id = [&](int i) -> std::string { return i >= 0 ? balls.balls(i).id() : std::string(); };
  out->set_speed(s.shot.speed);
  out->set_heading_deg(physics::RadToDeg(s.shot.heading));
  out->set_topspin(s.shot.topspin);
  out->set_sidespin(s.shot.sidespin);
  out->set_swerve_spin(s.shot.swerve_spin);
  v1::CueStrike* cue = out->mutable_cue();
  cue->set_speed(s.cue.speed);
  cue->set_heading_deg(physics::RadToDeg(s.cue.heading));
  cue->set_tip_side(s.cue.side);
  cue->set_tip_height(s.cue.height);
  cue->set_elevation_deg(physics::RadToDeg(s.cue.elevation));
  out->set_cut_deg(physics::RadToDeg(s.cut));
  out->set_object_ball(id(s.object_ball));
  const bool pot = s.kind == planner::ShotKind::kPot;
  if (pot) out->set_pocket(physics::ToString(s.pocket));
  out->set_pot_probability(s.pot_probability);
  out->set_pocket_probability(s.pocket_probability);
  out->set_position_value(s.position_value);
  out->set_next_ball(id(s.next_ball));
  ToProto(s.cue_ball_end, out->mutable_cue_ball_end());
  for (const physics::SimEvent& e : s.events) ToProto(e, balls, model, out->add_events());
  out->set_kind(ToProto(s.kind));
  if (pot) out->set_route(ToProto(s.route));
  out->set_first_ball(id(s.first_ball));
  out->set_foul_probability(s.foul_probability);
  out->set_expected_points(s.score);
  out->set_monte_carlo_samples(s.monte_carlo_samples);
  if (s.opponent) {
    v1::OpponentLeave* o = out->mutable_opponent();
    o->set_pot_probability(s.opponent->pot_probability);
    o->set_expected_points(s.opponent->expected_points);
    o->set_snookered(s.opponent->snookered);
    o->set_foul_probability(s.opponent->foul_probability);
    o->set_penalty_points(s.opponent->penalty);
  }
  if (s.monte_carlo_samples > 0) {
    v1::Handovers* h = out->mutable_handovers();
    h->set_runs(s.handovers.runs);
    h->set_snookered_runs(s.handovers.snookered_runs);
    h->set_mean_pot_probability(s.handovers.mean_pot_probability);
    h->set_mean_expected_points(s.handovers.mean_expected_points);
  }
  if (s.cue_start) ToProto(*s.cue_start, out->mutable_cue_ball_start());
  for (std::size_t i = 0; i < s.balls_end.size(); ++i) {
    const planner::BallEnd& end = s.balls_end[i];
    v1::BallEnd* b = out->add_balls_end();
    b->set_ball(id(static_cast<int>(i)));
    ToProto(end.position, b->mutable_position());
    if (end.pocket) b->set_pocket(physics::ToString(*end.pocket));
  }
}

void ToProto(const planner::PlanAnswer& a, const v1::TableState& table,
             const physics::TableModel& model, v1::PlanResponse* out) {
  for (const planner::PlannedShot& s : a.shots) ToProto(s, table, model, out->add_shots());
  out->set_reason(a.reason);
  out->set_simulations(static_cast<std::int32_t>(std::min<std::int64_t>(a.simulations, INT32_MAX)));
  out->set_evaluations(static_cast<std::int32_t>(std::min<std::int64_t>(a.evaluations, INT32_MAX)));
  out->set_elapsed_ms(a.elapsed * 1e3);
  out->set_simulation_cap(static_cast<std::int32_t>(std::min<std::int64_t>(a.simulation_cap, INT32_MAX)));
  out->set_cut_short(a.cut_short);
}

void ToProto(const std::vector<planner::NamedBall>& balls, v1::TableState* out) {
  out->Clear();
  for (const planner::NamedBall& b : balls) {
    v1::Ball* ball = out->add_balls();
    ball->set_id(b.id);
    ball->set_kind(ToProto(b.ball.kind));
    ToProto(b.ball.position, ball->mutable_position());
  }
}

void BuiltinTablesToProto(v1::GetModelResponse* response) {
  for (const planner::BuiltinTableEntry& entry : planner::BuiltinTableList()) {
    v1::BuiltinTable* table = response->add_builtin_tables();
    table->set_name(std::string(entry.name));
    table->set_description(std::string(entry.description));
    ToProto(*planner::BuiltinTable(entry.name), table->mutable_state());
  }
}

}  // namespace snooker::server
