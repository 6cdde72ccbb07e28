// Self-play: the planner plays breaks alone, to measure it.
//
// Each frame starts from a seeded random mid-frame table: 6 to 10 reds scattered
// where they touch nothing (no ball, no spot), the colours on their spots, the cue
// ball anywhere free, a red on. Each shot the planner sees the table as vision
// would (every ball moved by the vision noise), plans, and its best shot is
// played on the true table with the execution noise added, simulated at full
// fidelity and judged by the rules (rules.h). The break goes on until a miss, a
// foul (cue ball potted, wrong ball first, a ball not on potted), a plan with no
// shot or whose best shot is not a pot (a safety: the break ends there, and is not
// counted as an attempted pot), or a cleared table. Potted colours are re-spotted by the rules while reds
// remain.
//
// A pot attempt is a shot played; it drops when its object ball drops with no foul.
// Planning time is the planner's own elapsed time per shot.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "planner/planner.h"
#include "planner/random.h"

namespace snooker::planner {

struct SelfPlayOptions {
  int frames = 100;
  std::uint64_t seed = 1;
  /// Planning budget per shot, s.
  double time_budget = 0.08;
  /// The world is the model: the cue's noise, no model uncertainty (ModelWorldNoise).
  NoiseModel noise = ModelWorldNoise();
  RobotLimits limits;
  bool position_play = true;
  /// Search the next shot of the best pots (two-ply); false: estimate it only.
  bool lookahead = true;
  int threads = 2;
  /// Per-plan simulation cap (0: from the budget).
  std::int64_t max_simulations = 0;
  int monte_carlo_samples = 48;
  /// The break value (PlanRequest::break_value), points; nullopt: the planner's
  /// own (30), which scores the most in a break alone at the table.
  std::optional<double> break_value;
  /// The search's position spread (PlanRequest::position_spread); nullopt: the
  /// planner's own (0, the nominal end).
  std::optional<double> position_spread;
  int min_reds = 6;
  int max_reds = 10;
  /// Cap on shots in one frame (a cleared 10-red table takes 26).
  int max_shots_per_frame = 64;
  /// The world the shots are played in (sim-to-real: a table unlike the planner's
  /// model); none: the planner's own model.
  std::optional<physics::Model> world;
  /// The world's squirt and throw differ from the model's on every stroke, by the
  /// noise's squirt and throw fractions (SampleStroke's model uncertainty), as a real
  /// table's do; false: the world is the model. Set the fractions with it: 0 leaves
  /// the world the model.
  bool uncertain_world = false;
};

struct FrameRecord {
  int reds = 0;
  int points = 0;         ///< the break
  int attempts = 0;       ///< shots played
  int pots = 0;           ///< attempts whose object ball dropped without a foul
  std::string end;        ///< "miss", "foul: ...", "no pot", "SAFETY", "ESCAPE", "cleared", "shot cap"
};

struct SelfPlayReport {
  int frames = 0;
  int shots = 0;            ///< attempts over all frames
  int pots = 0;
  double mean_break = 0;
  int max_break = 0;
  double pot_rate = 0;      ///< pots / shots
  double plan_ms_p50 = 0;   ///< median planning time per shot, ms
  double plan_ms_p99 = 0;   ///< 99th percentile (nearest rank), ms
  /// Plans the clock cut short (PlanAnswer::cut_short): with none, the run is a
  /// function of its seed and options.
  int plans_cut_short = 0;
  std::vector<FrameRecord> records;
  std::vector<double> plan_ms;  ///< every plan, in order
};

/// A random mid-frame table (see above) with `reds` reds.
TableState RandomFrame(Rng& rng, int reds, const physics::TableModel& table);

/// Plays `options.frames` frames. `on_frame`, when given, is called after each
/// frame with its index and record (for progress output).
SelfPlayReport RunSelfPlay(const Planner& planner, const SelfPlayOptions& options,
                           void (*on_frame)(int frame, const FrameRecord& record, void* context) = nullptr,
                           void* context = nullptr);

/// Nearest-rank percentile (q in [0, 1]) of `values`; 0 when empty.
double Percentile(std::vector<double> values, double q);

}  // namespace snooker::planner
