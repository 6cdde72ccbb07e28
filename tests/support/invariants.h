// Invariants of a finished simulation run, shared by the simulation tests and the
// sweeps: each returns testing::AssertionResult so a failure names the event.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "physics/sim/simulate.h"
#include "physics/table/table.h"

namespace snooker::physics::invariants {

/// Distance by which two balls may overlap or a ball pass a cushion nose. m (the
/// detectors' contact tolerance, physics/events/detect.h).
inline constexpr double kOverlapTol = 1e-9;
/// Relative rise of the kinetic energy allowed between events (impact integrators
/// at tolerance 1e-10).
inline constexpr double kEnergyRiseRel = 1e-9;

/// For a run made with RunOptions recording events and paths: event times never
/// decrease; at every event no two balls on the table overlap by more than
/// kOverlapTol and none lies beyond a cushion nose except in a pocket mouth; the
/// kinetic energy never rises (relative kEnergyRiseRel).
inline testing::AssertionResult RunKeepsInvariants(const Simulator& sim, const TableModel& table) {
  const int n = sim.ball_count();
  const double r2 = 2 * table.ball_radius();
  const double c = table.cushion_contact_distance() - kOverlapTol;
  const double w = table.spec().width, l = table.spec().length;
  double previous_time = 0, previous_energy = std::numeric_limits<double>::infinity();
  std::vector<Vec2> at(static_cast<size_t>(n));
  std::vector<bool> on(static_cast<size_t>(n));
  for (size_t k = 0; k < sim.events().size(); ++k) {
    const SimEvent& e = sim.events()[k];
    if (e.time < previous_time) {
      return testing::AssertionFailure() << "event " << k << " at t = " << e.time
                                         << " s comes before the previous one at " << previous_time;
    }
    if (e.kinetic_energy > previous_energy * (1 + kEnergyRiseRel) + 1e-15) {
      return testing::AssertionFailure() << "energy rose at event " << k << " (t = " << e.time
                                         << " s): " << previous_energy << " -> " << e.kinetic_energy;
    }
    previous_time = e.time;
    previous_energy = e.kinetic_energy;
    for (int i = 0; i < n; ++i) {
      on[static_cast<size_t>(i)] = !(sim.pocket_of(i) >= 0 && sim.path(i).back().t <= e.time);
      at[static_cast<size_t>(i)] = sim.PositionAt(i, e.time);
    }
    for (int i = 0; i < n; ++i) {
      if (!on[static_cast<size_t>(i)]) continue;
      const Vec2& ri = at[static_cast<size_t>(i)];
      for (int j = i + 1; j < n; ++j) {
        if (!on[static_cast<size_t>(j)]) continue;
        const double d = (ri - at[static_cast<size_t>(j)]).norm();
        if (d < r2 - kOverlapTol) {
          return testing::AssertionFailure() << "balls " << i << " and " << j << " overlap by "
                                             << r2 - d << " m at event " << k << " (t = " << e.time << " s)";
        }
      }
      if (ri.x() < c || ri.x() > w - c || ri.y() < c || ri.y() > l - c) {
        double nearest = std::numeric_limits<double>::infinity();
        for (const Pocket& p : table.pockets()) nearest = std::min(nearest, (ri - p.mouth_centre).norm());
        if (nearest > 0.1) {
          return testing::AssertionFailure() << "ball " << i << " off the bed at (" << ri.x() << ", "
                                             << ri.y() << ") at event " << k << " (t = " << e.time << " s)";
        }
      }
    }
  }
  return testing::AssertionSuccess();
}

}  // namespace snooker::physics::invariants
