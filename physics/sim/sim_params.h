// The parameters of a table simulation (physics/sim/simulate.h): the physical
// parameters of the balls, the cloth and the two impact models, the impact solvers'
// settings, the resting-contact rules (physics/sim/contacts.h, physics/sim/cluster.h)
// and the caps on a run. Kept apart from the Simulator so that the resolvers and the
// contact rules can take them without the event loop.
#pragma once

#include <cstdint>

#include "physics/core/params.h"
#include "physics/impact/ball_ball.h"
#include "physics/impact/ball_cushion.h"
#include "physics/impact/impulse_solver.h"

namespace snooker::physics {

struct SimParams {
  static ImpulseSolverOptions ShotImpactOptions() {
    ImpulseSolverOptions o;
    o.tolerance = kShotTolerance;
    return o;
  }

  BallParams ball;
  ClothParams cloth;
  BallBallParams ball_ball;
  /// Cushion model (Mathavan et al. 2010) with the restitution curve fitted to the
  /// measured rebounds of Mathavan et al. (2009) (MeasuredReboundCurve): the paper's
  /// constant e_e = 0.98 rebounds up to 0.4 m/s too fast at 3.5 m/s. Its
  /// contact_height is replaced by the table's cushion_height (TableSpec), the one
  /// source of the nose geometry.
  CushionParams cushion = [] {
    CushionParams c;
    c.restitution_curve = MeasuredReboundCurve();
    return c;
  }();
  /// The impact integrators within a whole shot. Their tolerance is set from the
  /// final positions it gives, not by habit: the largest tolerance at which every ball
  /// of the planner's workload, of several-cushion shots and of break-offs ends within
  /// a tenth of the 1 mm a final position may differ from a converged run's
  /// (measured: 0.07 mm) on every well-conditioned shot - one that a change of 1e-9
  /// in the cue ball's speed (relative) or direction (rad) does not move by more
  /// than 1 um (docs/shot-speed-vs-error.md, scripts/shot-speed-error).
  static constexpr double kShotTolerance = 1e-7;
  /// Both with ImpulseSolverOptions' own Runge-Kutta pair, Dormand-Prince 5(4): the
  /// cheaper at kShotTolerance (docs/impact-methods.md, scripts/impact-methods; 8(5,3)
  /// pays at tighter ones).
  ImpulseSolverOptions ball_ball_solver = ShotImpactOptions();
  ImpulseSolverOptions cushion_solver = ShotImpactOptions();
  /// Answer the impacts of a rolling ball on a cushion or on a ball at rest from the
  /// precomputed tables (DefaultCushionTable, DefaultBallBallTable; physics/impact/
  /// impact_table.h) where they cover them and were built for these parameters; every
  /// other impact goes to its solver. The tables' errors are within those of the
  /// solvers at kShotTolerance (docs/impact-tables.md), so a table is used only while
  /// its solver is the adaptive one at a tolerance of at least kShotTolerance
  /// (TablesCarry): asking a solver for more precision, or for the paper's fixed-step
  /// scheme, solves every impact of its kind. The reference fidelity tier turns them
  /// off.
  bool impact_tables = true;
  /// After an impact, a ball whose centre and contact point both move slower than
  /// this is set at rest (its Z spin kept). m/s. Without it a slow ball pushing a
  /// resting one makes an endless cascade of ever smaller collisions (inelastic
  /// collapse). A rolling ball at 1e-4 m/s would travel v^2 / (2 mu_r g) ~ 4e-8 m
  /// more: far below anything measurable. 0 disables it.
  double rest_speed = 1e-4;
  /// Scales what a ball-ball impact changes of each ball's velocity across the line
  /// of centres (the friction's part: throw) before the balls move on. 1: the
  /// model as it is. The planner's Monte Carlo draws it around 1 for the model's
  /// uncertainty in throw (a real table throws differently from any fixed model).
  double throw_scale = 1.0;
  /// A ball that leaves a cushion (or knuckle, or jaw wall, or another ball) after
  /// an impact while the cloth drives it back, and would rise less than this off it
  /// before it returns, is held against it instead: a resting contact. m. Without
  /// it such a ball bounces in ever shorter flights without end (a Zeno sequence);
  /// 1e-6 m is far below anything measurable.
  double resting_contact_excursion = 1e-6;
  /// Two touching balls pressed together by their rolling decelerations, both
  /// slower than this, are set at rest together (a resting contact). m/s. They
  /// would have rolled on together at most v^2 / (2 mu_r g): 0.1 mm at 5 mm/s.
  double resting_pair_speed = 5e-3;
  /// A ball-ball contact that comes within this time of an earlier impact of
  /// either ball is resolved with the whole cluster of balls touching them, as one
  /// impulse problem (McNamara and Young's "TC" criterion, with a simultaneous
  /// resolution instead of their elastic one). s. Without it three touching balls
  /// can exchange ever smaller impacts ever faster (inelastic collapse).
  /// docs/resting-contacts.md shows the measurements behind the default. Negative:
  /// never (every contact resolved pairwise with the impact model).
  double cluster_time = 1e-6;
  /// Newton restitution of the cluster resolution (frictionless, centre velocities
  /// only). Dimensionless, in [0, 1].
  double cluster_restitution = 0.89;
  /// Cap on resolved events in one run.
  std::int32_t max_events = 5000;
  /// Cap on simulated time, s.
  double max_time = 600.0;
};

}  // namespace snooker::physics
