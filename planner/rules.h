// Snooker's rules as the planner needs them (WPBSA rules, section 3;
// docs/planning-notes.md §1): ball values, the ball on, legal first contacts and
// pots, fouls, the score of a shot, and re-spotting the colours.
//
// The table state here is what vision reports: each ball's kind and centre, all at
// rest. A ball's identity is its index in TableState::balls; the API layer maps its
// own ids onto those indices.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "physics/core/types.h"
#include "physics/table/table.h"

namespace snooker::planner {

enum class BallKind : std::uint8_t { kCue, kRed, kYellow, kGreen, kBrown, kBlue, kPink, kBlack };
inline constexpr int kBallKindCount = 8;

/// "cue", "red", "yellow", "green", "brown", "blue", "pink", "black".
const char* ToString(BallKind k);
/// Points for potting the ball: red 1, yellow 2, ... black 7; the cue ball 0.
int Value(BallKind k);
bool IsColour(BallKind k);
/// The colour of a colour ball (IsColour(k) must hold).
physics::Colour ColourOf(BallKind k);
BallKind KindOf(physics::Colour c);

/// What the striker must hit first and may pot.
enum class BallOn : std::uint8_t {
  kRed,        ///< any red
  kAnyColour,  ///< after a red: any colour, the striker choosing (nominating) which
  kYellow,     ///< once the reds are gone: the colours in ascending value
  kGreen,
  kBrown,
  kBlue,
  kPink,
  kBlack,
};
/// "red", "colour", "yellow", ..., "black".
const char* ToString(BallOn on);
/// The specific colour on (kYellow..kBlack) for a colour kind.
BallOn BallOnFor(BallKind colour);

/// One ball at rest. Table frame (physics/table/table.h), m.
struct Ball {
  BallKind kind = BallKind::kRed;
  physics::Vec2 position = physics::Vec2::Zero();
};

struct TableState {
  std::vector<Ball> balls;

  /// Index of the cue ball, or -1.
  int cue_index() const;
  int Count(BallKind k) const;
  int reds() const { return Count(BallKind::kRed); }
};

/// True when a ball of `kind` may be struck first and potted with `on`.
/// kAnyColour accepts every colour; a specific colour only itself.
bool IsLegalTarget(BallOn on, BallKind kind);

/// The ball on at the start of a visit: a red while any remain on the table,
/// otherwise the lowest-valued colour on it; nullopt on an empty table (the frame
/// is over).
std::optional<BallOn> OpeningBallOn(const TableState& table);

/// Why a shot ended the visit.
enum class Foul : std::uint8_t {
  kNone,
  kNoBallHit,         ///< the cue ball touched no ball
  kWrongBallFirst,    ///< the first ball hit is not on (or not the nominated colour)
  kCuePotted,         ///< in-off
  kWrongBallPotted,   ///< a ball not on was potted
  kSimulationFailed,  ///< the shot could not be simulated to its end (cap, solver)
};
const char* ToString(Foul f);

/// What a shot did, by the rules.
struct ShotJudgement {
  Foul foul = Foul::kNone;
  /// Legal balls potted (no foul): the visit goes on when this is > 0.
  int legal_pots = 0;
  /// Points scored by the striker (0 on a foul).
  int points = 0;
  /// On a foul, the points it gives the opponent (FoulPenalty); 0 otherwise.
  int penalty = 0;
  /// The kind potted legally (the last one for several reds).
  std::optional<BallKind> potted_kind;
};

/// Balls whose gap (centre distance less 2R) is at most this count as touching. m.
inline constexpr double kTouchingGap = 1e-4;

/// The indices of the balls touching the cue ball (gap at most kTouchingGap, balls
/// of `model`'s radius), ascending; empty when the table has no cue ball.
std::vector<int> TouchingCueBall(const TableState& table, const physics::TableModel& model);

/// Whether a stroke along the unit vector `u` plays into a ball touching the cue ball
/// at `to_ball` from it (a push): any component towards it, bar rounding. Along the
/// tangent, as when the cue ball is hemmed in on both sides and plays between, it
/// plays away; a heading's rounding (cos 270 deg is -1.8e-16, not 0) must not make
/// that a push.
inline bool PlaysInto(const physics::Vec2& u, const physics::Vec2& to_ball) {
  return u.dot(to_ball) > 1e-12 * to_ball.norm();
}

/// The value of a foul (docs/planning-notes.md §1.4): 4, or the value of the ball
/// on (the nominated colour when a colour is on and one was nominated), of the first
/// ball hit, or of any ball potted in the stroke, whichever is highest: 4 to 7.
/// Arguments as JudgeShot's.
int FoulPenalty(const TableState& table, BallOn on, std::optional<BallKind> nominated, int first_hit,
                std::span<const int> potted);

/// Judges a shot. `on` is the ball on; with kAnyColour, `nominated` is the colour
/// the striker chose (required then, ignored otherwise). `first_hit` is the index
/// of the first ball the cue ball touched (-1 for none); `potted` lists the indices
/// of the balls that dropped. `table` is the state before the shot.
///
/// `touching` lists the balls that touched the cue ball before the stroke
/// (TouchingCueBall). When one of them is on, the striker counts as having hit a
/// ball on (docs/planning-notes.md §1.5): playing away from it is neither "no ball
/// hit" nor "wrong ball first", whatever the cue ball meets next; potting a ball
/// not on is still a foul. A touching ball that is not on changes nothing. On a
/// foul, `penalty` is FoulPenalty's.
ShotJudgement JudgeShot(const TableState& table, BallOn on, std::optional<BallKind> nominated,
                        int first_hit, std::span<const int> potted, std::span<const int> touching = {});

/// The ball on after a shot that potted `potted_kind` legally while `on` was on,
/// given the table after the shot (potted balls removed, colours re-spotted):
/// after a red any colour; after a colour a red while reds remain, else the lowest
/// colour left; nullopt when the table is cleared.
std::optional<BallOn> NextBallOn(BallOn on, BallKind potted_kind, const TableState& after);

/// Where a colour goes back on the table (WPBSA 3.4): its own spot if free (no ball
/// would touch or cover it); else the highest-valued free spot; else as near its
/// own spot as possible on the line from it towards the top cushion (for the pink
/// and black, if that line is blocked up to the cushion, towards the baulk
/// cushion). `others` are the centres of the balls on the table. Table frame, m.
/// nullopt only if no place on those lines is free (impossible in a real frame).
std::optional<physics::Vec2> RespotPosition(BallKind colour, std::span<const physics::Vec2> others,
                                            const physics::TableModel& table);

/// The table after a shot, by the rules: potted balls removed; each potted colour
/// re-spotted (RespotPosition), highest value first, unless it was the ball on in
/// the final sequence (no reds left and `on` was that colour) and the shot was no
/// foul. `final_positions` are where the simulation left every ball (same order as
/// `before`); `potted` the indices that dropped. When `origin` is given it receives,
/// for each ball of the result, its index in `before`.
TableState ApplyShot(const TableState& before, BallOn on, std::span<const physics::Vec2> final_positions,
                     std::span<const int> potted, bool foul, const physics::TableModel& table,
                     std::vector<int>* origin = nullptr);

/// ApplyShot into `after` and `origin` (each cleared first, its buffer kept): once
/// they have grown to the table's size, no allocation, for the search's and the
/// Monte Carlo's every evaluation. `origin` may be null; `after` must not be
/// `before`.
void ApplyShotInto(const TableState& before, BallOn on, std::span<const physics::Vec2> final_positions,
                   std::span<const int> potted, bool foul, const physics::TableModel& table, TableState* after,
                   std::vector<int>* origin);

}  // namespace snooker::planner
