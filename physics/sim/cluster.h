// The cluster resolution of the table simulation: a ball-ball impact that comes
// within SimParams::cluster_time of an earlier impact of either ball is resolved
// together with every ball touching them (and those touching those, and so on) as
// one impulse problem. McNamara and Young's criterion against inelastic collapse,
// with a simultaneous resolution instead of their elastic one: without it three
// touching balls can exchange ever smaller impacts ever faster.
//
// The problem. The cluster's ball-ball and ball-boundary contacts (touching within
// kContactTolerance) take frictionless impulses lambda_k >= 0 along their normals,
// on the centre velocities only, such that afterwards no contact approaches and one
// that approached before separates at cluster_restitution times its approach speed
// (Newton). Projected Gauss-Seidel solves it: each sweep brings every contact to its
// target given the others, which converges for this positive definite problem.
// Where Newton restitution adds energy or has no solution, the plastic solution
// (restitution 0: the projection onto the velocities that approach no contact)
// always exists and never adds energy. A ball that the solution leaves slower than
// rest_speed is set at rest and held still like a wall in the next round.
//
// Table frame; SI units. No allocation, no exception: the cluster lives in fixed
// arrays sized by limits::kMaxBalls.
#pragma once

#include <span>

#include "physics/core/ball_state.h"
#include "physics/core/limits.h"
#include "physics/core/types.h"
#include "physics/sim/sim_params.h"
#include "physics/table/table.h"

namespace snooker::physics {

/// One contact of a cluster.
struct ClusterContact {
  int a = -1;  ///< a ball (an index into Cluster::state)
  int b = -1;  ///< the other ball, or -1 for a fixed boundary
  Vec2 n = Vec2::Zero();  ///< unit normal, from a to b, or from the boundary to a
  double target = 0;  ///< separation speed the solution must reach. m/s
  double lambda = 0;  ///< accumulated impulse per unit mass. m/s
};

/// The balls resolved together and their contacts.
struct Cluster {
  static constexpr int kMaxBalls = limits::kMaxBalls;
  static constexpr int kMaxContacts = 4 * kMaxBalls;

  /// Every ball's state at the instant of resolution, by ball index; the members'
  /// are replaced by the solution.
  BallState state[kMaxBalls];
  int balls = 0;  ///< how many entries of `state` are set
  int members[kMaxBalls];  ///< the cluster's balls, breadth first from the pair
  int count = 0;
  ClusterContact contacts[kMaxContacts];
  int contact_count = 0;
};

/// The cluster around the touching pair (i, j): the balls within 2R +
/// kContactTolerance of a member, breadth first; pocketed balls are left out.
/// Reads cluster->state[0, balls) and sets members and count.
void GatherCluster(int i, int j, double radius, Cluster* cluster);

/// The members' contacts with each other and with the table's cushion noses, jaw
/// walls and knuckles (`contact_distance`: from a ball's centre to a cushion nose at
/// contact, m), at most Cluster::kMaxContacts.
void FindClusterContacts(const TableModel& table, double contact_distance, const SimParams& p,
                         Cluster* cluster);

/// Solves the cluster's impulse problem (see the top of this file) and replaces the
/// members' states by the solution, settled, with rest_speed applied (AfterImpact).
void SolveCluster(const SimParams& p, Cluster* cluster);

}  // namespace snooker::physics
