// A frame of snooker between two players, by the rules (docs/planning-notes.md §1):
// the table, the scores, whose visit it is, the ball on, the cue ball in hand, and
// one function that applies a played stroke to all of that.
//
// What a stroke does to the frame (ApplyStroke):
//  * fair, potting balls on: the striker scores them and the visit goes on; the
//    ball on follows (NextBallOn: a colour after a red, a red after a colour while
//    reds remain, then the colours in ascending value);
//  * fair, potting nothing: the visit passes to the opponent, who starts with a red
//    while reds remain, else the lowest colour;
//  * a foul (JudgeShot, with the touching-ball rule): the opponent scores the
//    penalty (4 to 7, FoulPenalty) and plays next;
//  * every stroke: potted reds stay down; a potted colour is re-spotted
//    (RespotPosition, highest value first) while reds remain, when it was the colour
//    after the last red, and on a foul; in the final sequence a colour potted fairly
//    stays down (ApplyShot);
//  * an in-off: the incoming player has the cue ball in hand (placed in the D);
//  * the frame ends when the black is potted in the final sequence, or on a foul
//    when the black is the last ball; the higher score wins. On equal scores the
//    black is re-spotted and the player the frame's seed chooses plays it with the
//    cue ball in hand; the next score or foul decides. A frame also ends, undecided
//    by the rules, after max_shots strokes (kFrameShotCap): the higher score then
//    takes it, and equal scores leave it with no winner.
//
// Not applied, and why:
//  * the free ball (after a foul that leaves the incoming player snookered, any ball
//    may be nominated as a ball on): it needs a snooker test (can the cue ball hit
//    both sides of every ball on?) that the planner does not make yet;
//  * the miss rule (the referee may have the balls replaced after a foul when the
//    striker did not try hard enough to hit a ball on): it is a judgement of intent,
//    and replaying would need the opponent's choice as well;
//  * a ball forced off the table: the simulator keeps every ball on the bed, so the
//    foul cannot arise;
//  * the push stroke and moving a touching ball: a stroke here is the cue ball's
//    state after the strike, so there is nothing to push with.
//
// Indices: a stroke's ball indices refer to StrokeTable(frame, cue_start): the frame's
// table, with the placed cue ball appended last when it was in hand.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "physics/table/table.h"
#include "planner/rules.h"

namespace snooker::planner {

/// Strokes after which a frame is stopped undecided.
inline constexpr int kFrameShotCap = 200;

enum class FrameEnd : std::uint8_t {
  kPlaying,      ///< not over
  kBlackPotted,  ///< the black potted fairly in the final sequence
  kBlackFouled,  ///< a foul with the black the last ball
  kShotCap,      ///< max_shots strokes played
};
/// "playing", "black potted", "black fouled", "shot cap".
const char* ToString(FrameEnd end);

struct FrameState {
  /// The balls on the table; no cue ball while cue_in_hand.
  TableState table;
  std::array<int, 2> score{0, 0};
  /// The player at the table: 0 or 1.
  int striker = 0;
  BallOn ball_on = BallOn::kRed;
  bool cue_in_hand = true;
  /// Strokes played so far, and the cap.
  int shots = 0;
  int max_shots = kFrameShotCap;
  /// Points of the striker's visit so far (the current break).
  int visit_points = 0;
  bool over = false;
  FrameEnd end = FrameEnd::kPlaying;
  /// The player who won: 0 or 1, or -1 (not over, or equal scores at the cap).
  int winner = -1;
  /// The black was re-spotted after the frame ended level.
  bool black_respotted = false;
  /// Chooses who plays the re-spotted black.
  std::uint64_t seed = 1;
};

/// The standard start: the 15 reds in their triangle, the colours on their spots,
/// no cue ball (in hand for the break-off), a red on, `breaker` (0 or 1) to play.
FrameState StartFrame(std::uint64_t seed, int breaker, const physics::TableModel& model = physics::DefaultTable());

/// True when `p` lies in the D (on its lines included): at most `d_radius` from the
/// middle of the baulk line, on the baulk cushion's side of it. Table frame, m.
bool InTheD(const physics::Vec2& p, const physics::TableModel& model);

/// Empty when the cue ball may be placed at `p` on `table` (in the D, overlapping no
/// ball); otherwise why not, naming the values.
std::string CuePlacementError(const TableState& table, const physics::Vec2& p, const physics::TableModel& model);

/// The table a stroke is played on: the frame's, with the cue ball appended at
/// `cue_start` when it is in hand.
TableState StrokeTable(const FrameState& frame, const std::optional<physics::Vec2>& cue_start);

/// A stroke as it was played (indices into StrokeTable(frame, cue_start)).
struct Stroke {
  /// Where the cue ball was placed: required when it was in hand, ignored otherwise.
  std::optional<physics::Vec2> cue_start;
  /// The first ball the cue ball hit, or -1.
  int first_hit = -1;
  /// The balls that dropped, in order.
  std::vector<int> potted;
  /// Where every ball ended (potted balls: anywhere). Table frame, m.
  std::vector<physics::Vec2> ends;
  /// The colour nominated when a colour is on; unset, the first ball hit is taken
  /// as nominated when it is a colour (as a referee takes an obvious intention).
  std::optional<BallKind> nominated;
  /// The balls touching the cue ball before the stroke (TouchingCueBall).
  std::vector<int> touching;
  /// The stroke could not be simulated to rest: scored as a foul (the penalty of the
  /// ball on), the balls left where they were before it.
  bool simulation_failed = false;
};

/// What a stroke did to the frame.
struct StrokeResult {
  ShotJudgement judgement;
  /// The player who played it.
  int striker = 0;
  /// The visit ended with this stroke (a foul, no pot, or the end of the frame);
  /// `break_points` is then its break (the points its striker scored in it).
  bool visit_over = false;
  int break_points = 0;
};

/// Empty when `stroke` can be applied to `frame`; otherwise why not, naming the value
/// (the frame is over, a missing or illegal cue placement, an index out of range,
/// ends of the wrong size, a nomination that is not a colour).
std::string StrokeError(const FrameState& frame, const Stroke& stroke, const physics::TableModel& model);

/// Applies a played stroke to the frame (the rules above). Throws
/// std::invalid_argument with StrokeError's message when it cannot be applied.
StrokeResult ApplyStroke(FrameState& frame, const Stroke& stroke,
                         const physics::TableModel& model = physics::DefaultTable());

}  // namespace snooker::planner
