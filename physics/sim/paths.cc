#include "physics/sim/paths.h"

#include <algorithm>
#include <cmath>

namespace snooker::physics {

double PathSampleInterval(double asked, double duration, int balls, std::int64_t max_points) {
  return std::max(asked, duration * static_cast<double>(balls) / static_cast<double>(max_points));
}

void SamplePath(const Simulator& sim, int i, double dt, std::vector<PathSample>* out) {
  out->clear();
  const auto knots = sim.path(i);
  const double end = sim.pocket_of(i) >= 0 && !knots.empty() ? knots.back().t : sim.end_time();
  auto add = [&](double t) { out->push_back({t, sim.PositionAt(i, t)}); };
  for (size_t k = 0; k < knots.size(); ++k) {  // every knot, samples in between
    const double t0 = knots[k].t;
    const double t1 = k + 1 < knots.size() ? knots[k + 1].t : end;
    // Counted in integers: t += dt could stall once dt is below t's last place.
    const auto m = t1 > t0 ? static_cast<std::int64_t>(std::ceil((t1 - t0) / dt)) : 0;
    for (std::int64_t j = 0; j < m; ++j) add(t0 + static_cast<double>(j) * dt);
  }
  add(end);
}

}  // namespace snooker::physics
