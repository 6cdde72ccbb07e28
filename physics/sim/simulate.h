// Event-driven simulation of a whole snooker table (detect -> evolve -> resolve ->
// record, as pooltool's event-based simulate). Table frame: X across, Y along, Z up.
//
// Why it looks like this:
//  * Between events every ball moves in closed form (physics/motion/motion.h), so the
//    simulation jumps from event to event. Event times are polynomial roots
//    (physics/events/detect.h): no tunnelling, no overlap, no time step.
//  * Lazy state: each ball keeps its state at the time it last changed; nothing
//    evolves a ball at rest that nothing reaches.
//  * Event cache: each ball's next own event (motion transition, cushion nose, jaw
//    wall, knuckle, pocket) and each pair's next contact are kept; after an event
//    only the balls it changed are recomputed. A pair is checked only if the two can
//    reach each other before either changes (a distance bound before any quartic),
//    so two moving balls on a full table cost about what they cost on an empty one.
//  * Early stop: a caller that needs only part of the outcome drives Step() itself
//    and ends the run once that is decided (Decided(), last_event()).
//  * Every run is capped in events and in simulated time and returns a status.
//  * Time never goes back: every ball whose motion an event touches restarts at the
//    event's time (even when nothing is resolved), so every search starts at the
//    current time; Step checks it and ends with kEventOrder (a bug) otherwise.
//
// Contacts by design (issue 7). A ball frozen to a cushion, a knuckle, a jaw wall or
// another ball is an ordinary state. The detectors (physics/events/detect.h) say
// how each contact stands, and the resolver acts on that, not on luck:
//  * approaching: an impact, with the paper's model (ball-ball, Mathavan 2014) or
//    the cushion model (Mathavan 2010);
//  * pressing (no normal speed, the cloth driving the two together): a resting
//    contact. Against a boundary the ball loses its normal velocity and the spin
//    that drives its slip into the boundary (HoldAgainst); two balls lose the spin
//    that drives them together, and if rolling still presses them, stop together
//    when slow (resting_pair_speed) or lose their motion along the line of centres
//    (HoldTogether). A ball pressed twice at one instant is wedged and stops. Each
//    step only takes energy out.
//  * an impact after which the cloth would bring the two back within a flight of
//    resting_contact_excursion is turned into a resting contact (no Zeno bounces);
//  * a ball-ball impact within cluster_time of an earlier one of either ball is
//    resolved with every ball touching them as one impulse problem (ResolveCluster:
//    McNamara and Young's criterion against inelastic collapse; projected
//    Gauss-Seidel on the contact normals, Newton restitution, plastic where that has
//    no solution, balls brought to rest held still). docs/resting-contacts.md
//    measures the choice on break-offs.
// Deterministic: ties are broken by a fixed order (time, then kind, then indices).
// Run() allocates only while its buffers grow; reuse a Simulator for many runs.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "physics/impact/ball_ball.h"
#include "physics/impact/ball_cushion.h"
#include "physics/impact/impact_table.h"
#include "physics/core/ball_state.h"
#include "physics/core/limits.h"
#include "physics/motion/motion.h"
#include "physics/core/params.h"
#include "physics/events/detect.h"
#include "physics/table/table.h"

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
  /// a tenth of the 1 mm the issue allows of a converged run (measured: 0.07 mm) on
  /// every well-conditioned shot - one that a change of 1e-9 in the cue ball's speed
  /// (relative) or direction (rad) does not move by more than 1 um
  /// (docs/shot-speed-vs-error.md, scripts/shot-speed-error).
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

/// True when an impact table may stand in for a solver run with these options: the
/// adaptive integrator (after the options' fidelity) at a tolerance no tighter than
/// SimParams::kShotTolerance, the precision the tables carry.
bool TablesCarry(const ImpulseSolverOptions& solver);

enum class EventKind : std::uint8_t {
  kBallBall,    ///< two balls collide
  kCushion,     ///< a ball hits a straight cushion nose
  kJawWall,     ///< a ball hits a straight jaw wall inside a pocket mouth
  kKnuckle,     ///< a ball hits the rounded end of a jaw
  kPocket,      ///< a ball drops into a pocket
  kTransition,  ///< a ball's motion changes (sliding -> rolling -> spinning -> rest)
};
const char* ToString(EventKind k);

struct SimEvent {
  double time = 0;  ///< s from the start of the run
  EventKind kind = EventKind::kTransition;
  std::int16_t ball = -1;   ///< the ball (for kBallBall, the lower index)
  std::int16_t other = -1;  ///< kBallBall: the other ball
  /// kCushion, kJawWall: index into TableModel::segments(); kKnuckle: into jaws();
  /// kPocket: into pockets(); otherwise -1.
  std::int16_t where = -1;
  MotionState state_after = MotionState::kStationary;  ///< of `ball`
  /// Contact events: how the contact stood when it was resolved (kApproaching: an
  /// impact; kPressing: a resting contact; kTouching: nothing left to resolve).
  ContactStart contact = ContactStart::kApart;
  /// kBallBall resolved as a cluster: the number of balls resolved together; else 0.
  std::int16_t cluster_balls = 0;
  double kinetic_energy = 0;  ///< of all balls just after the event, J
};

enum class SimStatus : std::uint8_t {
  kRunning,       ///< Step(): an event was processed and the run goes on
  kAtRest,        ///< every ball is at rest or pocketed
  kEventLimit,    ///< max_events reached
  kTimeLimit,     ///< max_time reached with balls still moving
  kInvalidInput,  ///< a ball state is not finite or balls overlap; nothing was run
  kSolverFailure, ///< an impact solver failed (its step cap); the run stopped there
  kInterrupted,   ///< RunOptions' deadline passed or its cancel flag was set
  /// A broken invariant of the event loop (an event scheduled before the current
  /// time): a bug, reported rather than hidden behind the event cap.
  kEventOrder,
};
const char* ToString(SimStatus s);

/// Ends a long run from outside: checked every `check_every` events (a clock read
/// costs about 20 ns, an event about a microsecond).
struct Interrupt {
  /// Stop with kInterrupted once the steady clock passes this.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  /// Stop with kInterrupted once this is true (set from another thread). Optional.
  const std::atomic<bool>* cancelled = nullptr;
  /// Stop with kInterrupted once poll(poll_context) returns true (for a transport's
  /// own cancellation test, e.g. grpc::ServerContext::IsCancelled). Optional.
  bool (*poll)(void* context) = nullptr;
  void* poll_context = nullptr;
  std::int32_t check_every = 16;

  /// True when the run should stop now (reads the clock).
  bool Due() const;
};

struct RunOptions {
  /// Keep every event for events().
  bool record_events = true;
  /// Keep every ball's path knots for path() and PositionAt().
  bool record_paths = true;
  Interrupt interrupt;

  /// Neither events nor paths: the cheapest run, for a search that needs only the
  /// outcome (final_balls(), pocket_of()).
  static RunOptions Lean() {
    RunOptions o;
    o.record_events = o.record_paths = false;
    return o;
  }
};

/// A point of a ball's path: its state from time t until the next knot.
struct PathKnot {
  double t = 0;
  BallState state;
};

class Simulator {
 public:
  Simulator(const TableModel& table, const SimParams& params);

  /// Simulates from `balls` at t = 0 (at most kMaxBalls) until every ball is at rest
  /// or pocketed, a cap is reached or the run is interrupted: Start, then Step until
  /// it returns anything but kRunning.
  SimStatus Run(std::span<const BallState> balls, const RunOptions& options = {});

  /// Sets up a run from `balls` at t = 0: kRunning, or kInvalidInput (too many
  /// balls, a state that is not finite, two balls overlapping). A caller that ends a
  /// run as soon as its outcome is decided (a planner) drives Step itself.
  SimStatus Start(std::span<const BallState> balls, const RunOptions& options = {});
  /// Processes the next event (detect, evolve, resolve, record) and returns kRunning,
  /// or ends the run and returns its final status; after the end it returns that
  /// status again. During such a run StateNow() gives the balls' states;
  /// final_balls() is set when the run ends.
  SimStatus Step();
  /// The event Step last processed.
  const SimEvent& last_event() const { return last_event_; }
  /// True when ball i is pocketed, or at rest (stationary or spinning) with no
  /// contact predicted for it in the moving balls' current motion phases (a ball
  /// that a later bounce brings back is not foreseen).
  bool Decided(int i) const;

  static constexpr int kMaxBalls = limits::kMaxBalls;

  int ball_count() const { return n_; }

  double end_time() const { return time_; }
  std::int32_t event_count() const { return event_count_; }
  /// Recorded events (RunOptions::record_events).
  std::span<const SimEvent> events() const { return events_; }
  /// Every ball's state when the run ended (pocketed balls: where they dropped).
  /// Set by the end of a run; while a caller still drives Step, use StateNow().
  std::span<const BallState> final_balls() const { return final_; }
  /// Ball i's state at end_time(), the time of the last processed event; valid
  /// during a run driven by Step and after it. Needs no recorded paths.
  BallState StateNow(int i) const { return StateAt(i, time_); }
  /// Index into TableModel::pockets() of the pocket ball i fell into, or -1.
  int pocket_of(int i) const { return pocket_of_[static_cast<size_t>(i)]; }
  /// Ball i's path knots (RunOptions::record_paths), first at t = 0.
  std::span<const PathKnot> path(int i) const { return paths_[static_cast<size_t>(i)]; }
  /// Position of ball i at time t in [0, end_time()] from the recorded path. m.
  Vec2 PositionAt(int i, double t) const;
  /// Work of the impact solvers during the last run.
  const ImpulseWork& impact_work() const { return impact_work_; }
  /// Pair contact checks that reached the quartic solver / were culled by distance.
  std::int64_t pair_checks() const { return pair_checks_; }
  std::int64_t pair_culls() const { return pair_culls_; }

 private:
  struct Slot {
    BallState s;      // state at time t
    double t = 0;     // when s was last set
    double horizon;   // absolute time of the next motion transition (or +inf)
    PositionPoly poly;  // from time t
    bool moving = false;
  };
  struct Own {  // a ball's next own event
    double time = std::numeric_limits<double>::infinity();
    EventKind kind = EventKind::kTransition;
    int where = -1;
  };

  BallState StateAt(int i, double t) const;
  BallState AfterImpact(const BallState& s) const;  // applies rest_speed
  // Resting contacts (see SimParams::resting_contact_excursion); n is the contact
  // normal, horizontal, from the boundary to the ball / from a to b.
  BallState HoldAgainst(const BallState& s, const Vec2& n) const;
  BallState HoldIfReturning(const BallState& s, const Vec2& n) const;
  void HoldIfReturning(BallState* a, BallState* b, const Vec2& n, int level_a, int level_b) const;
  void RemoveApproach(BallState* a, BallState* b, const Vec2& n) const;
  void HoldTogether(BallState* a, BallState* b, const Vec2& n, int level_a, int level_b) const;
  BallState Stopped(const BallState& s) const;  // v = 0, horizontal spin 0
  // How many pressing contacts ball i has had resolved at time t before this one.
  int PressLevel(int i, double t);
  // Resolves the touching cluster around the pair at time t; returns its size.
  int ResolveCluster(int i, int j, double t);
  static constexpr int kMaxClusterContacts = 4 * kMaxBalls;
  void SetState(int i, const BallState& s, double t);  // and mark for recompute
  void RecomputeOwn(int i);
  void RecomputePair(int i, int j);
  double Reach(int i, double dt) const;  // bound on ball i's travel in dt seconds
  SimStatus Finish(SimStatus status);  // sets final_ and the end status
  SimStatus ResolvePair(int i, int j, double t);
  SimStatus ResolveOwn(int i, double t);
  void Changed(int i);  // recompute ball i's own event and its pairs
  void Record(const SimEvent& e);
  double TotalKineticEnergy() const;

  const TableModel& table_;
  SimParams params_;
  double contact_distance_ = 0;  // ball centre to cushion nose at contact, m
  const CushionTable* cushion_table_ = nullptr;     // when params_.impact_tables and
  const BallBallTable* ball_ball_table_ = nullptr;  // they match the parameters
  int n_ = 0;
  double time_ = 0;
  std::int32_t event_count_ = 0;
  RunOptions options_;
  SimStatus status_ = SimStatus::kAtRest;
  SimEvent last_event_;
  Slot slots_[kMaxBalls];
  Own own_[kMaxBalls];
  double last_impact_[kMaxBalls];  // time of each ball's last ball-ball impact
  double press_time_[kMaxBalls];   // instant of each ball's last pressing contact
  int press_count_[kMaxBalls] = {};  // and how many it had then
  // Upper triangle: next contact time of (i < j); +inf when none.
  double pair_[kMaxBalls][kMaxBalls];
  std::vector<SimEvent> events_;
  std::vector<BallState> final_;
  std::vector<int> pocket_of_;
  std::vector<std::vector<PathKnot>> paths_;
  ImpulseWork impact_work_;
  std::int64_t pair_checks_ = 0, pair_culls_ = 0;
};

}  // namespace snooker::physics
