// Fidelity tiers: how precisely a whole shot is simulated, as one knob a caller (the
// planner's search, its final check, a report) can turn. Each tier is a SimParams
// preset; its cost and its error against a converged reference are measured on the
// planner's workload, several-cushion shots and break-offs in
// docs/shot-speed-vs-error.md (scripts/shot-speed-error).
#pragma once

#include <cstdint>

#include "physics/sim/simulate.h"

namespace snooker::physics {

enum class Fidelity : std::uint8_t {
  /// Converged: impact integrators at 1e-12, every impact solved (no impact tables).
  /// For references and tests.
  kReference,
  /// SimParams' own: impact integrators at SimParams::kShotTolerance, set from the
  /// final positions it gives (within 0.1 mm of the reference on well-conditioned
  /// shots), and the impacts of rolling balls from the impact tables (within 0.25 mm
  /// with them; docs/shot-speed-vs-error.md).
  kDefault,
  /// For a search whose answers are checked at kDefault before anyone sees them: the
  /// impact solvers' ImpulseFidelity::kSearch (tolerance 1e-6, about 11 % fewer
  /// instructions than kDefault per shot; final positions within about 0.7 mm of the
  /// reference on well-conditioned shots).
  kSearch,
};

/// "reference", "default", "search".
const char* ToString(Fidelity f);

/// `base` with the impact integrators set for the tier (the rest of `base` kept).
SimParams FidelityParams(Fidelity f, SimParams base = {});

}  // namespace snooker::physics
