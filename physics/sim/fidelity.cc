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
  for (ImpulseSolverOptions* o : {&base.ball_ball_solver, &base.cushion_solver}) {
    switch (f) {
      case Fidelity::kReference:
        o->fidelity = ImpulseFidelity::kExact;
        o->tolerance = 1e-12;
        break;
      case Fidelity::kDefault:
        o->fidelity = ImpulseFidelity::kExact;
        o->tolerance = defaults.ball_ball_solver.tolerance;
        break;
      case Fidelity::kSearch: o->fidelity = ImpulseFidelity::kSearch; break;
    }
  }
  return base;
}

}  // namespace snooker::physics
