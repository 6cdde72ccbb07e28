#include "physics/cue/strike.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace snooker::physics {

const char* ToString(StrikeStatus s) {
  switch (s) {
    case StrikeStatus::kOk: return "ok";
    case StrikeStatus::kMiscue: return "miscue";
    case StrikeStatus::kHop: return "hop";
    case StrikeStatus::kInvalid: return "invalid";
  }
  return "?";
}

double MiscueLimit(const CueParams& cue) { return std::sin(std::atan(cue.tip_friction)); }

double SquirtAngle(double side, const CueParams& cue, const BallParams& ball) {
  const double a = std::abs(side);
  if (!(a < 1)) return 0;
  return std::atan(2.5 * a * std::sqrt(1 - a * a) / (1 + ball.mass / cue.end_mass + 2.5 * (1 - a * a)));
}

StrikeResult Strike(const CueStrike& k, const CueParams& cue, const BallParams& ball, double gravity) {
  StrikeResult out;
  const double offset2 = k.side * k.side + k.height * k.height;
  if (!std::isfinite(k.speed) || k.speed < 0 || !std::isfinite(k.heading) || !std::isfinite(offset2) ||
      !(k.elevation >= 0) || !(k.elevation < 0.5 * kPi) || !(offset2 < 1)) {
    return out;
  }
  const double R = ball.radius, m = ball.mass;
  const double ce = std::cos(k.elevation), se = std::sin(k.elevation);
  const double ch = std::cos(k.heading), sh = std::sin(k.heading);
  const Vec3 d(ce * ch, ce * sh, -se);
  const Vec3 s(sh, -ch, 0);
  const Vec3 u = s.cross(d);
  const double c = std::sqrt(1 - offset2);  // of R
  const Vec3 r = R * (k.side * s + k.height * u - c * d);

  const double J = (1 + cue.tip_restitution) * m * k.speed / (1 + m / cue.mass + 2.5 * offset2);
  const double Fs = -2.5 * k.side * c * J / (1 + m / cue.end_mass + 2.5 * (1 - k.side * k.side));
  const Vec3 F = J * d + Fs * s;
  out.axial_impulse = J;
  out.lateral_impulse = Fs;
  out.v = F / m;
  out.w = r.cross(F) / ball.Inertia();

  // The bed takes the downward part; the rest is the shot.
  const double v_down = std::max(0.0, -out.v.z());
  const double rise = cue.bed_restitution * v_down;
  out.hop = gravity > 0 ? rise * rise / (2 * gravity) : 0;
  const Vec2 vh(out.v.x(), out.v.y());
  const double speed = vh.norm();
  const double heading = speed > 0 ? std::atan2(vh.y(), vh.x()) : k.heading;
  const Vec3 h(std::cos(heading), std::sin(heading), 0);
  const Vec3 left(-h.y(), h.x(), 0);
  out.shot.speed = speed;
  out.shot.heading = heading;
  out.shot.topspin = out.w.dot(left);
  out.shot.sidespin = out.w.z();
  out.shot.swerve_spin = out.w.dot(h);
  out.squirt = RemainderTwoPi(heading - k.heading);

  out.status = std::sqrt(offset2) > MiscueLimit(cue) ? StrikeStatus::kMiscue
               : out.hop > cue.max_hop              ? StrikeStatus::kHop
                                                    : StrikeStatus::kOk;
  return out;
}

std::optional<CueStrike> StrikeFor(const Shot& shot, double elevation, const CueParams& cue,
                                   const BallParams& ball, double gravity) {
  if (!std::isfinite(shot.speed) || !(shot.speed > 0) || !std::isfinite(shot.topspin) ||
      !std::isfinite(shot.sidespin) || !std::isfinite(shot.heading)) {
    return std::nullopt;
  }
  const double R = ball.radius;
  // Spins per unit speed: what the offsets alone decide (the strike is linear in
  // the cue's speed and turns with its heading).
  const double want_t = shot.topspin * R / shot.speed, want_s = shot.sidespin * R / shot.speed;
  auto spins = [&](double side, double height) {
    CueStrike k{1.0, 0.0, side, height, elevation};
    const StrikeResult res = Strike(k, cue, ball, gravity);
    return std::array<double, 3>{res.shot.topspin * R / res.shot.speed, res.shot.sidespin * R / res.shot.speed,
                                 res.shot.speed};
  };
  // A level strike without squirt gives w R / v = 5/2 offset: the first guess.
  double side = want_s / 2.5, height = want_t / 2.5;
  const double limit = MiscueLimit(cue);
  constexpr double kStep = 1e-7;
  bool converged = false;
  for (int it = 0; it < 30; ++it) {
    if (!(side * side + height * height < 0.98)) return std::nullopt;
    const auto f = spins(side, height);
    const double et = f[0] - want_t, es = f[1] - want_s;
    if (std::abs(et) < 1e-12 && std::abs(es) < 1e-12) {
      converged = true;
      break;
    }
    const auto fs = spins(side + kStep, height), fh = spins(side, height + kStep);
    // Jacobian of (topspin, sidespin) per unit speed in (side, height).
    const double j11 = (fs[0] - f[0]) / kStep, j12 = (fh[0] - f[0]) / kStep;
    const double j21 = (fs[1] - f[1]) / kStep, j22 = (fh[1] - f[1]) / kStep;
    const double det = j11 * j22 - j12 * j21;
    if (!(std::abs(det) > 1e-12)) return std::nullopt;
    side -= (j22 * et - j12 * es) / det;
    height -= (-j21 * et + j11 * es) / det;
  }
  if (!converged || std::hypot(side, height) > limit) return std::nullopt;
  const StrikeResult unit = Strike(CueStrike{1.0, 0.0, side, height, elevation}, cue, ball, gravity);
  CueStrike k;
  k.speed = shot.speed / unit.shot.speed;
  k.heading = RemainderTwoPi(shot.heading - unit.squirt);
  k.side = side;
  k.height = height;
  k.elevation = elevation;
  return k;
}

}  // namespace snooker::physics
