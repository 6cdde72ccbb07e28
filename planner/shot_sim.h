// One shot simulated and judged by the rules, with the stop rule the caller needs.
//
// Search and Monte Carlo runs (Mode::kDecide) stop as soon as the shot has failed:
// the cue ball's first contact is not the object ball, the cue ball or a ball not on
// drops, the object ball comes to rest (Simulator::Decided) outside a pocket, or the
// cue ball stops without touching anything. A shot that is succeeding runs on until
// every ball rests, because the position it leaves is the point of it (and a late
// in-off would still foul it). Verification runs (Mode::kFull) never stop early and
// record the events. kEventLimit, kSolverFailure, kEventOrder and kTimeLimit are
// failures, never successes (Foul::kSimulationFailed). Simulator::Decided does not
// foresee a ball that a later bounce brings back, so a fluke (a moving ball knocking
// the resting object ball in afterwards) counts as a miss in these runs: the rule
// errs on the safe side, and tests/planner/shot_sim_test.cc checks that it changes
// no verdict on a set of random shots.
//
// At the cue ball's first contact with the object ball the object ball's rolling
// line is measured (its post-impact state carried through its slip phase in closed
// form): its offset from the target pocket's mouth centre, its direction and the
// speed it will reach the mouth with. That is what the fast estimate of this
// shot's pot probability and the aim's correction use.
#pragma once

#include <span>
#include <vector>

#include "physics/core/shot.h"
#include "physics/sim/simulate.h"
#include "planner/rules.h"

namespace snooker::planner {

struct ShotSetup {
  const TableState* table = nullptr;  ///< kinds (and seen positions)
  int cue = -1;
  int object = -1;
  physics::PocketId pocket = physics::PocketId::kBaulkLeft;  ///< the intended pocket
  BallOn on = BallOn::kRed;
};

struct ObjectLine {
  bool valid = false;
  double offset = 0;          ///< at the intended pocket's mouth centre, m (PocketModel's sign)
  double direction = 0;       ///< rad, table frame
  double distance = 0;        ///< from where it rolls to the mouth, m
  double arrival_speed = 0;   ///< at the mouth, m/s (0 if it stops short)
  double contact_speed = 0;   ///< estimated cue-ball speed at contact, m/s
};

struct ShotOutcome {
  physics::SimStatus status = physics::SimStatus::kAtRest;
  bool stopped_early = false;
  int first_hit = -1;
  Foul foul = Foul::kNone;
  /// The object ball dropped (any pocket), no foul, and the run ended at rest.
  bool success = false;
  int object_pocket = -1;
  std::vector<int> potted;
  ObjectLine line;
  int events = 0;
};

class ShotSimulator {
 public:
  enum class Mode { kDecide, kFull };

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
  /// Simulations run since construction.
  long runs() const { return runs_; }

 private:
  void MeasureLine(const ShotSetup& setup, const physics::BallState& object);

  const physics::TableModel& table_;
  physics::SimParams params_;
  physics::Simulator sim_;
  std::vector<physics::BallState> balls_;
  ShotOutcome out_;
  long runs_ = 0;
};

}  // namespace snooker::planner
