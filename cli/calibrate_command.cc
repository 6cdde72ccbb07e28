// `snooker calibrate` (fit the physical model to observations of a table) and
// `snooker record` (tracked shots made in a world model with vision-like noise: test
// data, and the reference of the tracked-shot format).
#include <iomanip>
#include <iostream>
#include <stdexcept>

#include <google/protobuf/util/json_util.h>

#include "calibration/record.h"
#include "cli/args.h"
#include "cli/commands.h"
#include "cli/json.h"
#include "cli/json_input.h"
#include "cli/model_file.h"
#include "cli/write_file.h"
#include "server/calibrate_api.h"
#include "server/model_convert.h"
#include "server/read_file.h"

namespace snooker::cli {
namespace {

constexpr const char* kCalibrateHelp = R"(usage: snooker calibrate --data FILE [FILE...] --fit GROUPS [--model START.json]
                         [--max-evaluations N] [--json] [--out MODEL.json]

Fits the physical model to observations of a table: a bounded least-squares fit
(NLopt's BOBYQA, derivative-free) of the groups asked for, every other value held.
Prints each fitted value with its standard uncertainty (from the residual Jacobian
at the optimum) and the residuals before and after, and writes the fitted model.

  --data FILE...          observation files (JSON of snooker.v1.Observations:
                          {"throw": [...], "cushion": [...], "tracked": [...]});
                          several are merged
  --fit GROUPS            comma-separated: ball-ball (the friction law
                          mu(s) = a + b exp(-c s)), cushion (nose friction and the
                          restitution the rebounds cover), cloth (sliding and
                          rolling friction, spin decay), cue (end mass, tip
                          restitution). Data that cannot identify a group asked
                          for is refused, with the reason.
  --model START.json      the model the fit starts from and keeps (default: the
                          default model)
  --max-evaluations N     cap on model evaluations (10 to 100000; default 4000: a fit of
                          200 tracked shots converges in about 2000)
  --json                  print the answer as JSON (snooker.v1.CalibrateResponse):
                          "model", "parameters" [{"name", "unit", "start", "value",
                          "uncertainty" (-1: not determined), "atBound"}],
                          "residuals" [{"kind", "unit", "count", "rmsBefore",
                          "rmsAfter"}], "evaluations"
  --out MODEL.json        write the fitted model as a model file (--model FILE of
                          every other command reads it)
  --help                  this text
)";

constexpr const char* kRecordHelp = R"(usage: snooker record --world W.json --shots N --seed S [--vision-noise-mm X]
                      --out TRACKED.json

Plays N random shots on a table whose physics is the model file W.json (random
scenes of the cue ball and one or two object balls, strikes in the cue's terms,
mostly aimed at a ball), and writes what a vision system would see: every ball's
position every 0.1 s until all rest, with Gaussian noise of X mm per coordinate.
The output is an observations file for snooker calibrate ("tracked" shots). The
same arguments give the same file.

  --world W.json          the table's model (a model file; "default": the default)
  --shots N               shots, 1 to 100000
  --seed S                random seed
  --vision-noise-mm X     vision noise per coordinate, mm (default 1, 0 to 50)
  --out TRACKED.json      where to write
  --help                  this text
)";

// The words after --data, up to the next flag, taken out of `argv`.
std::vector<std::string> TakeDataFiles(std::vector<std::string>* argv) {
  std::vector<std::string> files, rest;
  for (std::size_t i = 0; i < argv->size(); ++i) {
    if ((*argv)[i] != "--data") {
      rest.push_back((*argv)[i]);
      continue;
    }
    while (i + 1 < argv->size() && (*argv)[i + 1].rfind("--", 0) != 0) files.push_back((*argv)[++i]);
  }
  *argv = rest;
  return files;
}

bool ReadObservations(const std::vector<std::string>& files, v1::Observations* all, std::ostream& err) {
  for (const std::string& path : files) {
    std::string text, why;
    if (!server::ReadInputFile(path, &text, &why)) {
      err << "snooker calibrate: --data '" << path << "': " << why << "\n";
      return false;
    }
    v1::Observations one;
    if (!ReadJsonMessage(text, &one, &why)) {
      err << "snooker calibrate: --data '" << path << "': " << why << "\n";
      return false;
    }
    all->MergeFrom(one);
  }
  return true;
}

void PrintFit(const v1::CalibrateResponse& r, std::ostream& out) {
  out << std::setprecision(5) << "parameter" << std::string(24, ' ') << "start        fitted       uncertainty\n";
  for (const v1::FittedParameter& p : r.parameters()) {
    out << std::left << std::setw(33) << p.name() << std::setw(13) << p.start() << std::setw(13) << p.value();
    // -1: the data do not determine it at the optimum (calibrate.proto).
    if (p.uncertainty() < 0) {
      out << "undetermined";
    } else {
      out << "+- " << p.uncertainty() << (p.unit().empty() ? "" : " " + p.unit());
    }
    out << (p.at_bound() ? "  (at its bound)" : "") << std::right << "\n";
  }
  out << "\nresiduals (rms)                  before       after\n";
  for (const v1::ResidualSummary& s : r.residuals()) {
    out << std::left << std::setw(33) << (s.kind() + " (" + std::to_string(s.count()) + ", " + s.unit() + ")")
        << std::setw(13) << s.rms_before() << s.rms_after() << std::right << "\n";
  }
  out << "\nmodel evaluations: " << r.evaluations() << "\n";
}

bool WriteJson(const google::protobuf::Message& m, const std::string& path, const char* command, std::ostream& err) {
  std::string json;
  google::protobuf::util::JsonPrintOptions o;
  o.add_whitespace = true;
  if (!google::protobuf::util::MessageToJsonString(m, &json, o).ok()) {
    err << command << ": cannot write JSON\n";
    return false;
  }
  return WriteOutputFile(path, json, command, err);
}

}  // namespace

int RunCalibrate(const std::vector<std::string>& argv_in, std::ostream& out, std::ostream& err) {
  std::vector<std::string> argv = argv_in;
  const std::vector<std::string> files = TakeDataFiles(&argv);
  Args args(argv, {"fit", "model", "max-evaluations", "out"}, {"json", "help"});
  if (args.error().empty() && args.Switch("help")) {
    out << kCalibrateHelp;
    return kExitOk;
  }
  const auto groups = args.Text("fit", std::nullopt);
  const auto evaluations = args.Integer("max-evaluations", 4000, 10, 100000);
  const auto out_path = args.Text("out", "");
  bool model_ok = true;
  const std::optional<physics::Model> start = ModelFlag(args, "snooker calibrate", err, &model_ok);
  if (!model_ok) return kExitUsage;
  if (args.error().empty() && files.empty()) {
    err << "snooker calibrate: --data needs at least one file\n(see snooker calibrate --help)\n";
    return kExitUsage;
  }
  if (!args.error().empty()) {
    err << "snooker calibrate: " << args.error() << "\n(see snooker calibrate --help)\n";
    return kExitUsage;
  }
  v1::CalibrateRequest req;
  if (!ReadObservations(files, req.mutable_observations(), err)) return kExitUsage;
  req.add_fit(*groups);
  req.set_max_evaluations(static_cast<int>(*evaluations));
  server::CallLimits limits;
  if (start) limits.model = &*start;
  v1::CalibrateResponse resp;
  const server::ApiStatus status = server::Calibrate(req, &resp, limits);
  if (!status.ok()) {
    err << "snooker calibrate: " << status.message << "\n";
    return status.code == server::ApiStatus::Code::kInvalidArgument ? kExitUsage : kExitFailure;
  }
  if (!out_path->empty() && !WriteJson(resp.model(), *out_path, "snooker calibrate", err)) return kExitFailure;
  if (args.Switch("json")) return PrintJson(resp, "snooker calibrate", out, err) ? kExitOk : kExitFailure;
  PrintFit(resp, out);
  if (!out_path->empty()) out << "fitted model written to " << *out_path << "\n";
  return kExitOk;
}

int RunRecord(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args(argv, {"world", "shots", "seed", "vision-noise-mm", "out"}, {"help"});
  if (args.error().empty() && args.Switch("help")) {
    out << kRecordHelp;
    return kExitOk;
  }
  const auto world_path = args.Text("world", std::nullopt);
  const auto shots = args.Integer("shots", std::nullopt, 1, calibration::kMaxRecordedShots);
  const auto seed = args.Unsigned64("seed", std::nullopt);
  const auto noise = args.Number("vision-noise-mm", 1.0);
  const auto out_path = args.Text("out", std::nullopt);
  if (args.error().empty() && !(*noise >= 0 && *noise <= 50)) {
    err << "snooker record: --vision-noise-mm " << *noise << " is outside [0, 50]\n";
    return kExitUsage;
  }
  if (!args.error().empty()) {
    err << "snooker record: " << args.error() << "\n(see snooker record --help)\n";
    return kExitUsage;
  }
  physics::Model world;
  if (*world_path != "default" && !ReadModelFile("snooker record", "world", *world_path, &world, err)) {
    return kExitUsage;
  }
  calibration::Observations recorded;
  recorded.shots = calibration::Record(world, static_cast<int>(*shots), *seed, *noise * 1e-3);
  v1::Observations file;
  server::ObservationsToProto(recorded, &file);
  if (!WriteJson(file, *out_path, "snooker record", err)) return kExitFailure;
  std::size_t sightings = 0;
  for (const calibration::TrackedShot& s : recorded.shots) sightings += s.sightings.size();
  out << "recorded " << recorded.shots.size() << " tracked shots (" << sightings << " sightings) to " << *out_path
      << "\n";
  return kExitOk;
}

}  // namespace snooker::cli
