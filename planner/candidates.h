// Candidate pots: every legal object ball with every pocket, pruned before any
// search by what can be decided from the geometry (microseconds each):
//  * the cut is thinner than the robot can play reliably (max_cut);
//  * the pocket cannot take the ball from that direction (its window is empty:
//    PocketModel), e.g. a middle pocket from a shallow angle;
//  * the cue ball's path to the ghost-ball position passes closer than 2R (plus a
//    margin) to another ball, or the object ball's path to the mouth does;
//  * the robot's cue has no room behind the cue ball for that heading (a ball or a
//    cushion in the way: geometry.h CueMargin).
// Survivors carry the fast pot estimate (pot_estimate.h), which orders the search.
#pragma once

#include <array>
#include <vector>

#include "planner/geometry.h"
#include "planner/pot_estimate.h"
#include "planner/rules.h"

namespace snooker::planner {

/// Everything the geometric judgements need; shared, read-only during a plan.
struct PotContext {
  const physics::TableModel* table = nullptr;
  const PocketModel* pockets = nullptr;
  const ThrowModel* throws = nullptr;
  NoiseModel noise;
  /// Vision sigma per ball (m, per axis), same order as the table; empty: all
  /// balls use noise.position.
  std::vector<double> position_sigma;
  CueClearance cue;
  /// Thinnest cut considered, rad.
  double max_cut = 80.0 * physics::kPi / 180;
  /// Room beyond 2R a path must leave to every other ball, m (vision's error and
  /// the throw's curvature).
  double path_clearance = 0.5e-3;

  double sigma_of(int ball) const {
    return position_sigma.empty() ? noise.position : position_sigma[static_cast<size_t>(ball)];
  }
};

enum class PruneReason : std::uint8_t {
  kNone,
  kCutTooThin,
  kPocketAngle,
  kCueBallPath,
  kObjectBallPath,
  kCueRoom,
};
inline constexpr int kPruneReasonCount = 6;
const char* ToString(PruneReason r);

struct Candidate {
  int object = -1;
  physics::PocketId pocket = physics::PocketId::kBaulkLeft;
  PotEstimate estimate;
  /// CueMargin for the aimed heading, m.
  double cue_margin = 0;
};

/// One ball-pocket pair judged from the geometry: the candidate, or nullopt with
/// the reason in *why.
std::optional<Candidate> AssessPot(const TableState& table, int cue, int object,
                                   physics::PocketId pocket, const PotContext& ctx,
                                   PruneReason* why = nullptr);

struct CandidateSet {
  std::vector<Candidate> candidates;  ///< by estimate, most likely first
  int pairs = 0;                      ///< legal ball-pocket pairs considered
  std::array<int, kPruneReasonCount> pruned{};
};

/// Every legal object ball (IsLegalTarget(on, kind)) with every pocket.
CandidateSet EnumerateCandidates(const TableState& table, BallOn on, const PotContext& ctx);

}  // namespace snooker::planner
