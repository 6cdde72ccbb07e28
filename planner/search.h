// The NLopt search of one candidate pot (one object ball into one pocket) over the
// four numbers of a stroke in the robot's terms: its strength, where the tip meets
// the ball (up and across) and the cut angle; the cue's elevation follows from the
// room behind the ball.
//
// Parametrisation (all searched in the unit cube, so every step is in proportion
// to the robot's range):
//   speed    the cue ball's speed in [v_lo, v_hi]: v_lo just brings the object ball
//            to the mouth, v_hi caps a positional shot within the robot's largest
//            speed; the cue's speed is the one that gives it (strike.h's axial
//            impulse at the tip offset), within RobotLimits' cue speeds;
//   height   the tip's offset up, fraction of R, in [-1, 1] x min(kMaxTipOffset,
//            max_topspin_fraction / 2.5) (draw to follow: a level strike at height
//            h spins the ball at 5/2 h v / R);
//   side     the tip's offset across, in [-1, 1] x min(kMaxTipOffset,
//            max_sidespin_fraction / 2.5);
//   elevation the lowest at which the cue clears the balls and cushions behind
//            (geometry.h CueElevation): level wherever it can be;
//   cut      = the aim that the collision model predicts will send the object ball
//            along the planned line (the ghost-ball cut corrected for the throw of
//            this speed and spin: ThrowModel's impact solve of the cue ball as it
//            arrives), + a correction in [-max_cut_correction, +max_cut_correction]
//            that the search sets from the full simulation (what the prediction
//            misses: the object ball's slip, the cue ball's state at contact).
// Throw is the correction that matters: a rolling cue ball throws the object ball
// 0.5 deg at a 10 deg cut and 2.8 deg at 80 deg (Mathavan et al.'s friction),
// more than the pocket's tolerance on any pot longer than about 30 cm.
//
// Objective (maximised): a shot that succeeds in its (cheaper, early-stopping)
// simulation scores P x (value + position), P being this shot's pot probability
// under noise (pot_estimate.h, from the simulated object-ball line), value the
// ball's points and position the expected points of the position left
// (position.h; omitted in pot-only mode). A failed shot scores -1 + P/2: below
// every success, and still graded towards a centred object-ball line, so the
// constraints (object ball drops, cue ball does not, first ball hit is the object
// ball) act as a barrier the search can climb out of. The best succeeding shot
// seen is kept apart from NLopt's iterate: the search is anytime.
//
// Algorithms (derivative-free: the objective is a simulation with discontinuities
// where a ball starts to hit another or a jaw):
//  * global: GN_DIRECT_L over speed, topspin and sidespin (cut at its predicted
//    value). DIRECT-L (Gablonsky & Kelley) is deterministic (no random seed to
//    manage across threads), needs only bounds, and at a few dozen evaluations in
//    three dimensions samples the box evenly while refining the best regions:
//    the position a shot leaves is multi-modal in speed and spin (stun, follow,
//    screw), which a local method from one start would miss.
//  * local: LN_BOBYQA (Powell) over all four from the best global point: a
//    quadratic model fits the smooth part of the objective (the Gaussian pot
//    probability and the position's slow change) in few evaluations, which is
//    what centring the cut on its narrow ridge needs. Measured against LN_SBPLX
//    and LN_COBYLA at equal work (docs/planner.md, "Search choices"): the three
//    score alike there, while the global stage and the throw prediction each add
//    measurably; BOBYQA stays for its bound handling and its cheap steps.
// Both have bounds, tolerances, an evaluation cap and a time limit.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <optional>
#include <span>
#include <string>

#include "physics/core/shot.h"
#include "planner/candidates.h"
#include "planner/outlook.h"
#include "planner/position.h"
#include "planner/shot_sim.h"

namespace snooker::planner {

/// What the robot can play.
struct RobotLimits {
  /// Cue-ball speed range, m/s.
  double min_speed = 0.3;
  double max_speed = 6.0;
  /// Largest |topspin| and |sidespin| as a fraction of the rolling spin v / R at
  /// the shot's speed v (a level tip offset of half the radius gives 1.25; a raised
  /// cue more per unit of speed). Topspin 1.25: a tip up to 0.45 R raised to 25 deg.
  double max_topspin_fraction = 1.25;
  double max_sidespin_fraction = 0.5;
  /// Room the cue needs behind the cue ball, and how steep it may be.
  CueClearance cue;
  /// The cue's speed range at impact, m/s (the strike gives the ball about 1.37
  /// times the cue's speed from the centre).
  double min_cue_speed = 0.1;
  double max_cue_speed = 5.0;
};

/// A struck shot within the robot's ball-term limits: its speed in [min_speed,
/// max_speed], its topspin and sidespin within their fractions of the rolling spin
/// (a raised cue spins the ball more per unit of speed than a level one).
bool WithinLimits(const physics::Shot& shot, const RobotLimits& limits, double radius);

/// A cue stroke within the robot's cue-term limits: its speed in [min_cue_speed,
/// max_cue_speed] and its elevation at most cue.max_elevation.
bool CueWithinLimits(const physics::CueStrike& cue, const RobotLimits& limits);

/// Local optimiser of the second stage.
enum class LocalAlgorithm : std::uint8_t { kBobyqa, kSubplex, kCobyla, kNone };
const char* ToString(LocalAlgorithm a);

struct SearchSettings {
  RobotLimits limits;
  /// Evaluations of the global and the local stage (each evaluation is one
  /// simulation). 0 skips a stage.
  int global_evaluations = 24;
  int local_evaluations = 24;
  LocalAlgorithm local = LocalAlgorithm::kBobyqa;
  /// Aim by the collision model's predicted throw (false: the geometric ghost-ball
  /// cut, for the comparison in docs/planner.md).
  bool predict_throw = true;
  /// Largest correction of the predicted cut, rad.
  double max_cut_correction = 0.6 * physics::kPi / 180;
  /// Stop a stage when a step changes no variable by more than this (unit cube).
  double x_tolerance = 1e-3;
  /// Score the position left (false: pot only, P x value).
  bool position_play = true;
  /// Points a shot's score loses per m/s of speed above 3 m/s: of two shots that
  /// score alike the softer one (a power shot spreads the cue ball's position more
  /// than the Monte Carlo's few samples show).
  double speed_cost = 0.3;
  /// The search values a pot's position as its mean over the cue ball's end spread
  /// rather than at the nominal end: k standard deviations of that spread, where
  /// one is what the speed's noise gives a path after contact (2 x its fraction x
  /// the path: a rolling path scales as the square of the speed), along the last
  /// direction the cue ball moved. 0: the nominal end only (PlanRequest::
  /// position_spread; docs/whole-frame-planner.md, section 10, measures it).
  double position_spread = 0;
  PositionOptions position;
};

/// One evaluated shot.
struct ShotCandidate {
  /// The stroke as the robot plays it, and what it gives the cue ball
  /// (physics::Strike of `cue`).
  physics::CueStrike cue;
  physics::Shot shot;
  double cut = 0;               ///< rad
  double score = 0;             ///< the objective
  double pot_estimate = 0;      ///< P of the objective
  PositionValue position;       ///< of the position left (position play or not)
  physics::Vec2 cue_end = physics::Vec2::Zero();
};

enum class SearchStatus : std::uint8_t {
  kConverged,    ///< both stages ended by tolerance or their evaluation caps
  kInterrupted,  ///< the deadline passed or the cancel flag was set
  kFailed,       ///< NLopt reported an error (the best shot found is still valid)
};

/// How a shot's cue ball plays through the object ball: by its topspin at the
/// strike as a fraction of the rolling spin, below -kSpinClass screw, above
/// +kSpinClass follow, stun between.
enum class SpinClass : std::uint8_t { kScrew, kStun, kFollow };
inline constexpr double kSpinClass = 0.25;
inline constexpr int kSpinClassCount = 3;
SpinClass SpinClassOf(const physics::Shot& shot, double radius);

struct SearchResult {
  std::optional<ShotCandidate> best;  ///< the best succeeding shot, if any
  /// The best succeeding shot of each spin class (a pot's alternatives: the same
  /// ball and pocket played with stun, follow or screw), best included.
  std::array<std::optional<ShotCandidate>, kSpinClassCount> by_spin;
  int evaluations = 0;
  int simulations = 0;
  SearchStatus status = SearchStatus::kConverged;
  std::string detail;                 ///< NLopt's results or error, for reports
};

/// What stops a search from outside.
struct StopControl {
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  const std::atomic<bool>* cancelled = nullptr;
  bool Due() const;
  physics::Interrupt AsInterrupt() const;
};

/// The speed range [v_lo, v_hi] searched for a candidate (see above). m/s.
std::pair<double, double> SpeedRange(const TableState& table, int cue, const Candidate& cand,
                                     const RobotLimits& limits, const physics::SimParams& params);

/// The cut (rad) that the collision model predicts sends the object ball along
/// `object_direction` for a shot of this speed and spin from `cue` onto `object`
/// (three Newton steps on the throw); nullopt when the cue ball cannot reach it.
std::optional<double> PredictCut(const physics::Vec2& cue, const physics::Vec2& object,
                                 double object_direction, double speed, double topspin,
                                 double sidespin, const physics::SimParams& params);

/// The plain shot behind a fast estimate: the cue ball struck rolling, fast enough
/// to reach the contact at TypicalContactSpeed, aimed by PredictCut along the
/// estimate's object-ball line. What the estimate assumes the robot plays (tests
/// and reports compare it with Monte Carlo). nullopt if no cut realises it.
std::optional<physics::Shot> RollingPotShot(const physics::Vec2& cue, const physics::Vec2& object,
                                            const PotEstimate& estimate,
                                            const physics::SimParams& params);

struct LeaveScratch;

/// Searches one candidate. `sim` runs at the search's fidelity. `scratch`: the
/// caller's buffers for the table each evaluation leaves, kept from one search to
/// the next (its lines into the pockets among them), or none.
SearchResult SearchCandidate(const TableState& table, BallOn on, const Candidate& cand,
                             const PotContext& ctx, const SearchSettings& settings,
                             ShotSimulator& sim, const StopControl& stop, LeaveScratch* scratch = nullptr);

/// The objective of a succeeding shot: pot_probability x (value + the expected
/// points of the position left; the latter only with position_play).
double ShotScore(double pot_probability, int value, const PositionValue& position,
                 bool position_play);

/// What a succeeding shot leaves, scored.
struct Leave {
  PositionValue position;
  /// LayoutChange of the shot (pots, with a layout summary), points.
  double layout = 0;
  /// ScoreSafety without a pot: the opponent's outlook of the table left.
  std::optional<Outlook> opponent;
  /// ShotScore of the shot with the given pot probability.
  double score = 0;
  /// The ball the position sets up, as an index of the table before the shot (-1:
  /// none).
  int next_ball = -1;
};

/// The buffers ScoreSafety and ScoreLeave build the table left in: a caller that
/// scores many shots (a search, a Monte Carlo) keeps one, and once grown to the
/// table's size the scoring allocates nothing for it. Without one each call makes
/// its own.
struct LeaveScratch {
  TableState after;
  std::vector<int> origin;
  /// `after` with the cue ball placed in hand, for the opponent's outlook.
  TableState placed;
  /// The lines into the pockets of the balls positions are valued with.
  PocketLineCache lines;
};

/// Scores what a legal safety, escape or break-off leaves, for the striker, in
/// ShotScore's points: when a ball on dropped after all, the points and the
/// striker's position (the visit goes on); otherwise minus the opponent's expected
/// points from the table left less the penalty a snooker makes them expect to give
/// away (OpponentOutlook; the ball on theirs: a red while reds remain). `first_hit`
/// is the first ball the cue ball hit. Leave::next_ball is then the opponent's best
/// ball.
Leave ScoreSafety(const TableState& table, BallOn on, int first_hit, std::span<const physics::Vec2> finals,
                  std::span<const int> potted, const PotContext& after_ctx, const SearchSettings& settings,
                  LeaveScratch* scratch = nullptr);

/// The outlook (outlook.h) of the table `after` for the opponent, to play with `on`
/// (the cue ball in hand when `after` has none; `placed`: the buffer for the table
/// with it placed, or none; `lines`: a cache of lines into the pockets, or none).
Outlook OpponentOutlook(const TableState& after, BallOn on, const PotContext& after_ctx,
                        const SearchSettings& settings, TableState* placed = nullptr,
                        PocketLineCache* lines = nullptr);

/// Scores what a succeeding shot of `object` with `on` leaves, the one sequence the
/// search, the verification and the Monte Carlo share: the table after the rules
/// (ApplyShot: potted balls off, colours re-spotted), the ball on then, the value of
/// that position (EvaluatePosition with `after_ctx`, whose per-ball vision sigmas
/// no longer apply: the balls have moved) and ShotScore. `finals` are where the
/// simulation left every ball of `table`, `potted` the balls that dropped.
/// `scratch`: the caller's buffers for the table left (LeaveScratch), or none.
/// `cue_spread`, when not zero, is one standard deviation of the cue ball's end,
/// m, as a vector along the direction it spreads: the position is then the mean
/// over that line by three-point Gauss-Hermite quadrature (the end and +-sqrt(3)
/// of the spread, weights 2/3, 1/6 and 1/6; points past a cushion's contact line
/// are held on it).
Leave ScoreLeave(const TableState& table, BallOn on, int object, std::span<const physics::Vec2> finals,
                 std::span<const int> potted, double pot_probability, const PotContext& after_ctx,
                 const SearchSettings& settings, LeaveScratch* scratch = nullptr,
                 const physics::Vec2& cue_spread = physics::Vec2::Zero());

}  // namespace snooker::planner
