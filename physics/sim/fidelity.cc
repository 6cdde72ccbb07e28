#include "physics/sim/fidelity.h"

#include <utility>

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
  const std::pair<ImpulseSolverOptions*, const ImpulseSolverOptions*> solvers[] = {
      {&base.ball_ball_solver, &defaults.ball_ball_solver},
      {&base.cushion_solver, &defaults.cushion_solver}};
  // The impact tables' errors are those of the solvers at the shot tolerance, so the
  // converged tier solves every impact.
  base.impact_tables = f != Fidelity::kReference && base.impact_tables;
  for (const auto& [o, d] : solvers) {
    switch (f) {
      case Fidelity::kReference:
        // At 1e-12 DOP853 takes about 1.5x fewer instructions a shot than 5(4)
        // (docs/impact-methods.md).
        o->fidelity = ImpulseFidelity::kExact;
        o->tolerance = 1e-12;
        o->method = ImpulseMethod::kDormandPrince853;
        break;
      case Fidelity::kDefault:
        o->fidelity = ImpulseFidelity::kExact;
        o->tolerance = d->tolerance;
        o->method = d->method;
        break;
      case Fidelity::kSearch: o->fidelity = ImpulseFidelity::kSearch; break;
    }
  }
  return base;
}

}  // namespace snooker::physics
