#include "physics/impact/impulse_solver.h"

namespace snooker::physics {

const char* ToString(ImpactStatus status) {
  switch (status) {
    case ImpactStatus::kOk: return "ok";
    case ImpactStatus::kNotApproaching: return "not approaching";
    case ImpactStatus::kInvalidInput: return "invalid input";
    case ImpactStatus::kStepLimit: return "step limit reached";
  }
  return "unknown";
}

}  // namespace snooker::physics
