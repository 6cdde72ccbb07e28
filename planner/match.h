// A match: two players, each a way of asking the planner, play whole frames by the
// rules (frame.h), to compare planners against each other.
//
// Each frame starts from the standard start (StartFrame); player A breaks off in
// the odd frames (the first, the third, ...), player B in the even ones. Each turn:
//  1. the striker's planner sees the table as vision would (every ball moved by the
//     vision noise, SampleTruePositions) and plans with the player's settings, the
//     match's budget, the frame's ball on and, with the cue ball in hand, the
//     planner placing it (PlannedShot::cue_start);
//  2. the first shot of the plan is played on the true table with the execution
//     noise (SampleExecution), from where the planner placed the cue ball (moved
//     clear of a ball that vision misplaced, if it overlaps one), simulated at
//     full fidelity to rest, and applied to the frame (ApplyStroke);
//  3. a turn whose plan has no shot (or whose placement cannot be played) is a
//     stall: the match plays NearestBallOnShot for the player and counts it.
// The `direct-pots` player's own fallback when it has no pot is that same shot, so
// its stalls are the turns it had no direct pot.
//
// Deterministic: every random draw comes from streams derived from the seed
// (random.h), and with max_simulations set each plan is too, so the whole match is
// a function of the options (timing changes only the planning times reported).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "planner/frame.h"
#include "planner/planner.h"

namespace snooker::planner {

enum class PlayerKind : std::uint8_t {
  kDefault,     ///< the planner with every shot kind, route and the lookahead
  kDirectPots,  ///< direct pots only (kinds: kPot; routes: kDirect; no lookahead)
  kOnePly,      ///< the default without the lookahead
};
inline constexpr int kPlayerKindCount = 3;
/// "default", "direct-pots", "one-ply".
const char* ToString(PlayerKind kind);
/// The player of that name, or nullopt.
std::optional<PlayerKind> ParsePlayerKind(std::string_view name);
/// The break value (PlanRequest::break_value) the players that play for position
/// (`default`, `one-ply`) plan with in a frame against an opponent: a miss there
/// also hands over the table, which the planner's own 30 (a break alone at the
/// table) does not count. docs/whole-frame-planner.md measures both.
inline constexpr double kFrameBreakValue = 100.0;
/// Sets the request fields the player chooses (kinds, routes, lookahead, the break
/// value, the position's spread): `default` and `one-ply` plan with `break_value`
/// and `position_spread` (0: unset); `direct-pots` with the planner's own, as it
/// played before whole frames were (the frame targets' mark).
void ConfigureRequest(PlayerKind kind, PlanRequest* request, double break_value = kFrameBreakValue,
                      double position_spread = 0);

/// The kinds of turn whose planning times a match reports apart.
enum class TurnType : std::uint8_t { kOnTable, kInHand, kBreakOff };
/// "on table", "in hand", "break-off".
const char* ToString(TurnType t);

/// One stroke of a match as it was chosen and played, for a log of the match
/// (MatchOptions::on_stroke; `snooker match --strokes`).
struct StrokeRecord {
  /// Frame (0-based) and stroke within it (1-based); who played it (0 A, 1 B) and
  /// the kind of turn.
  int frame = 0;
  int stroke = 0;
  int striker = 0;
  TurnType turn = TurnType::kOnTable;
  /// What the plan labelled the shot (meaningless for a stall: the match's own
  /// straight shot), its Monte Carlo pot probability (NaN for shots other than pots
  /// and for stalls) and its ranking score, points (NaN for a stall).
  ShotKind kind = ShotKind::kPot;
  PotRoute route = PotRoute::kDirect;
  bool stall = false;
  double pot_probability = std::numeric_limits<double>::quiet_NaN();
  double plan_score = std::numeric_limits<double>::quiet_NaN();
  /// What the stroke did: balls potted (the cue ball included), the foul, the
  /// striker's points and the opponent's penalty, and the score after it.
  int potted = 0;
  Foul foul = Foul::kNone;
  int points = 0;
  int penalty = 0;
  std::array<int, 2> score{0, 0};
  double plan_ms = 0;
  /// When the stroke handed the table to the other player and the frame goes on:
  /// that player's best pot probability by MatchOptions::outlook (what a safety is
  /// measured by, here after every kind of stroke, so that a plan's belief about
  /// what a miss leaves can be checked against what the opponent then did). NaN
  /// otherwise, or with no outlook set.
  double handover_outlook = std::numeric_limits<double>::quiet_NaN();
  /// What the plan's Monte Carlo predicted for the stroke's handovers: its samples
  /// (0 for a stall, or when the plan ran none) and, of those, the runs that handed
  /// the table over and what they left (PlannedShot::handovers), to be set against
  /// whether this stroke handed it over and `handover_outlook`.
  int plan_samples = 0;
  Handovers plan_handovers;
  /// A stall only: why the plan gave no stroke (its status and reason, or why its
  /// placement in the D could not be used).
  std::string stall_reason;
  /// What the turn's plan was given: the table as the striker's vision saw it (no
  /// cue ball when in hand), the ball on and the plan's seed. With the match's
  /// options they are the whole request (ReplayRequest), so that any turn can be
  /// planned again, to the same shot when the plans are capped in simulations.
  TableState table;
  BallOn ball_on = BallOn::kRed;
  std::uint64_t plan_seed = 0;
};

/// How good a table is for the side to play: its best pot probability in [0, 1],
/// NaN when unknown. Given the table (no cue ball when it is in hand) and the ball
/// on. Supplied by whoever can evaluate one (a planner's outlook); optional.
using TableOutlook = std::function<double(const TableState& table, bool cue_in_hand, BallOn on)>;

struct MatchOptions {
  int frames = 1;
  std::uint64_t seed = 1;
  /// Player A, player B.
  std::array<PlayerKind, 2> players{PlayerKind::kDefault, PlayerKind::kDirectPots};
  /// Planning budget per shot, s (both players).
  double time_budget = 0.08;
  /// The world is the model: the cue's noise, no model uncertainty (ModelWorldNoise).
  NoiseModel noise = ModelWorldNoise();
  RobotLimits limits;
  int threads = 2;
  /// Per-plan simulation cap (0: from the budget).
  std::int64_t max_simulations = 0;
  int monte_carlo_samples = 48;
  /// The break value of `default` and `one-ply` (ConfigureRequest), points.
  double break_value = kFrameBreakValue;
  /// The position's spread of `default` and `one-ply` (PlanRequest::position_spread;
  /// 0: the planner's own, the nominal end).
  double position_spread = 0;
  /// Every player's break-offs also search the thin break (PlanRequest::thin_break_off).
  bool thin_break_off = false;
  /// Strokes after which a frame is stopped (1 to kFrameShotCap).
  int max_shots_per_frame = kFrameShotCap;
  /// Evaluates the table a safety leaves for the opponent; unset: not measured.
  TableOutlook outlook;
  /// The world the strokes are played in (sim-to-real: a table unlike the
  /// planner's model); none: the planner's own model.
  std::optional<physics::Model> world;
  /// Called after every stroke, in the order of play; unset: no log.
  std::function<void(const StrokeRecord&)> on_stroke;
};

/// Empty when `options` can be played; otherwise the bad values, named.
std::string MatchOptionsError(const MatchOptions& options);

/// The request the plan of a logged turn was made with: the record's table, ball on
/// and seed, the striker's settings (ConfigureRequest) and the match's noise,
/// limits, budget, threads and caps. Planning it again, with the planner the match
/// was played with, gives the turn's shot when `options.max_simulations` is set (the
/// plans are then functions of their requests).
PlanRequest ReplayRequest(const MatchOptions& options, const StrokeRecord& stroke);

/// The stroke of a player with no plan: a firm straight shot (no spin, at the centre
/// of the ball) at the nearest ball on whose path is clear (the first ball the cue
/// ball meets on the way is a ball on: the target, or another ball on in front of
/// it), else at the nearest ball on; balls touching the cue ball are not aimed at,
/// and when only such a ball is on the cue ball is played straight away from it.
/// With the cue ball in hand it is placed at the point of a fixed grid over the D
/// that gives the best such shot.
struct FallbackShot {
  /// Where the cue ball is placed when it was in hand.
  std::optional<physics::Vec2> cue_start;
  physics::Shot shot;
  /// The ball aimed at (index into the stroke's table: the cue ball appended last
  /// when it was in hand), or -1 when playing away from a touching ball.
  int target = -1;
  /// The first ball the cue ball meets on its straight line, or -1.
  int first_ball = -1;
  /// That first ball is on.
  bool clear = false;
};
/// The fallback's speed before the robot's limits, m/s.
inline constexpr double kFallbackSpeed = 2.5;
FallbackShot NearestBallOnShot(const TableState& table, bool cue_in_hand, BallOn on, const RobotLimits& limits,
                               const physics::TableModel& model);

struct PlayerStats {
  PlayerKind kind = PlayerKind::kDefault;
  int frames_won = 0;
  /// Points over all frames, the opponent's penalties included; those alone.
  int points = 0;
  int penalty_points = 0;
  /// Every break (the points of a visit that scored), in order of play.
  std::vector<int> breaks;
  double mean_break = 0;
  int highest_break = 0;
  int centuries = 0;
  int fouls = 0;
  /// Strokes of kind kSafety played.
  int safeties = 0;
  /// Shots played by kind (stalls not counted), and pots by route.
  std::array<int, kShotKindCount> kinds{};
  std::array<int, kPotRouteCount> routes{};
  int shots = 0;
  int stalls = 0;
  /// Planning time of every turn, ms, and its median and 99th percentile.
  std::vector<double> plan_ms;
  double plan_ms_p50 = 0;
  double plan_ms_p99 = 0;
  /// After each of its safeties that handed the table over: the opponent's outlook
  /// (MatchOptions::outlook; empty when unset), and its mean and median (NaN when
  /// empty).
  std::vector<double> safety_outlook;
  double mean_safety_outlook = 0;
  double median_safety_outlook = 0;
  /// The same after each of its break-offs (the frame's first stroke, whatever was
  /// played) that handed the table over, and its mean and median.
  std::vector<double> break_off_outlook;
  double mean_break_off_outlook = 0;
  double median_break_off_outlook = 0;
};

struct FrameSummary {
  std::array<int, 2> score{0, 0};
  /// 0 (A), 1 (B), or -1 (level at the shot cap).
  int winner = -1;
  int breaker = 0;
  FrameEnd end = FrameEnd::kPlaying;
  int shots = 0;
  int stalls = 0;
  int fouls = 0;
  bool black_respotted = false;
};

struct MatchReport {
  int frames = 0;
  std::array<PlayerStats, 2> players;
  /// Frames stopped at the shot cap, and of those the ones left level (no winner).
  int frames_capped = 0;
  int frames_undecided = 0;
  /// Frames that ended level and went to a re-spotted black.
  int black_respots = 0;
  /// Strokes the simulator could not carry to rest (scored as fouls).
  int simulation_failures = 0;
  int shots = 0;
  int stalls = 0;
  int highest_break = 0;
  int centuries = 0;
  /// Both players' planning times, ms.
  double plan_ms_p50 = 0;
  double plan_ms_p99 = 0;
  /// Plans the clock cut short (PlanAnswer::cut_short): with none, the match is a
  /// function of its options and seed (a simulation cap that binds first).
  int plans_cut_short = 0;
  /// The same by kind of turn: the cue ball on the table, in hand after a foul,
  /// and the break-off (TurnType); NaN for a kind no turn was of.
  std::array<double, 3> plan_ms_p50_by_turn{};
  std::array<double, 3> plan_ms_p99_by_turn{};
  std::vector<FrameSummary> records;
};

/// Plays options.frames frames. Throws std::invalid_argument with
/// MatchOptionsError's message on bad options. `on_frame`, when set, is called after
/// each frame with its index and summary (for progress output).
MatchReport RunMatch(const Planner& planner, const MatchOptions& options,
                     const std::function<void(int frame, const FrameSummary& summary)>& on_frame = {});

}  // namespace snooker::planner
