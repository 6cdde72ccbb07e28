// Study for a cheap fidelity tier: a precomputed table of the whole ball-ball impact
// map (cut, topspin and sidespin) against the exact solver. It measures whether such
// a table would pay (docs/impact-speed.md records the choice); the library's tables
// (physics/impact/impact_table.h) cover only rolling arrivals.
//
// With constant ball-ball friction every force in the impulse equations is
// proportional to the normal impulse, so the outcome of a cue ball C hitting a
// resting object ball O scales with the incident speed V0: it is V0 times a map of
// three numbers - the cut angle, topspin / (V0/R) and sidespin / (V0/R). The table
// samples that map (both balls' v / V0 and R w / V0 after the impact) on a regular
// grid, built with the hybrid integrator at tolerance 1e-10, and interpolates it
// (trilinear, or tricubic Catmull-Rom). The benchmark times one lookup; counters:
//   max_err, p99_err, median_err  error against the solver at tolerance 1e-10 over
//                     2000 seeded random shots inside the grid, largest over the
//                     horizontal velocities and R x spins, in units of V0 (m/s at 1 m/s)
//   table_mb          memory of the table; build_s  time to build it
// Run: build/bench/impact_table_bench (about a minute).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

#include "physics/impact/ball_ball.h"

namespace snooker::physics {
namespace {

constexpr double kMaxCutDeg = 89.0;
constexpr double kMaxSpin = 3.0;  // |topspin|, |sidespin| in units of V0 / R
constexpr int kOutputs = 12;      // v_C, R w_C, v_O, R w_O over V0
using Outputs = std::array<double, kOutputs>;

Outputs Exact(double cut, double top, double side) {
  const BallParams ball;
  const double r = ball.radius;
  ImpulseSolverOptions o;
  o.tolerance = 1e-10;
  const ImpactResult res =
      ResolveImpact(PaperIncidentState(1.0, top / r, side / r, cut), ball, {}, 0.21, o);
  const ImpactState& s = res.out;
  return {s.c.v.x(),     s.c.v.y(),     s.c.v.z(),     r * s.c.w.x(), r * s.c.w.y(), r * s.c.w.z(),
          s.o.v.x(),     s.o.v.y(),     s.o.v.z(),     r * s.o.w.x(), r * s.o.w.y(), r * s.o.w.z()};
}

class ImpactTable {
 public:
  explicit ImpactTable(int n) : n_(n), data_(static_cast<size_t>(n) * n * n) {
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        for (int k = 0; k < n; ++k) At(i, j, k) = Exact(Cut(i), Spin(j), Spin(k));
      }
    }
  }
  double bytes() const { return static_cast<double>(data_.size() * sizeof(Outputs)); }

  Outputs Lookup(double cut, double top, double side, bool cubic) const {
    const double x = cut / DegToRad(kMaxCutDeg) * (n_ - 1);
    const double y = (top + kMaxSpin) / (2 * kMaxSpin) * (n_ - 1);
    const double z = (side + kMaxSpin) / (2 * kMaxSpin) * (n_ - 1);
    return cubic ? Cubic(x, y, z) : Linear(x, y, z);
  }

 private:
  double Cut(int i) const { return DegToRad(kMaxCutDeg) * i / (n_ - 1); }
  double Spin(int j) const { return -kMaxSpin + 2 * kMaxSpin * j / (n_ - 1); }
  Outputs& At(int i, int j, int k) { return data_[(static_cast<size_t>(i) * n_ + j) * n_ + k]; }
  const Outputs& At(int i, int j, int k) const {
    auto c = [this](int a) { return std::clamp(a, 0, n_ - 1); };
    return data_[(static_cast<size_t>(c(i)) * n_ + c(j)) * n_ + c(k)];
  }
  static void Split(double x, int n, int* i, double* f) {
    *i = std::clamp(static_cast<int>(std::floor(x)), 0, n - 2);
    *f = x - *i;
  }
  Outputs Linear(double x, double y, double z) const {
    int i, j, k;
    double fx, fy, fz;
    Split(x, n_, &i, &fx), Split(y, n_, &j, &fy), Split(z, n_, &k, &fz);
    Outputs out{};
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        for (int c = 0; c < 2; ++c) {
          const double w = (a ? fx : 1 - fx) * (b ? fy : 1 - fy) * (c ? fz : 1 - fz);
          const Outputs& v = At(i + a, j + b, k + c);
          for (int m = 0; m < kOutputs; ++m) out[m] += w * v[m];
        }
      }
    }
    return out;
  }
  static std::array<double, 4> CatmullRom(double t) {
    const double t2 = t * t, t3 = t2 * t;
    return {0.5 * (-t3 + 2 * t2 - t), 0.5 * (3 * t3 - 5 * t2 + 2), 0.5 * (-3 * t3 + 4 * t2 + t),
            0.5 * (t3 - t2)};
  }
  Outputs Cubic(double x, double y, double z) const {
    int i, j, k;
    double fx, fy, fz;
    Split(x, n_, &i, &fx), Split(y, n_, &j, &fy), Split(z, n_, &k, &fz);
    const auto wx = CatmullRom(fx), wy = CatmullRom(fy), wz = CatmullRom(fz);
    Outputs out{};
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        for (int c = 0; c < 4; ++c) {
          const double w = wx[a] * wy[b] * wz[c];
          const Outputs& v = At(i + a - 1, j + b - 1, k + c - 1);
          for (int m = 0; m < kOutputs; ++m) out[m] += w * v[m];
        }
      }
    }
    return out;
  }

  int n_;
  std::vector<Outputs> data_;
};

struct Sample {
  double cut, top, side;
};

std::vector<Sample> Samples() {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Sample> s;
  for (int i = 0; i < 2000; ++i) {
    s.push_back({DegToRad(kMaxCutDeg) * u(rng), kMaxSpin * (2 * u(rng) - 1),
                 kMaxSpin * (2 * u(rng) - 1)});
  }
  return s;
}

void BM_Table(benchmark::State& state) {  // range(0): grid points per axis; range(1): cubic
  const auto t0 = std::chrono::steady_clock::now();
  const ImpactTable table(static_cast<int>(state.range(0)));
  const double build_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const bool cubic = state.range(1) != 0;
  const std::vector<Sample> samples = Samples();
  std::vector<double> errors;
  for (const Sample& s : samples) {
    const Outputs exact = Exact(s.cut, s.top, s.side);
    const Outputs got = table.Lookup(s.cut, s.top, s.side, cubic);
    double e = 0;
    for (int m = 0; m < kOutputs; ++m) {
      // The vertical velocities (a small jump) are dropped by the table simulation.
      if (m != 2 && m != 8) e = std::max(e, std::abs(got[m] - exact[m]));
    }
    errors.push_back(e);
  }
  std::sort(errors.begin(), errors.end());
  state.counters["max_err"] = errors.back();
  state.counters["p99_err"] = errors[errors.size() * 99 / 100];
  state.counters["median_err"] = errors[errors.size() / 2];
  state.counters["table_mb"] = table.bytes() / 1e6;
  state.counters["build_s"] = build_s;
  size_t i = 0;
  for (auto _ : state) {
    const Sample& s = samples[i];
    benchmark::DoNotOptimize(table.Lookup(s.cut, s.top, s.side, cubic));
    i = (i + 1) % samples.size();
  }
}
BENCHMARK(BM_Table)->Args({16, 0})->Args({16, 1})->Args({32, 0})->Args({32, 1})->Args({48, 1})
    ->Iterations(200000);

}  // namespace
}  // namespace snooker::physics

BENCHMARK_MAIN();
