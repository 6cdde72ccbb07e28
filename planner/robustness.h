// Robustness of a shot: seeded Monte Carlo with the full simulator under the
// robot's execution noise and the vision system's position noise.
//
// Each sample draws the true table (every ball where vision saw it plus a Gaussian
// error per axis: NoiseModel::position or the ball's own sigma; balls pushed apart
// if the draw overlaps them, and kept on the bed) and the shot as the robot plays
// it: the cue's speed x (1 + e_v), its aim + e_a, the tip's offsets + e_x, e_y, its
// elevation + e_e, struck through physics/cue/strike.h; with the model's
// uncertainty, the squirt x (1 + e_q) and the throw of every ball-ball impact x
// (1 + e_w) (SimParams::throw_scale); then the cue ball's own extra noise, if any.
// It simulates that at full fidelity. Success = what the shot is for (a pot's object
// ball drops, in any pocket, with no foul; a safety is legal); the tally also counts
// the successes in the named pocket and the fouls. Every sample is scored in points
// for the striker (MonteCarloScore): a success by the position it really left, a
// miss or a foul by what it gives the opponent, so that the ranking compares pots
// and safeties in one currency and prefers shots whose position play survives the
// noise. For a direct pot it can also tally each sample's object-ball line at the
// pocket, whose Gaussian fit estimates the tail of near-certain pots that 48 counted
// samples cannot resolve (MonteCarloTally::tail_corrected_score).
//
// Samples come in blocks with their own random stream (DeriveSeed(seed, shot,
// block)): blocks can run on any thread in any order and give the same sums.
#pragma once

#include <span>
#include <vector>

#include "physics/core/shot.h"
#include "planner/candidates.h"
#include "planner/position.h"
#include "planner/random.h"
#include "planner/search.h"
#include "planner/shot_sim.h"

namespace snooker::planner {

/// The true positions behind what vision saw: `seen` plus Gaussian noise (sigma per
/// ball from ctx), overlaps pushed apart along the line of centres and every ball
/// kept inside the cushions. Writes `out` (same order).
void SampleTruePositions(const TableState& seen, const PotContext& ctx, Rng& rng,
                         std::vector<physics::Vec2>* out);

/// The shot as the robot plays it under `noise`'s extra noise on the cue ball
/// (speed kept >= 0).
physics::Shot SampleExecution(const physics::Shot& shot, const NoiseModel& noise, Rng& rng);

/// A stroke as played: what the cue ball got, and the throw scale of the world.
struct PlayedStroke {
  physics::Shot shot;
  double throw_scale = 1;
  physics::StrikeStatus status = physics::StrikeStatus::kOk;
};

/// `cue` as the robot plays it under `noise` (the cue's execution, then the cue
/// ball's extra noise); with `model_uncertainty` also the squirt's and the throw's
/// (the Monte Carlo's belief about a real table; a simulated world that is the
/// model itself leaves them out). A miscue keeps its strike (a real miscue
/// squirts off unpredictably: the sample is a failure of the planned shot anyway).
PlayedStroke SampleStroke(const physics::CueStrike& cue, const physics::CueParams& cue_params,
                          const physics::BallParams& ball, double gravity, const NoiseModel& noise,
                          bool model_uncertainty, Rng& rng);

/// The level strike that gives `shot` (physics::StrikeFor), or for spins beyond
/// the miscue limit a centre strike of its speed and heading.
physics::CueStrike LevelStrikeFor(const physics::Shot& shot, const physics::CueParams& cue,
                                  const physics::BallParams& ball, double gravity);

struct MonteCarloTally {
  int samples = 0;
  /// Samples that did what the shot is for (shot_sim.h's success: a pot's object
  /// ball dropped legally, any pocket; a safety legal).
  int successes = 0;
  /// Successes with the object ball in the named pocket.
  int pocket_successes = 0;
  /// Samples that fouled.
  int fouls = 0;
  /// Sum over samples of the points the sample is worth to the striker (MonteCarloScore).
  double score_sum = 0;
  /// Sum of the scores of the successes (the other samples': score_sum less this).
  double success_score_sum = 0;
  /// Samples that handed the table to the opponent (SampleWorth::handed_over), of
  /// those the samples that left them snookered, and the sums over those samples of
  /// their best pot's probability and of their expected points (Outlook's).
  int handovers = 0;
  int handovers_snookered = 0;
  double opponent_pot_sum = 0;
  double opponent_points_sum = 0;
  /// A direct pot's lines at the pocket (RunSamples with measure_line): the samples
  /// whose object ball left its first contact on a measured line, how many of those
  /// lines lay inside the pocket's window, and the sums of z and z^2, z being the
  /// line's offset from the window's centre in half-widths (|z| < 1: inside).
  int line_samples = 0;
  int line_inside = 0;
  double z_sum = 0;
  double z2_sum = 0;
  bool interrupted = false;

  void Add(const MonteCarloTally& o);
  double success_rate() const { return Rate(successes); }
  double pocket_rate() const { return Rate(pocket_successes); }
  double foul_rate() const { return Rate(fouls); }
  double mean_score() const { return samples > 0 ? score_sum / samples : 0; }
  /// The chance of a line inside the window by a Gaussian fit of the measured lines'
  /// z (needs at least two lines).
  double fitted_line_rate() const;
  /// The mean score with the counted share of lines inside replaced by the fitted
  /// one, times what a pot is worth over a miss; the mean score itself with fewer
  /// than `min_line_samples` lines or no pot.
  double tail_corrected_score(int min_line_samples) const;

 private:
  double Rate(int n) const { return samples > 0 ? static_cast<double>(n) / samples : 0; }
};

/// What one played sample is worth, and what it left the opponent when it handed
/// them the table.
struct SampleWorth {
  /// Points for the striker (MonteCarloScore).
  double score = 0;
  /// The opponent is to play a table with a ball on left (no ball on dropped
  /// legally: a pot's miss, a safety's leave, any foul); then their outlook's best
  /// pot probability, expected points and whether they are snookered.
  bool handed_over = false;
  double opponent_pot = 0;
  double opponent_points = 0;
  bool snookered = false;
};

/// What one played sample is worth to the striker, in ShotScore's points, whatever
/// the shot meant to do: a pot that drops, its value and the position left
/// (ScoreLeave); any other legal stroke, what ScoreSafety makes of the table left
/// (a ball on dropping after all continues the visit; otherwise the opponent's
/// expected points, negated); a foul, minus the penalty and the opponent's
/// expected points (OpponentOutlook: from the D when the cue ball went down).
/// With the opponent's outlook when the table went to them. `scratch`: the
/// caller's buffers for the table left (LeaveScratch), or none.
SampleWorth MonteCarloScore(const ShotSetup& setup, const ShotOutcome& out, std::span<const physics::Vec2> finals,
                            const PotContext& after_ctx, const SearchSettings& settings,
                            LeaveScratch* scratch = nullptr);

/// What RunSamples fills on every sample: the positions sampled and the final
/// ones, the context that scores the table left and the table itself. A caller
/// that keeps one from block to block (a worker) makes every block after its first
/// run without allocating.
struct SampleScratch {
  PotContext after_ctx;
  std::vector<physics::Vec2> truth;
  std::vector<physics::Vec2> finals;
  LeaveScratch leave;
};

/// Runs `count` samples of block stream `seed` for the stroke `cue` played as
/// `setup` says (its table as vision saw it), under ctx.execution's noise and
/// ctx.cue_params(). `sim` should run at full fidelity. With `measure_line` (a
/// direct pot; ctx.pockets set) it also tallies the object ball's lines at the
/// named pocket. `scratch`: the caller's buffers, or none (then its own).
MonteCarloTally RunSamples(const ShotSetup& setup, const physics::CueStrike& cue, const PotContext& ctx,
                           const SearchSettings& settings, ShotSimulator& sim, const StopControl& stop,
                           std::uint64_t seed, int count, bool measure_line = false,
                           SampleScratch* scratch = nullptr);

}  // namespace snooker::planner
