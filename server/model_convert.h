// The physical model (physics/model/model.h) in API form (physics_model.proto): the
// model file that `--model FILE` reads and `snooker model` / `snooker calibrate`
// write, and GetModel's `physics`.
#pragma once

#include <optional>
#include <string>

#include "physics/model/model.h"
#include "snooker/v1/physics_model.pb.h"

namespace snooker::server {

/// Sets in `*model` every field `file` gives (the rest keeps its value) and checks
/// the result. Returns "" when valid, otherwise a sentence naming each bad field and
/// value ("cloth.mu_s = -1 (must be in [0, 1])"); `*model` is then unspecified.
std::string ModelFromProto(const v1::PhysicsModel& file, physics::Model* model);

/// Every field of `model` (the restitution curve's knots when it has one).
void ModelToProto(const physics::Model& model, v1::PhysicsModel* out);

/// The library's law for an API value; nullopt for UNSPECIFIED and for values not
/// listed (the callers keep a base law or name the bad value).
std::optional<physics::BallBallFrictionLaw> FrictionLawFromProto(int law);

/// "constant", "marlow", "exponential" or "exponential-impact-speed".
const char* FrictionLawName(physics::BallBallFrictionLaw law);

}  // namespace snooker::server
