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
  /// Converged: impact integrators at 1e-12. For references and tests.
  kReference,
  /// What SimParams defaults to: final positions within a fraction of a millimetre
  /// of the reference on the planner's workload (the measured figure is in the doc).
  kDefault,
  /// The cheapest setting whose final positions stay within about a millimetre of the
  /// reference on the planner's workload: for a search whose answers are checked at
  /// kDefault before anyone sees them.
  kSearch,
};

/// "reference", "default", "search".
const char* ToString(Fidelity f);

/// `base` with the impact integrators set for the tier (the rest of `base` kept).
SimParams FidelityParams(Fidelity f, SimParams base = {});

}  // namespace snooker::physics
