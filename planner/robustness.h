// Robustness of a shot: seeded Monte Carlo with the full simulator under the
// robot's execution noise and the vision system's position noise.
//
// Each sample draws the true table (every ball where vision saw it plus a Gaussian
// error per axis: NoiseModel::position or the ball's own sigma; balls pushed apart
// if the draw overlaps them, and kept on the bed) and the shot as the robot plays
// it (speed x (1 + e_v), heading + e_h, topspin + e_t, sidespin + e_s), then
// simulates it at full fidelity. Success = the object ball drops, in any pocket,
// and no foul; the tally also counts the successes in the named pocket. A
// success also scores the position it really left (position.h), so the ranking
// prefers shots whose position play survives the noise.
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

/// The shot as the robot plays it under `noise` (speed kept >= 0).
physics::Shot SampleExecution(const physics::Shot& shot, const NoiseModel& noise, Rng& rng);

struct MonteCarloTally {
  int samples = 0;
  int successes = 0;
  /// Successes with the object ball in the named pocket.
  int pocket_successes = 0;
  /// Sum over samples of the objective the sample achieved (0 on failure).
  double score_sum = 0;
  /// Sum over successful samples of the position value they left.
  double position_sum = 0;
  bool interrupted = false;

  void Add(const MonteCarloTally& o);
  double success_rate() const { return samples > 0 ? static_cast<double>(successes) / samples : 0; }
  double pocket_rate() const { return samples > 0 ? static_cast<double>(pocket_successes) / samples : 0; }
  double mean_score() const { return samples > 0 ? score_sum / samples : 0; }
};

/// Runs samples [first, first + count) of block stream `seed` for `shot` of ball
/// `object`, named for `pocket`. `sim` should run at full fidelity.
MonteCarloTally RunSamples(const TableState& table, BallOn on, int object, physics::PocketId pocket,
                           const physics::Shot& shot, const PotContext& ctx,
                           const SearchSettings& settings, ShotSimulator& sim,
                           const StopControl& stop, std::uint64_t seed, int count);

}  // namespace snooker::planner
