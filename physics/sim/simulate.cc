#include "physics/sim/simulate.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/events/detect.h"
#include "physics/sim/cluster.h"
#include "physics/sim/contacts.h"
#include "physics/sim/resolve.h"

namespace snooker::physics {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Balls given closer than 2R by more than this are rejected as overlapping. m.
constexpr double kOverlapTolerance = 1e-9;

bool Moving(MotionState s) { return s == MotionState::kSliding || s == MotionState::kRolling; }

// The distance culls below round by about 1e-16 m; this is far beyond that.
constexpr double kBoxMargin = 1e-9;

// True when q lies more than `room` outside the box [lo, hi] along either axis (by
// more than kBoxMargin besides): then every point of the box is farther than `room`
// from q, and an exact distance test against anything inside the box rejects q too.
// Four comparisons, where the exact test takes a division and a square root; most
// of a table's cushions, jaws and pockets are far from a ball along one axis.
bool OutsideBox(const Vec2& q, const Vec2& lo, const Vec2& hi, double room) {
  room += kBoxMargin;
  return lo.x() - q.x() > room || q.x() - hi.x() > room || lo.y() - q.y() > room ||
         q.y() - hi.y() > room;
}

// The segment from p0 to p1 widened by `pad`: Bound(q) is q's distance to the
// segment less the pad, a lower bound on its distance to anything within the pad.
// A cushion's nose line is met by a ball centre within the contact distance of it;
// a path p(t) = c + b t + a t^2 over [0, w] stays within |a| w^2 / 4 of its chord
// from p(0) to p(w) (the second constructor). Built once when many points are
// tested against it.
struct PaddedSegment {
  PaddedSegment(const Vec2& a, const Vec2& b, double widen)
      : p0(a), d(b - a), lo(a.cwiseMin(b)), hi(a.cwiseMax(b)), len2(d.squaredNorm()), pad(widen) {}
  /// The chord of the path p(t) over [0, w], widened by the bulge.
  PaddedSegment(const PositionPoly& p, double w)
      : PaddedSegment(p.c, p.At(w), p.a.norm() * w * w / 4) {}
  double Bound(const Vec2& q) const {
    const double u = len2 > 0 ? std::clamp((q - p0).dot(d) / len2, 0.0, 1.0) : 0.0;
    return (q - (p0 + u * d)).norm() - pad;
  }
  /// Bound(q) > room, decided by the segment's box where that suffices.
  bool Beyond(const Vec2& q, double room) const {
    return OutsideBox(q, lo, hi, room + pad) || Bound(q) > room;
  }
  Vec2 p0, d, lo, hi;
  double len2, pad;
};

// Adds one impact's work to a run's totals (the counters Simulator::impact_work reports).
void AddImpactWork(const ImpulseWork& w, ImpulseWork* total) {
  total->steps += w.steps;
  total->rhs_evals += w.rhs_evals;
  total->table_lookups += w.table_lookups;
}

}  // namespace

const char* ToString(EventKind k) {
  switch (k) {
    case EventKind::kBallBall: return "ball-ball";
    case EventKind::kCushion: return "cushion";
    case EventKind::kJawWall: return "jaw-wall";
    case EventKind::kKnuckle: return "knuckle";
    case EventKind::kPocket: return "pocket";
    case EventKind::kTransition: return "transition";
  }
  return "unknown";
}

bool Interrupt::Due() const {
  if (cancelled != nullptr && cancelled->load(std::memory_order_relaxed)) return true;
  if (poll != nullptr && poll(poll_context)) return true;
  return deadline != std::chrono::steady_clock::time_point::max() &&
         std::chrono::steady_clock::now() >= deadline;
}

const char* ToString(SimStatus s) {
  switch (s) {
    case SimStatus::kRunning: return "running";
    case SimStatus::kAtRest: return "at rest";
    case SimStatus::kEventLimit: return "event limit reached";
    case SimStatus::kTimeLimit: return "time limit reached";
    case SimStatus::kInvalidInput: return "invalid input";
    case SimStatus::kSolverFailure: return "impact solver failure";
    case SimStatus::kInterrupted: return "interrupted";
    case SimStatus::kEventOrder: return "event before the current time (a bug)";
  }
  return "unknown";
}

bool TablesCarry(const ImpulseSolverOptions& solver) {
  if (!FidelityValid(solver.fidelity)) return false;
  const ImpulseSolverOptions o = EffectiveOptions(solver);
  return o.integrator == ImpulseIntegrator::kAdaptive && o.tolerance >= SimParams::kShotTolerance;
}

Simulator::Simulator(const TableModel& table, const SimParams& params)
    : table_(table), params_(params) {
  // One source for the cushion's contact geometry: the table's nose height.
  params_.cushion.contact_height = table.spec().cushion_height;
  contact_distance_ = table.cushion_contact_distance();
  if (params_.impact_tables) {
    const CushionTable* cushion = DefaultCushionTable();
    if (cushion != nullptr && TablesCarry(params_.cushion_solver) &&
        cushion->Matches(params_.ball, params_.cushion)) {
      cushion_table_ = cushion;
    }
    const BallBallTable* ball_ball = DefaultBallBallTable();
    if (ball_ball != nullptr && TablesCarry(params_.ball_ball_solver) &&
        ball_ball->Matches(params_.ball, params_.ball_ball, params_.cloth.mu_s)) {
      ball_ball_table_ = ball_ball;
    }
  }
  events_.reserve(256);
  for (auto& row : pair_) {
    for (double& t : row) t = kInf;
  }
}

int Simulator::PressLevel(int i, double t) {
  if (press_time_[i] != t) {
    press_time_[i] = t;
    press_count_[i] = 0;
  }
  return press_count_[i]++;
}

int Simulator::ResolveCluster(int bi, int bj, double te) {
  Cluster cluster;
  cluster.balls = n_;
  for (int i = 0; i < n_; ++i) cluster.state[i] = StateAt(i, te);
  GatherCluster(bi, bj, params_.ball.radius, &cluster);
  FindClusterContacts(table_, contact_distance_, params_, &cluster);
  SolveCluster(params_, &cluster);
  BallState* st = cluster.state;
  HoldIfReturning(&st[bi], &st[bj], (st[bj].r - st[bi].r).normalized(), PressLevel(bi, te),
                  PressLevel(bj, te), params_);
  for (int k = 0; k < cluster.count; ++k) {
    const int i = cluster.members[k];
    SetState(i, st[i], te);
    last_impact_[i] = te;
  }
  Changed(std::span<const int>(cluster.members, static_cast<size_t>(cluster.count)));
  return cluster.count;
}

BallState Simulator::StateAt(int i, double t) const {
  const Slot& s = slots_[i];
  if (!s.moving || t <= s.t) return s.s;
  return Evolve(s.s, t - s.t, params_.ball, params_.cloth);
}

double Simulator::Reach(int i, double dt) const {
  const Slot& s = slots_[i];
  if (!s.moving || !(dt > 0)) return 0;
  if (!std::isfinite(dt)) return kInf;
  return s.speed_bound * dt + s.accel_bound * dt * dt;
}

void Simulator::SetState(int i, const BallState& state, double t) {
  Slot& s = slots_[i];
  s.s = state;
  s.t = t;
  s.moving = Moving(state.s);
  s.horizon = state.s == MotionState::kPocketed
                  ? kInf
                  : t + TransitionTime(state, params_.ball, params_.cloth);
  s.poly = PositionPolynomial(state, params_.ball, params_.cloth);
  s.speed_bound = s.poly.b.norm();
  s.accel_bound = s.poly.a.norm();
  if (options_.record_paths) paths_[static_cast<size_t>(i)].push_back({t, state});
}

void Simulator::RecomputeOwn(int i) {
  Slot& s = slots_[i];
  Own own{s.horizon, EventKind::kTransition, -1};
  if (s.s.s == MotionState::kPocketed) {
    own_[i] = {kInf, EventKind::kTransition, -1};
    return;
  }
  if (s.moving) {
    double window = std::min(s.horizon, params_.max_time) - s.t;
    const double reach = Reach(i, window);
    auto consider = [&](double dt, EventKind kind, int where) {
      if (s.t + dt < own.time) own = {s.t + dt, kind, where};
    };
    const auto segments = table_.segments();
    for (int k = 0; k < static_cast<int>(segments.size()); ++k) {
      const CushionSegment& seg = segments[static_cast<size_t>(k)];
      // Cull: distance from the centre to the segment against the reach.
      if (PaddedSegment(seg.p0, seg.p1, contact_distance_).Beyond(s.s.r, reach)) continue;
      // Cull exactly: the gap to the segment's line, f(t) = g0 + g1 t + g2 t^2, must
      // reach 0 within the window (its minimum is at an end or at the vertex).
      const double g0 = seg.normal.dot(s.poly.c - seg.p0) - contact_distance_;
      const double g1 = seg.normal.dot(s.poly.b), g2 = seg.normal.dot(s.poly.a);
      double lowest = std::min(g0, g0 + window * (g1 + window * g2));
      if (g2 > 0 && -g1 > 0 && -g1 < 2 * g2 * window) lowest = g0 - g1 * g1 / (4 * g2);
      if (lowest > kContactTolerance) continue;
      consider(DetectBallCushion(s.poly, seg, contact_distance_, window),
               seg.kind == SegmentKind::kCushion ? EventKind::kCushion : EventKind::kJawWall, k);
    }
    // Nothing behind the first straight contact can happen first: search the rounded
    // shapes (quartics) only up to it, and only those near the path.
    window = std::min(window, own.time - s.t);
    const PaddedSegment chord(s.poly, window);
    const auto jaws = table_.jaws();
    for (int k = 0; k < static_cast<int>(jaws.size()); ++k) {
      const JawCircle& jaw = jaws[static_cast<size_t>(k)];
      if (chord.Beyond(jaw.centre, jaw.radius + contact_distance_)) continue;
      // The knuckle meets the ball at the nose height too: centre distance
      // r_jaw + R cos(theta), which DetectBallJaw computes from this "radius".
      consider(DetectBallJaw(s.poly, jaw, contact_distance_, window), EventKind::kKnuckle, k);
    }
    const auto pockets = table_.pockets();
    for (int k = 0; k < static_cast<int>(pockets.size()); ++k) {
      const Pocket& p = pockets[static_cast<size_t>(k)];
      if (chord.Beyond(p.capture_centre, p.capture_radius)) continue;
      consider(DetectBallPocket(s.poly, p, window), EventKind::kPocket, k);
    }
  }
  own_[i] = own;
}

void Simulator::RecomputePair(int i, int j) {
  if (i > j) std::swap(i, j);
  const double t = PairTime(i, j);
  pair_[i][j] = t;
  // Keep row i's earliest time and its first index (the scan in Step breaks ties
  // to the lower indices): a time below it, or equal at a lower index, replaces it;
  // the earliest itself put later means a scan of the row.
  RowFirst& row = row_first_[i];
  if (t < row.time || (t == row.time && j < row.j)) {
    row = {t, j};
  } else if (j == row.j && !(t <= row.time)) {
    row = {kInf, -1};
    for (int k = i + 1; k < n_; ++k) {
      if (pair_[i][k] < row.time) row = {pair_[i][k], k};
    }
  }
}

double Simulator::PairTime(int i, int j) {
  const Slot& a = slots_[i];
  const Slot& b = slots_[j];
  if (a.s.s == MotionState::kPocketed || b.s.s == MotionState::kPocketed) return kInf;
  if (!a.moving && !b.moving) return kInf;
  const double t = std::max(a.t, b.t);
  // Nothing after either ball's next own event matters: its motion changes there and
  // its pairs are recomputed (own_ is always current when pairs are computed).
  const double horizon = std::min({a.horizon, b.horizon, own_[i].time, own_[j].time,
                                   params_.max_time});
  const double window = horizon - t;
  if (!(window >= 0)) return kInf;
  // Cheapest cull first, before evolving either ball: each stays within its reach of
  // where it was last set, until the horizon.
  const double reach_a = Reach(i, horizon - a.t), reach_b = Reach(j, horizon - b.t);
  const double contact = 2 * params_.ball.radius;
  if (OutsideBox(a.s.r, b.s.r, b.s.r, reach_a + reach_b + contact) ||
      (a.s.r - b.s.r).norm() - reach_a - reach_b > contact) {
    ++pair_culls_;
    return kInf;
  }
  const BallState sa = StateAt(i, t), sb = StateAt(j, t);
  const PositionPoly pa = a.t == t ? a.poly : PositionPolynomial(sa, params_.ball, params_.cloth);
  const PositionPoly pb = b.t == t ? b.poly : PositionPolynomial(sb, params_.ball, params_.cloth);
  // Cull on the relative path b - a, which must come within 2R of the origin.
  PositionPoly rel;
  rel.c = pb.c - pa.c;
  rel.b = pb.b - pa.b;
  rel.a = pb.a - pa.a;
  if (PaddedSegment(rel, window).Beyond(Vec2::Zero(), contact)) {
    ++pair_culls_;
    return kInf;
  }
  ++pair_checks_;
  const double dt = DetectBallBall(pa, pb, params_.ball.radius, window);
  return std::isfinite(dt) ? t + dt : kInf;
}

bool Simulator::Decided(int i) const {
  if (slots_[i].moving) return false;  // at rest, spinning in place, or pocketed...
  for (int j = 0; j < n_; ++j) {       // ... and no moving ball is about to hit it
    if (j != i && std::isfinite(pair_[std::min(i, j)][std::max(i, j)])) return false;
  }
  return true;
}

double Simulator::TotalKineticEnergy() const {
  double e = 0;
  for (int i = 0; i < n_; ++i) e += KineticEnergy(StateAt(i, time_), params_.ball);
  return e;
}

void Simulator::Record(const SimEvent& e) {
  last_event_ = e;
  if (!options_.record_events) return;
  SimEvent r = e;
  r.kinetic_energy = TotalKineticEnergy();
  events_.push_back(r);
}

void Simulator::Changed(std::span<const int> balls) {
  // A pair's time depends on its two balls' own events (its window ends at the
  // earlier), so every changed ball's own event comes first; then each pair that
  // has a changed ball is computed once, a pair of two changed balls included.
  for (const int i : balls) RecomputeOwn(i);
  bool done[kMaxBalls] = {};
  for (const int i : balls) {
    for (int j = 0; j < n_; ++j) {
      if (j != i && !done[j]) RecomputePair(i, j);
    }
    done[i] = true;
  }
}

SimStatus Simulator::Run(std::span<const BallState> balls, const RunOptions& options) {
  SimStatus status = Start(balls, options);
  while (status == SimStatus::kRunning) status = Step();
  return status;
}

SimStatus Simulator::Start(std::span<const BallState> balls, const RunOptions& options) {
  options_ = options;
  n_ = static_cast<int>(balls.size());
  time_ = 0;
  event_count_ = 0;
  events_.clear();
  last_event_ = {};
  impact_work_ = {};
  pair_checks_ = pair_culls_ = 0;
  final_.assign(balls.begin(), balls.end());
  pocket_of_.assign(balls.size(), -1);
  paths_.resize(balls.size());
  for (auto& p : paths_) p.clear();
  status_ = SimStatus::kRunning;
  for (double& t : last_impact_) t = -kInf;
  for (double& t : press_time_) t = -kInf;
  if (n_ > kMaxBalls) return Finish(SimStatus::kInvalidInput);
  for (int i = 0; i < n_; ++i) {
    const BallState& b = balls[static_cast<size_t>(i)];
    if (!(b.r.allFinite() && b.v.allFinite() && b.w.allFinite())) {
      return Finish(SimStatus::kInvalidInput);
    }
    for (int j = 0; j < i; ++j) {
      if ((b.r - balls[static_cast<size_t>(j)].r).norm() <
          2 * params_.ball.radius - kOverlapTolerance) {
        return Finish(SimStatus::kInvalidInput);
      }
    }
  }
  for (int i = 0; i < n_; ++i) {
    const BallState& b = balls[static_cast<size_t>(i)];
    SetState(i, b.s == MotionState::kPocketed ? b : Settle(b, params_.ball), 0.0);
  }
  for (int i = 0; i < n_; ++i) RecomputeOwn(i);  // pair windows need every own event
  for (RowFirst& row : row_first_) row = {};
  for (int i = 0; i < n_; ++i) {
    for (int j = i + 1; j < n_; ++j) RecomputePair(i, j);
  }
  return status_;
}

SimStatus Simulator::Finish(SimStatus status) {
  status_ = status;
  if (status != SimStatus::kInvalidInput) {
    for (int i = 0; i < n_; ++i) final_[static_cast<size_t>(i)] = StateAt(i, time_);
  }
  return status;
}

SimStatus Simulator::Step() {
  if (status_ != SimStatus::kRunning) return status_;
  const Interrupt& stop = options_.interrupt;
  if (stop.check_every > 0 && event_count_ > 0 && event_count_ % stop.check_every == 0 &&
      stop.Due()) {
    return Finish(SimStatus::kInterrupted);
  }
  // Next event: the earliest; ties go to pairs (lower indices first), then own events.
  double te = kInf;
  int bi = -1, bj = -1;
  for (int i = 0; i < n_; ++i) {
    if (row_first_[i].time < te) te = row_first_[i].time, bi = i, bj = row_first_[i].j;
  }
  for (int i = 0; i < n_; ++i) {
    if (own_[i].time < te) te = own_[i].time, bi = i, bj = -1;
  }
  if (!std::isfinite(te)) return Finish(SimStatus::kAtRest);
  if (te > params_.max_time) {
    time_ = params_.max_time;
    return Finish(SimStatus::kTimeLimit);
  }
  if (event_count_ >= params_.max_events) return Finish(SimStatus::kEventLimit);
  if (te < time_) return Finish(SimStatus::kEventOrder);
  ++event_count_;
  // Evolve: nothing to do, each ball is evaluated lazily at te (StateAt).
  time_ = te;
  // Resolve and record.
  const SimStatus status = bj >= 0 ? ResolvePair(bi, bj, te) : ResolveOwn(bi, te);
  if (status != SimStatus::kRunning) return Finish(status);
  return SimStatus::kRunning;
}

SimStatus Simulator::ResolvePair(int bi, int bj, double te) {
  SimEvent ev;
  ev.time = te;
  ev.kind = EventKind::kBallBall;
  ev.ball = static_cast<std::int16_t>(bi);
  ev.other = static_cast<std::int16_t>(bj);
  const BallState sa = StateAt(bi, te), sb = StateAt(bj, te);
  const PositionPoly pa = PositionPolynomial(sa, params_.ball, params_.cloth);
  const PositionPoly pb = PositionPolynomial(sb, params_.ball, params_.cloth);
  const Gap gap = BallBallGap(pa, pb, params_.ball.radius);
  ev.contact = ClassifyContact(gap.g, gap.per_metre);
  const bool repeated = te - last_impact_[bi] <= params_.cluster_time ||
                        te - last_impact_[bj] <= params_.cluster_time;
  if (repeated && ev.contact == ContactStart::kApproaching) {
    ev.cluster_balls = static_cast<std::int16_t>(ResolveCluster(bi, bj, te));
    ev.state_after = slots_[bi].s.s;
    Record(ev);
    return SimStatus::kRunning;
  }
  const bool pressing = ev.contact == ContactStart::kPressing;
  const PairContactResolution r =
      ResolveBallBallContact(sa, sb, ev.contact, pressing ? PressLevel(bi, te) : 0,
                             pressing ? PressLevel(bj, te) : 0, params_, ball_ball_table_);
  AddImpactWork(r.work, &impact_work_);
  if (r.status != ImpactStatus::kOk) return SimStatus::kSolverFailure;
  if (r.impact) last_impact_[bi] = last_impact_[bj] = te;
  ev.contact = r.contact;
  // Both balls restart at te, so no search can go back before the current time.
  SetState(bi, r.a, te);
  SetState(bj, r.b, te);
  const int pair[] = {bi, bj};
  Changed(pair);
  ev.state_after = slots_[bi].s.s;
  Record(ev);
  return SimStatus::kRunning;
}

SimStatus Simulator::ResolveOwn(int bi, double te) {
  const Own own = own_[bi];
  SimEvent ev;
  ev.time = te;
  ev.ball = static_cast<std::int16_t>(bi);
  ev.kind = own.kind;
  ev.where = static_cast<std::int16_t>(own.where);
  const BallState s = StateAt(bi, te);
  switch (own.kind) {
    case EventKind::kTransition: {
      // Evolve by the transition's own duration: te - t can come out a rounding
      // short of it, which would leave a vanishing slide and repeat the event.
      const BallState& from = slots_[bi].s;
      SetState(bi, Evolve(from, TransitionTime(from, params_.ball, params_.cloth), params_.ball,
                          params_.cloth),
               te);
      Changed(bi);
      break;
    }
    case EventKind::kPocket: {
      BallState p = s;
      p.v.setZero();
      p.w.setZero();
      p.s = MotionState::kPocketed;
      pocket_of_[static_cast<size_t>(bi)] = own.where;
      SetState(bi, p, te);
      Changed(bi);
      break;
    }
    case EventKind::kCushion:
    case EventKind::kJawWall:
    case EventKind::kKnuckle: {
      const PositionPoly poly = PositionPolynomial(s, params_.ball, params_.cloth);
      Vec2 normal;
      Gap gap;
      if (own.kind == EventKind::kKnuckle) {
        const JawCircle& jaw = table_.jaws()[static_cast<size_t>(own.where)];
        normal = (s.r - jaw.centre).normalized();
        gap = JawGap(poly, jaw, contact_distance_);
      } else {
        const CushionSegment& seg = table_.segments()[static_cast<size_t>(own.where)];
        normal = seg.normal;
        gap = CushionGap(poly, seg, contact_distance_);
      }
      ev.contact = ClassifyContact(gap.g, gap.per_metre);
      const BoundaryContactResolution r = ResolveBoundaryContact(
          s, normal, ev.contact, ev.contact == ContactStart::kPressing ? PressLevel(bi, te) : 0,
          params_, cushion_table_);
      AddImpactWork(r.work, &impact_work_);
      if (r.status != ImpactStatus::kOk) return SimStatus::kSolverFailure;
      ev.contact = r.contact;
      // Restarts at te even when nothing was resolved: no search goes back in time.
      SetState(bi, r.ball, te);
      Changed(bi);
      break;
    }
    case EventKind::kBallBall: break;  // ResolvePair
  }
  ev.state_after = slots_[bi].s.s;
  Record(ev);
  return SimStatus::kRunning;
}

Vec2 Simulator::PositionAt(int i, double t) const {
  const auto& knots = paths_[static_cast<size_t>(i)];
  if (knots.empty()) return final_[static_cast<size_t>(i)].r;
  size_t k = 0;
  while (k + 1 < knots.size() && knots[k + 1].t <= t) ++k;
  return EvolveThrough(knots[k].state, t - knots[k].t, params_.ball, params_.cloth).r;
}

}  // namespace snooker::physics
