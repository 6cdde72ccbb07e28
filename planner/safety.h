// Candidates for shots that do not pot: safeties, and playing away from a touching
// ball on. Each is a Candidate for the NLopt search (search.h), whose objective for
// them is ScoreSafety: minus what the opponent can expect from the table left.
//
// A safety plays a ball on: the search varies the cut on it over a wide range (a
// thin contact that sends the cue ball back up the table, a fuller one that sends
// the object ball to a cushion), with speed and spin; the candidates are the balls
// on nearest the cue ball with a clear line to some part of them, each split into
// its left and right halves of cut so that each half is one smooth region. A ball on
// touching the cue ball counts as hit (the touching-ball rule): the cue ball may
// then simply roll away from it, within 80 deg of straight away.
#pragma once

#include <vector>

#include "planner/candidates.h"

namespace snooker::planner {

struct SafetyOptions {
  /// Balls on played at most (the nearest with a clear line first).
  int max_balls = 3;
  /// Largest |cut| of a safety's contact, rad (thinner contacts are unreliable).
  double max_cut = 80 * physics::kPi / 180;
  /// Cue-ball speeds searched, m/s.
  double speed_lo = 0.4;
  double speed_hi = 4.0;
};

/// The safety candidates for the cue ball `cue` of `table` with `on` (kind
/// kSafety), on table index `table_index` of the plan; `touching_on`: a ball on
/// touching the cue ball (TouchingBallOn), or -1.
std::vector<Candidate> SafetyCandidates(const TableState& table, int cue, BallOn on, const PotContext& ctx,
                                        int touching_on, int table_index, const SafetyOptions& options);

}  // namespace snooker::planner
