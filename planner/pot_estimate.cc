#include "planner/pot_estimate.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace snooker::planner {

using physics::Vec2;

NoiseModel BallTermsNoise(const NoiseModel& noise, const physics::CueParams& cue, const physics::BallParams& ball,
                          double speed) {
  NoiseModel out = noise;
  const double R = ball.radius;
  // Squirt per unit of side offset at the centre: d alpha / d side.
  const double squirt_rate = 2.5 / (1 + ball.mass / cue.end_mass + 2.5);
  const double spin = 2.5 * speed * noise.tip_offset / (R * R);
  out.heading = std::hypot(noise.heading, noise.aim, squirt_rate * noise.tip_offset / R);
  out.speed_fraction = std::hypot(noise.speed_fraction, noise.cue_speed_fraction);
  out.topspin = std::hypot(noise.topspin, spin);
  out.sidespin = std::hypot(noise.sidespin, spin);
  return out;
}

double NormalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

double WindowProbability(double mean, double sigma, const PocketWindow& window) {
  if (window.empty) return 0;
  if (!(sigma > 0)) return mean >= window.lo && mean <= window.hi ? 1.0 : 0.0;
  return std::max(0.0, NormalCdf((window.hi - mean) / sigma) - NormalCdf((window.lo - mean) / sigma));
}

double HeadingGain(const Vec2& cue, const Vec2& object, double heading, double cut, double distance,
                   double radius) {
  const Vec2 u(std::cos(heading), std::sin(heading));
  const double cos_c = std::max(std::cos(cut), 1e-3);
  return std::abs(distance * (1 - u.dot(object - cue) / (2 * radius * cos_c)));
}

double SquirtSigma(double squirt, double heading_gain, const NoiseModel& noise) {
  return noise.squirt_fraction * std::abs(squirt) * heading_gain;
}

double ThrowSigma(double throw_angle, double distance, const NoiseModel& noise) {
  return noise.throw_fraction * std::abs(throw_angle) * distance;
}

double LateralSigma(const Vec2& cue, const Vec2& object, double heading, double cut,
                    double distance, double contact_speed, double cue_sigma, double object_sigma,
                    const NoiseModel& noise, const ThrowModel& throws, double radius) {
  const double cos_c = std::max(std::cos(cut), 1e-3);
  const double k = distance / (2 * radius * cos_c);
  const double heading_gain = HeadingGain(cue, object, heading, cut, distance, radius);
  const ThrowSensitivity t = throws.At(cut, contact_speed);
  auto sq = [](double x) { return x * x; };
  const double throw_var = sq(t.per_sidespin * noise.sidespin) + sq(t.per_topspin * noise.topspin) +
                           sq(t.per_log_speed * noise.speed_fraction);
  const double var = sq(noise.heading * heading_gain) + sq(cue_sigma * k) +
                     sq(object_sigma) * (k * k + 1 + 2 * k * cos_c) + sq(distance) * throw_var;
  return std::sqrt(var);
}

double TypicalContactSpeed(double distance, double cut) {
  constexpr double kArrival = kTypicalArrivalSpeed;
  constexpr double kRollDecel = 0.1256;  // mu_r g, m/s^2
  constexpr double kTransfer = 0.9;      // object speed / cue speed along the line, full ball
  constexpr double kSlide = 5.0 / 7.0;   // the object ball leaves sliding, rolls at 5/7
  const double v_object = std::sqrt(kArrival * kArrival + 2 * kRollDecel * distance) / kSlide;
  return std::clamp(v_object / (kTransfer * std::max(std::cos(cut), 0.2)), 0.5, 5.0);
}

std::optional<PocketLine> LineIntoPocket(const PocketModel& pockets, const Vec2& from, physics::PocketId pocket,
                                         double arrival_speed) {
  const physics::Pocket& p = pockets.table().pocket(pocket);
  const Vec2 q = p.mouth_centre - from;
  const double l0 = q.norm();
  PocketLine line;
  // A ball past the mouth's line, on this pocket's lip: the line in is the pocket's
  // axis, straight in (the mouth's centre is behind it). Balls on the bed keep the line
  // through the mouth's window.
  if (q.dot(p.axis) < 0 && pockets.table().PocketMouthAt(from) == pocket) {
    line.direction = Direction(p.axis);
    line.window = pockets.Window(pocket, line.direction, arrival_speed);
    if (line.window.empty) return std::nullopt;
    line.distance = std::max(0.0, q.dot(p.axis));
    return line;
  }
  if (!(l0 > 0)) return std::nullopt;
  // The line whose offset at the mouth is the window's centre: offset =
  // -l0 sin(phi_q - theta).
  double theta = Direction(q);
  for (int pass = 0; pass < 2; ++pass) {
    line.window = pockets.Window(pocket, theta, arrival_speed);
    if (line.window.empty) return std::nullopt;
    const double s = line.window.centre() / l0;
    if (std::abs(s) >= 1) return std::nullopt;
    theta = Direction(q) + std::asin(s);
  }
  line.direction = theta;
  line.distance = l0 * std::cos(std::asin(line.window.centre() / l0));
  return line;
}

std::optional<PocketLine> PocketLineCache::Line(const PocketModel& pockets, const Vec2& from,
                                                physics::PocketId pocket, double arrival_speed) {
  const int k = static_cast<int>(pocket);
  const std::uint64_t model = pockets.serial();
  // The key's bits mixed (splitmix64's multipliers), the set from the top bits.
  std::uint64_t h = std::bit_cast<std::uint64_t>(from.x()) * 0x9E3779B97F4A7C15ull;
  h = (h ^ (h >> 31) ^ std::bit_cast<std::uint64_t>(from.y())) * 0xBF58476D1CE4E5B9ull;
  h = (h ^ (h >> 29) ^ std::bit_cast<std::uint64_t>(arrival_speed) ^ static_cast<std::uint64_t>(k)) *
      0x94D049BB133111EBull;
  Set& set = sets_[static_cast<std::size_t>(h >> (64 - kSetBits))];
  for (std::size_t i = 0; i < set.ways.size(); ++i) {
    if (set.hashes[i] != h) continue;
    const Entry& e = set.ways[i];
    if (e.model == model && e.pocket == k && e.x == from.x() && e.y == from.y() && e.speed == arrival_speed) {
      ++hits_;
      return e.line;
    }
  }
  ++misses_;
  const auto way = static_cast<std::size_t>(set.next);
  set.next = (set.next + 1) % kWays;
  set.hashes[way] = h;
  Entry& e = set.ways[way];
  e.model = model;
  e.x = from.x();
  e.y = from.y();
  e.speed = arrival_speed;
  e.pocket = k;
  e.line = LineIntoPocket(pockets, from, pocket, arrival_speed);
  return e.line;
}

std::optional<PotEstimate> EstimatePot(const Vec2& cue, const Vec2& object, physics::PocketId pocket,
                                       double cue_sigma, double object_sigma,
                                       const NoiseModel& noise, const PocketModel& pockets,
                                       const ThrowModel& throws, double arrival_speed) {
  const auto line = LineIntoPocket(pockets, object, pocket, arrival_speed);
  if (!line) return std::nullopt;
  return EstimatePotAlong(*line, cue, object, pocket, cue_sigma, object_sigma, noise, pockets, throws);
}

std::optional<PotEstimate> EstimatePotAlong(const PocketLine& line, const Vec2& cue, const Vec2& object,
                                            physics::PocketId pocket, double cue_sigma, double object_sigma,
                                            const NoiseModel& noise, const PocketModel& pockets,
                                            const ThrowModel& throws) {
  const double radius = pockets.table().ball_radius();
  const double theta = line.direction;
  PotEstimate e;
  e.window = line.window;
  const auto aim = AimAlong(cue, object, theta, radius);
  if (!aim) return std::nullopt;
  e.aim = *aim;
  e.object_direction = theta;
  e.approach = pockets.Approach(pocket, theta);
  e.distance = line.distance;
  const double contact = TypicalContactSpeed(e.distance, e.aim.cut);
  e.sigma = LateralSigma(cue, object, e.aim.heading, e.aim.cut, e.distance, contact, cue_sigma,
                         object_sigma, noise, throws, radius);
  e.probability = WindowProbability(e.window.centre(), e.sigma, e.window);
  return e;
}

}  // namespace snooker::planner
