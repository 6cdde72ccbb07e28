#include "physics/sim/cluster.h"

#include <algorithm>
#include <cmath>

#include "physics/events/detect.h"
#include "physics/motion/motion.h"
#include "physics/sim/contacts.h"

namespace snooker::physics {
namespace {

// Caps of the solution and the velocity to which its contacts are solved. Along a
// straight line of touching balls a sweep shrinks the error only by about
// cos^2(pi / (n + 1)) for n contacts, so the longest line (limits::kMaxBalls, 31
// contacts) needs between 2000 and 3000 sweeps; at 200 a line of nine ran out and
// HoldApproaching stopped it dead. A cluster stops sweeping as soon as it converges
// (the break-off's triangle within the first 200), so the cap costs only such lines.
constexpr int kMaxClusterSweeps = 5000;
constexpr double kClusterSpeedTolerance = 1e-12;  // m/s, below the detector's 1e-9

// Normal separation speed of a contact (> 0: separating). m/s.
double Separation(const ClusterContact& c, const BallState* st) {
  const Vec2 va = st[c.a].v.head<2>();
  return c.b >= 0 ? (st[c.b].v.head<2>() - va).dot(c.n) : va.dot(c.n);
}

// What every round starts from: the members' states before the resolution (those
// held still with v = 0) and their inverse masses (0: held still).
struct RoundStart {
  BallState initial[Cluster::kMaxBalls];
  double inv_mass[Cluster::kMaxBalls];
};

// Holds ball i still in the next rounds.
void HoldStill(int i, RoundStart* start) {
  start->inv_mass[i] = 0;
  start->initial[i].v.setZero();
}

// Restarts the members from `start` and sets every contact's target: separation at
// `restitution` times its approach speed, or no approach.
void BeginRound(const RoundStart& start, double restitution, Cluster* c) {
  for (int k = 0; k < c->count; ++k) c->state[c->members[k]] = start.initial[c->members[k]];
  for (int k = 0; k < c->contact_count; ++k) {
    ClusterContact& contact = c->contacts[k];
    const double s0 = Separation(contact, c->state);
    contact.target = s0 < 0 ? -restitution * s0 : 0.0;
    contact.lambda = 0;
  }
}

// Projected Gauss-Seidel sweeps until no impulse changes a velocity by more than
// kClusterSpeedTolerance, at most kMaxClusterSweeps. True when converged. The sweeps
// work on a local copy of the members' horizontal velocities: the compiler then knows
// that an impulse's update leaves the contacts alone (no reloads in the inner loop).
bool Sweep(const RoundStart& start, Cluster* c) {
  Vec2 v[Cluster::kMaxBalls];
  for (int k = 0; k < c->count; ++k) v[c->members[k]] = c->state[c->members[k]].v.head<2>();
  const double* inv_mass = start.inv_mass;
  bool converged = false;
  for (int sweep = 0; sweep < kMaxClusterSweeps && !converged; ++sweep) {
    double worst = 0;
    for (int k = 0; k < c->contact_count; ++k) {
      ClusterContact& contact = c->contacts[k];
      const double wa = inv_mass[contact.a], wb = contact.b >= 0 ? inv_mass[contact.b] : 0.0;
      if (wa + wb == 0.0) continue;  // both held still
      const Vec2& va = v[contact.a];
      const double separation =
          contact.b >= 0 ? (v[contact.b] - va).dot(contact.n) : va.dot(contact.n);
      const double next =
          std::max(0.0, contact.lambda + (contact.target - separation) / (wa + wb));
      const double dl = next - contact.lambda;
      contact.lambda = next;
      v[contact.a] -= (contact.b >= 0 ? dl : -dl) * wa * contact.n;
      if (contact.b >= 0) v[contact.b] += dl * wb * contact.n;
      worst = std::max(worst, std::abs(dl) * (wa + wb));
    }
    converged = worst <= kClusterSpeedTolerance;
  }
  for (int k = 0; k < c->count; ++k) c->state[c->members[k]].v.head<2>() = v[c->members[k]];
  return converged;
}

double MembersEnergy(const Cluster& c, const BallParams& ball) {
  double e = 0;
  for (int k = 0; k < c.count; ++k) e += KineticEnergy(c.state[c.members[k]], ball);
  return e;
}

// Projected Gauss-Seidel crawls where contacts are nearly parallel (a ball jammed in
// a straight line of still balls). Every movable ball left approaching a contact is
// held still for the next round. True when any was.
bool HoldApproaching(const Cluster& c, RoundStart* start) {
  bool stopped = false;
  for (int k = 0; k < c.contact_count; ++k) {
    const ClusterContact& contact = c.contacts[k];
    if (!(Separation(contact, c.state) < -kClusterSpeedTolerance)) continue;
    for (int i : {contact.a, contact.b}) {
      if (i < 0 || start->inv_mass[i] == 0) continue;
      HoldStill(i, start);
      stopped = true;
    }
  }
  return stopped;
}

// Settles the members (rest_speed applied). A movable ball that this brings to rest
// is held still in the next round. True when any was.
bool RestSlowBalls(const SimParams& p, Cluster* c, RoundStart* start) {
  bool rested = false;
  for (int k = 0; k < c->count; ++k) {
    const int i = c->members[k];
    BallState& s = c->state[i];
    const bool moved = s.v.head<2>().squaredNorm() > 0.0;
    s = AfterImpact(Settle(s, p.ball), p);
    if (start->inv_mass[i] > 0 && moved && s.v.head<2>().squaredNorm() == 0.0) {
      HoldStill(i, start);
      rested = true;
    }
  }
  return rested;
}

}  // namespace

void GatherCluster(int i, int j, double radius, Cluster* cluster) {
  const double r2 = 2.0 * radius;
  bool in[Cluster::kMaxBalls] = {};
  cluster->count = 0;
  auto add = [&](int b) {
    if (in[b]) return;
    in[b] = true;
    cluster->members[cluster->count++] = b;
  };
  add(i);
  add(j);
  for (int k = 0; k < cluster->count; ++k) {  // breadth first; at most `balls` members
    const Vec2 centre = cluster->state[cluster->members[k]].r;
    for (int b = 0; b < cluster->balls; ++b) {
      const BallState& s = cluster->state[b];
      if (in[b] || s.s == MotionState::kPocketed) continue;
      if ((s.r - centre).norm() <= r2 + kContactTolerance) add(b);
    }
  }
}

void FindClusterContacts(const TableModel& table, double contact_distance, const SimParams& p,
                         Cluster* cluster) {
  const double r2 = 2.0 * p.ball.radius;
  const BallState* st = cluster->state;
  ClusterContact* contacts = cluster->contacts;
  int& nc = cluster->contact_count;
  nc = 0;
  constexpr int kCap = Cluster::kMaxContacts;
  for (int k = 0; k < cluster->count && nc < kCap; ++k) {
    const int i = cluster->members[k];
    for (int m = k + 1; m < cluster->count && nc < kCap; ++m) {
      const int j = cluster->members[m];
      const Vec2 d = st[j].r - st[i].r;
      if (d.norm() <= r2 + kContactTolerance) contacts[nc++] = {i, j, d.normalized()};
    }
    const PositionPoly poly = PositionPolynomial(st[i], p.ball, p.cloth);
    const auto segments = table.segments();
    for (size_t g = 0; g < segments.size() && nc < kCap; ++g) {
      const Gap gap = CushionGap(poly, segments[g], contact_distance);
      const Vec2 along = segments[g].p1 - segments[g].p0;
      const double u = (st[i].r - segments[g].p0).dot(along);
      if (gap.g[0] <= kContactTolerance && u >= 0 && u <= along.squaredNorm()) {
        contacts[nc++] = {i, -1, segments[g].normal};
      }
    }
    for (const JawCircle& jaw : table.jaws()) {
      if (nc >= kCap) break;
      const Vec2 d = st[i].r - jaw.centre;
      if (d.norm() <= jaw.radius + contact_distance + kContactTolerance) {
        contacts[nc++] = {i, -1, d.normalized()};
      }
    }
  }
}

void SolveCluster(const SimParams& p, Cluster* cluster) {
  RoundStart start;
  double before = 0;
  for (int k = 0; k < cluster->count; ++k) {
    const int i = cluster->members[k];
    start.initial[i] = cluster->state[i];
    start.inv_mass[i] = 1.0 / p.ball.mass;
    before += KineticEnergy(cluster->state[i], p.ball);
  }
  double restitution = p.cluster_restitution;
  // Rounds: one with restitution, one plastic, then at most one per ball held still.
  for (int round = 0; round <= cluster->count + 2; ++round) {
    BeginRound(start, restitution, cluster);
    const bool converged = Sweep(start, cluster);
    if ((MembersEnergy(*cluster, p.ball) > before || !converged) && restitution > 0) {
      // Newton restitution at several contacts at once can add energy in rare
      // arrangements, and has no solution for a ball jammed between two still ones
      // (it cannot leave both faster than it came): solve the plastic problem.
      restitution = 0;
      continue;
    }
    if (!converged && HoldApproaching(*cluster, &start)) continue;
    if (!RestSlowBalls(p, cluster, &start)) break;
  }
}

}  // namespace snooker::physics
