#include "server/calibrate_api.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <utility>

#include "physics/core/types.h"
#include "physics/table/table.h"
#include "server/limits.h"
#include "server/model_convert.h"

namespace snooker::server {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// FittedParameter.uncertainty of a parameter the data do not determine.
constexpr double kUndetermined = -1;

std::string Index(const char* list, int i) { return std::string(list) + "[" + std::to_string(i) + "]"; }

// Degrees to radians; a value that is not finite stays so.
double Rad(double deg) { return physics::DegToRad(deg); }

// The angles are checked here, in the API's degrees and names: Validate checks the
// same ranges in radians and would name the library's fields. The bounds of throws
// and rebounds are the library's own (compared in radians), so that a value accepted
// here is never refused there; a strike's heading and elevation take the ranges of
// the shared messages (table.proto), within the library's.
void CheckAngle(bool ok, const std::string& field, double deg, const char* rule, std::vector<FieldError>* errors) {
  if (!ok) errors->push_back({field, FormatNumber(deg), rule});
}

void ThrowsAndReboundsFrom(const v1::Observations& in, calibration::Observations* out,
                           std::vector<FieldError>* errors) {
  for (int i = 0; i < in.throw__size(); ++i) {
    const v1::ThrowObservation& t = in.throw_(i);
    const std::string at = Index("throw", i);
    const double cut = Rad(t.cut_deg()), thrown = Rad(t.throw_deg());
    CheckAngle(std::isfinite(cut) && cut >= 0 && cut <= calibration::kMaxCut, at + ".cut_deg", t.cut_deg(),
               "must be in [0, 89] deg", errors);
    CheckAngle(std::isfinite(thrown) && std::abs(thrown) <= calibration::kMaxThrow, at + ".throw_deg",
               t.throw_deg(), "must be in [-45, 45] deg", errors);
    calibration::ThrowObservation o;
    o.cut = Rad(t.cut_deg());
    if (t.has_cue_ball_speed()) o.cue_ball_speed = t.cue_ball_speed();
    if (t.has_object_ball_speed()) o.object_ball_speed = t.object_ball_speed();
    o.topspin = t.topspin();
    o.sidespin = t.sidespin();
    o.measured_throw = Rad(t.throw_deg());
    out->throws.push_back(o);
  }
  for (int i = 0; i < in.cushion_size(); ++i) {
    const v1::CushionObservation& c = in.cushion(i);
    const std::string at = Index("cushion", i);
    auto angle_ok = [](double rad) { return std::isfinite(rad) && rad > 0 && rad < physics::kPi; };
    CheckAngle(angle_ok(Rad(c.angle_deg())), at + ".angle_deg", c.angle_deg(), "must be in (0, 180) deg", errors);
    if (c.has_rebound_angle_deg()) {
      CheckAngle(angle_ok(Rad(c.rebound_angle_deg())), at + ".rebound_angle_deg", c.rebound_angle_deg(),
                 "must be in (0, 180) deg", errors);
    }
    calibration::CushionObservation o;
    o.speed = c.speed();
    o.angle = Rad(c.angle_deg());
    o.topspin = c.topspin();
    o.sidespin = c.sidespin();
    o.rebound_speed = c.rebound_speed();
    if (c.has_rebound_angle_deg()) o.rebound_angle = Rad(c.rebound_angle_deg());
    out->rebounds.push_back(o);
  }
}

// A seen coordinate within calibration::kTableMargin of the playing area [0, size].
void CheckOnTable(double x, double size, const std::string& field, std::vector<FieldError>* errors) {
  if (x >= -calibration::kTableMargin && x <= size + calibration::kTableMargin) return;
  errors->push_back({field, FormatNumber(x),
                     "must be on the table, in [" + FormatNumber(-calibration::kTableMargin) + ", " +
                         FormatNumber(size + calibration::kTableMargin) + "] m"});
}

// One tracked shot; false with the errors added when its balls or sightings cannot
// be matched up.
bool TrackedFrom(const v1::TrackedShot& s, const std::string& at, calibration::TrackedShot* out,
                 std::vector<FieldError>* errors) {
  const std::size_t before = errors->size();
  std::map<std::string, int> index;
  out->cue_ball = -1;
  for (int i = 0; i < s.table().balls_size(); ++i) {
    const v1::Ball& b = s.table().balls(i);
    if (!index.emplace(b.id(), i).second) {
      errors->push_back({at + ".table.balls[" + std::to_string(i) + "].id", QuoteId(b.id()), "must be unique"});
    }
    if (b.kind() == v1::CUE) {
      if (out->cue_ball >= 0) errors->push_back({at + ".table", "2 CUE balls", "must have exactly one"});
      out->cue_ball = i;
    }
    out->balls.emplace_back(b.position().x(), b.position().y());
  }
  if (out->cue_ball < 0) errors->push_back({at + ".table", "no CUE ball", "must have exactly one"});
  auto heading_ok = [](double deg) { return limits::kHeadingDeg.Contains(deg); };
  switch (s.strike_case()) {
    case v1::TrackedShot::kCue:
      CheckAngle(heading_ok(s.cue().heading_deg()), at + ".cue.heading_deg", s.cue().heading_deg(),
                 "must be in [-3600, 3600] deg", errors);
      // The shared CueStrike message's range, within the library's [0, 90).
      CheckAngle(std::isfinite(s.cue().elevation_deg()) && s.cue().elevation_deg() >= 0 &&
                     s.cue().elevation_deg() < 60,
                 at + ".cue.elevation_deg", s.cue().elevation_deg(), "must be in [0, 60) deg", errors);
      out->strike = physics::CueStrike{s.cue().speed(), Rad(NormalizedHeadingDeg(s.cue().heading_deg())),
                                       s.cue().tip_side(), s.cue().tip_height(), Rad(s.cue().elevation_deg())};
      break;
    case v1::TrackedShot::kShot:
      CheckAngle(heading_ok(s.shot().heading_deg()), at + ".shot.heading_deg", s.shot().heading_deg(),
                 "must be in [-3600, 3600] deg", errors);
      out->strike = ShotFrom(s.shot());
      break;
    default: errors->push_back({at, "no strike", "must give cue or shot"});
  }
  const physics::TableSpec& table = physics::DefaultTable().spec();
  for (int k = 0; k < s.sightings_size(); ++k) {
    const v1::Sighting& seen = s.sightings(k);
    calibration::Sighting g;
    g.t = seen.t_s();
    g.positions.assign(out->balls.size(), physics::Vec2(kNaN, kNaN));
    for (int j = 0; j < seen.balls_size(); ++j) {
      const v1::BallSighting& b = seen.balls(j);
      const auto it = index.find(b.id());
      const std::string field = at + ".sightings[" + std::to_string(k) + "].balls[" + std::to_string(j) + "]";
      if (it == index.end()) {
        errors->push_back({field + ".id", QuoteId(b.id()), "must be a ball of the shot's table"});
        continue;
      }
      if (!std::isnan(g.positions[static_cast<std::size_t>(it->second)].x())) {
        errors->push_back({field + ".id", QuoteId(b.id()), "must be seen once per sighting"});
      }
      // A ball seen where no number is (NaN) would read as "not seen": refused.
      if (!std::isfinite(b.position().x()) || !std::isfinite(b.position().y())) {
        errors->push_back({field + ".position", FormatNumber(b.position().x()) + ", " + FormatNumber(b.position().y()),
                           "must be finite (leave out a ball not seen)"});
      } else {
        // Named here by the sighting's own list; Validate would name the table's.
        CheckOnTable(b.position().x(), table.width, field + ".position.x", errors);
        CheckOnTable(b.position().y(), table.length, field + ".position.y", errors);
      }
      g.positions[static_cast<std::size_t>(it->second)] = physics::Vec2(b.position().x(), b.position().y());
    }
    out->sightings.push_back(std::move(g));
  }
  return errors->size() == before;
}

// The library names observation lists and a few fields as it stores them; the
// API's names differ. The angles and the sighted positions never reach the library
// unchecked (ObservationsFrom names them), so their names need no translation.
std::string ApiNames(std::string message) {
  using Names = std::pair<std::string_view, std::string_view>;
  // List names, only at the start of a path ("shot[2].cue.speed", "rebound: 1
  // observation"), not inside one ("tracked[0].shot.speed").
  for (const auto& [from, to] :
       {Names{"rebound[", "cushion["}, Names{"rebound:", "cushion:"}, Names{"shot[", "tracked["}}) {
    std::size_t at = message.find(from);
    while (at != std::string::npos) {
      const bool path = at == 0 || message[at - 1] == ' ' || message[at - 1] == ';';
      if (path) message.replace(at, from.size(), to);
      at = message.find(from, at + (path ? to.size() : from.size()));
    }
  }
  // Fields of a tracked shot, after its index.
  for (const auto& [from, to] :
       {Names{"].cue.side = ", "].cue.tip_side = "}, Names{"].cue.height = ", "].cue.tip_height = "},
        Names{"].balls: ", "].table.balls: "}, Names{"].balls.size = ", "].table.balls.size = "},
        Names{"].t = ", "].t_s = "}}) {
    for (std::size_t at = message.find(from); at != std::string::npos; at = message.find(from, at + to.size())) {
      message.replace(at, from.size(), to);
    }
  }
  return message;
}

const char* UnitOf(const std::string& name) {
  if (name == "ball_ball.slip_decay") return "s/m";
  if (name == "cloth.spin_decel") return "rad/s^2";
  if (name == "cue.end_mass") return "kg";
  return "";
}

void ResponseFrom(const calibration::FitResult& fit, const std::vector<calibration::ParameterSpec>& specs,
                  v1::CalibrateResponse* out) {
  ModelToProto(fit.model, out->mutable_model());
  for (std::size_t i = 0; i < fit.parameters.size(); ++i) {
    const calibration::ParameterEstimate& e = fit.parameters[i];
    v1::FittedParameter* p = out->add_parameters();
    p->set_name(e.name);
    p->set_unit(UnitOf(e.name));
    p->set_start(e.start);
    p->set_value(e.fitted);
    // The library's NaN (J^T J singular at the optimum: the data do not determine
    // the parameter there) as calibrate.proto's -1: an answer has finite numbers.
    p->set_uncertainty(std::isfinite(e.uncertainty) ? e.uncertainty : kUndetermined);
    if (i < specs.size()) {
      const double room = 1e-6 * (specs[i].hi - specs[i].lo);
      p->set_at_bound(e.fitted <= specs[i].lo + room || e.fitted >= specs[i].hi - room);
    }
  }
  auto add = [&](const char* kind, const char* unit, const calibration::KindResiduals& r) {
    if (r.count <= 0) return;
    v1::ResidualSummary* s = out->add_residuals();
    s->set_kind(kind);
    s->set_unit(unit);
    s->set_count(r.count);
    s->set_rms_before(r.rms_before);
    s->set_rms_after(r.rms_after);
  };
  add("throw", "deg", fit.throw_deg);
  add("cushion_speed", "m/s", fit.rebound_speed);
  add("cushion_angle", "deg", fit.rebound_angle_deg);
  add("tracked", "m", fit.position);
  out->set_evaluations(fit.evaluations);
}

}  // namespace

calibration::Observations ObservationsFrom(const v1::Observations& in, std::vector<FieldError>* errors) {
  calibration::Observations out;
  ThrowsAndReboundsFrom(in, &out, errors);
  for (int i = 0; i < in.tracked_size(); ++i) {
    calibration::TrackedShot shot;
    TrackedFrom(in.tracked(i), Index("tracked", i), &shot, errors);
    out.shots.push_back(std::move(shot));
  }
  return out;
}

void ObservationsToProto(const calibration::Observations& in, v1::Observations* out) {
  out->Clear();
  for (const calibration::ThrowObservation& t : in.throws) {
    v1::ThrowObservation* o = out->add_throw_();
    o->set_cut_deg(physics::RadToDeg(t.cut));
    if (t.cue_ball_speed) o->set_cue_ball_speed(*t.cue_ball_speed);
    if (t.object_ball_speed) o->set_object_ball_speed(*t.object_ball_speed);
    o->set_topspin(t.topspin);
    o->set_sidespin(t.sidespin);
    o->set_throw_deg(physics::RadToDeg(t.measured_throw));
  }
  for (const calibration::CushionObservation& c : in.rebounds) {
    v1::CushionObservation* o = out->add_cushion();
    o->set_speed(c.speed);
    o->set_angle_deg(physics::RadToDeg(c.angle));
    o->set_topspin(c.topspin);
    o->set_sidespin(c.sidespin);
    o->set_rebound_speed(c.rebound_speed);
    if (c.rebound_angle) o->set_rebound_angle_deg(physics::RadToDeg(*c.rebound_angle));
  }
  for (const calibration::TrackedShot& s : in.shots) {
    v1::TrackedShot* o = out->add_tracked();
    std::vector<std::string> ids;
    int object = 0;
    for (std::size_t i = 0; i < s.balls.size(); ++i) {
      const bool cue = static_cast<int>(i) == s.cue_ball;
      ids.push_back(cue ? "cue" : "ball-" + std::to_string(++object));
      v1::Ball* b = o->mutable_table()->add_balls();
      b->set_id(ids.back());
      b->set_kind(cue ? v1::CUE : v1::RED);
      b->mutable_position()->set_x(s.balls[i].x());
      b->mutable_position()->set_y(s.balls[i].y());
    }
    if (const auto* cue = std::get_if<physics::CueStrike>(&s.strike)) {
      v1::CueStrike* c = o->mutable_cue();
      c->set_speed(cue->speed);
      c->set_heading_deg(physics::RadToDeg(cue->heading));
      c->set_tip_side(cue->side);
      c->set_tip_height(cue->height);
      c->set_elevation_deg(physics::RadToDeg(cue->elevation));
    } else {
      ToProto(std::get<physics::Shot>(s.strike), o->mutable_shot());
    }
    for (const calibration::Sighting& g : s.sightings) {
      v1::Sighting* seen = o->add_sightings();
      seen->set_t_s(g.t);
      for (std::size_t i = 0; i < g.positions.size() && i < ids.size(); ++i) {
        if (!std::isfinite(g.positions[i].x()) || !std::isfinite(g.positions[i].y())) continue;
        v1::BallSighting* b = seen->add_balls();
        b->set_id(ids[i]);
        b->mutable_position()->set_x(g.positions[i].x());
        b->mutable_position()->set_y(g.positions[i].y());
      }
    }
  }
}

ApiStatus Calibrate(const v1::CalibrateRequest& request, v1::CalibrateResponse* response, const CallLimits& limits) {
  std::vector<FieldError> errors;
  std::string groups_text;
  for (const std::string& g : request.fit()) groups_text += (groups_text.empty() ? "" : ",") + g;
  const calibration::ParsedGroups groups = calibration::ParseGroups(groups_text);
  if (request.fit_size() == 0) {
    errors.push_back({"fit", "(none)", "must name at least one group: ball-ball, cushion, cloth, cue"});
  } else if (!groups.error.empty()) {
    errors.push_back({"fit", groups_text, groups.error});
  }
  if (request.has_max_evaluations() && (request.max_evaluations() < 10 || request.max_evaluations() > 100000)) {
    errors.push_back({"max_evaluations", std::to_string(request.max_evaluations()), "must be in [10, 100000]"});
  }
  physics::Model start = limits.physics_model();
  if (std::string e = ModelFromProto(request.start(), &start); !e.empty()) {
    errors.push_back({"start", "not a valid model", e});
  }
  const calibration::Observations observations = ObservationsFrom(request.observations(), &errors);
  if (!errors.empty()) return ApiStatus::Invalid(Describe(errors));
  if (std::string e = calibration::Validate(observations); !e.empty()) {
    return ApiStatus::Invalid(BoundMessage("observations: " + ApiNames(e)));
  }
  calibration::FitOptions options;
  if (request.has_max_evaluations()) options.max_evaluations = request.max_evaluations();
  options.interrupt = limits.interrupt;
  const calibration::FitResult fit = calibration::Fit(observations, groups.groups, start, options);
  if (fit.interrupted) {
    const bool late = std::chrono::steady_clock::now() >= limits.interrupt.deadline;
    return {late ? ApiStatus::Code::kDeadlineExceeded : ApiStatus::Code::kCancelled,
            late ? "the deadline passed before the fit ended" : "the call was cancelled"};
  }
  if (!fit.error.empty()) return ApiStatus::Invalid(BoundMessage(ApiNames(fit.error)));
  ResponseFrom(fit, calibration::FittedParameters(groups.groups, observations, start), response);
  return ApiStatus::Ok();
}

}  // namespace snooker::server
