// Test helper: a single ball struck from a point, run by the full simulator, and
// where it passes a target after its cushions; used to measure the error of the
// mirror paths (cushion_paths_test.cc) and the rebound's noise (routes_test.cc).
#pragma once

#include <cmath>
#include <optional>
#include <span>
#include <vector>

#include "physics/core/shot.h"
#include "physics/sim/simulate.h"
#include "planner/geometry.h"

namespace snooker::planner::testing_roll {

struct Pass {
  /// Signed miss where the ball crosses the line through the target perpendicular
  /// to `along` (m, positive: the target on the ball's left); nullopt when it never
  /// crosses it after its cushions.
  std::optional<double> miss;
  /// The cushion segments it touched (kCushion events) before the crossing, and
  /// whether a knuckle or jaw wall was touched.
  std::vector<int> cushions;
  bool jaw = false;
};

class Roller {
 public:
  Roller() : sim_(physics::DefaultTable(), physics::SimParams{}) {}

  /// Strikes the ball at `start` along `heading` at `speed` with `topspin_fraction`
  /// of the rolling topspin and `sidespin` (rad/s); measures the crossing past
  /// `target` along the unit vector `along` after `cushions` cushion contacts.
  Pass Run(const physics::Vec2& start, double heading, double speed, const physics::Vec2& target,
           const physics::Vec2& along, int cushions, double topspin_fraction = 1.0, double sidespin = 0) {
    const double r = physics::DefaultTable().ball_radius();
    const physics::Shot shot{speed, heading, topspin_fraction * speed / r, sidespin};
    const physics::BallState b = physics::StruckBall(shot, start);
    sim_.Run(std::span<const physics::BallState>(&b, 1));
    Pass pass;
    double after = 0;
    int seen = 0;
    for (const physics::SimEvent& e : sim_.events()) {
      if (e.kind == physics::EventKind::kCushion && ++seen == cushions) {
        after = e.time;
        break;
      }
    }
    if (seen < cushions) return pass;
    const double end = sim_.end_time(), dt = 5e-4;
    auto past = [&](double t) { return (sim_.PositionAt(0, t) - target).dot(along) >= 0; };
    double prev = after;
    for (int k = 0; k < 100000 && after + k * dt <= end; ++k) {
      const double t = after + k * dt;
      if (past(t)) {
        double lo = prev, hi = t;
        for (int it = 0; it < 40; ++it) {
          const double mid = 0.5 * (lo + hi);
          (past(mid) ? hi : lo) = mid;
        }
        pass.miss = Cross(along, target - sim_.PositionAt(0, hi));
        for (const physics::SimEvent& e : sim_.events()) {
          if (e.time > hi) break;
          if (e.kind == physics::EventKind::kCushion) pass.cushions.push_back(e.where);
          if (e.kind == physics::EventKind::kKnuckle || e.kind == physics::EventKind::kJawWall) pass.jaw = true;
        }
        return pass;
      }
      prev = t;
    }
    return pass;
  }

  /// The heading within `half` (rad) of `nominal` whose path crosses exactly at the
  /// target, by bisection on the signed miss; nullopt when the miss does not change
  /// sign over the range or a run never crosses.
  std::optional<double> TrueHeading(const physics::Vec2& start, double nominal, double speed,
                                    const physics::Vec2& target, const physics::Vec2& along,
                                    int cushions, double half, double topspin_fraction = 1.0,
                                    double sidespin = 0) {
    auto miss = [&](double h) {
      return Run(start, h, speed, target, along, cushions, topspin_fraction, sidespin).miss;
    };
    double lo = nominal - half, hi = nominal + half;
    auto f_lo = miss(lo);
    const auto f_hi = miss(hi);
    if (!f_lo || !f_hi || (*f_lo < 0) == (*f_hi < 0)) return std::nullopt;
    for (int it = 0; it < 40; ++it) {
      const double mid = 0.5 * (lo + hi);
      const auto f = miss(mid);
      if (!f) return std::nullopt;
      if ((*f < 0) == (*f_lo < 0)) {
        lo = mid;
        f_lo = f;
      } else {
        hi = mid;
      }
    }
    return 0.5 * (lo + hi);
  }

 private:
  physics::Simulator sim_;
};

}  // namespace snooker::planner::testing_roll
