// Builds and checks the impact tables (physics/impact/impact_table.h).
// Usage:
//   impact_tables build cushion|ball-ball OUT [N0 N1 [N2] MAX_SIDE CELL_TOLERANCE]
//       Builds the table for the simulator's default parameters (SimParams, with the
//       default TableSpec's nose height) and writes it to OUT. Grid: cushion angles,
//       sides, restitutions; ball-ball cuts, sides. Prints the build time and the
//       marked cells.
//   impact_tables check cushion|ball-ball FILE SAMPLES SEED
//       JSON: over SAMPLES seeded random impacts of rolling balls (speed 0.2-4 m/s,
//       inside the grid), the share the table answers and its error against the
//       exact solver at 1e-12 (largest over both balls' v and R w, in units of V):
//       median, 99th percentile, max; the same for the exact solver at SimParams'
//       shot tolerance, and the time of one lookup against one solve there.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "physics/impact/impact_table.h"
#include "physics/sim/simulate.h"
#include "physics/table/table.h"
#include "tests/physics/impact/impact_test_support.h"

namespace {

using namespace snooker::physics;
using Clock = std::chrono::steady_clock;

CushionParams DefaultCushion() {
  CushionParams c = SimParams{}.cushion;
  c.contact_height = TableSpec{}.cushion_height;
  return c;
}

double Quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

double Seconds(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

bool Write(const char* path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (out) return true;
  std::fprintf(stderr, "cannot write %s\n", path);
  return false;
}

int Build(const std::string& kind, const char* path, const std::vector<double>& grid) {
  const auto t0 = Clock::now();
  std::vector<std::uint8_t> bytes;
  int cells = 0, marked = 0;
  const SimParams sim;
  if (kind == "cushion") {
    CushionTableGrid g;
    if (grid.size() == 5) {
      g.angles = static_cast<int>(grid[0]);
      g.sides = static_cast<int>(grid[1]);
      g.restitutions = static_cast<int>(grid[2]);
      g.max_side = grid[3];
      g.cell_tolerance = grid[4];
    }
    const CushionTable t = CushionTable::Build(sim.ball, DefaultCushion(), g);
    bytes = t.Serialize();
    cells = t.grid().cells();
    marked = t.grid().marked_cells();
  } else {
    BallBallTableGrid g;
    if (grid.size() == 4) {
      g.cuts = static_cast<int>(grid[0]);
      g.sides = static_cast<int>(grid[1]);
      g.max_side = grid[2];
      g.cell_tolerance = grid[3];
    }
    const BallBallTable t = BallBallTable::Build(sim.ball, sim.ball_ball, sim.cloth.mu_s, g);
    bytes = t.Serialize();
    cells = t.grid().cells();
    marked = t.grid().marked_cells();
  }
  const double s = Seconds(t0);
  if (!Write(path, bytes)) return 1;
  std::printf("{\"table\": \"%s\", \"build_s\": %.1f, \"bytes\": %zu, \"cells\": %d, \"marked_cells\": %d}\n",
              kind.c_str(), s, bytes.size(), cells, marked);
  return 0;
}

struct Errors {
  std::vector<double> table, shot;
  int samples = 0, answered = 0;
  double lookup_s = 0, solve_s = 0;
};

void Print(const std::string& kind, const Errors& e, const GridTable& g) {
  std::printf(
      "{\"table\": \"%s\", \"samples\": %d, \"answered\": %d, \"cells\": %d, \"marked_cells\": %d,\n"
      " \"lookup_us\": %.3f, \"solve_us\": %.3f,\n"
      " \"table_error\": {\"median\": %.2e, \"p99\": %.2e, \"max\": %.2e},\n"
      " \"solver_error\": {\"median\": %.2e, \"p99\": %.2e, \"max\": %.2e}}\n",
      kind.c_str(), e.samples, e.answered, g.cells(), g.marked_cells(),
      1e6 * e.lookup_s / std::max(1, e.answered), 1e6 * e.solve_s / static_cast<double>(std::max<std::size_t>(1, e.shot.size())),
      Quantile(e.table, 0.5), Quantile(e.table, 0.99), Quantile(e.table, 1.0), Quantile(e.shot, 0.5),
      Quantile(e.shot, 0.99), Quantile(e.shot, 1.0));
}

std::vector<std::uint8_t> ReadFile(const char* path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// One random impact: the converged answer, the solver at the shot tolerance (timed)
// and the table (timed). `solve(options)` returns a solver's result, `lookup(&out)`
// the table's answer.
template <class Solve, class Lookup>
void Measure(double v, double radius, const Solve& solve, const Lookup& lookup, Errors* e) {
  ImpulseSolverOptions reference, shot = SimParams::ShotImpactOptions();
  reference.tolerance = 1e-12;
  reference.method = ImpulseMethod::kDormandPrince853;
  const auto exact = solve(reference);
  auto t0 = Clock::now();
  const auto loose = solve(shot);
  e->solve_s += Seconds(t0);
  if (exact.status != ImpactStatus::kOk || loose.status != ImpactStatus::kOk) return;
  e->shot.push_back(test::MaxDifference(loose.out, exact.out, radius) / v);
  decltype(exact.out) out;
  t0 = Clock::now();
  const bool hit = lookup(&out);
  e->lookup_s += Seconds(t0);
  if (!hit) return;
  ++e->answered;
  e->table.push_back(test::MaxDifference(out, exact.out, radius) / v);
}

// Reads a table of type T from `path`; false (with a message) if it is unreadable or
// was built for other parameters.
template <class T, class Matches>
bool Load(const char* path, const Matches& matches, T* t) {
  const std::vector<std::uint8_t> bytes = ReadFile(path);
  const std::string error = T::Deserialize(bytes.data(), bytes.size(), false, t);
  if (error.empty() && matches(*t)) return true;
  std::fprintf(stderr, "%s: %s\n", path, error.empty() ? "built for other parameters" : error.c_str());
  return false;
}

int Check(const std::string& kind, const char* path, int samples, unsigned seed) {
  const SimParams sim;
  const double R = sim.ball.radius;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> speed(0.2, 4.0), coin(0, 1);
  Errors e;
  e.samples = samples;
  if (kind == "cushion") {
    const CushionParams cushion = DefaultCushion();
    CushionTable t;
    if (!Load(path, [&](const CushionTable& c) { return c.Matches(sim.ball, cushion); }, &t)) return 1;
    const auto& ax = t.grid().axes();
    std::uniform_real_distribution<double> angle(ax[0].lo, ax[0].hi), side(ax[1].lo, ax[1].hi);
    for (int i = 0; i < samples; ++i) {
      const double a = angle(rng), sd = side(rng), v = speed(rng);
      BallMotion m = CushionIncidentState(v, a, v / R, sd * v / R);
      if (coin(rng) < 0.5) m = {Vec3(-m.v.x(), m.v.y(), 0), Vec3(m.w.x(), -m.w.y(), -m.w.z())};
      auto solve = [&](const ImpulseSolverOptions& o) {
        return ResolveCushionImpact(m, sim.ball, cushion, o);
      };
      auto lookup = [&](BallMotion* out) {
        return t.Lookup(m, R, CushionRestitution(cushion, m.v.y()), out);
      };
      Measure(v, R, solve, lookup, &e);
    }
    Print(kind, e, t.grid());
    return 0;
  }
  BallBallTable t;
  auto matches = [&](const BallBallTable& b) {
    return b.Matches(sim.ball, sim.ball_ball, sim.cloth.mu_s);
  };
  if (!Load(path, matches, &t)) return 1;
  const auto& ax = t.grid().axes();
  std::uniform_real_distribution<double> cut(ax[0].lo, ax[0].hi), side(ax[1].lo, ax[1].hi);
  for (int i = 0; i < samples; ++i) {
    const double c = cut(rng), sd = side(rng), v = speed(rng);
    const double sign = coin(rng) < 0.5 ? -1.0 : 1.0;
    const ImpactState in = PaperIncidentState(v, v / R, sd * v / R, sign * c);
    auto solve = [&](const ImpulseSolverOptions& o) {
      return ResolveImpact(in, sim.ball, sim.ball_ball, sim.cloth.mu_s, o);
    };
    Measure(v, R, solve, [&](ImpactState* out) { return t.Lookup(in, R, out); }, &e);
  }
  Print(kind, e, t.grid());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string cmd = argc > 1 ? argv[1] : "";
  const std::string kind = argc > 2 ? argv[2] : "";
  if ((kind == "cushion" || kind == "ball-ball") && argc >= 4) {
    if (cmd == "build") {
      std::vector<double> grid;
      for (int i = 4; i < argc; ++i) grid.push_back(std::atof(argv[i]));
      const std::size_t want = kind == "cushion" ? 5 : 4;
      if (grid.empty() || grid.size() == want) return Build(kind, argv[3], grid);
    }
    if (cmd == "check" && argc == 6) {
      return Check(kind, argv[3], std::atoi(argv[4]), static_cast<unsigned>(std::atoi(argv[5])));
    }
  }
  std::fprintf(stderr,
               "usage: impact_tables build cushion|ball-ball OUT [N0 N1 [N2] MAX_SIDE CELL_TOLERANCE]\n"
               "       impact_tables check cushion|ball-ball FILE SAMPLES SEED\n");
  return 2;
}
