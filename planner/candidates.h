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
#include "planner/shot_kind.h"

namespace snooker::planner {

struct LayoutSummary;  // layout.h

/// Everything the geometric judgements need; shared, read-only during a plan.
struct PotContext {
  const physics::TableModel* table = nullptr;
  const PocketModel* pockets = nullptr;
  const ThrowModel* throws = nullptr;
  /// The noise in the fast estimates' terms (BallTermsNoise of `execution`).
  NoiseModel noise;
  /// The request's noise as given: what the Monte Carlo samples (robustness.h).
  NoiseModel execution;
  /// The robot's cue (nullptr: the default cue).
  const physics::CueParams* cue_model = nullptr;
  const physics::CueParams& cue_params() const {
    static const physics::CueParams kDefault;
    return cue_model != nullptr ? *cue_model : kDefault;
  }
  /// Vision sigma per ball (m, per axis), same order as the table; empty: all
  /// balls use noise.position.
  std::vector<double> position_sigma;
  CueClearance cue;
  /// Thinnest cut considered, rad.
  double max_cut = 80.0 * physics::kPi / 180;
  /// Room beyond 2R a path must leave to every other ball, m (vision's error and
  /// the throw's curvature).
  double path_clearance = 0.5e-3;
  /// The plan's table as layout.h summarises it, for the layout term of what a
  /// pot leaves (nullptr: no layout term).
  const LayoutSummary* layout = nullptr;

  /// Vision's sigma of ball `ball`; noise.position for balls past position_sigma's
  /// end (a cue ball placed in hand, whose place the robot sets).
  double sigma_of(int ball) const {
    return static_cast<size_t>(ball) < position_sigma.size() ? position_sigma[static_cast<size_t>(ball)]
                                                             : noise.position;
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

/// How a candidate's fourth search variable becomes the cue ball's heading.
enum class AimMode : std::uint8_t {
  /// A cut on aim_ball: PredictCut's throw-corrected aim that sends it along
  /// aim_direction, plus at most aim_range either way (0: the search's default).
  kPredictedCut,
  /// A cut on aim_ball in aim_base +- aim_range.
  kCut,
  /// The cue ball's heading aim_base +- aim_range (routes off a cushion).
  kHeading,
};

/// One shot to search: a direct pot from AssessPot, or another kind or route.
struct Candidate {
  ShotKind kind = ShotKind::kPot;
  PotRoute route = PotRoute::kDirect;
  /// A pot's object ball (the ball to pot), or the ball a safety plays (-1: any).
  int object = -1;
  /// The ball the cue ball must hit first (ShotSetup::first; -1: the object ball
  /// for a pot, any ball on otherwise).
  int first = -1;
  physics::PocketId pocket = physics::PocketId::kBaulkLeft;
  /// The fast estimate of a direct pot; for other candidates its probability is
  /// the prior's (what the search's share of the work follows).
  PotEstimate estimate;
  /// CueMargin for the aimed heading, m.
  double cue_margin = 0;
  AimMode aim = AimMode::kPredictedCut;
  /// The ball the cut is on (-1: the object ball), and for kPredictedCut the
  /// direction it must leave in (unset: the estimate's object direction).
  int aim_ball = -1;
  std::optional<double> aim_direction;
  double aim_base = 0;   ///< rad
  double aim_range = 0;  ///< rad; 0: the search's default correction
  /// The cue-ball speeds searched, m/s; both 0: SpeedRange's for a direct pot.
  double speed_lo = 0, speed_hi = 0;
  /// Which of the plan's tables the candidate plays on (0: the request's; others
  /// place the cue ball in hand), and that placement.
  int table = 0;
  std::optional<physics::Vec2> cue_start;

  int AimBall() const { return aim_ball >= 0 ? aim_ball : object; }
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
