#include "calibration/observations.h"

#include <algorithm>
#include <array>
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
  // As Check, for a rule about which values are given rather than about a value:
  // "where: what".
  bool Require(bool ok, const std::string& what) {
    if (ok || bad_) return ok;
    bad_ = true;
    Separate();
    out_ << where_ << ": " << what;
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
  p->Require(o.cue_ball_speed.has_value() != o.object_ball_speed.has_value(),
             o.cue_ball_speed ? "both cue_ball_speed and object_ball_speed are given (give exactly one)"
                              : "neither cue_ball_speed nor object_ball_speed is given (give exactly one)");
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

// An observation's input as a key: identical inputs, identical keys. Only
// observations whose values are all finite take part (Validate names the others),
// so that the keys are totally ordered.
// The keys end with the measurement, which is not part of the input.
using ThrowKey = std::array<double, 8>;
using ReboundKey = std::array<double, 5>;
constexpr std::size_t kThrowInputs = 7, kReboundInputs = 4;

ThrowKey KeyOf(const ThrowObservation& o) {
  // Which speed is given is part of the input.
  return {o.cut,
          o.cue_ball_speed ? 1.0 : 0.0,
          o.cue_ball_speed.value_or(0),
          o.object_ball_speed ? 1.0 : 0.0,
          o.object_ball_speed.value_or(0),
          o.topspin,
          o.sidespin,
          o.measured_throw};
}
ReboundKey KeyOf(const CushionObservation& o) { return {o.speed, o.angle, o.topspin, o.sidespin, o.rebound_speed}; }

template <typename Key>
bool Finite(const Key& k) {
  return std::all_of(k.begin(), k.end(), [](double x) { return std::isfinite(x); });
}

// The indices of the observations with finite keys, in groups of identical inputs
// (the first `inputs` values of the key), each group in index order, the groups in
// the order of their first index. Sorting, not comparing every pair: a request may
// hold a hundred thousand observations.
template <typename Observation>
std::vector<std::vector<std::size_t>> SameInputGroups(const std::vector<Observation>& all, std::size_t inputs) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (Finite(KeyOf(all[i]))) order.push_back(i);
  }
  auto input_less = [&](std::size_t a, std::size_t b) {
    const auto ka = KeyOf(all[a]), kb = KeyOf(all[b]);
    return std::lexicographical_compare(ka.begin(), ka.begin() + static_cast<std::ptrdiff_t>(inputs), kb.begin(),
                                        kb.begin() + static_cast<std::ptrdiff_t>(inputs));
  };
  std::stable_sort(order.begin(), order.end(), input_less);  // stable: index order within a group
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i + 1;
    while (j < order.size() && !input_less(order[i], order[j])) ++j;
    if (j - i >= 2) groups.emplace_back(order.begin() + static_cast<std::ptrdiff_t>(i),
                                        order.begin() + static_cast<std::ptrdiff_t>(j));
    i = j;
  }
  std::sort(groups.begin(), groups.end());
  return groups;
}

// The observations of a group with the smallest and the largest `value`, in index
// order.
template <typename Value>
std::pair<std::size_t, std::size_t> Extremes(const std::vector<std::size_t>& group, Value value) {
  auto less = [&](std::size_t a, std::size_t b) { return value(a) < value(b); };
  // The first of each: with measurements alternating, the earliest pair.
  const std::size_t lo = *std::min_element(group.begin(), group.end(), less);
  const std::size_t hi = *std::max_element(group.begin(), group.end(), less);
  return std::minmax(lo, hi);
}

// Identical inputs whose measurements are further apart than the stated
// tolerances: one message per group of identical inputs, naming its two most
// different measurements.
void CheckContradictions(const Observations& o, Problems* p) {
  for (const std::vector<std::size_t>& group : SameInputGroups(o.throws, kThrowInputs)) {
    auto measured = [&](std::size_t i) { return o.throws[i].measured_throw; };
    const auto [i, j] = Extremes(group, measured);
    if (std::abs(measured(i) - measured(j)) <= kThrowContradiction) continue;
    std::ostringstream m;
    m << "throw[" << i << "] and throw[" << j << "] contradict: the same input, measured_throw = " << measured(i)
      << " and " << measured(j) << " rad (at most 0.0524 rad, 3 deg, apart)";
    p->Add(m.str());
  }
  for (const std::vector<std::size_t>& group : SameInputGroups(o.rebounds, kReboundInputs)) {
    auto speed = [&](std::size_t i) { return o.rebounds[i].rebound_speed; };
    std::vector<std::size_t> with_angle;
    for (std::size_t i : group) {
      if (o.rebounds[i].rebound_angle && std::isfinite(*o.rebounds[i].rebound_angle)) with_angle.push_back(i);
    }
    auto angle = [&](std::size_t i) { return *o.rebounds[i].rebound_angle; };
    std::ostringstream m;
    if (const auto [i, j] = Extremes(group, speed); std::abs(speed(i) - speed(j)) > kReboundSpeedContradiction) {
      m << "rebound[" << i << "] and rebound[" << j << "] contradict: the same input, rebound_speed = " << speed(i)
        << " and " << speed(j) << " m/s (at most 0.25 m/s apart)";
    } else if (with_angle.size() >= 2) {
      if (const auto [k, l] = Extremes(with_angle, angle); std::abs(angle(k) - angle(l)) > kReboundAngleContradiction) {
        m << "rebound[" << k << "] and rebound[" << l << "] contradict: the same input, rebound_angle = " << angle(k)
          << " and " << angle(l) << " rad (at most 0.0873 rad, 5 deg, apart)";
      }
    }
    if (m.tellp() > 0) p->Add(m.str());
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
