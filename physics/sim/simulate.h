// Event-driven simulation of a whole snooker table (next event -> evolve -> resolve
// -> record, as pooltool's event-based simulate). Table frame: X across, Y along, Z
// up (docs/physics-notes.md section 1).
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
// Contacts by design. A ball frozen to a cushion, a knuckle, a jaw wall or another
// ball is an ordinary state. The detectors (physics/events/detect.h) say how each
// contact stands, and the resolvers (physics/sim/resolve.h) act on that, not on luck:
//  * approaching: an impact, with the paper's model (ball-ball, Mathavan 2014) or
//    the cushion model (Mathavan 2010);
//  * pressing (no normal speed, the cloth driving the two together): a resting
//    contact (physics/sim/contacts.h). Against a boundary the ball loses its normal
//    velocity and the spin that drives its slip into the boundary (HoldAgainst); two
//    balls lose the spin that drives them together, and if rolling still presses
//    them, stop together when slow (resting_pair_speed) or lose their motion along
//    the line of centres (HoldTogether). A ball pressed twice at one instant is
//    wedged and stops. Each step only takes energy out.
//  * an impact after which the cloth would bring the two back within a flight of
//    resting_contact_excursion is turned into a resting contact (no Zeno bounces);
//  * a ball-ball impact within cluster_time of an earlier one of either ball is
//    resolved with every ball touching them as one impulse problem
//    (physics/sim/cluster.h: McNamara and Young's criterion against inelastic
//    collapse; projected Gauss-Seidel on the contact normals, Newton restitution,
//    plastic where that has no solution, balls brought to rest held still).
//    docs/resting-contacts.md measures the choice on break-offs.
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
#include "physics/sim/sim_params.h"
#include "physics/table/table.h"

namespace snooker::physics {

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
  /// SimParams::throw_scale of the next runs.
  void set_throw_scale(double scale) { params_.throw_scale = scale; }

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
    double speed_bound = 0;  // |poly.b| and |poly.a|, for Reach: a pair's cull
    double accel_bound = 0;  // reads them for both balls on every recompute
    bool moving = false;
  };
  struct Own {  // a ball's next own event
    double time = std::numeric_limits<double>::infinity();
    EventKind kind = EventKind::kTransition;
    int where = -1;
  };

  BallState StateAt(int i, double t) const;
  // How many pressing contacts ball i has had resolved at time t before this one.
  int PressLevel(int i, double t);
  // Resolves the touching cluster around the pair at time t (physics/sim/cluster.h);
  // returns its size.
  int ResolveCluster(int i, int j, double t);
  void SetState(int i, const BallState& s, double t);  // and mark for recompute
  void RecomputeOwn(int i);
  void RecomputePair(int i, int j);  // and the lower index's row_first_
  double PairTime(int i, int j);      // i < j: the pair's next contact, or +inf
  double Reach(int i, double dt) const;  // bound on ball i's travel in dt seconds
  SimStatus Finish(SimStatus status);  // sets final_ and the end status
  SimStatus ResolvePair(int i, int j, double t);
  SimStatus ResolveOwn(int i, double t);
  // Recomputes the own events of balls whose states were just set, then their pairs.
  void Changed(std::span<const int> balls);
  void Changed(int i) { Changed(std::span<const int>(&i, 1)); }
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
  struct RowFirst {  // the earliest time in a row of pair_, at its lowest index j
    double time = std::numeric_limits<double>::infinity();
    int j = -1;
  };
  RowFirst row_first_[kMaxBalls];
  std::vector<SimEvent> events_;
  std::vector<BallState> final_;
  std::vector<int> pocket_of_;
  std::vector<std::vector<PathKnot>> paths_;
  ImpulseWork impact_work_;
  std::int64_t pair_checks_ = 0, pair_culls_ = 0;
};

}  // namespace snooker::physics
