#include "cli/model_file.h"

#include "cli/json_input.h"
#include "server/model_convert.h"
#include "server/read_file.h"
#include "snooker/v1/physics_model.pb.h"

namespace snooker::cli {

std::string LoadModelFile(const std::string& path, physics::Model* model) {
  std::string text, why;
  const std::string where = "'" + path + "': ";
  if (!server::ReadInputFile(path, &text, &why)) return where + why;
  v1::PhysicsModel file;
  std::string error;
  if (!ReadJsonMessage(text, &file, &error)) return where + error;
  physics::Model m;
  if (std::string bad = server::ModelFromProto(file, &m); !bad.empty()) return where + bad;
  *model = m;
  return "";
}

bool ReadModelFile(const std::string& command, const std::string& flag, const std::string& path,
                   physics::Model* model, std::ostream& err) {
  if (std::string e = LoadModelFile(path, model); !e.empty()) {
    err << command << ": --" << flag << " " << e << "\n";
    return false;
  }
  return true;
}

std::optional<physics::Model> ModelFlag(Args& args, const std::string& command, std::ostream& err, bool* ok,
                                        const std::string& flag) {
  *ok = true;
  if (!args.Has(flag)) return std::nullopt;
  const auto path = args.Text(flag, std::nullopt);
  if (!path) return std::nullopt;  // args.error() says why
  physics::Model m;
  if (!ReadModelFile(command, flag, *path, &m, err)) {
    *ok = false;
    return std::nullopt;
  }
  return m;
}

}  // namespace snooker::cli
