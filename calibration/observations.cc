#include "calibration/observations.h"

#include <cmath>
#include <sstream>

#include "physics/core/limits.h"
#include "physics/table/table.h"

namespace snooker::calibration {
namespace {

using physics::Vec2;

// Collects "where.name = value (must be rule)" messages, one per observation: the
// first bad value of each names it.
class Problems {
 public:
  // Starts the checks of one observation, "throw[3]".
  void Begin(const char* kind, std::size_t index) {
    std::ostringstream w;
    w << kind << '[' << index << ']';
    where_ = w.str();
    bad_ = false;
  }
  // Adds the message unless `ok` or this observation already has one; returns ok.
  bool Check(bool ok, const std::string& name, double value, const char* rule) {
    if (ok || bad_) return ok;
    bad_ = true;
    Separate();
    out_ << where_ << '.' << name << " = " << value << " (must be " << rule << ")";
    return false;
  }
  // A message about the set as a whole, or about an observation without a value.
  void Add(const std::string& message) {
    Separate();
    out_ << message;
  }
  bool bad() const { return bad_; }
  std::string str() const { return out_.str(); }

 private:
  void Separate() {
    if (out_.tellp() > 0) out_ << "; ";
  }
  std::ostringstream out_;
  std::string where_;
  bool bad_ = false;
};

bool InSpeedRange(double v) { return std::isfinite(v) && v > 0 && v <= kMaxSpeed; }
bool Spin(double w) { return std::isfinite(w) && std::abs(w) <= physics::limits::kMaxSpin; }
constexpr const char* kSpeedRule = "a finite number in (0, 10] m/s";
constexpr const char* kSpinRule = "a finite number of at most 1000 rad/s in size";

void CheckThrow(const ThrowObservation& o, Problems* p) {
  p->Check(std::isfinite(o.cut) && o.cut >= 0 && o.cut <= kMaxCut, "cut", o.cut, "in [0, 1.553] rad (89 deg)");
  if (o.cue_ball_speed.has_value() == o.object_ball_speed.has_value()) {
    p->Check(false, "cue_ball_speed", o.cue_ball_speed.value_or(NAN),
             "given alone: exactly one of cue_ball_speed and object_ball_speed");
  }
  if (o.cue_ball_speed) p->Check(InSpeedRange(*o.cue_ball_speed), "cue_ball_speed", *o.cue_ball_speed, kSpeedRule);
  if (o.object_ball_speed) {
    p->Check(InSpeedRange(*o.object_ball_speed), "object_ball_speed", *o.object_ball_speed, kSpeedRule);
  }
  p->Check(Spin(o.topspin), "topspin", o.topspin, kSpinRule);
  p->Check(Spin(o.sidespin), "sidespin", o.sidespin, kSpinRule);
  p->Check(std::isfinite(o.measured_throw) && std::abs(o.measured_throw) <= kMaxThrow, "measured_throw",
           o.measured_throw, "a finite number in [-0.785, 0.785] rad (45 deg)");
}

void CheckRebound(const CushionObservation& o, Problems* p) {
  p->Check(InSpeedRange(o.speed), "speed", o.speed, kSpeedRule);
  p->Check(std::isfinite(o.angle) && o.angle > 0 && o.angle < physics::kPi, "angle", o.angle,
           "in (0, pi) rad");
  p->Check(Spin(o.topspin), "topspin", o.topspin, kSpinRule);
  p->Check(Spin(o.sidespin), "sidespin", o.sidespin, kSpinRule);
  p->Check(std::isfinite(o.rebound_speed) && o.rebound_speed >= 0 && o.rebound_speed <= kMaxSpeed,
           "rebound_speed", o.rebound_speed, "a finite number in [0, 10] m/s");
  if (o.rebound_angle) {
    p->Check(std::isfinite(*o.rebound_angle) && *o.rebound_angle > 0 && *o.rebound_angle < physics::kPi,
             "rebound_angle", *o.rebound_angle, "in (0, pi) rad");
  }
}

void CheckStrike(const TrackedShot& s, Problems* p) {
  if (const auto* k = std::get_if<physics::CueStrike>(&s.strike)) {
    p->Check(InSpeedRange(k->speed), "cue.speed", k->speed, kSpeedRule);
    p->Check(std::isfinite(k->heading), "cue.heading", k->heading, "a finite number of rad");
    const double offset = std::hypot(k->side, k->height);
    p->Check(std::isfinite(k->side) && offset < 1, "cue.side", k->side, "finite, with side^2 + height^2 < 1");
    p->Check(std::isfinite(k->height) && offset < 1, "cue.height", k->height,
             "finite, with side^2 + height^2 < 1");
    p->Check(std::isfinite(k->elevation) && k->elevation >= 0 && k->elevation < physics::kPi / 2,
             "cue.elevation", k->elevation, "in [0, pi/2) rad");
    return;
  }
  const physics::Shot& b = std::get<physics::Shot>(s.strike);
  p->Check(InSpeedRange(b.speed), "shot.speed", b.speed, kSpeedRule);
  p->Check(std::isfinite(b.heading), "shot.heading", b.heading, "a finite number of rad");
  p->Check(Spin(b.topspin), "shot.topspin", b.topspin, kSpinRule);
  p->Check(Spin(b.sidespin), "shot.sidespin", b.sidespin, kSpinRule);
  p->Check(Spin(b.swerve_spin), "shot.swerve_spin", b.swerve_spin, kSpinRule);
}

// The start: a ball count the simulator takes, a cue ball among them, a placement
// the table accepts.
void CheckStart(const TrackedShot& s, std::size_t index, Problems* p) {
  const int n = static_cast<int>(s.balls.size());
  if (!p->Check(n >= 1 && n <= physics::limits::kMaxBalls, "balls.size", n, "in [1, 32]")) return;
  if (!p->Check(s.cue_ball >= 0 && s.cue_ball < n, "cue_ball", s.cue_ball, "the index of one of the balls")) {
    return;
  }
  std::vector<physics::BallPlacement> placed(s.balls.size());
  for (std::size_t i = 0; i < s.balls.size(); ++i) placed[i].r = s.balls[i];
  const std::string bad = physics::DefaultTable().ValidatePlacement(placed, 1);
  if (!bad.empty()) {
    std::ostringstream m;
    m << "shot[" << index << "].balls: " << bad;
    p->Add(m.str());
  }
}

void CheckSightings(const TrackedShot& s, Problems* p) {
  if (!p->Check(!s.sightings.empty(), "sightings.size", 0, "at least 1")) return;
  const physics::TableSpec& table = physics::DefaultTable().spec();
  double last = 0;
  for (std::size_t j = 0; j < s.sightings.size() && !p->bad(); ++j) {
    const Sighting& g = s.sightings[j];
    const std::string at = "sightings[" + std::to_string(j) + "]";
    p->Check(std::isfinite(g.t) && g.t > last && g.t <= kMaxSightingTime, at + ".t", g.t,
             j == 0 ? "in (0, 600] s" : "after the sighting before it, at most 600 s");
    last = g.t;
    p->Check(g.positions.size() == s.balls.size(), at + ".positions.size", static_cast<double>(g.positions.size()),
             "the number of balls");
    for (std::size_t i = 0; i < g.positions.size() && !p->bad(); ++i) {
      const Vec2 r = g.positions[i];
      if (std::isnan(r.x()) && std::isnan(r.y())) continue;  // not seen
      const std::string name = at + ".positions[" + std::to_string(i) + "]";
      p->Check(std::isfinite(r.x()) && r.x() >= -kTableMargin && r.x() <= table.width + kTableMargin,
               name + ".x", r.x(), "on the table, in [-0.05, 1.828] m (NaN in both when not seen)");
      p->Check(std::isfinite(r.y()) && r.y() >= -kTableMargin && r.y() <= table.length + kTableMargin,
               name + ".y", r.y(), "on the table, in [-0.05, 3.619] m (NaN in both when not seen)");
    }
  }
}

bool SameThrowInput(const ThrowObservation& a, const ThrowObservation& b) {
  return a.cut == b.cut && a.cue_ball_speed == b.cue_ball_speed && a.object_ball_speed == b.object_ball_speed &&
         a.topspin == b.topspin && a.sidespin == b.sidespin;
}

bool SameReboundInput(const CushionObservation& a, const CushionObservation& b) {
  return a.speed == b.speed && a.angle == b.angle && a.topspin == b.topspin && a.sidespin == b.sidespin;
}

// Identical inputs, measurements further apart than the stated tolerances. The
// pairs are few (a calibration has hundreds of points at most): a plain double loop.
void CheckContradictions(const Observations& o, Problems* p) {
  for (std::size_t i = 0; i < o.throws.size(); ++i) {
    for (std::size_t j = i + 1; j < o.throws.size(); ++j) {
      const ThrowObservation &a = o.throws[i], &b = o.throws[j];
      if (!SameThrowInput(a, b) || std::abs(a.measured_throw - b.measured_throw) <= kThrowContradiction) continue;
      std::ostringstream m;
      m << "throw[" << i << "] and throw[" << j << "] contradict: the same input, measured_throw = "
        << a.measured_throw << " and " << b.measured_throw << " rad (at most 0.0524 rad, 3 deg, apart)";
      p->Add(m.str());
    }
  }
  for (std::size_t i = 0; i < o.rebounds.size(); ++i) {
    for (std::size_t j = i + 1; j < o.rebounds.size(); ++j) {
      const CushionObservation &a = o.rebounds[i], &b = o.rebounds[j];
      if (!SameReboundInput(a, b)) continue;
      std::ostringstream m;
      if (std::abs(a.rebound_speed - b.rebound_speed) > kReboundSpeedContradiction) {
        m << "rebound[" << i << "] and rebound[" << j << "] contradict: the same input, rebound_speed = "
          << a.rebound_speed << " and " << b.rebound_speed << " m/s (at most 0.25 m/s apart)";
      } else if (a.rebound_angle && b.rebound_angle &&
                 std::abs(*a.rebound_angle - *b.rebound_angle) > kReboundAngleContradiction) {
        m << "rebound[" << i << "] and rebound[" << j << "] contradict: the same input, rebound_angle = "
          << *a.rebound_angle << " and " << *b.rebound_angle << " rad (at most 0.0873 rad, 5 deg, apart)";
      }
      if (m.tellp() > 0) p->Add(m.str());
    }
  }
}

}  // namespace

std::string Validate(const Observations& o) {
  Problems p;
  if (o.throws.empty() && o.rebounds.empty() && o.shots.empty()) {
    p.Add("no observations (give throws, rebounds or tracked shots)");
    return p.str();
  }
  if (o.throws.size() == 1) p.Add("throw: 1 observation (a fit needs at least 2 points of a kind)");
  if (o.rebounds.size() == 1) p.Add("rebound: 1 observation (a fit needs at least 2 points of a kind)");
  for (std::size_t i = 0; i < o.throws.size(); ++i) {
    p.Begin("throw", i);
    CheckThrow(o.throws[i], &p);
  }
  for (std::size_t i = 0; i < o.rebounds.size(); ++i) {
    p.Begin("rebound", i);
    CheckRebound(o.rebounds[i], &p);
  }
  for (std::size_t i = 0; i < o.shots.size(); ++i) {
    p.Begin("shot", i);
    CheckStart(o.shots[i], i, &p);
    CheckStrike(o.shots[i], &p);
    CheckSightings(o.shots[i], &p);
  }
  CheckContradictions(o, &p);
  return p.str();
}

}  // namespace snooker::calibration
