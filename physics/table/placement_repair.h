// Repairing ball positions that are a little wrong, as vision reports them: two balls
// overlapping by a fraction of a millimetre, or a centre a hair past the cushion
// contact distance. Within a tolerance the balls are moved apart or back onto the bed;
// beyond it the placement is an error, and nothing is moved.
//
// How: the violated constraints (no two centres closer than 2R; every centre at
// least the cushion contact distance inside each cushion line, as
// TableModel::ValidatePlacement asks) are satisfied by alternating projections: a
// pair that overlaps moves apart along its line of centres, each ball by half the
// overlap; a ball past a cushion moves straight back onto its line. For an isolated
// pair or ball that is the least displacement that resolves it; for a touching group
// the sweeps settle near it. The tolerance bounds each overlap and overshoot, not
// each move: along a row of touching balls pressed against a cushion the moves add
// up, and a ball may move further than the tolerance (RepairedBall::distance says how
// far). What ValidatePlacement accepts (within its 1e-9 m
// tolerance) is left exactly as it is. Capped at kMaxRepairSweeps; a placement the sweeps cannot
// resolve is reported, never returned half repaired.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "physics/core/types.h"
#include "physics/table/table.h"

namespace snooker::physics {

struct RepairedBall {
  /// Index into the placements given.
  std::size_t index = 0;
  /// Centre before and after. m.
  Vec2 from = Vec2::Zero();
  Vec2 to = Vec2::Zero();
  /// |to - from|. m.
  double distance = 0;
};

struct PlacementRepair {
  /// Balls that moved, by index.
  std::vector<RepairedBall> moved;
  /// Empty when the placement is valid now (repaired or already fine); otherwise why
  /// not (each problem beyond the tolerance, named), and no ball was moved.
  std::string error;
};

inline constexpr int kMaxRepairSweeps = 200;

/// Repairs `balls` in place when every overlap and every cushion violation is at most
/// `tolerance` (m, >= 0). Quadratic in the number of balls: callers bound it first
/// (limits::kMaxBalls). A position that is not finite is an error.
PlacementRepair RepairPlacement(const TableModel& table, std::span<BallPlacement> balls,
                                double tolerance);

}  // namespace snooker::physics
