// Ball in hand: where in the D to place the cue ball for a pot.
//
// The choice is a candidate grid refined with NLopt, not a fifth variable of the
// shot search. A placement changes a pot's geometry (cut, distances, what is in the
// way), which the fast estimate (pot_estimate.h) and the path checks
// (candidates.h) judge in microseconds without a simulation; the shot search's four
// variables then do what they do for any pot. So:
//  1. a polar grid over the D (radius 0.3 to 0.9 of the D's, seven directions,
//     and the centre line), every point clear of the balls, is enumerated with
//     EnumerateCandidates; each ball-pocket pair keeps its best grid point;
//  2. for each pair kept, LN_BOBYQA moves the placement within the D to the best
//     estimated points (a few dozen estimates), refused where it would touch a ball
//     or block a path.
// A fifth search variable would instead pay a simulation for every placement tried,
// and the search's global stage (DIRECT-L) grows with the dimension; the grid and
// its refinement cost about a millisecond for a full table (bench/, planner_bench).
#pragma once

#include <optional>
#include <vector>

#include "planner/candidates.h"
#include "planner/frame.h"

namespace snooker::planner {

/// `table` (no cue ball) with a cue ball appended at `p`.
TableState WithCueBall(const TableState& table, const physics::Vec2& p);

struct PlacedCandidate {
  Candidate candidate;    ///< as AssessPot made it on the table with the cue ball placed
  physics::Vec2 place = physics::Vec2::Zero();
  double points = 0;      ///< the prior: estimated probability x (value + continuation)
};

/// The pots the striker with the cue ball in hand can play: for every ball on and
/// pocket, the best placement in the D found (grid, then NLopt), best points first.
/// `table` has no cue ball; the candidates' ball indices are those of
/// WithCueBall(table, place) (the cue ball last). `continuation`: as
/// PositionOptions::continuation.
std::vector<PlacedCandidate> PlaceForPots(const TableState& table, BallOn on, const PotContext& ctx,
                                          double continuation);

/// A placement in the D clear of every ball, as central as possible (the brown
/// spot if free): for strokes that need only a legal place (the nearest-ball shot).
std::optional<physics::Vec2> FreePlaceInTheD(const TableState& table, const physics::TableModel& model);

}  // namespace snooker::planner
