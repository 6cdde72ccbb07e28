// What a shot does to the rest of the table, in points the planner can add to the
// shot's position value: colours knocked off good places, reds freed or tied up.
//
// The cue ball takes no part: where it stops is the position value's business
// (position.h), and it will have moved before the colours and reds matter. It is
// neither scored nor an obstacle here.
//
// Colours. A colour's pottability is how well it can be potted from where it lies,
// wherever the cue ball may come from. For each pocket: the line from the colour to
// the pocket, aimed at the centre of the pocket's acceptance window (PocketModel,
// taken along the line to the mouth's centre, at the typical arrival speed of
// pot_estimate.h), must find the window open and pass every other ball by 2R +
// path_clearance; the ghost ball (the cue ball's centre at contact) must lie on the
// bed, 2R + path_clearance clear of every ball; and a cue ball must have a run of
// at least min_cue_run (up to cue_distance) to it, on the bed and clear, straight
// behind (a straight pot) or, when that is blocked or off the bed, at the smallest
// cut in steps of cut_step up to max_cut. The bed is the rectangle of the
// cushions' contact lines, widened by touch_gap, so that a ball frozen to a cushion
// can be potted along it by a cue ball on the cushion (the ghost ball and the cue
// ball then lie up to touch_gap past the contact line: on the cushion, the line a
// fraction of a millimetre off the window's centre). The pocket's chance is that of
// a pot whose object-ball line is off by a Gaussian angle of sigma = line_sigma /
// cos(cut) (the ghost-ball leverage, docs/planning-notes.md §2.2):
//   P = 2 Phi(w / (2 L sigma)) - 1,   w the window's width, L the distance to the mouth.
// The pottability is the best pocket's P plus pocket_weights[1] times the second
// best (a colour with two pockets beats one with one, as position.h's alternatives
// do), in [0, 1 + pocket_weights[1]]. A colour's change is
//   colour_weight x value x (pottability after - pottability before),
// summed over the colours on both tables (matched by kind: each colour is unique).
// A colour potted and not re-spotted is left out: its pot is scored elsewhere.
//
// Reds. A red is tied up when it touches a cushion or another ball (its surface
// within touch_gap of the cushion's contact line or of another ball's surface), or
// when no pocket passes the colours' test for it (no clear object-ball line with a
// cue ball able to reach the ghost ball). Reds have no identity across a shot, so
// the count is compared: each red tied up after the shot beyond those before costs
// tied_red_cost (a potted red that was tied up is one fewer).
//
// LayoutChange (points, positive: better for the striker's next shots) is the sum
// of both. Cost: per table, 6 colours x 6 pockets of window lookups, the pockets'
// paths checked best first until the best two are settled, and up to 6 pockets per
// red (stopping at the first open one); the table after a shot judges again only
// the balls the shot can have changed (LayoutChange with a summary); no allocation.
// bench/planner_outlook_bench.cc measures it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "physics/core/limits.h"
#include "planner/pocket_model.h"
#include "planner/rules.h"

namespace snooker::planner {

struct LayoutOptions {
  /// The pockets' acceptance windows for the table model passed alongside; nullptr:
  /// PocketModel::Default(), which is for physics::DefaultTable() only (built on
  /// first use, a few thousand simulations; the planner passes its own).
  const PocketModel* pockets = nullptr;
  /// Points per unit of pottability per point of the colour's value. 1: the next
  /// time the colour is wanted it pots that much more or less often and its value is
  /// what is at stake; later uses are not counted, because a colour potted while reds
  /// remain goes back on its spot, so a colour's bad place lasts until it is next
  /// potted. The break's continuation (position.h) is not counted either: the
  /// position value already carries it for the next shot.
  double colour_weight = 1.0;
  /// Weights of the best and second-best pocket of a colour (position.h's first two).
  std::array<double, 2> pocket_weights = {1.0, 0.33};
  /// Standard deviation of a straight pot's object-ball direction, rad. 0.0058 rad:
  /// the default noise (pot_estimate.h), 0.2 mm of vision error on each ball
  /// (sqrt(2) x 0.2 mm / 2R, 5.4e-3 rad) and 0.02 deg of heading over a 0.3 m run
  /// (0.3 m x 3.5e-4 rad / 2R, 2.0e-3 rad), added in quadrature.
  double line_sigma = 0.0058;
  /// The cue ball's run to the ghost ball that must be clear and on the bed, m:
  /// 0.1 m. A cue ball that can stop that close behind the ghost ball can play the
  /// pot; a ball further back on the line only means it must stop nearer. Shorter
  /// where the bed ends, down to min_cue_run (closer than 5 cm the cue ball is all
  /// but touching the object ball). The noise of line_sigma is a 0.3 m run's, a
  /// position a player aims for.
  double cue_distance = 0.1;
  double min_cue_run = 0.05;
  /// Cuts tried when the straight pot is blocked: steps and the thinnest, rad (60
  /// deg: every error counts twice there, §2.2); at most 90 steps each side.
  double cut_step = 15.0 * physics::kPi / 180;
  double max_cut = 60.0 * physics::kPi / 180;
  /// Room beyond 2R that a line must leave to every ball, m (as PotContext).
  double path_clearance = 0.5e-3;
  /// A red is touching when its surface is within this of a cushion's contact line
  /// or another ball, m: 1 mm is five vision sigmas (0.2 mm), so a red reported that
  /// close may well be touching, and a player treats it as touching.
  double touch_gap = 1e-3;
  /// Points per red tied up. 1.5: a free red is worth 1 and the colour after it
  /// (about 4 to 7) when taken at the pot rates of docs/planner.md; a tied red is
  /// out of play until a shot frees it, and that shot (a split or a cannon) risks the
  /// visit. An estimate, a fraction of a red-and-colour's 5 to 8 points.
  double tied_red_cost = 1.5;
};

/// How the object balls of a table lie.
struct LayoutSummary {
  /// Pottability of each colour (physics::Colour order; see above), in
  /// [0, 1 + pocket_weights[1]]; 0 for a colour not on the table.
  std::array<double, physics::kColourCount> colour_pottability{};
  /// Each colour is on the table.
  std::array<bool, physics::kColourCount> colour_present{};
  int reds = 0;
  int tied_reds = 0;
  /// Per ball of the table, by index (the first physics::limits::kMaxBalls): a
  /// colour's pottability, 1 for a red tied up, otherwise 0; and for a red, why:
  /// the first pocket found open (its PocketId's value) when free, -1 when closed
  /// to every pocket, -2 when touching (unused for other balls).
  std::array<double, physics::limits::kMaxBalls> ball{};
  std::array<std::int8_t, physics::limits::kMaxBalls> red_state{};
};

/// A pot that the layout's test finds open (see above).
struct LayoutPot {
  /// The pot's chance P (see above), a probability.
  double chance = 0;
  /// The cue ball's approach found: the cut (geometry.h's sign, rad), where the
  /// cue ball starts (m, table frame; up to touch_gap past a contact line, see
  /// above) and its heading to the ghost ball (rad).
  double cut = 0;
  physics::Vec2 cue = physics::Vec2::Zero();
  double heading = 0;
  /// The object ball's line, rad, aimed at the centre of the pocket's window.
  double object_direction = 0;
};

/// Ball `ball` of `table` into `pocket` by the layout's test, or nullopt when the
/// pocket is closed to it (the window shut, the line or the ghost ball blocked, no
/// approach for the cue ball).
std::optional<LayoutPot> OpenPot(const TableState& table, int ball, physics::PocketId pocket,
                                 const physics::TableModel& model, const LayoutOptions& options);

/// Pottability of ball `ball` (any object ball): best pocket + weight x second.
double Pottability(const TableState& table, int ball, const physics::TableModel& model,
                   const LayoutOptions& options);

/// Red (or any ball) `ball` is tied up: touching a cushion or another object ball,
/// or closed to every pocket.
bool TiedUp(const TableState& table, int ball, const physics::TableModel& model,
            const LayoutOptions& options);

LayoutSummary SummarizeLayout(const TableState& table, const physics::TableModel& model,
                              const LayoutOptions& options);

/// The colours' and reds' change from `before` to `after` (the table after the
/// shot: potted balls removed, colours re-spotted, as ApplyShot makes it). Points;
/// positive: better for the striker's future. Exactly 0 when the two tables hold
/// the same balls at the same places.
double LayoutChange(const TableState& before, const TableState& after,
                    const physics::TableModel& model, const LayoutOptions& options);

/// The same with `before_summary` = SummarizeLayout(before, model, options) given,
/// for a planner that scores many shots from one table. A ball of `after` that lies
/// exactly where a ball of its kind lay in `before` keeps its result from
/// before_summary instead of being judged again when no change can alter it: balls
/// that arrive (moved to a place, re-spotted) can only close lines and balls that
/// leave (moved away, potted) only open them, so a free red is judged again only
/// when a ball arrives within reach of its approaches or of its open pocket's line,
/// a tied red only when a ball leaves within reach of its approaches or of any of
/// its lines, a colour when any change comes within reach of either. The answer is
/// the same, for a fraction of the cost.
double LayoutChange(const TableState& before, const LayoutSummary& before_summary,
                    const TableState& after, const physics::TableModel& model,
                    const LayoutOptions& options);

}  // namespace snooker::planner
