// The shot planner: given a table state from vision, the ranked shots that pot a
// ball on and leave the cue ball well.
//
// One request runs, within its time budget:
//  1. candidates: every legal object ball with every pocket, pruned by geometry
//     (candidates.h), ordered by the fast pot estimate;
//  2. search: an NLopt search per candidate over speed, topspin, sidespin and cut
//     (search.h), on a cheaper, early-stopping simulation; the candidates' share
//     of the work follows their estimate;
//  3. verification: each candidate's best shot is simulated again at full
//     fidelity, to the end, and dropped if it fails there: no shot leaves the
//     planner that its own full simulation says fails, and a shot's label (object
//     ball and pocket) is what that simulation did;
//  4. robustness: seeded Monte Carlo of the best few under execution and vision
//     noise (robustness.h); the final ranking is by the Monte Carlo mean of the
//     objective (success x (points + position)), and potProbability is the
//     Monte Carlo success rate.
//
// Anytime and interruptible: the work is capped in simulations (derived from the
// budget at a calibrated rate, so the same seed gives the same answer whatever the
// timing) and in time (the budget, the caller's deadline, its cancel flag): when
// time runs out the best verified shots so far are returned. The progress callback
// is called, from a worker thread and never concurrently, whenever a verified shot
// beats the best so far (its potProbability then is the fast estimate).
//
// Threads: candidates and Monte Carlo blocks are shared among `threads` workers
// (the caller's thread and threads - 1 more), each with its own simulators. Every
// task's result depends only on the task (its own seed), so the answer does not
// depend on which thread ran what.
//
// Units: SI inside (m, s, rad, m/s, rad/s); degrees and milliseconds only at the
// API and command-line edges.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "physics/core/shot.h"
#include "physics/model/model.h"
#include "physics/sim/fidelity.h"
#include "physics/sim/simulate.h"
#include "planner/candidates.h"
#include "planner/limits.h"
#include "planner/pocket_model.h"
#include "planner/position.h"
#include "planner/rules.h"
#include "planner/search.h"
#include "planner/shot_kind.h"
#include "planner/throw_model.h"

namespace snooker::planner {

struct PlannedShot;

/// Called whenever the best verified shot so far improves: the shot and the
/// caller's context. From a worker thread; calls never overlap.
using ProgressFn = void (*)(const PlannedShot& best, void* context);

struct PlanRequest {
  /// The table as vision saw it: exactly one cue ball, or none with cue_in_hand.
  TableState table;
  /// The striker has the cue ball in hand (the break-off, or after an in-off): the
  /// table holds no cue ball and the planner places it in the D as part of the
  /// search (PlannedShot::cue_start).
  bool cue_in_hand = false;
  /// The ball on; nullopt: a red while reds remain, else the lowest colour.
  std::optional<BallOn> ball_on;
  RobotLimits limits;
  /// Execution noise and the vision sigma for every ball.
  NoiseModel noise;
  /// Vision sigma per ball (m, per axis), same order as table.balls; empty: all
  /// balls use noise.position.
  std::vector<double> position_sigma;
  /// Time budget. s.
  double time_budget = limits::kDefaultTimeBudget;
  /// How many shots to return (best first).
  int max_shots = 3;
  std::uint64_t seed = 1;

  /// false: pot only (the objective ignores the position left).
  bool position_play = true;
  /// The kinds of shot the plan may return, and the routes its pots may take.
  ShotKinds kinds;
  PotRoutes routes;
  /// Search the next shot after the best few (two-ply) where the budget allows;
  /// false: the position left is only estimated (one-ply).
  bool lookahead = true;
  /// The break value, points: what keeping the table is worth beyond the potted
  /// ball's own value (PositionOptions::continuation); nullopt: the configured one
  /// (30). Alone at the table (a break for its own sake) 30 scores the most; in a
  /// frame against an opponent about 100 wins more frames, since a miss also hands
  /// the opponent the table (docs/whole-frame-planner.md).
  std::optional<double> break_value;
  /// The search values a pot's position over the cue ball's end spread, this many
  /// standard deviations of what the speed's noise gives it
  /// (SearchSettings::position_spread); nullopt: the configured one (0, the
  /// nominal end only).
  std::optional<double> position_spread;
  /// At the break-off, also search the thin break beside the soft one; nullopt: the
  /// configured choice (PlannerConfig::thin_break_off, off).
  std::optional<bool> thin_break_off;
  /// Worker threads (the caller's included).
  int threads = 2;
  /// Cap on simulations; 0: derived from the budget (Planner::Config).
  std::int64_t max_simulations = 0;
  /// Monte Carlo samples per ranked shot (rounded up to blocks of 8; fewer when
  /// the budget is small); 0 ranks by the search's estimate alone.
  int monte_carlo_samples = 48;

  /// The caller's own deadline (e.g. an RPC's): the plan ends by the earlier of
  /// this and start + time_budget, its stages sharing out the time to the earlier
  /// (and a plan without max_simulations capped by what that time buys), except that
  /// a plan with no shot verified by then runs its fallback scan (fallback.h, capped
  /// in simulations) and verifies its stroke until this deadline: a robot gets a
  /// stroke whenever the deadline allows.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  /// Set from another thread to stop the plan as soon as possible. Optional.
  const std::atomic<bool>* cancel = nullptr;
  ProgressFn progress = nullptr;
  void* progress_context = nullptr;
};

/// An event of a shot's verification run (physics::SimEvent; indices into the
/// request's table.balls, the placed cue ball last when it was in hand; `where`
/// indexes the table's segments, jaws or pockets).
using PlannedEvent = physics::SimEvent;

/// Where a ball ended in a shot's verification run.
struct BallEnd {
  /// Table frame, m; a pocketed ball where it dropped.
  physics::Vec2 position = physics::Vec2::Zero();
  /// The pocket it dropped into, or nullopt.
  std::optional<physics::PocketId> pocket;
};

/// What a stroke that hands the table over leaves the opponent: the outlook
/// (outlook.h) of the table its verification run leaves, the estimate it is scored by.
struct OpponentLeave {
  /// Their best pot's probability (the fast estimate), and what their best pots are
  /// worth to them (PositionValue::expected_points), points.
  double pot_probability = 0;
  double expected_points = 0;
  /// They cannot hit a ball on directly; then the chance they foul by missing it (a
  /// one-cushion escape's miss, or OutlookOptions::blind_miss) and the penalty that
  /// gives the striker, points; both 0 when not snookered.
  bool snookered = false;
  double foul_probability = 0;
  double penalty = 0;
};

/// What the Monte Carlo's runs that handed the table to the opponent left them
/// (robustness.h's SampleWorth): a pot's misses, a safety's leaves, every foul; a
/// run that pots a ball on keeps the table, one that ends the frame leaves nothing.
struct Handovers {
  /// Runs that handed the table over (of PlannedShot::monte_carlo_samples), and of
  /// those the runs that left them snookered.
  int runs = 0;
  int snookered_runs = 0;
  /// Over those runs, the means of their best pot's probability and of their
  /// expected points (Outlook's); 0 when `runs` is 0.
  double mean_pot_probability = 0;
  double mean_expected_points = 0;
};

struct PlannedShot {
  /// What the shot is, from its verification run; `route` for pots only.
  ShotKind kind = ShotKind::kPot;
  PotRoute route = PotRoute::kDirect;
  /// The cue ball in hand: where the robot places it (table frame, m, in the D).
  std::optional<physics::Vec2> cue_start;
  /// The stroke in the robot's terms (physics/cue/strike.h): cue speed, heading
  /// (squirt compensated), tip offsets and elevation.
  physics::CueStrike cue;
  /// The shot, as `snooker simulate` takes it (heading in rad here): what `cue`
  /// gives the cue ball (physics::Strike), exactly.
  physics::Shot shot;
  /// Cut angle (geometry.h's sign), rad.
  double cut = 0;
  /// The object ball (index as in events): for a pot the ball potted, and the
  /// pocket it drops into; for other kinds the ball played (first_ball), the pocket
  /// unused. Both from the shot's verification run, so the label is what the shot
  /// did, whatever the search aimed at.
  int object_ball = -1;
  physics::PocketId pocket = physics::PocketId::kBaulkLeft;
  /// Probability, under execution and vision noise, that the stroke is legal (no
  /// foul) and pots the object ball, in any pocket: the Monte Carlo success rate
  /// (the fast estimate for the aimed-at pocket when no Monte Carlo ran).
  double pot_probability = 0;
  /// The same for the named pocket only (equal to pot_probability when no Monte
  /// Carlo ran).
  double pocket_probability = 0;
  /// Value of the position left (position.h: weighted next pot probabilities).
  double position_value = 0;
  /// The ball the position sets up (index in the request's table; -1 if none).
  int next_ball = -1;
  /// Where the cue ball stops (table frame, m).
  physics::Vec2 cue_ball_end = physics::Vec2::Zero();
  /// The first ball the cue ball hits (a touching ball on counts as hit), or -1:
  /// for pots other than plants the object ball, for safeties and escapes the ball
  /// played.
  int first_ball = -1;
  /// Probability, under the same noise as pot_probability, that the stroke fouls.
  double foul_probability = 0;
  /// Every ball's end in the verification run: the request's balls in order, then
  /// the placed cue ball when it was in hand.
  std::vector<BallEnd> balls_end;
  /// The full-fidelity simulation's events.
  std::vector<PlannedEvent> events;
  /// What the stroke is worth to the striker, in points (the ranking score): the
  /// Monte Carlo's mean objective, with lookahead's correction for the pots that
  /// drop; the nominal run's objective until a Monte Carlo ran.
  double score = 0;
  /// The Monte Carlo runs behind the probabilities and `score` (0: none ran).
  int monte_carlo_samples = 0;
  /// A safety, escape or break-off that pots no ball on: what it leaves the
  /// opponent (nullopt after a pot or a foul).
  std::optional<OpponentLeave> opponent;
  /// What the Monte Carlo's runs left the opponent when they handed the table over
  /// (all 0 when no Monte Carlo ran). For a safety with runs, the spread of leaves
  /// the noise gives around `opponent`'s one.
  Handovers handovers;

  // For reports (not part of the API's answer).
  double search_score = 0;       ///< the objective at the nominal shot
  double pot_estimate = 0;       ///< fast estimate from the nominal object-ball line
  int source = -1;               ///< the plan's candidate it came from
  double position_points = 0;    ///< the leave's estimated expected points (position.h)
  double lookahead = 0;          ///< two-ply's change of the leave's value (NextShotValue)
};

enum class PlanStatus : std::uint8_t {
  kOk,              ///< at least one shot
  kNoPot,           ///< no candidate survived pruning, or none was found to pot
  kInvalidRequest,  ///< reason names the field (validate.h)
  kBudgetSpent,     ///< the time budget ran out before any shot was verified
  kDeadline,        ///< the caller's deadline passed before any shot was verified
  kCancelled,       ///< the cancel flag stopped it (shots found so far are kept)
};
const char* ToString(PlanStatus s);

struct PlanAnswer {
  PlanStatus status = PlanStatus::kOk;
  /// Best first; empty with a reason when no pot exists or none was found.
  std::vector<PlannedShot> shots;
  std::string reason;
  /// The ball on the plan used.
  std::optional<BallOn> ball_on;
  /// Work done: every simulation (search, verification, Monte Carlo), NLopt
  /// objective evaluations, and wall time (s).
  std::int64_t simulations = 0;
  std::int64_t evaluations = 0;
  double elapsed = 0;
  /// The simulations the plan could run: the request's max_simulations, or what its
  /// time budget (or the deadline, when earlier) buys
  /// (PlannerConfig::simulations_per_ms, whole simulations). The stages' shares of the
  /// work follow from it alone.
  std::int64_t simulation_cap = 0;
  /// The clock (the budget's stage ends, the caller's deadline) or the cancel flag
  /// stopped some of the work before the caps did, so another run may differ. When
  /// false, the same request with max_simulations set to simulation_cap gives this
  /// answer again on any machine, given the time (a budget large enough).
  bool cut_short = false;
  // For reports.
  int candidate_pairs = 0;
  int candidates = 0;
  int searched = 0;
  int verified = 0;
  int verification_failures = 0;
  bool deadline_hit = false;
};

/// How a Planner is set up (fidelity, budget calibration and shares).
struct PlannerConfig {
  const physics::TableModel* table = &physics::DefaultTable();
  /// Full fidelity (physics::Fidelity::kDefault): verification and Monte Carlo.
  /// The event cap is lower than the simulator's 5000: a pot and its positional
  /// run take 10 to 60 events (a mean of 14 in docs/planner.md's fidelity set) and
  /// break-offs into the pack stay under 400 (docs/resting-contacts.md), so a run
  /// past 2000 is far outside what a planned shot does and counts as a failed
  /// candidate.
  physics::SimParams full = [] {
    physics::SimParams p = physics::FidelityParams(physics::Fidelity::kDefault);
    p.max_events = 2000;
    return p;
  }();
  /// The search's fidelity (physics::Fidelity::kSearch: the impact solvers at
  /// 1e-6; docs/planner.md measures what it costs and changes) and a tighter
  /// event cap.
  physics::SimParams search = [] {
    physics::SimParams p = physics::FidelityParams(physics::Fidelity::kSearch);
    p.max_events = 400;
    return p;
  }();
  SearchSettings search_settings;
  /// The robot's cue: how its strikes become the cue ball's motion.
  physics::CueParams cue;
  /// Simulations per millisecond per thread that the budget buys (the answer's
  /// simulation_cap). A plan whose searches NLopt's tolerances end early ends by its
  /// cap, the same answer for a seed whatever the timing (the demo's table: 2363 of
  /// 4800 at 80 ms). One whose searches all run to their caps simulates about 22 a
  /// millisecond a thread (BM_PlanWork, docs/planner.md), fewer than this, so the
  /// clock ends it and says so (PlanAnswer::cut_short; how often: operations.md §4).
  double simulations_per_ms = 30.0;
  /// Shares of the budget (time and simulations): the search ends at
  /// search_share, the Monte Carlo at search_share + monte_carlo_share.
  double search_share = 0.65;
  double monte_carlo_share = 0.27;
  /// Share of the budget at which all work stops (the rest is left for the
  /// simulation in flight and the answer's assembly).
  double end_share = 0.95;
  /// Share of each candidate's evaluations given to the global stage (the rest
  /// to the local one).
  double global_share = 0.5;
  /// Shots ranked by Monte Carlo: the max_shots asked for plus two, and at least
  /// this many (the nominal objective's best is not always the most robust).
  int min_ranked = 3;
  /// A direct pot's Monte Carlo score corrected by a Gaussian fit of its object
  /// ball's lines at the pocket (MonteCarloTally::tail_corrected_score) when at
  /// least this many lines were measured; 0: off. Forty-eight samples cannot tell a
  /// 0.99 pot from a 0.999 one, which the fit can (it agrees with what the played
  /// pots did within about 1 %), but on (16) it changed neither self-play's pot rate
  /// nor the frames won against direct-pots (docs/whole-frame-planner.md §10), so
  /// it is off.
  int pot_tail_min_samples = 0;
  /// Candidates searched at most, and the smallest evaluation count worth a search.
  int max_candidates = 12;
  int min_evaluations = 8;
  /// A candidate whose prior (estimated points) is under this share of the best
  /// prior is not searched: a tenth of the best is not worth the time it takes.
  double min_prior_share = 0.1;
  /// The search evaluations are shared by weight: the weight halves after every
  /// search_weight_band candidates in order of prior, down to min_search_weight.
  int search_weight_band = 4;
  double min_search_weight = 0.25;
  /// The weight of the candidate of this rank (0: the best prior).
  double SearchWeight(int rank) const;
  /// This configuration planning with `model`: the physical parameters of both
  /// fidelity tiers and the cue replaced, every numerical setting kept.
  PlannerConfig WithModel(const physics::Model& model) const;
  /// The physical model it plans with (taken from `full` and `cue`).
  physics::Model model() const { return physics::ModelOf(full, cue); }
  /// The break-off: the soft break into the pack only (break_off.h), or also the
  /// thin break on an end red. Off: the search's noiseless score prefers the thin
  /// break, so it is the one that reaches the Monte Carlo, but in whole frames
  /// against an opponent who pots as well as this planner it handed that opponent a
  /// red to pot at once in 32 of 50 frames and the soft break in none
  /// (docs/whole-frame-planner.md §9).
  bool thin_break_off = false;
  /// Safeties are searched only when no pot's fast estimate reaches this: a table
  /// with a near-certain pot is not one to play safe on.
  double safety_below = 0.85;
  /// Candidates of kinds other than pots searched at most, and ranked by Monte
  /// Carlo at most (beside the pots).
  int max_others = 6;
  int ranked_others = 2;
  /// Candidates of each route other than the direct (plants, doubles, kicks) and of
  /// escapes, the likeliest first: their searches are dearer and their pots rarer.
  int routes_each = 3;
  /// A pot's alternatives (the best of its other spin classes) are verified, and
  /// offered, when they score at least this share of its best shot.
  double alternative_share = 0.6;
  /// Two-ply: the budget's share moved from the search to searching the next shot
  /// (the likeliest next pot) for this many of the best pots.
  double lookahead_share = 0.15;
  int lookahead_shots = 2;
};

class Planner {
 public:
  using Config = PlannerConfig;

  /// Builds the pocket and throw models for the configured table (the defaults'
  /// are shared and built once per process).
  explicit Planner(const Config& config = Config());
  /// A planner with the default configuration, built on first use.
  static const Planner& Default();

  /// Plans a shot. Thread-safe (const); any number of plans may run at once. A
  /// request that ValidatePlanRequest (validate.h) refuses is kInvalidRequest.
  PlanAnswer Plan(const PlanRequest& request) const;

  const Config& config() const { return config_; }
  const PocketModel& pockets() const { return *pockets_; }
  /// The geometric context of a request (noise, sigmas, models).
  PotContext ContextFor(const PlanRequest& request) const;

 private:
  Config config_;
  std::unique_ptr<PocketModel> own_pockets_;
  std::unique_ptr<ThrowModel> own_throws_;
  const PocketModel* pockets_ = nullptr;
  const ThrowModel* throws_ = nullptr;
};

}  // namespace snooker::planner
