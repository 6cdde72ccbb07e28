// State of a ball on the table (table frame: X across, Y along, Z up; see types.h).
#pragma once

#include <cstdint>

#include "physics/core/types.h"

namespace snooker::physics {

/// How a ball moves on the cloth; each has a closed-form motion (physics/motion/motion.h).
enum class MotionState : std::uint8_t {
  kStationary,  ///< at rest, no spin
  kSpinning,    ///< at rest, spinning about Z only
  kSliding,     ///< the contact point slips on the cloth
  kRolling,     ///< rolling without slip (Z spin may remain)
  kPocketed,    ///< fallen into a pocket; out of play
};

const char* ToString(MotionState s);

struct BallState {
  /// Centre position on the table, m (the centre is R above the cloth).
  Vec2 r = Vec2::Zero();
  /// Centre velocity, m/s. Z is kept for impacts; on the cloth it is zero.
  Vec3 v = Vec3::Zero();
  /// Angular velocity, rad/s.
  Vec3 w = Vec3::Zero();
  MotionState s = MotionState::kStationary;
};

}  // namespace snooker::physics
