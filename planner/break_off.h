// The break-off's geometry: where to place the cue ball in the D and what to aim
// at, so that the planner searches speed, spin and cut around a sound shot.
//
// The shot (docs/planning-notes.md §1.6): from the D, a thin contact on the end red
// of the pack's back row, sending the cue ball off the top cushion and a side
// cushion back down the table towards baulk, while the pack stays nearly whole.
// The cue ball is placed on one side of the brown spot, between it and the yellow
// (right, +x) or the green (left, -x), and plays the end red of the back row on that
// side on its outer side: the right end red with a positive cut (geometry.h: the
// cue ball takes it on its right-hand side and sends it to the left, into the pack),
// the left one with a negative cut. The cue ball, thrown outwards, comes off the
// top cushion, its own side's cushion and the far side's, back towards the baulk
// cushion.
//
// From the D a fuller contact is not on: the reds beside and in front of the end
// red shield its face, so the straight path to a full contact passes through them.
// The cut range is the run of cuts, on the nominal's side, whose straight path to
// the contact passes every other ball by 2R + BreakOffOptions::path_clearance
// (scanned in cut_step steps from the full ball; on the default table from 30.5 to
// 34.5 deg, by placement, to the scan's end at 85 deg); the nominal cut is the
// range's fullest cut plus nominal_offset.
//
// The nominal stroke (BreakOffOptions::nominal_offset, speed, side) was chosen in
// the simulator on the default table with the standard rack: over the six
// candidates, offsets of 2-16 deg, speeds of 5.5-7.5 m/s and sidespins of -60..60
// rad/s, each played 15 times (cut +-0.5 and +-1 deg, speed +-3 %), 8 deg past the
// fullest clear cut at 6-7 m/s with 60 rad/s of side against the placement's side
// (left-hand side from the right, right-hand side from the left; a quarter of a
// rolling ball's spin at 6.5 m/s) hit the end red first, potted nothing and kept the
// cue ball on the table in 268 of 270 runs, and brought it back behind the baulk
// line in 248. Thinner or fuller, slower or faster, or side the other way did worse
// (4 deg potted the cue ball in a third of the runs). tests/planner/break_off_test.cc
// plays each candidate's nominal stroke at 6, 6.5 and 7 m/s.
//
// The soft break (SoftBreakCandidates) is the other way to open a frame: from the
// same placements, the nearest red whose full-ball line meets a red first (never the
// pink or the blue in front of the pack), at a pace that leaves the cue ball near
// the pack and the reds nearly where they were. An opponent who pots as well as
// this planner punishes the red or two that a thin break at 6-7 m/s knocks loose
// (docs/frame-play.md measures it), and a stroke into the pack leaves fewer. The
// planner plays the soft break; the thin break only when the request asks for it
// (PlanRequest::thin_break_off; unset, PlannerConfig::thin_break_off), and then the
// two kinds are searched alternately and the Monte Carlo of each searched stroke
// decides between them. It is off because the search's noiseless score prefers the
// thin break, so that only thin breaks reached the Monte Carlo (a median of -27
// points where the soft break alone has -2), and in whole frames against direct-pots
// the thin break let it pot a red at once in 32 of 50 frames and the soft break in
// none of 50 (docs/whole-frame-planner.md §9).
//
// The rack is untouched when every one of the 15 reds lies within rack_tolerance of
// a distinct position of the opening triangle (physics::TableModel::reds()): a
// rack set by hand is off by a millimetre or two and vision adds its 0.2 mm, while
// any red the cue ball or another red touched has moved by centimetres.
#pragma once

#include <vector>

#include "planner/rules.h"

namespace snooker::planner {

struct BreakOffOptions {
  /// Placements per side (at most 32), evenly between the brown spot and the
  /// yellow (or green) spot, excluding the spots themselves: 3 gives a quarter,
  /// half and three quarters of the way.
  int placements_per_side = 3;
  /// Placements lie this far behind the baulk line (a cue ball over the line is a
  /// foul; 5 mm covers the robot's placement error), m, and this far clear of every
  /// ball beyond 2R, m.
  double line_inset = 0.005;
  double ball_clearance = 0.005;
  /// Room beyond 2R a straight path to the contact must leave to every other ball, m.
  double path_clearance = 2e-3;
  /// The nominal cut: the fullest clear cut plus this (thinner), rad; and the
  /// nominal stroke's speed, m/s, and sidespin, rad/s, against the placement's side
  /// (see above for how they were chosen).
  double nominal_offset = 8.0 * physics::kPi / 180;
  double speed = 6.5;
  double side = 60.0;
  /// Cuts scanned for the range: steps, rad (at most 900 of them), and the
  /// thinnest, rad.
  double cut_step = 0.5 * physics::kPi / 180;
  double max_cut = 85.0 * physics::kPi / 180;
  /// A red within this of its rack position is untouched, m.
  double rack_tolerance = 0.005;
  /// Also offer the soft break: the nearest red whose centre line from the
  /// placement meets a red first, taken nearly full at soft_speed (m/s), no side.
  bool soft_break = true;
  double soft_speed = 1.6;
};

struct BreakOffCandidate {
  /// Where the cue ball is placed (table frame, m), inside the D.
  physics::Vec2 placement = physics::Vec2::Zero();
  /// The target: index in the table given (the cue ball, placed, comes after all of
  /// its balls), and its position, m.
  int target = -1;
  physics::Vec2 target_position = physics::Vec2::Zero();
  /// True for the right-hand side (+x, the yellow's), false for the left (green's).
  bool right = true;
  /// Nominal cut (geometry.h's sign: positive on the right end red), rad, and the
  /// heading (rad) that plays it from the placement: HeadingForCut(placement,
  /// target_position, cut, R); other cuts' headings likewise.
  double cut = 0;
  double heading = 0;
  /// The cuts with a clear straight path to the contact, on the nominal's side:
  /// cut_lo <= cut <= cut_hi (signed, rad).
  double cut_lo = 0;
  double cut_hi = 0;
  /// A nominal stroke to start the search from: speed (m/s) and sidespin (rad/s,
  /// physics::Shot's sign: positive = counter-clockwise from above, a tip struck
  /// right of centre): options.speed, and -options.side from the right, +options.side
  /// from the left; no topspin.
  double speed = 0;
  double sidespin = 0;
  /// A soft break (nearly full on the nearest red), not the thin contact on an end red.
  bool soft = false;
};

/// The candidates for the break-off on `table_without_cue` (no cue ball; the reds
/// racked, the colours wherever they are): right side first, then left, each from
/// the brown outwards. Empty when a side's end red is not within rack_tolerance of
/// its rack position (that side is skipped), or no placement is free or clear.
std::vector<BreakOffCandidate> BreakOffCandidates(const TableState& table_without_cue,
                                                  const physics::TableModel& model,
                                                  const BreakOffOptions& options = {});

/// The soft break's candidates on the same table: from each placement of
/// BreakOffCandidates, the nearest red whose centre line from it meets a red first,
/// nearly full (cuts within 6 deg of it), at options.soft_speed, no side. Empty
/// when options.soft_break is off.
std::vector<BreakOffCandidate> SoftBreakCandidates(const TableState& table_without_cue,
                                                   const physics::TableModel& model,
                                                   const BreakOffOptions& options = {});

/// True when the striker is to break off: the cue ball is in hand (`cue_in_hand`
/// and no cue ball on the table) and the rack is untouched (15 reds, each within
/// rack_tolerance of a distinct rack position).
bool IsBreakOffTable(const TableState& table, bool cue_in_hand, const physics::TableModel& model,
                     const BreakOffOptions& options = {});

}  // namespace snooker::planner
