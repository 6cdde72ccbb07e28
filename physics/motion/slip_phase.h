// The slip phase after an impact (Mathavan et al. 2014, section 2.5), in closed form.
//
// On the cloth a sliding ball's contact slip u = v + w x (-R z) keeps its direction
// and shrinks at (7/2) mu_s g, so the slip ends at T_s = 2|u| / (7 mu_s g) (eq. 19,
// with the g the print drops) with centre velocity v_S = v - (2/7) u; meanwhile the
// centre moves on a parabola with constant acceleration -mu_s g u/|u| (the curved
// "masse" path of the paper's Fig. 6). Spin about Z decays at wdot_r (eq. 21).
//
// A vertical velocity left by the impact (a small "jump", paper section 2.2) is
// dropped here: the ball is taken to stay on the cloth, as the paper's slip
// analysis does. The table simulation states its own choice.
#pragma once

#include "physics/core/params.h"
#include "physics/core/types.h"

namespace snooker::physics {

struct SlipEnd {
  /// Centre velocity when the slip ends (horizontal), m/s, in the input's frame.
  Vec2 velocity = Vec2::Zero();
  /// |velocity|, m/s (v_S of eq. 20a).
  double speed = 0;
  /// Time from the impact to the end of the slip, T_s. s.
  double time = 0;
  /// Centre displacement during the slip. m.
  Vec2 displacement = Vec2::Zero();
  /// Spin about Z at the end of the slip (eq. 21). rad/s.
  double sidespin = 0;
};

/// Horizontal slip of the ball's contact point on the cloth, v + w x (-R z). m/s.
Vec2 ClothSlip(const BallMotion& m, double radius);

/// Spin about Z after `t` seconds of decay at `spin_decel` (eq. 21). rad/s.
double SpinAfter(double wz, double spin_decel, double t);

/// Where the slip phase that starts from `m` ends.
SlipEnd SlipPhaseEnd(const BallMotion& m, const BallParams& ball, const ClothParams& cloth);

/// Unsigned angle between two horizontal directions, in [0, pi]. rad. Zero if
/// either vector is zero.
double AngleBetween(const Vec2& a, const Vec2& b);

}  // namespace snooker::physics
