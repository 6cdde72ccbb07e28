// One shot simulated and judged by the rules, with the stop rule the caller needs.
//
// A shot has a kind (shot_kind.h). A pot succeeds when its first contact is legal
// (the ball it names first: the object ball, or for a plant the ball that pots it),
// its object ball drops (in any pocket) and nothing fouls; a safety, escape or
// break-off succeeds when nothing fouls. A ball on touching the cue ball before the
// stroke counts as hit (the touching-ball rule), so a shot may play away from it.
//
// Search and Monte Carlo runs (Mode::kDecide) stop as soon as the shot has failed:
// a wrong first contact, the cue ball or a ball not on dropping, a pot's object ball
// at rest (Simulator::Decided) outside a pocket, or the cue ball stopping without
// touching anything. A shot that is succeeding runs on until every ball rests,
// because the position it leaves is the point of it (and a late in-off would still
// foul it). Verification runs (Mode::kFull) never stop early and record the events.
// kEventLimit, kSolverFailure, kEventOrder and kTimeLimit are failures, never
// successes (Foul::kSimulationFailed). Simulator::Decided does not foresee a ball that
// a later bounce brings back, so a fluke (a moving ball knocking the resting object
// ball in afterwards) counts as a miss in these runs: the rule errs on the safe side,
// and tests/planner/shot_sim_test.cc checks that it changes no verdict on a set of
// random shots.
//
// When the object ball leaves its last contact before the pocket (the cue ball's,
// for a direct pot), its rolling line is measured (its state carried through its
// slip phase in closed form): its offset from the target pocket's mouth centre, its
// direction and the speed it will reach the mouth with. That is what the fast
// estimate of a pot's probability and the aim's correction use.
#pragma once

#include <span>
#include <vector>

#include "physics/core/shot.h"
#include "physics/sim/simulate.h"
#include "planner/rules.h"
#include "planner/shot_kind.h"

namespace snooker::planner {

struct ShotSetup {
  const TableState* table = nullptr;  ///< kinds (and seen positions)
  int cue = -1;
  /// A pot's object ball (the ball to pot); for other kinds the ball aimed at, or -1.
  int object = -1;
  physics::PocketId pocket = physics::PocketId::kBaulkLeft;  ///< the intended pocket
  BallOn on = BallOn::kRed;
  ShotKind kind = ShotKind::kPot;
  /// The ball the cue ball must hit first; -1: a pot's object ball, or any ball on
  /// for the other kinds. A plant names here the ball that pots the object ball.
  int first = -1;
  /// A ball on touching the cue ball before the stroke (deemed hit), or -1.
  int touching_on = -1;

  /// The ball the cue ball must hit first, or -1 for any ball on.
  int FirstBall() const { return first >= 0 ? first : (kind == ShotKind::kPot ? object : -1); }
};

/// A ball on touching the cue ball (rules.h TouchingCueBall; the lowest index), or -1.
int TouchingBallOn(const TableState& table, BallOn on, const physics::TableModel& model);

struct ObjectLine {
  bool valid = false;
  double offset = 0;          ///< at the intended pocket's mouth centre, m (PocketModel's sign)
  double direction = 0;       ///< rad, table frame
  double distance = 0;        ///< from where it rolls to the mouth, m
  double arrival_speed = 0;   ///< at the mouth, m/s (0 if it stops short)
  double contact_speed = 0;   ///< estimated cue-ball speed at contact, m/s
  /// From a ball-ball contact: the throw, the line's direction less the line of
  /// centres at the contact (rad, counter-clockwise positive); 0 from a cushion.
  double throw_angle = 0;
};

struct ShotOutcome {
  physics::SimStatus status = physics::SimStatus::kAtRest;
  bool stopped_early = false;
  /// The first ball the cue ball touched (the touching ball on, when there is one).
  int first_hit = -1;
  Foul foul = Foul::kNone;
  /// A pot: the first contact legal, the object ball dropped (any pocket), no foul,
  /// and the run ended at rest. Other kinds: no foul, at rest.
  bool success = false;
  int object_pocket = -1;
  std::vector<int> potted;
  ObjectLine line;
  /// The object ball's line from its first contact (for a direct pot, the cue
  /// ball's), before any jaw or cushion changed it.
  ObjectLine first_line;
  int events = 0;
  /// Cushions the cue ball met before its first contact, and the object ball met
  /// before it dropped (a kick, a double).
  int cue_cushions_first = 0;
  int object_cushions = 0;
  /// The cue ball's path from its first contact to rest, m: the chords between its
  /// events (a bound from below on a curved path), and the direction of its last
  /// chord (zero when it did not move after the contact); a cue ball that went down
  /// is followed to its last event before the pocket. The search's position spread
  /// (SearchSettings::position_spread) is scaled by it.
  double cue_travel = 0;
  physics::Vec2 cue_last_direction = physics::Vec2::Zero();
};

class ShotSimulator {
 public:
  /// kDecide stops a failed shot early; kToRest runs every shot to rest (what a
  /// miss leaves matters too); kFull also records the events and paths.
  enum class Mode { kDecide, kToRest, kFull };

  ShotSimulator(const physics::TableModel& table, const physics::SimParams& params);

  /// Simulates `shot` from the cue ball of `setup` with every ball at `positions`
  /// (same order as setup.table; the table's own positions when empty).
  const ShotOutcome& Run(const ShotSetup& setup, const physics::Shot& shot,
                         std::span<const physics::Vec2> positions, Mode mode,
                         const physics::Interrupt& interrupt);

  /// After Run: where every ball ended (pocketed balls where they dropped), the
  /// events (kFull) and the simulator itself.
  std::span<const physics::BallState> final_balls() const { return sim_.final_balls(); }
  const physics::Simulator& simulator() const { return sim_; }
  const ShotOutcome& outcome() const { return out_; }
  const physics::SimParams& params() const { return params_; }
  /// Scales the throw of every ball-ball impact of the next runs (SimParams::
  /// throw_scale; 1: the model's).
  void set_throw_scale(double scale) {
    params_.throw_scale = scale;
    sim_.set_throw_scale(scale);
  }
  /// Simulations run since construction.
  long runs() const { return runs_; }

 private:
  void MeasureLine(const ShotSetup& setup, const physics::BallState& object, const physics::Vec2* partner);
  // The run's loop: steps until the end, or until the shot has failed in kDecide.
  physics::SimStatus Loop(const ShotSetup& setup, physics::SimStatus status, bool decide);
  void Judge(const ShotSetup& setup, physics::SimStatus status);

  const physics::TableModel& table_;
  physics::SimParams params_;
  physics::Simulator sim_;
  std::vector<physics::BallState> balls_;
  ShotOutcome out_;
  long runs_ = 0;
};

}  // namespace snooker::planner
