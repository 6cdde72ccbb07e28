// Sampling the balls' recorded paths at an interval, for an answer that shows them
// (a drawing, the service's Simulate answer). Table frame, SI units.
//
// A ball's recorded path is a list of knots (Simulator::path): its state from each
// knot's time until the next. A sampled path has a point at every knot, points every
// dt between knots, and a last point where the ball's path ends: at the end of the
// run, or where it dropped into a pocket. Knots are kept because each one is where
// the path turns (an impact) or changes its curve (a transition); samples in between
// show the curves. With the interval grown by PathSampleInterval, the samples of n
// balls over a run of duration T number at most max_points + (knots) + n: at most
// T / dt + 1 per knot interval and one last point per ball.
//
// Allocates (the samples); not for hot paths.
#pragma once

#include <cstdint>
#include <vector>

#include "physics/core/types.h"
#include "physics/sim/simulate.h"

namespace snooker::physics {

/// One point of a sampled path.
struct PathSample {
  double t = 0;           ///< time from the start of the run, s
  Vec2 r = Vec2::Zero();  ///< centre position, m
};

/// The sampling interval (s): `asked`, or longer if `balls` paths sampled over
/// `duration` s at `asked` would have more than `max_points` points between them:
/// max(asked, duration * balls / max_points).
double PathSampleInterval(double asked, double duration, int balls, std::int64_t max_points);

/// Samples ball i's recorded path (RunOptions::record_paths) every `dt` seconds
/// between its knots, into *out (cleared first): each knot's time, then every dt
/// after it until the next knot, then the path's end - sim.end_time(), or the time
/// of its last knot if the ball was pocketed. The first point is the ball's start and
/// the last its final position. Times do not decrease, up to rounding: the last
/// sample before a knot, t0 + j dt, may come out a few units in the last place past
/// that knot's time. Positions from Simulator::PositionAt. A ball without recorded
/// knots gets only its final point.
void SamplePath(const Simulator& sim, int i, double dt, std::vector<PathSample>* out);

}  // namespace snooker::physics
