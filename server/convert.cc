#include "server/convert.h"

#include "server/model_convert.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <sstream>
#include <string_view>

#include <google/protobuf/descriptor.h>

#include "physics/table/placement_repair.h"
#include "server/limits.h"

namespace snooker::server {
namespace {

namespace plim = physics::limits;
namespace slim = server::limits;

std::string RangeText(const physics::Range& r, const char* unit) {
  std::string out = "must be in [" + FormatNumber(r.lo) + ", " + FormatNumber(r.hi) + "]";
  if (unit[0] != '\0') out += std::string(" ") + unit;
  return out;
}

// Adds an error when x is outside r (NaN and infinities always are).
void CheckRange(std::vector<FieldError>* errors, double x, const char* field,
                const physics::Range& r, const char* unit = "") {
  if (!r.Contains(x)) errors->push_back({field, FormatNumber(x), RangeText(r, unit)});
}

// The same for an optional field: only when it is set.
template <typename Msg, typename Has, typename Get>
void CheckOptional(std::vector<FieldError>* errors, const Msg& m, Has has, Get get,
                   const char* field, const physics::Range& r, const char* unit = "") {
  if ((m.*has)()) CheckRange(errors, (m.*get)(), field, r, unit);
}

// "A (0), B (1), ..." for an enum, from its descriptor.
std::string EnumValues(const google::protobuf::EnumDescriptor* d) {
  std::string out;
  for (int i = 0; i < d->value_count(); ++i) {
    if (i > 0) out += ", ";
    out += d->value(i)->name() + " (" + std::to_string(d->value(i)->number()) + ")";
  }
  return out;
}

void CheckEnum(std::vector<FieldError>* errors, int value, bool valid, const char* field,
               const google::protobuf::EnumDescriptor* d) {
  if (!valid) errors->push_back({field, std::to_string(value), "must be one of " + EnumValues(d)});
}

// Length of the longest prefix of s of at most n bytes that does not end inside a
// UTF-8 sequence.
// An ASCII control character (below 0x20, or DEL).
bool IsControlByte(char ch) {
  const auto c = static_cast<unsigned char>(ch);
  return c < 0x20 || c == 0x7F;
}

std::size_t Utf8Prefix(std::string_view s, std::size_t n) {
  if (s.size() <= n) return s.size();
  while (n > 0 && (static_cast<unsigned char>(s[n]) & 0xC0) == 0x80) --n;
  return n;
}

}  // namespace

std::string FormatNumber(double x) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
  return ec == std::errc() ? std::string(buf, end) : std::string("?");
}

std::string QuoteId(std::string_view id) {
  const std::size_t shown = Utf8Prefix(id, slim::kMaxQuotedIdBytes);
  std::string out = "\"";
  for (char ch : id.substr(0, shown)) {
    const auto c = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (IsControlByte(ch)) {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 0xF];
    } else {
      out += ch;
    }
  }
  if (shown < id.size()) out += "...\" (" + std::to_string(id.size()) + " bytes)";
  else out += "\"";
  return out;
}

std::string Describe(const std::vector<FieldError>& errors) {
  std::string out;
  const std::size_t shown = std::min<std::size_t>(errors.size(), slim::kMaxReportedProblems);
  for (std::size_t i = 0; i < shown; ++i) {
    const FieldError& e = errors[i];
    if (!out.empty()) out += "; ";
    out += e.field + " = " + e.value + " (" + e.rule + ")";
  }
  if (errors.size() > shown) {
    out += "; and " + std::to_string(errors.size() - shown) + " more problem" +
           (errors.size() - shown == 1 ? "" : "s");
  }
  return BoundMessage(std::move(out));
}

std::string BoundMessage(std::string message) {
  if (message.size() <= slim::kMaxMessageBytes) return message;
  constexpr std::string_view kCut = " ... (message cut)";
  message.resize(Utf8Prefix(message, slim::kMaxMessageBytes - kCut.size()));
  message += kCut;
  return message;
}

std::vector<FieldError> ValidateCollideRequest(const v1::CollideRequest& r) {
  std::vector<FieldError> errors;
  CheckRange(&errors, r.speed(), "speed", plim::kImpactSpeed, "m/s");
  const physics::Range spin{-plim::kMaxSpin, plim::kMaxSpin};
  CheckRange(&errors, r.topspin(), "topspin", spin, "rad/s");
  CheckRange(&errors, r.sidespin(), "sidespin", spin, "rad/s");
  if (!(std::isfinite(r.cut_angle_deg()) &&
        std::abs(r.cut_angle_deg()) < slim::kCutAngleBoundDeg)) {
    errors.push_back({"cut_angle_deg", FormatNumber(r.cut_angle_deg()),
                      "must be in (-90, 90): at 90 deg or more the balls do not meet"});
  }
  using P = v1::CollisionParameters;
  const P& p = r.parameters();
  CheckOptional(&errors, p, &P::has_mu_bb, &P::mu_bb, "parameters.mu_bb", physics::limits::kFrictionCoefficient);
  CheckOptional(&errors, p, &P::has_restitution, &P::restitution, "parameters.restitution",
                physics::limits::kRestitution);
  CheckOptional(&errors, p, &P::has_mu_s, &P::mu_s, "parameters.mu_s", physics::limits::kClothSlideFriction);
  CheckOptional(&errors, p, &P::has_mass_kg, &P::mass_kg, "parameters.mass_kg", physics::limits::kBallMass, "kg");
  CheckOptional(&errors, p, &P::has_radius_m, &P::radius_m, "parameters.radius_m", physics::limits::kBallRadius, "m");
  CheckOptional(&errors, p, &P::has_gravity, &P::gravity, "parameters.gravity", physics::limits::kGravity, "m/s^2");
  CheckOptional(&errors, p, &P::has_spin_decel, &P::spin_decel, "parameters.spin_decel",
                physics::limits::kSpinDecel, "rad/s^2");
  CheckEnum(&errors, p.friction_law(), v1::BallBallFrictionLaw_IsValid(p.friction_law()),
            "parameters.friction_law", v1::BallBallFrictionLaw_descriptor());
  CheckOptional(&errors, p, &P::has_slip_gain, &P::slip_gain, "parameters.slip_gain", physics::limits::kSlipGain);
  CheckOptional(&errors, p, &P::has_slip_decay, &P::slip_decay, "parameters.slip_decay",
                physics::limits::kSlipDecay, "s/m");
  if (p.has_slip_gain() && p.slip_gain() + (p.has_mu_bb() ? p.mu_bb() : physics::BallBallParams{}.mu_bb) >
                                physics::limits::kFrictionCoefficient.hi) {
    errors.push_back({"parameters.slip_gain", FormatNumber(p.slip_gain()), "must be at most 1 - mu_bb (mu(0) <= 1)"});
  }
  using S = v1::ImpulseSolverOptions;
  const S& s = r.solver();
  CheckEnum(&errors, s.integrator(), v1::ImpulseIntegrator_IsValid(s.integrator()),
            "solver.integrator", v1::ImpulseIntegrator_descriptor());
  if (s.has_steps() && (s.steps() < 1 || s.steps() > plim::kMaxFixedSteps)) {
    errors.push_back({"solver.steps", std::to_string(s.steps()),
                      "must be an integer in [1, " + std::to_string(plim::kMaxFixedSteps) + "]"});
  }
  CheckOptional(&errors, s, &S::has_tolerance, &S::tolerance, "solver.tolerance", plim::kTolerance);
  return errors;
}

namespace {

std::string Mm(double metres) {
  std::ostringstream s;
  s.precision(3);
  s << metres * 1e3;
  return s.str();
}

std::string Point(const physics::Vec2& p) {
  std::ostringstream s;
  s.precision(6);
  s << "(" << p.x() << ", " << p.y() << ")";
  return s.str();
}

// Why ball i of `before` needed moving: the balls it overlapped and the cushions it
// was past, with by how much.
std::string WhyMoved(const std::vector<physics::BallPlacement>& before, std::size_t i,
                     const physics::TableModel& table) {
  std::vector<std::string> reasons;
  const double r2 = 2 * table.ball_radius();
  for (std::size_t j = 0; j < before.size(); ++j) {
    if (j == i) continue;
    const double overlap = r2 - (before[i].r - before[j].r).norm();
    if (overlap > physics::TableModel::kPlacementTolerance) {
      reasons.push_back("it overlapped " + std::string(before[j].name) + " by " + Mm(overlap) + " mm");
    }
  }
  const double c = table.cushion_contact_distance();
  const physics::Vec2& p = before[i].r;
  const struct {
    double past;
    const char* cushion;
  } cushions[] = {{c - p.x(), "left"},
                  {p.x() - (table.spec().width - c), "right"},
                  {c - p.y(), "baulk"},
                  {p.y() - (table.spec().length - c), "top"}};
  for (const auto& k : cushions) {
    if (k.past > physics::TableModel::kPlacementTolerance) {
      reasons.push_back("its centre was " + Mm(k.past) + " mm past where a ball touches the " +
                        k.cushion + " cushion");
    }
  }
  if (reasons.empty()) return "the balls it touches were moved";
  std::string out;
  for (const std::string& r : reasons) out += (out.empty() ? "" : ", and ") + r;
  return out;
}

// A ball's position: both coordinates given (a missing one would read as 0), finite,
// and on the table (the centre within the cushion noses' rectangle, or in a pocket's
// mouth where a ball stops on the lip: a ball elsewhere beyond it is not on the table
// at all, whatever the vision repair could do).
std::optional<FieldError> CheckPosition(const v1::Ball& b, const std::string& where,
                                        const physics::TableModel& table) {
  const std::string ball = "(ball " + QuoteId(b.id()) + ")";
  if (!b.has_position()) return FieldError{where + ".position", "missing " + ball, "must give x and y, in metres"};
  const v1::Vec2& p = b.position();
  for (const auto& [has, axis] : {std::pair{p.has_x(), "x"}, std::pair{p.has_y(), "y"}}) {
    if (!has) return FieldError{where + ".position." + axis, "missing " + ball, "must be given, in metres"};
  }
  const std::string at = "(" + FormatNumber(p.x()) + ", " + FormatNumber(p.y()) + ") " + ball;
  if (!(std::isfinite(p.x()) && std::isfinite(p.y()))) {
    return FieldError{where + ".position", at, "must be finite, in metres"};
  }
  const double w = table.spec().width, l = table.spec().length;
  if ((p.x() < 0 || p.x() > w || p.y() < 0 || p.y() > l) && !table.InPocketMouth(physics::Vec2(p.x(), p.y()))) {
    return FieldError{where + ".position", at,
                      "is off the table: the centre must lie on the bed, x in [0, " + FormatNumber(w) + "] m and y in [0, " +
                          FormatNumber(l) + "] m, or on a pocket's lip"};
  }
  return std::nullopt;
}

// Each ball's id, kind and position, and the number of CUE balls (`cue`); false when
// a position is missing or off the table (the placement cannot be checked).
bool CheckBalls(const v1::TableState& t, const physics::TableModel& table, CueBall cue,
                std::vector<FieldError>* out) {
  std::vector<FieldError>& errors = *out;
  const int n = t.balls_size();
  std::set<std::string_view> ids;
  std::vector<std::string> cue_ids;
  bool placeable = n > 0;
  for (int i = 0; i < n; ++i) {
    const v1::Ball& b = t.balls(i);
    const std::string where = "table.balls[" + std::to_string(i) + "]";
    if (b.id().empty()) {
      errors.push_back({where + ".id", "\"\"", "must not be empty"});
    } else if (b.id().size() > plim::kMaxIdBytes) {
      errors.push_back({where + ".id", QuoteId(b.id()),
                        "at most " + std::to_string(plim::kMaxIdBytes) + " bytes"});
    } else if (std::any_of(b.id().begin(), b.id().end(), IsControlByte)) {
      // An id is printed on the command line's output, in logs and in pictures: a
      // newline or an escape sequence in it would forge lines or drive a terminal.
      errors.push_back({where + ".id", QuoteId(b.id()), "must hold no control characters"});
    } else if (!ids.insert(b.id()).second) {
      errors.push_back({where + ".id", QuoteId(b.id()), "is used by another ball"});
    }
    if (b.kind() == v1::BALL_KIND_UNSPECIFIED || !v1::BallKind_IsValid(b.kind())) {
      errors.push_back({where + ".kind", std::to_string(b.kind()) + " (ball " + QuoteId(b.id()) + ")",
                        "must be one of CUE, RED, YELLOW, GREEN, BROWN, BLUE, PINK, BLACK"});
    }
    if (b.kind() == v1::CUE) cue_ids.push_back(QuoteId(b.id()));
    if (std::optional<FieldError> e = CheckPosition(b, where, table)) {
      errors.push_back(std::move(*e));
      placeable = false;
    }
  }
  const std::size_t cues = cue == CueBall::kInHand ? 0 : 1;
  if (n > 0 && cue_ids.size() != cues) {
    std::string value = std::to_string(cue_ids.size()) + (cue_ids.size() == 1 ? " CUE ball" : " CUE balls");
    for (std::size_t i = 0; i < cue_ids.size(); ++i) value += (i == 0 ? " (" : ", ") + cue_ids[i];
    if (!cue_ids.empty()) value += ")";
    const char* rule = "must have none: the cue ball is in hand (cue_in_hand), the planner places it";
    if (cues == 1) {
      rule = cue == CueBall::kOnTableUnlessInHand && cue_ids.empty()
                 ? "must have exactly one, or none with cue_in_hand set: the planner then places it"
                 : "must have exactly one";
    }
    errors.push_back({"table.balls", value, rule});
  }
  return placeable;
}

}  // namespace

TableCheck CheckTable(const v1::TableState& t, const physics::TableModel& table,
                      double vision_tolerance_m, CueBall cue) {
  TableCheck check;
  std::vector<FieldError>& errors = check.errors;
  const int n = t.balls_size();
  if (n == 0) {
    errors.push_back({"table.balls", "[]",
                      cue == CueBall::kInHand ? "must list at least one ball" : "must list at least the cue ball"});
  }
  if (n > plim::kMaxBalls) {
    // Refused before any ball is looked at: everything below is at least linear in
    // the balls, the placement check and repair quadratic.
    errors.push_back({"table.balls", std::to_string(n) + " balls",
                      "at most " + std::to_string(plim::kMaxBalls)});
    return check;
  }
  if (!CheckBalls(t, table, cue, &errors)) return check;
  std::vector<physics::BallPlacement> placed;
  placed.reserve(static_cast<std::size_t>(n));
  for (const v1::Ball& b : t.balls()) {
    // Names in the placement messages are ids, cut like QuoteId cuts them.
    const std::string_view id(b.id());
    placed.push_back({id.substr(0, Utf8Prefix(id, slim::kMaxQuotedIdBytes)),
                      physics::Vec2(b.position().x(), b.position().y())});
  }
  if (vision_tolerance_m > 0) {
    std::vector<physics::BallPlacement> repaired = placed;
    const physics::PlacementRepair repair =
        physics::RepairPlacement(table, repaired, vision_tolerance_m);
    if (!repair.error.empty()) {
      errors.push_back({"table.balls", "positions",
                        BoundMessage("beyond the vision tolerance of " + Mm(vision_tolerance_m) +
                                     " mm, which repairs smaller errors only: " + repair.error)});
      return check;
    }
    if (!repair.moved.empty()) {
      check.repaired = t;
      for (const physics::RepairedBall& m : repair.moved) {
        v1::Ball* b = check.repaired->mutable_balls(static_cast<int>(m.index));
        ToProto(m.to, b->mutable_position());
        v1::Warning& w = check.warnings.emplace_back();
        w.set_message("moved " + std::string(placed[m.index].name) + " by " + Mm(m.distance) +
                      " mm from " + Point(m.from) + " to " + Point(m.to) + ": " +
                      WhyMoved(placed, m.index, table));
        w.set_ball_id(b->id());
        ToProto(m.from, w.mutable_from());
        ToProto(m.to, w.mutable_to());
        w.set_moved_mm(m.distance * 1e3);
      }
      placed = std::move(repaired);
    }
  }
  // Also after a repair: it promises what ValidatePlacement accepts; this checks it.
  const std::string msg = table.ValidatePlacement(placed, slim::kMaxReportedProblems);
  if (!msg.empty()) errors.push_back({"table.balls", "positions", msg});
  return check;
}

std::optional<double> VisionTolerance(std::optional<double> requested_mm, double server_mm,
                                      const char* field, std::vector<FieldError>* errors) {
  if (!requested_mm) return server_mm * 1e-3;
  const physics::Range allowed{0, server_mm};
  if (!allowed.Contains(*requested_mm)) {
    errors->push_back({field, FormatNumber(*requested_mm),
                       RangeText(allowed, "mm") +
                           ": the server's vision tolerance is the largest a request may ask for"});
    return std::nullopt;
  }
  return *requested_mm * 1e-3;
}

std::optional<physics::Shot> ShotFromCue(const v1::CueStrike& cue, std::vector<FieldError>* errors,
                                         const physics::Model& physics_model) {
  const std::size_t before = errors->size();
  CheckRange(errors, cue.speed(), "cue.speed", physics::Range{0, 10}, "m/s");
  CheckRange(errors, cue.heading_deg(), "cue.heading_deg", slim::kHeadingDeg, "deg");
  CheckRange(errors, cue.tip_side(), "cue.tip_side", physics::Range{-1, 1}, "of R");
  CheckRange(errors, cue.tip_height(), "cue.tip_height", physics::Range{-1, 1}, "of R");
  CheckRange(errors, cue.elevation_deg(), "cue.elevation_deg", physics::Range{0, 59.999}, "deg");
  if (errors->size() > before) return std::nullopt;
  const physics::SimParams sim = physics_model.Apply(physics::SimParams{});
  const physics::CueParams& model = physics_model.cue;
  const physics::CueStrike k{cue.speed(), physics::DegToRad(NormalizedHeadingDeg(cue.heading_deg())), cue.tip_side(),
                             cue.tip_height(), physics::DegToRad(cue.elevation_deg())};
  const physics::StrikeResult res = physics::Strike(k, model, sim.ball, sim.cloth.g);
  if (res.status == physics::StrikeStatus::kMiscue || res.status == physics::StrikeStatus::kInvalid) {
    errors->push_back({"cue", "tip offset " + FormatNumber(std::hypot(cue.tip_side(), cue.tip_height())),
                       "a miscue: beyond the tip's limit of " + FormatNumber(physics::MiscueLimit(model)) + " of R"});
    return std::nullopt;
  }
  if (res.status != physics::StrikeStatus::kOk) {
    errors->push_back({"cue", "elevation " + FormatNumber(cue.elevation_deg()) + " deg at " + FormatNumber(cue.speed()) + " m/s",
                       "the ball would hop " + FormatNumber(res.hop * 1e3) + " mm, more than the model's " +
                           FormatNumber(model.max_hop * 1e3) + " mm"});
    return std::nullopt;
  }
  return res.shot;
}

void ToProto(const physics::Shot& shot, v1::Shot* out) {
  out->set_speed(shot.speed);
  out->set_heading_deg(physics::RadToDeg(shot.heading));
  out->set_topspin(shot.topspin);
  out->set_sidespin(shot.sidespin);
  out->set_swerve_spin(shot.swerve_spin);
}

std::vector<FieldError> ValidateShotAndOptions(const v1::SimulateRequest& r) {
  std::vector<FieldError> errors;
  if (r.has_cue() && r.has_shot()) {
    errors.push_back({"cue", "set", "give either shot or cue, not both"});
  } else if (!r.has_cue() && !r.has_shot()) {
    // The table's balls are at rest: without a stroke nothing would move.
    errors.push_back({"shot", "unset", "give the stroke: shot, or cue in the robot's terms"});
  }
  const v1::Shot& shot = r.shot();
  CheckRange(&errors, shot.speed(), "shot.speed", plim::kShotSpeed, "m/s");
  CheckRange(&errors, shot.heading_deg(), "shot.heading_deg", slim::kHeadingDeg, "deg");
  const physics::Range spin{-plim::kMaxSpin, plim::kMaxSpin};
  CheckRange(&errors, shot.topspin(), "shot.topspin", spin, "rad/s");
  CheckRange(&errors, shot.sidespin(), "shot.sidespin", spin, "rad/s");
  CheckRange(&errors, shot.swerve_spin(), "shot.swerve_spin", spin, "rad/s");
  using O = v1::SimulationOptions;
  const O& o = r.options();
  if (o.has_max_events() && (o.max_events() < 1 || o.max_events() > plim::kMaxEvents)) {
    errors.push_back({"options.max_events", std::to_string(o.max_events()),
                      "must be in [1, " + std::to_string(plim::kMaxEvents) + "]"});
  }
  CheckOptional(&errors, o, &O::has_max_time_s, &O::max_time_s, "options.max_time_s",
                plim::kMaxSimulatedTime, "s");
  CheckOptional(&errors, o, &O::has_tolerance, &O::tolerance, "options.tolerance", plim::kTolerance);
  CheckOptional(&errors, o, &O::has_path_sample_s, &O::path_sample_s, "options.path_sample_s",
                plim::kPathSample, "s");
  return errors;
}

int CueIndex(const v1::TableState& table) {
  for (int i = 0; i < table.balls_size(); ++i) {
    if (table.balls(i).kind() == v1::CUE) return i;
  }
  return -1;
}

double NormalizedHeadingDeg(double heading_deg) {
  double h = std::fmod(heading_deg, 360.0);  // exact; in (-360, 360)
  if (h < 0) h += 360.0;
  return h >= 360.0 ? 0.0 : h;  // -1e-20 + 360 rounds to 360
}

physics::Shot ShotFrom(const v1::Shot& shot) {
  return {shot.speed(), physics::DegToRad(NormalizedHeadingDeg(shot.heading_deg())), shot.topspin(),
          shot.sidespin(), shot.swerve_spin()};
}

std::vector<physics::BallState> BallStatesFrom(const v1::TableState& table, const v1::Shot& shot) {
  std::vector<physics::BallState> balls;
  balls.reserve(static_cast<std::size_t>(table.balls_size()));
  for (const v1::Ball& b : table.balls()) {
    const physics::Vec2 r(b.position().x(), b.position().y());
    if (b.kind() == v1::CUE) {
      balls.push_back(physics::StruckBall(ShotFrom(shot), r));
    } else {
      physics::BallState s;
      s.r = r;
      balls.push_back(s);
    }
  }
  return balls;
}

physics::SimParams SimParamsFrom(const v1::SimulationOptions& o, const physics::Model& model) {
  physics::SimParams p = model.Apply(physics::SimParams{});
  if (o.has_max_events()) p.max_events = o.max_events();
  if (o.has_max_time_s()) p.max_time = o.max_time_s();
  if (o.has_tolerance()) p.ball_ball_solver.tolerance = p.cushion_solver.tolerance = o.tolerance();
  if (o.has_impact_tables()) p.impact_tables = o.impact_tables();
  return p;
}

physics::BallParams BallParamsFrom(const v1::CollisionParameters& p, const physics::Model& base) {
  physics::BallParams b = base.ball;
  if (p.has_mass_kg()) b.mass = p.mass_kg();
  if (p.has_radius_m()) b.radius = p.radius_m();
  return b;
}

physics::ClothParams ClothParamsFrom(const v1::CollisionParameters& p, const physics::Model& base) {
  physics::ClothParams c = base.cloth;
  if (p.has_mu_s()) c.mu_s = p.mu_s();
  if (p.has_gravity()) c.g = p.gravity();
  if (p.has_spin_decel()) c.spin_decel = p.spin_decel();
  return c;
}

physics::BallBallParams BallBallParamsFrom(const v1::CollisionParameters& p, const physics::Model& base) {
  physics::BallBallParams c = base.ball_ball;
  if (p.has_mu_bb()) c.mu_bb = p.mu_bb();
  if (p.has_restitution()) c.e = p.restitution();
  if (p.has_slip_gain()) c.slip_gain = p.slip_gain();
  if (p.has_slip_decay()) c.slip_decay = p.slip_decay();
  if (const auto law = FrictionLawFromProto(p.friction_law())) c.friction_law = *law;  // else the base model's
  return c;
}

physics::ImpulseSolverOptions SolverOptionsFrom(const v1::ImpulseSolverOptions& o) {
  physics::ImpulseSolverOptions s;
  if (o.integrator() == v1::IMPULSE_INTEGRATOR_FIXED_STEP) {
    s.integrator = physics::ImpulseIntegrator::kFixedStep;
  }
  if (o.has_steps()) {
    s.steps = o.steps();
    // The scheme takes about N/2 steps (N for a wall): keep the cap above that. In 64
    // bits: 4 N overflows an int32 from N = 2^29 (validation caps N far below).
    const std::int64_t wanted = 4 * static_cast<std::int64_t>(s.steps);
    s.max_steps = static_cast<std::int32_t>(std::clamp<std::int64_t>(
        wanted, s.max_steps, std::numeric_limits<std::int32_t>::max()));
  }
  if (o.has_tolerance()) s.tolerance = o.tolerance();
  return s;
}

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

void ToProto(const physics::SimEvent& e, const v1::TableState& table,
             const physics::TableModel& model, v1::Event* out) {
  auto id = [&](int i) -> const std::string& { return table.balls(i).id(); };
  out->set_time(e.time);
  out->set_kind(EventKindToProto(e.kind));
  out->add_balls(id(e.ball));
  if (e.other >= 0) out->add_balls(id(e.other));
  out->set_motion(physics::ToString(e.state_after));
  const auto w = static_cast<std::size_t>(e.where);
  switch (e.kind) {
    case physics::EventKind::kCushion: out->set_cushion(model.segments()[w].name); break;
    case physics::EventKind::kJawWall:
      out->set_cushion(model.segments()[w].name);
      out->set_pocket(physics::ToString(model.segments()[w].pocket));
      break;
    case physics::EventKind::kKnuckle: out->set_pocket(physics::ToString(model.jaws()[w].pocket)); break;
    case physics::EventKind::kPocket: out->set_pocket(physics::ToString(model.pockets()[w].id)); break;
    default: break;
  }
}

void ToProto(const physics::Vec2& v, v1::Vec2* out) {
  out->set_x(v.x());
  out->set_y(v.y());
}

void ToProto(const physics::Vec3& v, v1::Vec3* out) {
  out->set_x(v.x());
  out->set_y(v.y());
  out->set_z(v.z());
}

void ToProto(const physics::TableModel& table, v1::TableGeometry* g) {
  g->set_width_m(table.spec().width);
  g->set_length_m(table.spec().length);
  g->set_baulk_line_m(table.spec().baulk_line);
  g->set_d_radius_m(table.spec().d_radius);
  g->set_cushion_height_m(table.spec().cushion_height);
  g->set_cushion_contact_distance_m(table.cushion_contact_distance());
  for (const physics::CushionSegment& seg : table.segments()) {
    v1::CushionSegment* out = g->add_segments();
    out->set_name(seg.name);
    out->set_kind(seg.kind == physics::SegmentKind::kCushion ? "cushion" : "jaw wall");
    ToProto(seg.p0, out->mutable_p0());
    ToProto(seg.p1, out->mutable_p1());
    ToProto(seg.normal, out->mutable_normal());
    out->set_pocket(physics::ToString(seg.pocket));
  }
  for (const physics::JawCircle& jaw : table.jaws()) {
    v1::Knuckle* out = g->add_knuckles();
    ToProto(jaw.centre, out->mutable_centre());
    out->set_radius_m(jaw.radius);
    out->set_pocket(physics::ToString(jaw.pocket));
  }
  for (const physics::Pocket& pocket : table.pockets()) {
    v1::Pocket* out = g->add_pockets();
    out->set_name(physics::ToString(pocket.id));
    ToProto(pocket.mouth_centre, out->mutable_mouth_centre());
    ToProto(pocket.axis, out->mutable_axis());
    ToProto(pocket.capture_centre, out->mutable_capture_centre());
    out->set_capture_radius_m(pocket.capture_radius);
  }
  const std::pair<physics::Colour, v1::BallKind> colours[] = {
      {physics::Colour::kYellow, v1::YELLOW}, {physics::Colour::kGreen, v1::GREEN},
      {physics::Colour::kBrown, v1::BROWN},   {physics::Colour::kBlue, v1::BLUE},
      {physics::Colour::kPink, v1::PINK},     {physics::Colour::kBlack, v1::BLACK}};
  for (const auto& [colour, kind] : colours) {
    v1::Spot* out = g->add_spots();
    out->set_kind(kind);
    ToProto(table.spot(colour), out->mutable_position());
  }
  for (const physics::Vec2& red : table.reds()) ToProto(red, g->add_red_triangle());
}

void ModelToProto(const physics::Model& physics_model, const physics::TableModel& table, double path_sample_s,
                  v1::GetModelResponse* response) {
  const physics::SimParams sim = physics_model.Apply(physics::SimParams{});
  v1::BallModel* ball = response->mutable_ball();
  ball->set_mass_kg(sim.ball.mass);
  ball->set_radius_m(sim.ball.radius);
  ball->set_inertia_kg_m2(sim.ball.Inertia());
  v1::ClothModel* cloth = response->mutable_cloth();
  cloth->set_mu_s(sim.cloth.mu_s);
  cloth->set_mu_r(sim.cloth.mu_r);
  cloth->set_spin_decel(sim.cloth.spin_decel);
  cloth->set_gravity(sim.cloth.g);
  v1::BallBallModel* bb = response->mutable_ball_ball();
  bb->set_mu_bb(sim.ball_ball.mu_bb);
  bb->set_restitution(sim.ball_ball.e);
  bb->set_friction_law(FrictionLawName(sim.ball_ball.friction_law));
  bb->set_slip_gain(sim.ball_ball.slip_gain);
  bb->set_slip_decay(sim.ball_ball.slip_decay);
  v1::CushionModel* cushion = response->mutable_cushion();
  cushion->set_mu_w(sim.cushion.mu_w);
  cushion->set_mu_s(sim.cushion.mu_s);
  cushion->set_contact_height_m(table.spec().cushion_height);  // the simulator uses the table's
  for (int i = 0; i < sim.cushion.restitution_curve.points; ++i) {
    cushion->add_restitution_speed(sim.cushion.restitution_curve.speed[static_cast<std::size_t>(i)]);
    cushion->add_restitution(sim.cushion.restitution_curve.e[static_cast<std::size_t>(i)]);
  }
  cushion->set_constant_restitution(sim.cushion.e_e);
  const physics::CueParams& cue = physics_model.cue;
  v1::CueModel* c = response->mutable_cue();
  c->set_mass_kg(cue.mass);
  c->set_tip_radius_m(cue.tip_radius);
  c->set_tip_restitution(cue.tip_restitution);
  c->set_tip_friction(cue.tip_friction);
  c->set_end_mass_kg(cue.end_mass);
  c->set_bed_restitution(cue.bed_restitution);
  c->set_max_hop_m(cue.max_hop);
  c->set_miscue_limit(physics::MiscueLimit(cue));
  c->set_squirt_at_045_deg(physics::RadToDeg(physics::SquirtAngle(0.45, cue, sim.ball)));
  c->set_centre_speed_ratio(physics::Strike(physics::CueStrike{1, 0, 0, 0, 0}, cue, sim.ball, sim.cloth.g).shot.speed);
  auto& sources = *c->mutable_sources();
  sources["mass_kg"] = "a 19 oz snooker cue (17-19 oz are usual)";
  sources["tip_radius_m"] = "a dime-shaped dome on a 9.5 mm tip";
  sources["tip_restitution"] = "leather tips on playing cues, 0.71-0.75 measured (Alciatore)";
  sources["tip_friction"] = "a chalked tip: miscues beyond about half the radius (Alciatore)";
  sources["end_mass_kg"] =
      "a snooker shaft: TP A.31's squirt at 0.45 R between TP B.1's measured 1.8 deg (low-deflection) and 2.5 "
      "deg (standard)";
  sources["bed_restitution"] = "a ball's bounce on slate and cloth, an estimate used only for the hop limit";
  sources["max_hop_m"] = "the model has no flight: under a tenth of the radius";
  sources["miscue_limit"] = "sin(atan(tip_friction))";
  sources["squirt_at_045_deg"] = "TP A.31 at the end mass";
  sources["centre_speed_ratio"] = "TP A.30 with the tip's restitution: (1 + e) / (1 + m / M)";
  v1::SimulationDefaults* d = response->mutable_simulation();
  d->set_max_events(sim.max_events);
  d->set_max_time_s(sim.max_time);
  d->set_tolerance(sim.ball_ball_solver.tolerance);
  d->set_path_sample_s(path_sample_s);
  d->set_rest_speed(sim.rest_speed);
  d->set_impact_tables(sim.impact_tables);
  server::ModelToProto(physics_model, response->mutable_physics());
}

}  // namespace snooker::server
