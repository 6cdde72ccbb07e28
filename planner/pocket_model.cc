#include "planner/pocket_model.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iterator>
#include <numeric>
#include <optional>

#include "planner/geometry.h"
#include "planner/parallel.h"
#include "planner/shot_sim.h"

namespace snooker::planner {
namespace {

using physics::PocketId;
using physics::Vec2;

constexpr PocketId kCornerSample = PocketId::kBaulkLeft;
constexpr PocketId kMiddleSample = PocketId::kMiddleLeft;
// Start distances tried before the mouth, m, longest first: a line that comes along
// a cushion may only start close to the pocket.
constexpr double kStartDistances[] = {0.5, 0.25, 0.12};
// A ball this far from the mouth centre and moving away from it has missed. m.
constexpr double kGiveUpDistance = 0.3;

// A serial number no other model of this process has (PocketModel::serial).
std::uint64_t NextSerial() {
  static std::atomic<std::uint64_t> built{0};
  return ++built;
}

bool IsCorner(PocketId id) { return id != PocketId::kMiddleLeft && id != PocketId::kMiddleRight; }

Vec2 Rotate(const Vec2& v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

}  // namespace

PocketModel::PocketModel(const physics::TableModel& table, const physics::SimParams& params,
                         const Options& options)
    : table_(table), params_(params), options_(options), serial_(NextSerial()) {
  SizeGrids();
  MeasureCells();
}

PocketModel::PocketModel(const physics::TableModel& table, const physics::SimParams& params,
                         const Options& options, const std::vector<PocketWindow>& cells)
    : table_(table), params_(params), options_(options), serial_(NextSerial()) {
  if (SizeGrids() != cells.size()) {
    MeasureCells();
    return;
  }
  auto next = cells.begin();
  for (AngleGrid* g : {&corner_, &middle_}) {
    std::copy(next, next + static_cast<std::ptrdiff_t>(g->cells.size()), g->cells.begin());
    next += static_cast<std::ptrdiff_t>(g->cells.size());
  }
}

std::size_t PocketModel::SizeGrids() {
  std::size_t total = 0;
  for (const bool corner : {true, false}) {
    AngleGrid& g = corner ? corner_ : middle_;
    g.max_angle = corner ? options_.corner_max_angle : options_.middle_max_angle;
    g.reach_cosine = std::cos(std::min(physics::kPi, g.max_angle + 0.1));
    g.count = 2 * static_cast<int>(std::lround(g.max_angle / options_.angle_step)) + 1;
    g.cells.assign(static_cast<size_t>(g.count) * options_.arrival_speeds.size(), PocketWindow{});
    total += g.cells.size();
  }
  return total;
}

void PocketModel::MeasureCells() {
  // Every cell is independent: two threads (one simulator each) share them, and the
  // table is the same whichever thread measured a cell.
  struct Cell {
    bool corner;
    size_t speed;
    int angle;
  };
  std::vector<Cell> cells;
  for (const bool corner : {true, false}) {
    const AngleGrid& g = Grid(corner);
    for (size_t s = 0; s < options_.arrival_speeds.size(); ++s) {
      for (int a = 0; a < g.count; ++a) cells.push_back({corner, s, a});
    }
  }
  // On two workers, as many as the system starts (planner/parallel.h); each keeps a
  // simulator and a count of its own.
  constexpr int kWorkers = 2;
  std::optional<physics::Simulator> sims[kWorkers];
  long counts[kWorkers] = {};
  ParallelFor(kWorkers, static_cast<int>(cells.size()), [&](int task, int worker) {
    std::optional<physics::Simulator>& sim = sims[worker];
    if (!sim) sim.emplace(table_, params_);
    const Cell& c = cells[static_cast<size_t>(task)];
    AngleGrid& g = c.corner ? corner_ : middle_;
    g.cells[c.speed * static_cast<size_t>(g.count) + static_cast<size_t>(c.angle)] =
        Measure(*sim, c.corner ? kCornerSample : kMiddleSample, angle_at(c.corner, c.angle),
                options_.arrival_speeds[c.speed], &counts[worker]);
  });
  simulations_ = std::accumulate(std::begin(counts), std::end(counts), 0L);
}

const PocketModel& PocketModel::Default() {
  static const PocketModel model(physics::DefaultTable(), physics::SimParams{}, Options{}, DefaultCells());
  return model;
}

std::vector<PocketWindow> PocketModel::Cells() const {
  std::vector<PocketWindow> cells(corner_.cells);
  cells.insert(cells.end(), middle_.cells.begin(), middle_.cells.end());
  return cells;
}

double PocketModel::angle_at(bool corner, int angle_index) const {
  const AngleGrid& g = Grid(corner);
  return -g.max_angle + angle_index * (2 * g.max_angle / (g.count - 1));
}

bool PocketModel::Drops(physics::Simulator& sim, PocketId id, double approach, double speed,
                        double offset, long* count) const {
  const physics::Pocket& p = table_.pocket(id);
  const Vec2 u = Rotate(p.axis, approach);
  const double c = table_.cushion_contact_distance();
  const double w = table_.spec().width, l = table_.spec().length;
  const double decel = params_.cloth.mu_r * params_.cloth.g;
  for (const double d : kStartDistances) {
    const Vec2 start = p.mouth_centre - d * u + offset * Left(u);
    if (start.x() < c || start.x() > w - c || start.y() < c || start.y() > l - c) continue;
    physics::BallState b;
    b.r = start;
    const double v0 = std::sqrt(speed * speed + 2 * decel * d);
    b.v = physics::Vec3(v0 * u.x(), v0 * u.y(), 0);
    b.w = physics::Vec3(-u.y(), u.x(), 0) * (v0 / table_.ball_radius());  // rolling
    ++*count;
    // Run until the ball drops, or has come away from the mouth (a miss: it is past
    // the pocket's reach and moving away from it), or rests.
    physics::SimStatus status =
        sim.Start(std::span<const physics::BallState>(&b, 1), physics::RunOptions::Lean());
    while (status == physics::SimStatus::kRunning) {
      status = sim.Step();
      if (sim.pocket_of(0) >= 0) break;
      const physics::BallState now = sim.StateNow(0);
      const Vec2 from_mouth = now.r - p.mouth_centre;
      if (from_mouth.norm() > kGiveUpDistance &&
          from_mouth.dot(Vec2(now.v.x(), now.v.y())) > 0) {
        break;
      }
    }
    return sim.pocket_of(0) == static_cast<int>(id);
  }
  return false;  // no ball can be on that line before the mouth
}

PocketWindow PocketModel::Measure(physics::Simulator& sim, PocketId id, double approach,
                                  double speed, long* count) const {
  const double h = options_.scan_half_width, step = options_.scan_step;
  const int n = 2 * static_cast<int>(std::lround(h / step)) + 1;
  auto offset = [&](int k) { return -h + k * step; };
  const int centre = n / 2;  // offset 0
  int best_lo = -1, best_hi = -1;
  if (Drops(sim, id, approach, speed, 0.0, count)) {
    // The usual case: walk out from the centre line to the first miss each way.
    best_lo = best_hi = centre;
    while (best_lo > 0 && Drops(sim, id, approach, speed, offset(best_lo - 1), count)) --best_lo;
    while (best_hi < n - 1 && Drops(sim, id, approach, speed, offset(best_hi + 1), count)) ++best_hi;
  } else {
    // Scan every offset; keep the widest dropping run.
    std::vector<char> drops(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) drops[static_cast<size_t>(k)] = Drops(sim, id, approach, speed, offset(k), count);
    for (int k = 0; k < n;) {
      if (!drops[static_cast<size_t>(k)]) {
        ++k;
        continue;
      }
      int e = k;
      while (e + 1 < n && drops[static_cast<size_t>(e + 1)]) ++e;
      if (best_lo < 0 || e - k > best_hi - best_lo) best_lo = k, best_hi = e;
      k = e + 1;
    }
  }
  PocketWindow win;
  if (best_lo < 0) return win;
  win.empty = false;
  win.lo = offset(best_lo);
  win.hi = offset(best_hi);
  // Bisect each edge between the last miss and the first drop.
  if (best_lo > 0) {
    double out = offset(best_lo - 1), in = win.lo;
    for (int i = 0; i < options_.bisections; ++i) {
      const double mid = 0.5 * (out + in);
      (Drops(sim, id, approach, speed, mid, count) ? in : out) = mid;
    }
    win.lo = in;
  }
  if (best_hi < n - 1) {
    double out = offset(best_hi + 1), in = win.hi;
    for (int i = 0; i < options_.bisections; ++i) {
      const double mid = 0.5 * (out + in);
      (Drops(sim, id, approach, speed, mid, count) ? in : out) = mid;
    }
    win.hi = in;
  }
  return win;
}

PocketWindow PocketModel::Cell(bool corner, int angle_index, int speed_index) const {
  const AngleGrid& g = Grid(corner);
  return g.cells[static_cast<size_t>(speed_index) * static_cast<size_t>(g.count) +
                 static_cast<size_t>(angle_index)];
}

double PocketModel::Approach(PocketId id, double direction) const {
  return WrapAngle(direction - Direction(table_.pocket(id).axis));
}

double PocketModel::ReachCosine(PocketId id) const { return Grid(IsCorner(id)).reach_cosine; }

PocketWindow PocketModel::InterpolateAngle(const AngleGrid& g, int speed_index,
                                           double approach) const {
  if (!(std::abs(approach) <= g.max_angle)) return {};
  const double f = (approach + g.max_angle) / (2 * g.max_angle) * (g.count - 1);
  const int i0 = std::clamp(static_cast<int>(std::floor(f)), 0, g.count - 1);
  const int i1 = std::min(i0 + 1, g.count - 1);
  const double t = f - i0;
  const PocketWindow& a = g.cells[static_cast<size_t>(speed_index) * static_cast<size_t>(g.count) +
                                  static_cast<size_t>(i0)];
  const PocketWindow& b = g.cells[static_cast<size_t>(speed_index) * static_cast<size_t>(g.count) +
                                  static_cast<size_t>(i1)];
  if (a.empty || b.empty) return t < 0.5 ? a : b;  // the nearest cell
  PocketWindow w;
  w.empty = false;
  w.lo = a.lo + t * (b.lo - a.lo);
  w.hi = a.hi + t * (b.hi - a.hi);
  return w;
}

PocketWindow PocketModel::Window(PocketId id, double direction, double arrival_speed) const {
  const AngleGrid& g = Grid(IsCorner(id));
  const double approach = Approach(id, direction);
  const std::vector<double>& v = options_.arrival_speeds;
  if (!(arrival_speed > v.front())) return InterpolateAngle(g, 0, approach);
  if (arrival_speed >= v.back()) return InterpolateAngle(g, static_cast<int>(v.size()) - 1, approach);
  int s = 0;
  while (s + 2 < static_cast<int>(v.size()) && arrival_speed > v[static_cast<size_t>(s + 1)]) ++s;
  const double t = (arrival_speed - v[static_cast<size_t>(s)]) /
                   (v[static_cast<size_t>(s + 1)] - v[static_cast<size_t>(s)]);
  const PocketWindow a = InterpolateAngle(g, s, approach);
  const PocketWindow b = InterpolateAngle(g, s + 1, approach);
  if (a.empty || b.empty) return t < 0.5 ? a : b;
  PocketWindow w;
  w.empty = false;
  w.lo = a.lo + t * (b.lo - a.lo);
  w.hi = a.hi + t * (b.hi - a.hi);
  return w;
}

}  // namespace snooker::planner
