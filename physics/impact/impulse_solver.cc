#include "physics/impact/impulse_solver.h"

#include <sstream>

#include "physics/core/limits.h"

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

bool FidelityValid(ImpulseFidelity fidelity) {
  return fidelity == ImpulseFidelity::kExact || fidelity == ImpulseFidelity::kSearch;
}

std::string ValidateFidelity(ImpulseFidelity fidelity) {
  if (FidelityValid(fidelity)) return "";
  return "fidelity = " + std::to_string(static_cast<int>(fidelity)) +
         " (must be kExact (0) or kSearch (1))";
}

bool SpeedScaleValid(double scale) { return scale <= limits::kMaxImpactSpeedScale; }

std::string ValidateSpeedScale(double scale, const char* what) {
  if (SpeedScaleValid(scale)) return "";
  std::ostringstream m;
  m << "speed scale = " << scale << " m/s (" << what << " must be at most " << limits::kMaxImpactSpeedScale
    << " m/s)";
  return m.str();
}

bool MethodValid(ImpulseMethod method) {
  return method == ImpulseMethod::kDormandPrince54 || method == ImpulseMethod::kDormandPrince853;
}

std::string ValidateMethod(ImpulseMethod method) {
  if (MethodValid(method)) return "";
  return "method = " + std::to_string(static_cast<int>(method)) +
         " (must be kDormandPrince54 (0) or kDormandPrince853 (1))";
}

ImpulseSolverOptions EffectiveOptions(const ImpulseSolverOptions& options) {
  ImpulseSolverOptions o = options;
  if (o.fidelity == ImpulseFidelity::kSearch) {
    o.integrator = ImpulseIntegrator::kAdaptive;
    o.tolerance = kSearchTolerance;
    o.method = ImpulseMethod::kDormandPrince54;  // the cheaper pair at that tolerance
  }
  return o;
}

}  // namespace snooker::physics
