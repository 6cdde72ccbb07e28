#include "physics/sim/fidelity.h"

namespace snooker::physics {

const char* ToString(Fidelity f) {
  switch (f) {
    case Fidelity::kReference: return "reference";
    case Fidelity::kDefault: return "default";
    case Fidelity::kSearch: return "search";
  }
  return "unknown";
}

SimParams FidelityParams(Fidelity f, SimParams base) {
  const SimParams defaults;
  double tolerance = defaults.cushion_solver.tolerance;
  switch (f) {
    case Fidelity::kReference: tolerance = 1e-12; break;
    case Fidelity::kDefault: break;
    // docs/shot-speed-vs-error.md: the loosest tolerance that keeps the planner
    // workload's final positions within about a millimetre of the reference.
    case Fidelity::kSearch: tolerance = 1e-7; break;
  }
  base.ball_ball_solver.tolerance = base.cushion_solver.tolerance = tolerance;
  return base;
}

}  // namespace snooker::physics
