#include "physics/core/ball_state.h"

namespace snooker::physics {

const char* ToString(MotionState s) {
  switch (s) {
    case MotionState::kStationary: return "stationary";
    case MotionState::kSpinning: return "spinning";
    case MotionState::kSliding: return "sliding";
    case MotionState::kRolling: return "rolling";
    case MotionState::kPocketed: return "pocketed";
  }
  return "unknown";
}

}  // namespace snooker::physics
