// `--model FILE`: a table's physical model read from a model file (protobuf JSON of
// snooker.v1.PhysicsModel, physics_model.proto) over the default model. Shared by
// every command that simulates or plans.
#pragma once

#include <optional>
#include <ostream>
#include <string>

#include "cli/args.h"
#include "physics/model/model.h"

namespace snooker::cli {

/// The help line of the flag, for each command's --help.
inline constexpr const char* kModelFlagHelp =
    "  --model FILE       the physical model to use: a model file (JSON of\n"
    "                     snooker.v1.PhysicsModel, as `snooker model --json` prints\n"
    "                     and `snooker calibrate --out` writes); fields left out keep\n"
    "                     the default model's values (default: the default model)\n";

/// Reads the model file at `path` over the default model: "" or the reason
/// ("'m.json': line 2, column 3: ...", "'m.json': cloth.mu_s = -1 (must be in [0, 1])").
std::string LoadModelFile(const std::string& path, physics::Model* model);

/// Reads the model file at `path` over the default model. On failure returns false
/// and writes "<command>: <flag> '<path>': <reason>" to `err` (the file cannot be
/// read, is not JSON, or names a bad field and value).
bool ReadModelFile(const std::string& command, const std::string& flag, const std::string& path,
                   physics::Model* model, std::ostream& err);

/// The model of `--<flag> FILE` when given (std::nullopt when not); `*ok` false (and
/// the reason on `err`) when the file is bad.
std::optional<physics::Model> ModelFlag(Args& args, const std::string& command, std::ostream& err, bool* ok,
                                        const std::string& flag = "model");

}  // namespace snooker::cli
