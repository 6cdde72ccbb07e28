// Which lines into a pocket drop: acceptance windows tabulated by simulation.
//
// A pot's precision is set by the pocket, not by the mouth's width alone: a ball
// coming in square can clip a knuckle and still drop, one coming along a cushion
// meets the near jaw early, and a middle pocket refuses anything much past 60 deg
// off its axis. The simulator knows all of that, so the window is measured, not
// modelled: a single ball rolls at the pocket along the direction `approach` (the
// angle from the pocket's axis, counter-clockwise positive) on a line that passes
// the mouth centre at a signed offset e (positive: the line passes to the left of
// the mouth centre, seen along the ball's travel), arriving at the mouth at a given
// speed. From e = 0 outwards in steps until a line misses on each side (or, when
// the centre line misses, over the whole range, keeping the widest dropping run),
// then each edge is found by bisection.
// All four corners are congruent by rotation, as are both middles (the jaws are
// symmetric), so one pocket of each kind is tabulated.
//
// Resolution (angle step, offset step, bisection depth) is a parameter with a cost:
// the default table takes about 4000 single-ball simulations on two threads. So the
// default model's windows are measured once, when the physics changes, and compiled
// in (pocket_model_default.cc, written by scripts/pocket-windows); a test measures
// them again and must find them the same to the bit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "physics/sim/simulate.h"
#include "physics/table/table.h"

namespace snooker::planner {

/// The offsets (m, see above) at the mouth whose lines drop; empty when none do.
struct PocketWindow {
  double lo = 0;
  double hi = 0;
  bool empty = true;
  double centre() const { return 0.5 * (lo + hi); }
  double width() const { return empty ? 0 : hi - lo; }
};

class PocketModel {
 public:
  struct Options {
    /// Angle grid, rad: corners up to corner_max_angle, middles up to middle_max_angle.
    double angle_step = 5.0 * physics::kPi / 180;
    double corner_max_angle = 50.0 * physics::kPi / 180;
    double middle_max_angle = 60.0 * physics::kPi / 180;
    /// Speeds at the mouth, m/s, ascending.
    std::vector<double> arrival_speeds = {0.3, 1.0, 2.5};
    /// Offsets scanned: [-scan_half_width, scan_half_width] in steps of scan_step. m.
    double scan_half_width = 0.070;
    double scan_step = 0.0025;
    /// Bisection steps on each edge (the edge to scan_step / 2^n).
    int bisections = 5;
  };

  PocketModel(const physics::TableModel& table, const physics::SimParams& params,
              const Options& options);
  /// The model with the windows `cells`, measured before for the same table, params and
  /// options (as Cells() gives them): no simulation, simulations() 0. Cells of another
  /// count than the options' grid are measured instead.
  PocketModel(const physics::TableModel& table, const physics::SimParams& params,
              const Options& options, const std::vector<PocketWindow>& cells);
  /// The model of DefaultTable(), default SimParams and Options, made on first use
  /// (thread-safe) from the windows compiled in.
  static const PocketModel& Default();

  /// The window of pocket `id` for a ball travelling in direction `direction` (rad,
  /// table frame) and arriving at `arrival_speed` (m/s), interpolated in the table.
  PocketWindow Window(physics::PocketId id, double direction, double arrival_speed) const;
  /// The angle from pocket `id`'s axis to `direction`, in (-pi, pi]. rad.
  double Approach(physics::PocketId id, double direction) const;
  /// The cheapest test of a pocket's reach: the cosine of the largest approach angle
  /// tabulated for the pocket's kind (beyond it the window is empty) plus 0.1 rad (a
  /// margin for the window's offset from the line to the mouth). A ball whose
  /// line to the mouth makes a larger angle with the axis, (mouth - ball) . axis <
  /// this x |mouth - ball|, has no window there.
  double ReachCosine(physics::PocketId id) const;
  /// The window at grid cell (kind, angle index, speed index), for reports and tests.
  PocketWindow Cell(bool corner, int angle_index, int speed_index) const;
  /// Every cell's window: the corners' grid, then the middles', each by speed, then by
  /// angle.
  std::vector<PocketWindow> Cells() const;
  int angle_count(bool corner) const { return Grid(corner).count; }
  double angle_at(bool corner, int angle_index) const;
  const Options& options() const { return options_; }
  /// Single-ball simulations spent building the table.
  long simulations() const { return simulations_; }
  const physics::TableModel& table() const { return table_; }
  /// A number no other model built in this process has (a copy keeps it, with the
  /// same windows): what a cache of this model's answers is keyed by.
  std::uint64_t serial() const { return serial_; }

 private:
  struct AngleGrid {
    double max_angle = 0;
    double reach_cosine = -1;  // ReachCosine
    int count = 0;
    std::vector<PocketWindow> cells;  // [speed][angle]
  };
  const AngleGrid& Grid(bool corner) const { return corner ? corner_ : middle_; }
  /// Sizes both grids for the options (their cells empty); the cells' count.
  std::size_t SizeGrids();
  void MeasureCells();
  /// The default model's windows as measured (pocket_model_default.cc).
  static std::vector<PocketWindow> DefaultCells();
  PocketWindow Measure(physics::Simulator& sim, physics::PocketId id, double approach,
                       double speed, long* count) const;
  bool Drops(physics::Simulator& sim, physics::PocketId id, double approach, double speed,
             double offset, long* count) const;
  PocketWindow InterpolateAngle(const AngleGrid& g, int speed_index, double approach) const;

  const physics::TableModel& table_;
  physics::SimParams params_;
  Options options_;
  AngleGrid corner_, middle_;
  long simulations_ = 0;
  std::uint64_t serial_ = 0;
};

}  // namespace snooker::planner
