#include "physics/table/placement_repair.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace snooker::physics {
namespace {

// Problems listed in an error before the rest are counted.
constexpr std::size_t kMaxListed = 5;
// Each projection moves a ball this much beyond the constraint, so rounding cannot
// leave it a hair short. m.
constexpr double kSlack = 1e-12;

}  // namespace

PlacementRepair RepairPlacement(const TableModel& table, std::span<BallPlacement> balls,
                                double tolerance) {
  PlacementRepair out;
  const double r2 = 2 * table.ball_radius();
  const double c = table.cushion_contact_distance();
  const double lo[2] = {c, c};
  const double hi[2] = {table.spec().width - c, table.spec().length - c};
  const std::size_t n = balls.size();

  // Everything beyond the tolerance is an error, reported whole, nothing moved.
  std::vector<std::string> problems;
  auto name = [&](std::size_t i) {
    return balls[i].name.empty() ? "ball " + std::to_string(i) : std::string(balls[i].name);
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!balls[i].r.allFinite()) {
      problems.push_back(name(i) + ": position not finite");
      continue;
    }
    if (table.InPocketMouth(balls[i].r)) continue;  // on a pocket's lip
    for (int axis = 0; axis < 2; ++axis) {
      const double x = balls[i].r[axis];
      const double past = std::max(lo[axis] - x, x - hi[axis]);
      if (!(past > tolerance)) continue;
      std::ostringstream m;
      m << name(i) << " is " << past << " m past the cushion contact distance ("
        << (axis == 0 ? "x" : "y") << " = " << x << " m; the tolerance is " << tolerance << " m)";
      problems.push_back(m.str());
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const double overlap = r2 - (balls[i].r - balls[j].r).norm();
      if (!(overlap > tolerance)) continue;
      std::ostringstream m;
      m << name(i) << " and " << name(j) << " overlap by " << overlap << " m (the tolerance is "
        << tolerance << " m)";
      problems.push_back(m.str());
    }
  }
  if (!problems.empty()) {
    for (std::size_t k = 0; k < problems.size() && k < kMaxListed; ++k) {
      out.error += (k > 0 ? "; " : "") + problems[k];
    }
    if (problems.size() > kMaxListed) {
      out.error += "; and " + std::to_string(problems.size() - kMaxListed) + " more";
    }
    return out;
  }

  std::vector<Vec2> r(n);
  for (std::size_t i = 0; i < n; ++i) r[i] = balls[i].r;
  bool clean = false;
  for (int sweep = 0; sweep < kMaxRepairSweeps && !clean; ++sweep) {
    clean = true;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
        Vec2 d = r[j] - r[i];
        const double dist = d.norm();
        if (dist >= r2 - TableModel::kPlacementTolerance) continue;  // as ValidatePlacement

        clean = false;
        d = dist > 0 ? Vec2(d / dist) : Vec2(1, 0);  // coincident: apart along x
        const double half = 0.5 * (r2 - dist) + kSlack;
        r[i] -= half * d;
        r[j] += half * d;
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (table.InPocketMouth(r[i])) continue;
      for (int axis = 0; axis < 2; ++axis) {
        double& x = r[i][axis];
        if (x < lo[axis] - TableModel::kPlacementTolerance) x = lo[axis], clean = false;
        if (x > hi[axis] + TableModel::kPlacementTolerance) x = hi[axis], clean = false;
      }
    }
  }
  if (!clean) {
    out.error = "the balls could not be separated within " + std::to_string(kMaxRepairSweeps) +
                " sweeps (a cluster jammed against the cushions)";
    return out;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double moved = (r[i] - balls[i].r).norm();
    if (moved == 0) continue;
    out.moved.push_back({i, balls[i].r, r[i], moved});
    balls[i].r = r[i];
  }
  return out;
}

}  // namespace snooker::physics
