#include "cli/play_flags.h"

#include <sstream>

#include "cli/model_file.h"
#include "planner/limits.h"

namespace snooker::cli {

std::string ReadPlayFlags(Args& args, const PlayFlags& defaults, PlayFlags* out) {
  namespace lim = planner::limits;
  const auto budget = args.Number("budget-ms", defaults.budget_ms);
  const auto heading = args.Number("noise-heading-deg", physics::RadToDeg(defaults.noise.heading));
  const auto speed = args.Number("noise-speed", defaults.noise.speed_fraction);
  const auto spin = args.Number("noise-spin", defaults.noise.topspin);
  const auto position = args.Number("noise-position-mm", defaults.noise.position * 1e3);
  const auto clearance = args.Number("cue-clearance-m", defaults.limits.cue.length);
  const auto aim = args.Number("noise-aim-deg", physics::RadToDeg(defaults.noise.aim));
  const auto cue_speed = args.Number("noise-cue-speed", defaults.noise.cue_speed_fraction);
  const auto tip = args.Number("noise-tip-mm", defaults.noise.tip_offset * 1e3);
  const auto elevation = args.Number("noise-elevation-deg", physics::RadToDeg(defaults.noise.elevation));
  const auto squirt = args.Number("squirt-uncertainty", defaults.noise.squirt_fraction);
  const auto throws = args.Number("throw-uncertainty", defaults.noise.throw_fraction);
  const auto max_elevation = args.Number("max-elevation-deg", physics::RadToDeg(defaults.limits.cue.max_elevation));
  const auto sims = args.Integer("max-simulations", defaults.max_simulations, lim::kMaxSimulations.lo,
                                 lim::kMaxSimulations.hi);
  const auto samples = args.Integer("samples", defaults.monte_carlo_samples, lim::kMonteCarloSamples.lo,
                                    lim::kMonteCarloSamples.hi);
  const auto threads = args.Integer("threads", defaults.threads, lim::kThreads.lo, lim::kThreads.hi);
  const std::optional<double> break_value =
      args.Has("break-value") ? args.Number("break-value", std::nullopt) : defaults.break_value;
  const std::optional<double> position_spread =
      args.Has("position-spread") ? args.Number("position-spread", std::nullopt) : defaults.position_spread;
  if (!args.error().empty()) return args.error();
  auto range = [](const char* flag, double x, double lo, double hi) -> std::string {
    if (x >= lo && x <= hi) return "";
    std::ostringstream s;
    s << "--" << flag << " " << x << " is out of range [" << lo << ", " << hi << "]";
    return s.str();
  };
  for (const std::string& e :
       {range("budget-ms", *budget, lim::kTimeBudget.lo * 1e3, lim::kTimeBudget.hi * 1e3),
        range("noise-heading-deg", *heading, 0, physics::RadToDeg(lim::kHeadingSigma.hi)),
        range("noise-speed", *speed, 0, lim::kSpeedSigmaFraction.hi), range("noise-spin", *spin, 0, lim::kSpinSigma.hi),
        range("noise-position-mm", *position, 0, lim::kPositionSigma.hi * 1e3),
        range("cue-clearance-m", *clearance, 0, lim::kCueClearance.hi),
        range("noise-aim-deg", *aim, 0, physics::RadToDeg(lim::kHeadingSigma.hi)),
        range("noise-cue-speed", *cue_speed, 0, lim::kSpeedSigmaFraction.hi),
        range("noise-tip-mm", *tip, 0, lim::kTipOffsetSigma.hi * 1e3),
        range("noise-elevation-deg", *elevation, 0, physics::RadToDeg(lim::kElevationSigma.hi)),
        range("squirt-uncertainty", *squirt, 0, lim::kModelUncertainty.hi),
        range("throw-uncertainty", *throws, 0, lim::kModelUncertainty.hi),
        range("max-elevation-deg", *max_elevation, 0, physics::RadToDeg(lim::kMaxElevation.hi)),
        break_value ? range("break-value", *break_value, lim::kBreakValue.lo, lim::kBreakValue.hi) : "",
        position_spread
            ? range("position-spread", *position_spread, lim::kPositionSpread.lo, lim::kPositionSpread.hi)
            : ""}) {
    if (!e.empty()) return e;
  }
  *out = defaults;
  out->budget_ms = *budget;
  out->noise.heading = physics::DegToRad(*heading);
  out->noise.speed_fraction = *speed;
  out->noise.topspin = out->noise.sidespin = *spin;
  out->noise.position = *position * 1e-3;
  out->limits.cue.length = *clearance;
  out->limits.cue.max_elevation = physics::DegToRad(*max_elevation);
  out->noise.aim = physics::DegToRad(*aim);
  out->noise.cue_speed_fraction = *cue_speed;
  out->noise.tip_offset = *tip * 1e-3;
  out->noise.elevation = physics::DegToRad(*elevation);
  out->noise.squirt_fraction = *squirt;
  out->noise.throw_fraction = *throws;
  out->max_simulations = *sims;
  out->monte_carlo_samples = static_cast<int>(*samples);
  out->threads = static_cast<int>(*threads);
  out->break_value = break_value;
  out->position_spread = position_spread;
  for (const char* flag : {"model", "world"}) {
    if (!args.Has(flag)) continue;
    physics::Model m;
    if (std::string e = LoadModelFile(*args.Text(flag, std::nullopt), &m); !e.empty()) {
      return std::string("--") + flag + " " + e;
    }
    (std::string(flag) == "model" ? out->model : out->world) = m;
  }
  return "";
}

}  // namespace snooker::cli
