// What a table offers the player to play it: their pots, whether they are
// snookered, and what a snooker is expected to cost them. The planner scores a
// safety by the outlook of the table it leaves, the opponent being the player to
// play; after an in-off the incoming player has the cue ball in hand, and the
// outlook is that of their best placement in the D.
//
// Pots. The player's pots are position.h's: EvaluatePosition on the table as it
// stands (the fast estimate with paths and cue room checked, discounted for a cue
// ball on a cushion or cramped), so a safety and a positional shot are judged in one
// currency: p (value + continuation), weighted over the best three balls.
//
// Snookered (WPBSA rules, docs/planning-notes.md §1.4-1.5): the cue ball cannot hit
// any ball on by a straight stroke. For each ball on, contacts are sampled across
// the ball from the thinnest cut the planner considers (PotContext::max_cut) on
// one side to the same on the other, evenly in the impact parameter (the offset of
// the cue ball's line from the object ball's centre, 2R sin(cut)), the full ball
// first: a contact is open when the cue ball's straight path to it passes every
// other ball by 2R plus PotContext::path_clearance and the cue has room behind the
// cue ball (geometry.h CueMargin). A ball on is hittable when one sampled contact is
// open. Sampling can miss a gap narrower than the samples' spacing (4R sin(max_cut)
// / (contacts - 1) across the ball on: 8.6 mm with the defaults); such a gap is no
// escape a player would bet a foul on.
//
// Touching ball (§1.5): a ball whose surface is within kTouchingGap of the cue
// ball's touches it. The player must play away from it: a heading with any
// component towards it is blocked, any other ignores it. A touching ball that is on
// counts as hit, so the player is never snookered then. For the pots (which
// EvaluatePosition judges without the rule) a touching ball is moved straight away
// from the cue ball until the paths' checks clear it, and stays an obstacle but no
// pot: potting it would mean playing into it.
//
// The cost of a snooker. A snookered player escapes off a cushion and fouls when the
// cue ball misses. The model: the best one-cushion escape over the balls on and the
// six cushion noses (the mirror image of the ball on in the line a ball centre
// touches the cushion at, aimed full ball; both legs clear of the other balls by
// 2R + path_clearance, the bounce on the straight nose at least R from a jaw, room
// for the cue). The cue ball's line at the ball on is off by a Gaussian lateral
// error of
//   sigma^2 = (L1 + L2)^2 sigma_h^2 + L2^2 sigma_rebound^2 + sigma_cue^2 + sigma_on^2
// (L1 to the cushion, L2 on from it to the contact, sigma_h the heading noise of
// the context, sigma_rebound the rebound's own error, the vision sigmas), and it
// misses when that error exceeds 2R (no contact at all):
//   P(miss) = 2 (1 - Phi(2R / sigma)).
// A mirror bounce is what a slow, spinless ball does; the real rebound depends on
// speed and spin, which the player's own aim allows for, so sigma_rebound stands for
// what they cannot (OutlookOptions::rebound_sigma). With no one-cushion escape open,
// the player needs two cushions or a swerve, and misses with
// OutlookOptions::blind_miss. A miss gives the opponent the penalty: the ball on's
// value and never less than 4 (§1.4), for the ball the escape aims at (reds: 4). Not
// modelled: an escape that hits a ball not on first (a larger penalty when that ball
// is worth more), a foul when not snookered, the free ball and the miss rule.
//
// Ball in hand (no cue ball on the table). The cue ball is tried on a coarse grid
// in the D: the point c, OutlookOptions::d_inset behind the brown spot, and on
// d_rings half circles around c, of radii (d_radius - 2 d_inset) k / d_rings,
// d_angles points evenly from the baulk line's -x end through -y to its +x end (one
// point: straight behind c), 22 points by default; points within 2R + d_inset of a
// ball are skipped. The outlook is that of the point with the most expected_points
// less expected_penalty (the first such point in grid order on ties). The placed
// ball's vision sigma is the context's noise.position. Snooker lets a ball in hand
// be played in any direction, so no direction is excluded.
//
// Cost: one EvaluatePosition, one snooker check (at most balls on x contacts x
// balls segment distances, stopping at the first open contact) and, only when
// snookered, the escape search (balls on x 6 cushions). No allocation with the cue
// ball on the table and touching nothing (a copy of the table otherwise); in hand,
// a copy of the table and of the context, then the grid's evaluations.
#pragma once

#include <optional>

#include "planner/candidates.h"
#include "planner/position.h"

namespace snooker::planner {

/// Whether the cue ball can hit the balls on directly (see the header's comment).
struct SnookerCheck {
  /// Balls on the table that are on (IsLegalTarget).
  int balls_on = 0;
  /// Of those, the balls hittable by a straight stroke (a touching ball on counts).
  int hittable = 0;
  /// hittable / balls_on, in [0, 1]; 0 when no ball is on.
  double hittable_share = 0;
  /// balls_on > 0 and hittable == 0.
  bool snookered = false;
  /// The lowest index of a ball touching the cue ball, or -1.
  int touching = -1;
  /// A ball touching the cue ball is on (the player is deemed to hit it).
  bool touching_on = false;
};

/// The heading (rad) of a straight stroke from the cue ball (index `cue`) that
/// reaches ball `ball` at one of `contacts` sampled contacts (odd counts include the
/// full ball; clamped to [1, 64]) with a clear path and room for the cue: the
/// fullest open contact, the side of positive cuts first on a tie; nullopt when none
/// is open, or when `ball` touches the cue ball (no stroke is needed: it is deemed
/// hit if on).
std::optional<double> DirectHitHeading(const TableState& table, int cue, int ball,
                                       const PotContext& ctx, int contacts);

/// True when `ball` touches the cue ball or DirectHitHeading finds a stroke. A
/// touching ball is hittable whatever its kind; the caller judges whether it is on.
bool CanHitDirectly(const TableState& table, int cue, int ball, const PotContext& ctx, int contacts);

/// The snooker check of the cue ball (index `cue`) for the balls on. The table may
/// hold at most physics::limits::kMaxBalls balls.
SnookerCheck CheckSnooker(const TableState& table, int cue, BallOn on, const PotContext& ctx,
                          int contacts);

struct OutlookOptions {
  /// The pots' weights and discounts (position.h).
  PositionOptions position;
  /// Contacts sampled across each ball on by the snooker check: odd, so that the
  /// full ball is one; 13 puts the samples 8.6 mm apart in the impact parameter
  /// with the default max_cut (80 deg), a sixth of a ball's radius.
  int contacts = 13;
  /// Error of a one-cushion rebound's direction that the striker's aim does not
  /// remove, rad. 1 deg is an estimate, not a measurement: a rolling ball's rebound
  /// angle changes by degrees between slow and firm strokes and with side, which a
  /// player judges by eye. It makes a 1.5 m second leg miss a ball 5 % of the time.
  double rebound_sigma = 1.0 * physics::kPi / 180;
  /// Probability of missing the ball on when no one-cushion escape is open (two or
  /// more cushions, or a swerve). An estimate: such escapes are hit about as often
  /// as missed by club players, and the robot plays neither reliably.
  double blind_miss = 0.5;
  /// Ball in hand: the D's grid (d_rings in [0, 16] rings of d_angles in [1, 32]
  /// points, the first and last of a ring towards the ends of the baulk line) and
  /// its margin, m: at least this much inside the D's arc and behind the baulk line
  /// (a ball placed over the line or outside the D is a foul; 5 mm covers the
  /// placement's error), and this much clear of every ball beyond 2R.
  int d_rings = 3;
  int d_angles = 7;
  double d_inset = 0.005;
};

/// The best one-cushion escape found for a snookered player.
struct Escape {
  /// The ball on aimed at (index in the table evaluated), or -1 when none is open.
  int ball = -1;
  /// The cushion nose of the bounce: index into physics::TableModel::segments().
  int cushion = -1;
  /// The cue ball's heading (rad) for a full-ball mirror aim.
  double heading = 0;
  /// Path length from the cue ball to the cushion, and on to the contact. m.
  double to_cushion = 0;
  double to_ball = 0;
  /// Probability that the cue ball misses the ball on (the model above).
  double miss_probability = 0;
};

struct Outlook {
  /// The player's best next pot: its probability (the fast estimate with the
  /// position's discounts; 0 when no pot is on), ball index (-1 when none) and pocket.
  double pot_probability = 0;
  int pot_ball = -1;
  physics::PocketId pot_pocket = physics::PocketId::kBaulkLeft;
  /// PositionValue::value: the weighted sum of the best three balls' probabilities
  /// (dimensionless, in [0, 1.48] with the default weights).
  double position_value = 0;
  /// PositionValue::expected_points: the weighted sum of p (value + continuation).
  /// Points.
  double expected_points = 0;
  /// Whether the player can hit the balls on directly.
  SnookerCheck snooker;
  /// When snookered: the best one-cushion escape (ball -1 when none is open).
  Escape escape;
  /// Probability that the player fouls by missing the ball on: the escape's miss
  /// probability, or blind_miss when none is open; 0 when not snookered.
  double foul_probability = 0;
  /// Points the opponent receives for that foul: max(4, value of the ball aimed at);
  /// 0 when not snookered.
  double penalty = 0;
  /// foul_probability x penalty: points expected to go to the opponent.
  double expected_penalty = 0;
  /// In hand: the D placement this outlook is for (nullopt when the cue ball was on
  /// the table), and the number of free grid points tried (0 with the cue ball on
  /// the table, or when every grid point is taken: then the outlook is all zeros).
  std::optional<physics::Vec2> placement;
  int placements_tried = 0;
};

/// The outlook of `table` for the player to play with `on` on. With no cue ball on
/// the table the player has it in hand (the grid in the D, above); indices in the
/// answer are those of `table` either way (the placed cue ball is not among them).
/// `placed`: the caller's buffer for the table with the cue ball placed in hand
/// (kept from call to call, it makes an outlook in hand allocate nothing once it
/// has grown, when ctx has no per-ball vision sigma), or none. `lines`: the
/// caller's cache of lines into the pockets (PocketLineCache), or none.
Outlook EvaluateOutlook(const TableState& table, BallOn on, const PotContext& ctx,
                        const OutlookOptions& options, TableState* placed = nullptr,
                        PocketLineCache* lines = nullptr);

}  // namespace snooker::planner
