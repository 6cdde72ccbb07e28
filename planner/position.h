// The value of the position a shot leaves: how likely the next shot by the rules is
// to pot, under the robot's noise (after a red the best colour, after a colour the
// best red, in the final sequence the next colour).
//
// As the strongest computer-pool players did (PickPocket: p1 + 0.33 p2 + 0.15 p3),
// the value is a weighted sum over the best few next shots, one per ball, so a
// position with alternatives beats one that hangs on a single pot. Each next shot is
// judged by the fast estimate (pot_estimate.h) with its paths and cue room checked
// (candidates.h), and discounted when the cue ball is left on a cushion or with
// little room for the cue behind it (a ball close behind). Shots are ranked by
// expected points p (value + continuation), so a black at 60 % can beat a yellow at
// 90 %; the reported value is the weighted sum of the ranked shots' probabilities.
//
// Cost: every option's estimate is cheap; only the options that could enter the
// ranking get their paths checked, best first, until enough balls are found.
#pragma once

#include <array>

#include "planner/candidates.h"

namespace snooker::planner {

struct PositionOptions {
  /// Weights of the best, second and third next shots (different balls).
  std::array<double, 3> weights = {1.0, 0.33, 0.15};
  /// Points a potted next ball is worth beyond its value (the break it keeps
  /// alive): ranks colours by p (value + continuation).
  double continuation = 30.0;
  /// A cue ball touching a cushion keeps this share of each next shot's
  /// probability, rising linearly to 1 at one ball radius off the cushion (the
  /// robot can strike it only high and without much spin).
  double cushion_factor = 0.75;
  /// Cue room below this (m) scales the probability down linearly to
  /// room_factor at no room: a ball close behind cramps the stroke.
  double cramped_room = 0.01;
  double room_factor = 0.6;
};

struct PositionValue {
  /// Weighted sum of the ranked next shots' pot probabilities (0 when none).
  double value = 0;
  /// Weighted sum of p (value + continuation): what the search maximises. Points.
  double expected_points = 0;
  /// The best next shot: ball index (-1 when no pot is on) and pocket.
  int next_ball = -1;
  physics::PocketId next_pocket = physics::PocketId::kBaulkLeft;
  double next_probability = 0;
};

/// Evaluates `table` (the cue ball where the shot left it) with `next_on` to play.
/// `lines`: the caller's cache of the balls' lines into the pockets (the same value
/// with or without it), or none.
PositionValue EvaluatePosition(const TableState& table, BallOn next_on, const PotContext& ctx,
                               const PositionOptions& options, PocketLineCache* lines = nullptr);

}  // namespace snooker::planner
