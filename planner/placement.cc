#include "planner/placement.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlopt.hpp>
#include <utility>

namespace snooker::planner {
namespace {

using physics::Vec2;

// The grid: radii as fractions of the D's, directions from the brown spot towards
// the baulk cushion (0: along +x on the baulk line, pi: along -x).
constexpr double kRadii[] = {0.3, 0.6, 0.9};
constexpr int kDirections = 7;
// A placement keeps this much room beyond 2R to every ball, m.
constexpr double kPlacementClearance = 1e-3;
// Estimates each refinement may spend.
constexpr int kRefineEvaluations = 30;

Vec2 DCentre(const physics::TableModel& table) {
  return Vec2(0.5 * table.spec().width, table.spec().baulk_line);
}

// Polar (fraction of the D's radius, angle in [0, pi]) to the table frame.
Vec2 FromPolar(double rho, double phi, const physics::TableModel& table) {
  return DCentre(table) + rho * table.spec().d_radius * Vec2(std::cos(phi), -std::sin(phi));
}

bool Clear(const Vec2& p, const TableState& table, const physics::TableModel& model) {
  const double need = 2 * model.ball_radius() + kPlacementClearance;
  for (const Ball& b : table.balls) {
    if ((b.position - p).norm() < need) return false;
  }
  return InTheD(p, model);
}

double Points(const Candidate& c, const TableState& table, double continuation) {
  return c.estimate.probability * (Value(table.balls[static_cast<size_t>(c.object)].kind) + continuation);
}

// One ball-pocket pair's placement refined with BOBYQA over (rho, phi).
struct Refinement {
  const TableState* table;
  int object;
  physics::PocketId pocket;
  const PotContext* ctx;
  double continuation;
  TableState placed;  // the table with the cue ball last, moved per evaluation

  double Evaluate(const double* x) {
    const Vec2 p = FromPolar(x[0], x[1], *ctx->table);
    if (!Clear(p, *table, *ctx->table)) return -1;
    placed.balls.back().position = p;
    const auto c = AssessPot(placed, static_cast<int>(placed.balls.size()) - 1, object, pocket, *ctx);
    return c ? Points(*c, placed, continuation) : -1;
  }

  // NLopt 2.7 takes a function pointer: no exception may cross it.
  static double Trampoline(unsigned /*n*/, const double* x, double* /*grad*/, void* data) {
    try {
      return static_cast<Refinement*>(data)->Evaluate(x);
    } catch (...) {
      return -1;  // this point is simply not used
    }
  }
};

std::pair<double, double> ToPolar(const Vec2& p, const physics::TableModel& table) {
  const Vec2 d = p - DCentre(table);
  const double rho = std::min(1.0, d.norm() / table.spec().d_radius);
  const double phi = rho > 0 ? std::clamp(std::atan2(-d.y(), d.x()), 0.0, physics::kPi) : 0.5 * physics::kPi;
  return {rho, phi};
}

void Refine(const TableState& table, PlacedCandidate* best, const PotContext& ctx, double continuation) {
  Refinement r{&table, best->candidate.object, best->candidate.pocket, &ctx, continuation,
               WithCueBall(table, best->place)};
  const auto [rho, phi] = ToPolar(best->place, *ctx.table);
  std::vector<double> x = {rho, phi};
  nlopt::opt opt(nlopt::LN_BOBYQA, 2);
  opt.set_lower_bounds({0.0, 0.0});
  opt.set_upper_bounds({1.0, physics::kPi});
  opt.set_max_objective(&Refinement::Trampoline, &r);
  opt.set_maxeval(kRefineEvaluations);
  opt.set_xtol_abs(1e-3);
  opt.set_initial_step(std::vector<double>{0.1, 0.2});
  double f = 0;
  try {
    opt.optimize(x, f);
  } catch (const std::exception&) {
    return;  // keep the grid's point: a refinement is optional
  }
  if (!(f > best->points)) return;
  const Vec2 p = FromPolar(x[0], x[1], *ctx.table);
  const TableState placed = WithCueBall(table, p);
  const auto c = AssessPot(placed, static_cast<int>(placed.balls.size()) - 1, best->candidate.object,
                           best->candidate.pocket, ctx);
  if (!c || !Clear(p, table, *ctx.table)) return;
  best->candidate = *c;
  best->place = p;
  best->points = Points(*c, placed, continuation);
}

}  // namespace

TableState WithCueBall(const TableState& table, const Vec2& p) {
  TableState out = table;
  out.balls.push_back({BallKind::kCue, p});
  return out;
}

std::vector<PlacedCandidate> PlaceForPots(const TableState& table, BallOn on, const PotContext& ctx,
                                          double continuation) {
  std::map<std::pair<int, int>, PlacedCandidate> best;  // by (object, pocket)
  TableState placed = WithCueBall(table, DCentre(*ctx.table));
  for (const double rho : kRadii) {
    for (int k = 0; k < kDirections; ++k) {
      const Vec2 p = FromPolar(rho, physics::kPi * k / (kDirections - 1), *ctx.table);
      if (!Clear(p, table, *ctx.table)) continue;
      placed.balls.back().position = p;
      for (const Candidate& c : EnumerateCandidates(placed, on, ctx).candidates) {
        const double points = Points(c, placed, continuation);
        PlacedCandidate& b = best[{c.object, static_cast<int>(c.pocket)}];
        if (points > b.points) b = {c, p, points};
      }
    }
  }
  std::vector<PlacedCandidate> out;
  out.reserve(best.size());
  for (auto& [key, b] : best) {
    Refine(table, &b, ctx, continuation);
    b.candidate.cue_start = b.place;
    out.push_back(b);
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const PlacedCandidate& a, const PlacedCandidate& b) { return a.points > b.points; });
  return out;
}

std::optional<Vec2> FreePlaceInTheD(const TableState& table, const physics::TableModel& model) {
  const Vec2 centre = DCentre(model);
  // The brown spot, then outwards along the D's directions.
  for (int ring = 0; ring <= 8; ++ring) {
    const double rho = ring / 9.0;
    for (int k = 0; k < (ring == 0 ? 1 : 2 * kDirections); ++k) {
      const double phi = physics::kPi * k / (2 * kDirections - 1);
      const Vec2 p = centre + rho * model.spec().d_radius * Vec2(std::cos(phi), -std::sin(phi));
      if (Clear(p, table, model)) return p;
    }
  }
  return std::nullopt;
}

}  // namespace snooker::planner
