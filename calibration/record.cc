#include "calibration/record.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "physics/core/splitmix64.h"
#include "physics/table/table.h"

namespace snooker::calibration {
namespace {

using physics::Vec2;

// SplitMix64 (physics/core/splitmix64.h): small, fast, the same numbers everywhere.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  /// Uniform in [0, 1), 53 bits.
  double Uniform() { return physics::UnitInterval(physics::SplitMix64(state_)); }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  /// Standard normal (Box-Muller, one of the pair).
  double Normal() {
    const double u = 1.0 - Uniform();  // (0, 1]
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2 * physics::kPi * Uniform());
  }

 private:
  std::uint64_t state_;
};

void Require(bool ok, const char* name, double value, const char* rule) {
  if (ok) return;
  std::ostringstream m;
  m << name << " = " << value << " (must be " << rule << ")";
  throw std::invalid_argument(m.str());
}

void CheckArguments(const physics::Model& world, int shots, double noise, const RecordOptions& o) {
  const std::string bad = physics::ValidateModel(world);
  if (!bad.empty()) throw std::invalid_argument("world: " + bad);
  Require(shots >= 0 && shots <= kMaxRecordedShots, "shots", shots, "in [0, 100000]");
  Require(std::isfinite(noise) && noise >= 0 && noise <= 0.1, "vision_noise_m", noise, "in [0, 0.1] m");
  Require(std::isfinite(o.min_cue_speed) && o.min_cue_speed > 0, "min_cue_speed", o.min_cue_speed, "> 0 m/s");
  Require(std::isfinite(o.max_cue_speed) && o.max_cue_speed >= o.min_cue_speed && o.max_cue_speed <= kMaxSpeed,
          "max_cue_speed", o.max_cue_speed, "in [min_cue_speed, 10] m/s");
  Require(o.tip_reach >= 0 && o.tip_reach < 1, "tip_reach", o.tip_reach, "in [0, 1)");
  Require(o.max_elevation >= 0 && o.max_elevation < 0.5, "max_elevation", o.max_elevation, "in [0, 0.5) rad");
  Require(o.max_cut >= 0 && o.max_cut <= kMaxCut, "max_cut", o.max_cut, "in [0, 1.553] rad");
  Require(o.aimed_fraction >= 0 && o.aimed_fraction <= 1, "aimed_fraction", o.aimed_fraction, "in [0, 1]");
  Require(o.two_object_fraction >= 0 && o.two_object_fraction <= 1, "two_object_fraction", o.two_object_fraction,
          "in [0, 1]");
  Require(o.sighting_interval >= 1e-3 && o.sighting_interval <= 10, "sighting_interval", o.sighting_interval,
          "in [0.001, 10] s");
  Require(o.max_sightings >= 1 && o.max_sightings <= 10000, "max_sightings", o.max_sightings, "in [1, 10000]");
}

Vec2 Anywhere(Random& rng) {
  const physics::TableSpec& t = physics::DefaultTable().spec();
  return {rng.Uniform(kSceneMargin, t.width - kSceneMargin), rng.Uniform(kSceneMargin, t.length - kSceneMargin)};
}

bool Inside(const Vec2& r) {
  const physics::TableSpec& t = physics::DefaultTable().spec();
  return r.x() >= kSceneMargin && r.x() <= t.width - kSceneMargin && r.y() >= kSceneMargin &&
         r.y() <= t.length - kSceneMargin;
}

// The balls, cue ball first; false when no placement was found within the cap.
bool Scene(Random& rng, const RecordOptions& o, double radius, std::vector<Vec2>* balls) {
  balls->assign(1, Anywhere(rng));
  for (int tries = 0; tries < kMaxDraws && balls->size() < 2; ++tries) {
    const double d = rng.Uniform(0.25, 1.0), a = rng.Uniform(0, 2 * physics::kPi);
    const Vec2 r = balls->front() + d * physics::HeadingVector(a);
    if (Inside(r)) balls->push_back(r);
  }
  if (balls->size() < 2) return false;
  if (rng.Uniform() >= o.two_object_fraction) return true;
  for (int tries = 0; tries < kMaxDraws; ++tries) {
    const Vec2 r = Anywhere(rng);
    if ((r - (*balls)[0]).norm() > 6 * radius && (r - (*balls)[1]).norm() > 6 * radius) {
      balls->push_back(r);
      return true;
    }
  }
  return false;
}

// The strike: offsets and speed drawn, the heading aimed (or not) with the world's
// squirt allowed for. The shot's refusal by the world's cue is the caller's check.
physics::CueStrike DrawStrike(Random& rng, const RecordOptions& o, const physics::Model& world,
                              const std::vector<Vec2>& balls) {
  physics::CueStrike k;
  k.speed = rng.Uniform(o.min_cue_speed, o.max_cue_speed);
  const double reach = o.tip_reach * physics::MiscueLimit(world.cue) * std::sqrt(rng.Uniform());
  const double around = rng.Uniform(0, 2 * physics::kPi);
  k.side = reach * std::cos(around);
  k.height = reach * std::sin(around);
  k.elevation = rng.Uniform(0, o.max_elevation);
  double heading = rng.Uniform(-physics::kPi, physics::kPi);
  if (rng.Uniform() < o.aimed_fraction) {
    // Cut th on a ball at distance d: the path passes 2R sin th from its centre.
    const Vec2 to = balls[1] - balls[0];
    const double cut = rng.Uniform(-o.max_cut, o.max_cut);
    heading = std::atan2(to.y(), to.x()) + std::asin(2 * world.ball.radius * std::sin(cut) / to.norm());
  }
  physics::CueStrike straight = k;
  straight.heading = 0;
  const double squirt = physics::Strike(straight, world.cue, world.ball, world.cloth.g).squirt;
  k.heading = physics::RemainderTwoPi(heading - squirt);
  return k;
}

// Sighting times from interval dt until the first at or after `end` (s).
std::vector<Sighting> Schedule(double end, const RecordOptions& o) {
  const double dt = std::max(o.sighting_interval, end / o.max_sightings);
  const int count = std::max(1, static_cast<int>(std::ceil(end / dt - 1e-9)));
  std::vector<Sighting> s(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) s[static_cast<std::size_t>(k)].t = (k + 1) * dt;
  return s;
}

// One shot drawn and run; false when the strike is refused or the run hits a cap.
bool DrawShot(Random& rng, const physics::Model& world, double noise, const RecordOptions& o, TrackedShot* shot) {
  if (!Scene(rng, o, world.ball.radius, &shot->balls)) return false;
  shot->cue_ball = 0;
  shot->strike = DrawStrike(rng, o, world, shot->balls);
  shot->sightings.clear();
  const ShotPrediction run = PredictShot(*shot, world, o.numerics);
  if (!run.error.empty()) return false;
  shot->sightings = Schedule(run.end_time, o);
  const ShotPrediction seen = PredictShot(*shot, world, o.numerics);
  if (!seen.error.empty()) return false;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t j = 0; j < shot->sightings.size(); ++j) {
    Sighting& g = shot->sightings[j];
    g.positions = seen.positions[j];
    for (std::size_t b = 0; b < g.positions.size(); ++b) {
      if (g.t >= seen.pocketed_at[b]) {
        g.positions[b] = Vec2(nan, nan);
        continue;
      }
      g.positions[b] += noise * Vec2(rng.Normal(), rng.Normal());
    }
  }
  if (o.noisy_start) {
    for (Vec2& r : shot->balls) r += noise * Vec2(rng.Normal(), rng.Normal());
  }
  return true;
}

}  // namespace

std::vector<TrackedShot> Record(const physics::Model& world, int shots, std::uint64_t seed, double vision_noise_m,
                                const RecordOptions& options) {
  CheckArguments(world, shots, vision_noise_m, options);
  Random rng(seed);
  std::vector<TrackedShot> out(static_cast<std::size_t>(shots));
  for (TrackedShot& shot : out) {
    int draws = 0;
    while (!DrawShot(rng, world, vision_noise_m, options, &shot)) {
      if (++draws >= kMaxDraws) {
        throw std::runtime_error("Record: no acceptable shot in " + std::to_string(kMaxDraws) + " draws");
      }
    }
  }
  return out;
}

}  // namespace snooker::calibration
