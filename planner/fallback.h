// The last resort of a plan: a legal stroke when the search verified none.
//
// A robot must strike on every turn. When no pot, safety or escape survives the
// search (a cramped table, a budget spent on candidates that all failed), the
// planner scans for a stroke that hits a ball on first and fouls nothing: for each
// ball on, nearest first, headings across the ball's visible width and then the
// one- and two-cushion paths to it (cushion_paths.h), each at a soft and a firm
// speed, simulated to rest; the legal stroke that leaves the opponent least
// (ScoreSafety) wins. When every stroke tried fouls (the cue ball hemmed in by
// balls not on), the foul that costs least (MonteCarloScore: the penalty and what
// the opponent can expect) is the answer, if the caller allows one: a robot still
// strikes, and the least harmful way. The scan is deterministic and capped in
// simulations.
#pragma once

#include <optional>

#include "planner/search.h"
#include "planner/shot_sim.h"

namespace snooker::planner {

struct FallbackOptions {
  /// Simulations the scan may run at most.
  int max_simulations = 240;
  /// Headings across a ball's width, and along a cushion path's bracket.
  int headings = 7;
  /// Cue-ball speeds tried, m/s.
  double soft = 1.2;
  double firm = 2.5;
  /// Balls on tried, nearest first.
  int max_balls = 4;
  /// Headings around the cue ball tried when no stroke at a ball on can be played.
  int ring_headings = 24;
  /// With no legal stroke, answer the least costly foul (kind kFoul).
  bool allow_foul = false;
};

struct FallbackShot {
  /// kEscape when it reaches its ball off a cushion; kFoul when it fouls.
  ShotKind kind = ShotKind::kSafety;
  /// The ball aimed at; for a foul the ball nominated (with any colour on, the
  /// lowest-valued colour).
  int object = -1;
  physics::CueStrike cue;             ///< the stroke: centre and level, or raised with the tip high
  physics::Shot shot;                 ///< what `cue` gives the cue ball
  double score = 0;                   ///< ScoreSafety's; a foul's, MonteCarloScore's
  int simulations = 0;
};

/// The best legal stroke the scan finds for the cue ball of `table` (index `cue`)
/// with `on`; else, with options.allow_foul, the least costly foul it played; else
/// nullopt (nothing found within the cap, or interrupted).
/// `sim` runs at full fidelity. Shots respect `settings.limits` (speed, room for
/// the cue).
std::optional<FallbackShot> FindLegalStroke(const TableState& table, int cue, BallOn on, const PotContext& ctx,
                                            const SearchSettings& settings, ShotSimulator& sim,
                                            const physics::Interrupt& interrupt, const FallbackOptions& options);

}  // namespace snooker::planner
