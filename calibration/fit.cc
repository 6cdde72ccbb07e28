#include "calibration/fit.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <thread>

#include <Eigen/Dense>
#include <nlopt.hpp>

namespace snooker::calibration {
namespace {

using physics::Model;

// Where a parameter lives in the model; `index` is the knot of a curve parameter.
using FieldRef = double* (*)(Model&, int);

struct Param {
  ParameterSpec spec;
  FieldRef ref = nullptr;
  int index = 0;
};

constexpr double kInf = std::numeric_limits<double>::infinity();

// A knot's restitution bounds: below 0.3 no snooker cushion rebounds; above 1 the
// model creates energy.
constexpr double kKnotLo = 0.3, kKnotHi = 1.0;
// A side offset below this (fraction of R) squirts too little to show end_mass.
constexpr double kMinSide = 0.05;

bool HasObjectBall(const Observations& o) {
  return std::any_of(o.shots.begin(), o.shots.end(), [](const TrackedShot& s) { return s.balls.size() >= 2; });
}

// Why a group's data cannot identify it; empty when it can.
std::string MissingData(Group g, const Observations& o) {
  switch (g) {
    case Group::kBallBall:
      if (o.throws.empty() && !HasObjectBall(o)) {
        return "ball-ball: no throw observations and no tracked shot with an object ball; rebounds do not "
               "depend on the ball-ball friction law";
      }
      return "";
    case Group::kCushion:
      if (o.rebounds.empty()) {
        return "cushion: no rebound observations; the restitution knots fitted are those the rebounds' "
               "approach speeds cover, and throw observations do not depend on the cushion";
      }
      return "";
    case Group::kCloth:
      if (o.shots.empty()) {
        return "cloth: no tracked shots; throw observations do not depend on mu_s, mu_r or spin_decel "
               "(mu_r and spin_decel do not enter a collision, mu_s only through the cloth's small part in "
               "it), nor do rebounds";
      }
      return "";
    case Group::kCue: {
      bool cue_form = false, side = false;
      for (const TrackedShot& s : o.shots) {
        if (const auto* k = std::get_if<physics::CueStrike>(&s.strike)) {
          cue_form = true;
          side = side || std::abs(k->side) >= kMinSide;
        }
      }
      if (!cue_form) {
        return "cue: no tracked shots struck in the cue's terms; the cue's parameters act only through a strike";
      }
      if (!side) {
        return "cue: no tracked shot struck with side (|side| >= 0.05 R); cue.end_mass sets only the squirt of "
               "a strike with side";
      }
      return "";
    }
  }
  return "unknown group";
}

void AddBallBall(std::vector<Param>* out) {
  out->push_back({{"ball_ball.mu_bb", "friction law a: mu at high speed", 0.0, 0.3, 0.005},
                  [](Model& m, int) { return &m.ball_ball.mu_bb; }, 0});
  out->push_back({{"ball_ball.slip_gain", "friction law b: mu(0) - a", 0.0, 0.5, 0.02},
                  [](Model& m, int) { return &m.ball_ball.slip_gain; }, 0});
  out->push_back({{"ball_ball.slip_decay", "friction law c: decay of mu with speed, s/m", 0.01, 20.0, 0.2},
                  [](Model& m, int) { return &m.ball_ball.slip_decay; }, 0});
}

void AddCushion(const Observations& o, const physics::RestitutionCurve& curve, std::vector<Param>* out) {
  out->push_back({{"cushion.mu_w", "ball-cushion friction at the nose", 0.0, 0.35, 0.01},
                  [](Model& m, int) { return &m.cushion.mu_w; }, 0});
  if (curve.points <= 0) {
    out->push_back({{"cushion.e_e", "restitution (constant)", kKnotLo, kKnotHi, 0.02},
                    [](Model& m, int) { return &m.cushion.e_e; }, 0});
    return;
  }
  const int n = std::min(curve.points, physics::RestitutionCurve::kMaxPoints);
  for (int k = 0; k < n; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    const double lo = k > 0 ? curve.speed[i - 1] : -kInf, hi = k + 1 < n ? curve.speed[i + 1] : kInf;
    const auto covered = std::count_if(o.rebounds.begin(), o.rebounds.end(), [&](const CushionObservation& r) {
      const double normal = r.speed * std::sin(r.angle);
      return normal > lo && normal < hi;
    });
    if (covered < 2) continue;
    std::ostringstream name, what;
    name << "cushion.restitution_curve.e[" << k << "]";
    what << "restitution at " << curve.speed[i] << " m/s approach";
    out->push_back({{name.str(), what.str(), kKnotLo, kKnotHi, 0.02},
                    [](Model& m, int j) { return &m.cushion.restitution_curve.e[static_cast<std::size_t>(j)]; },
                    k});
  }
}

void AddCloth(std::vector<Param>* out) {
  out->push_back({{"cloth.mu_s", "ball-cloth sliding friction", 0.05, 0.6, 0.01},
                  [](Model& m, int) { return &m.cloth.mu_s; }, 0});
  out->push_back({{"cloth.mu_r", "rolling resistance (deceleration / g)", 0.002, 0.05, 0.0005},
                  [](Model& m, int) { return &m.cloth.mu_r; }, 0});
  out->push_back({{"cloth.spin_decel", "vertical spin's deceleration, rad/s^2", 1.0, 100.0, 2.0},
                  [](Model& m, int) { return &m.cloth.spin_decel; }, 0});
}

void AddCue(std::vector<Param>* out) {
  out->push_back({{"cue.end_mass", "the shaft's end mass (squirt), kg", 0.001, 0.05, 0.0005},
                  [](Model& m, int) { return &m.cue.end_mass; }, 0});
  out->push_back({{"cue.tip_restitution", "the tip's normal restitution", 0.4, 0.95, 0.01},
                  [](Model& m, int) { return &m.cue.tip_restitution; }, 0});
}

// The model the search starts from: `start` with its ball-ball law in the
// exponential family when that group is fitted (a constant law as Marlow's), in the
// start's form (the impact-speed form stays one, any other becomes the slip form).
Model StartModel(std::span<const Group> groups, const Model& start) {
  Model m = start;
  if (std::find(groups.begin(), groups.end(), Group::kBallBall) == groups.end()) return m;
  physics::FrictionCurve f = physics::FrictionCurveOf(start.ball_ball);
  if (!(f.b > 0)) f = {9.951e-3, 0.108, 1.088};
  m.ball_ball = physics::WithFrictionCurve(m.ball_ball, f, start.ball_ball.friction_law);
  return m;
}

std::vector<Param> ParamsOf(std::span<const Group> groups, const Observations& o, const Model& start) {
  std::vector<Param> out;
  for (Group g : groups) {
    switch (g) {
      case Group::kBallBall: AddBallBall(&out); break;
      case Group::kCushion: AddCushion(o, start.cushion.restitution_curve, &out); break;
      case Group::kCloth: AddCloth(&out); break;
      case Group::kCue: AddCue(&out); break;
    }
  }
  return out;
}

Model WithValues(Model m, const std::vector<Param>& params, const std::vector<double>& values) {
  for (std::size_t i = 0; i < params.size(); ++i) *params[i].ref(m, params[i].index) = values[i];
  return m;
}

enum class Kind : std::uint8_t { kThrow, kReboundSpeed, kReboundAngle, kPosition };

// The weighted residuals of every observation for a model, in a fixed layout.
class Residuals {
 public:
  Residuals(const Observations& o, const FitOptions& options) : o_(o), options_(options) {
    for (std::size_t i = 0; i < o.throws.size(); ++i) kinds_.push_back(Kind::kThrow);
    for (const CushionObservation& r : o.rebounds) {
      kinds_.push_back(Kind::kReboundSpeed);
      if (r.rebound_angle) kinds_.push_back(Kind::kReboundAngle);
    }
    for (const TrackedShot& s : o.shots) {
      shot_offsets_.push_back(kinds_.size());
      for (const Sighting& g : s.sightings) {
        for (const physics::Vec2& r : g.positions) {
          if (std::isnan(r.x())) continue;
          kinds_.push_back(Kind::kPosition);
          kinds_.push_back(Kind::kPosition);
        }
      }
    }
  }

  std::size_t size() const { return kinds_.size(); }
  Kind kind(std::size_t i) const { return kinds_[i]; }
  /// The interrupt (FitOptions::interrupt) came due during an evaluation: its
  /// residuals from then on are kFailedResidual, and every later one's too.
  bool stopped() const { return stopped_.load(std::memory_order_relaxed); }
  /// Sightings later than this (s) count as zero residuals (the staged search).
  void set_horizon(double t) { horizon_ = t; }
  double Sigma(Kind k) const {
    switch (k) {
      case Kind::kThrow: return options_.throw_sigma;
      case Kind::kReboundSpeed: return options_.rebound_speed_sigma;
      case Kind::kReboundAngle: return options_.rebound_angle_sigma;
      case Kind::kPosition: break;
    }
    return options_.position_sigma;
  }

  // The weighted residuals; `first_error` gets the first failed prediction's
  // message when not null.
  std::vector<double> operator()(const Model& m, std::string* first_error = nullptr) const {
    std::vector<double> r(kinds_.size(), kFailedResidual);
    std::vector<std::string> errors(1 + o_.shots.size());
    std::size_t at = 0;
    for (std::size_t i = 0; i < o_.throws.size() && !Due(); ++i, ++at) {
      const ThrowPrediction p = PredictThrow(o_.throws[i], m, options_.numerics);
      if (p.error.empty()) {
        r[at] = (p.throw_angle - o_.throws[i].measured_throw) / options_.throw_sigma;
      } else if (errors[0].empty()) {
        errors[0] = "throw[" + std::to_string(i) + "]: " + p.error;
      }
    }
    for (std::size_t i = 0; i < o_.rebounds.size() && !Due(); ++i) {
      const CushionObservation& ob = o_.rebounds[i];
      const ReboundPrediction p = PredictRebound(ob, m, options_.numerics);
      const bool ok = p.error.empty();
      if (!ok && errors[0].empty()) errors[0] = "rebound[" + std::to_string(i) + "]: " + p.error;
      if (ok) r[at] = (p.speed - ob.rebound_speed) / options_.rebound_speed_sigma;
      ++at;
      if (!ob.rebound_angle) continue;
      if (ok) r[at] = (p.angle - *ob.rebound_angle) / options_.rebound_angle_sigma;
      ++at;
    }
    ShotsInParallel(m, &r, &errors);
    if (first_error != nullptr) {
      for (const std::string& e : errors) {
        if (!e.empty()) {
          *first_error = e;
          break;
        }
      }
    }
    return r;
  }

 private:
  // Checked before every prediction (a clock read against at least a microsecond of
  // work), so that a call's deadline ends even one evaluation of many observations.
  bool Due() const {
    if (stopped()) return true;
    if (!options_.interrupt.Due()) return false;
    stopped_.store(true, std::memory_order_relaxed);
    return true;
  }

  // Shot i's residuals from its prediction (kFailedResidual where it has none).
  void Shot(std::size_t i, const Model& m, std::vector<double>* r, std::string* error) const {
    const TrackedShot& s = o_.shots[i];
    const ShotPrediction p = PredictShot(s, m, options_.numerics);
    if (p.positions.empty()) {
      *error = "shot[" + std::to_string(i) + "]: " + p.error;
      return;
    }
    std::size_t at = shot_offsets_[i];
    for (std::size_t j = 0; j < s.sightings.size(); ++j) {
      const std::vector<physics::Vec2>& seen = s.sightings[j].positions;
      const bool late = s.sightings[j].t > horizon_;
      for (std::size_t b = 0; b < seen.size(); ++b) {
        if (std::isnan(seen[b].x())) continue;
        const physics::Vec2 d = late ? physics::Vec2::Zero().eval()
                                     : ((p.positions[j][b] - seen[b]) / options_.position_sigma).eval();
        (*r)[at++] = d.x();
        (*r)[at++] = d.y();
      }
    }
  }

  // Shots split round-robin among the threads; each writes only its shots' slots. A
  // share whose thread the system cannot start (a process or container limit) is run
  // by the caller after its own, so every shot is predicted either way.
  void ShotsInParallel(const Model& m, std::vector<double>* r, std::vector<std::string>* errors) const {
    const std::size_t n = o_.shots.size();
    const std::size_t threads = std::clamp<std::size_t>(static_cast<std::size_t>(std::max(1, options_.threads)),
                                                        1, std::max<std::size_t>(1, n));
    auto work = [&](std::size_t t) {
      for (std::size_t i = t; i < n && !Due(); i += threads) Shot(i, m, r, &(*errors)[1 + i]);
    };
    std::vector<std::thread> pool;
    pool.reserve(threads - 1);
    std::size_t started = 1;
    for (; started < threads; ++started) {
      try {
        pool.emplace_back(work, started);
      } catch (...) {  // std::system_error (no thread) or std::bad_alloc: start no more
        break;
      }
    }
    work(0);
    for (std::size_t t = started; t < threads; ++t) work(t);
    for (std::thread& th : pool) th.join();
  }

  const Observations& o_;
  const FitOptions& options_;
  std::vector<Kind> kinds_;
  std::vector<std::size_t> shot_offsets_;
  double horizon_ = kInf;
  mutable std::atomic<bool> stopped_{false};
};

// The position residuals through the Cauchy loss (FitOptions::position_outlier_scale).
void Robust(const Residuals& residuals, double c, std::vector<double>* r) {
  if (!(c > 0)) return;
  for (std::size_t i = 0; i < r->size(); ++i) {
    if (residuals.kind(i) != Kind::kPosition) continue;
    const double x = (*r)[i];
    (*r)[i] = std::copysign(c * std::sqrt(std::log1p((x / c) * (x / c))), x);
  }
}

double SumOfSquares(const std::vector<double>& r) {
  double s = 0;
  for (double x : r) s += x * x;
  return s;
}

// Counts the prediction sets a fit computes.
struct Evaluator {
  const Residuals& residuals;
  const std::vector<Param>& params;
  const Model& base;
  double outlier_scale = 0;
  int count = 0;

  // The residuals the search minimises: weighted, positions through the loss.
  std::vector<double> operator()(const std::vector<double>& values, std::string* error = nullptr) {
    std::vector<double> r = Raw(values, error);
    Robust(residuals, outlier_scale, &r);
    return r;
  }
  // Weighted only.
  std::vector<double> Raw(const std::vector<double>& values, std::string* error = nullptr) {
    ++count;
    return residuals(WithValues(base, params, values), error);
  }
};

// The Jacobian of the weighted residuals in the parameters measured in units of
// their scales: central differences over a hundredth of the scale, one-sided
// where a bound is nearer than that.
Eigen::MatrixXd Jacobian(Evaluator& eval, const std::vector<double>& at, const std::vector<double>& r0) {
  const std::size_t p = at.size();
  Eigen::MatrixXd j(static_cast<Eigen::Index>(r0.size()), static_cast<Eigen::Index>(p));
  for (std::size_t k = 0; k < p; ++k) {
    const ParameterSpec& s = eval.params[k].spec;
    const double h = 0.01 * s.scale;
    std::vector<double> up = at, down = at;
    up[k] = std::min(at[k] + h, s.hi);
    down[k] = std::max(at[k] - h, s.lo);
    std::vector<double> r_up, r_down;
    if (up[k] - at[k] < 0.5 * h) {  // at the upper bound: backward
      up[k] = at[k];
      r_up = r0;
      r_down = eval(down);
    } else if (at[k] - down[k] < 0.5 * h) {  // at the lower bound: forward
      down[k] = at[k];
      r_down = r0;
      r_up = eval(up);
    } else {
      r_up = eval(up);
      r_down = eval(down);
    }
    if (eval.residuals.stopped()) return j;  // interrupted: the caller ends the fit
    const double width = (up[k] - down[k]) / s.scale;
    for (std::size_t i = 0; i < r0.size(); ++i) {
      j(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = (r_up[i] - r_down[i]) / width;
    }
  }
  return j;
}

// Empty when J^T J's eigenvalues are within kIdentifiability of each other;
// otherwise the direction the data leave undetermined, "0.71 ball_ball.slip_gain -
// 0.70 ball_ball.slip_decay", in units of the parameters' scales.
std::string Unidentified(const Eigen::MatrixXd& j, const std::vector<Param>& params) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(j.transpose() * j);
  const Eigen::VectorXd& lambda = eig.eigenvalues();  // ascending
  const double largest = lambda(lambda.size() - 1);
  if (largest > 0 && lambda(0) >= kIdentifiability * largest) return "";
  const Eigen::VectorXd v = eig.eigenvectors().col(0);
  std::ostringstream out;
  out.precision(2);
  out << std::fixed;
  bool first = true;
  for (Eigen::Index k = 0; k < v.size(); ++k) {
    if (std::abs(v(k)) < 0.1) continue;
    const double c = first ? v(k) : std::abs(v(k));
    out << (first ? "" : v(k) < 0 ? " - " : " + ") << c << ' ' << params[static_cast<std::size_t>(k)].spec.name;
    first = false;
  }
  out << " (in units of their scales; smallest eigenvalue of J^T J " << std::scientific << lambda(0)
      << " of the largest " << largest << ")";
  return out.str();
}

std::string CheckOptions(const FitOptions& o) {
  std::ostringstream out;
  auto positive = [&](double v, const char* name, const char* unit) {
    if (std::isfinite(v) && v > 0) return;
    if (out.tellp() > 0) out << "; ";
    out << "options." << name << " = " << v << " (must be a finite number > 0 " << unit << ")";
  };
  positive(o.throw_sigma, "throw_sigma", "rad");
  positive(o.rebound_speed_sigma, "rebound_speed_sigma", "m/s");
  positive(o.rebound_angle_sigma, "rebound_angle_sigma", "rad");
  positive(o.position_sigma, "position_sigma", "m");
  positive(o.max_seconds, "max_seconds", "s");
  positive(o.x_tolerance, "x_tolerance", "of a range");
  positive(o.max_evaluations, "max_evaluations", "evaluations");
  positive(o.threads, "threads", "threads");
  if (!(std::isfinite(o.position_outlier_scale) && o.position_outlier_scale >= 0)) {
    if (out.tellp() > 0) out << "; ";
    out << "options.position_outlier_scale = " << o.position_outlier_scale
        << " (must be a finite number >= 0 sigmas; 0: plain least squares)";
  }
  double last = 0;
  for (std::size_t k = 0; k < o.horizons.size() && k < 20; ++k) {
    const double h = o.horizons[k];
    if (h > last && h <= kMaxSightingTime) {
      last = h;
      continue;
    }
    if (out.tellp() > 0) out << "; ";
    out << "options.horizons[" << k << "] = " << h << " (must increase, within (0, 600] s)";
    break;
  }
  if (o.horizons.size() > 20) {
    if (out.tellp() > 0) out << "; ";
    out << "options.horizons.size = " << o.horizons.size() << " (must be at most 20)";
  }
  return out.str();
}

// Refusals before any search: bad input, missing data, too few residuals.
std::string Refusal(const Observations& o, std::span<const Group> groups, const Model& start,
                    const FitOptions& options) {
  if (groups.empty()) return "no group to fit (one or more of ball-ball, cushion, cloth, cue)";
  std::string bad = Validate(o);
  if (!bad.empty()) return "observations: " + bad;
  bad = physics::ValidateModel(start);
  if (!bad.empty()) return "start model: " + bad;
  bad = CheckOptions(options);
  if (!bad.empty()) return bad;
  std::string missing;
  for (Group g : groups) {
    const std::string m = MissingData(g, o);
    if (!m.empty()) missing += (missing.empty() ? "" : "; ") + m;
  }
  return missing;
}

struct Search {
  Evaluator& eval;
  std::vector<double> best;
  double best_cost = kInf;
  const physics::Interrupt* interrupt = nullptr;
  bool interrupted = false;

  static double Objective(unsigned n, const double* u, double* /*grad*/, void* data) {
    Search& s = *static_cast<Search*>(data);
    if (s.interrupt != nullptr && s.interrupt->Due()) {
      s.interrupted = true;
      throw nlopt::forced_stop();  // NLopt ends the search and optimize() rethrows it
    }
    std::vector<double> values(n);
    for (unsigned k = 0; k < n; ++k) {
      const ParameterSpec& p = s.eval.params[k].spec;
      values[k] = p.lo + std::clamp(u[k], 0.0, 1.0) * (p.hi - p.lo);
    }
    const double cost = SumOfSquares(s.eval(values));
    if (s.eval.residuals.stopped()) {
      s.interrupted = true;
      throw nlopt::forced_stop();
    }
    if (cost < s.best_cost) {
      s.best_cost = cost;
      s.best = values;
    }
    return cost;
  }
};

// Runs the bounded search from `start` (values); returns how it ended and leaves
// the best point in search->best.
std::string RunSearch(Search* search, const std::vector<double>& start, const FitOptions& options,
                      double seconds_left) {
  const std::size_t p = start.size();
  nlopt::opt opt(p >= 2 ? nlopt::LN_BOBYQA : nlopt::LN_COBYLA, static_cast<unsigned>(p));
  std::vector<double> u(p), step(p);
  for (std::size_t k = 0; k < p; ++k) {
    const ParameterSpec& s = search->eval.params[k].spec;
    u[k] = (start[k] - s.lo) / (s.hi - s.lo);
    step[k] = std::clamp(s.scale / (s.hi - s.lo), 1e-3, 0.25);
  }
  opt.set_lower_bounds(std::vector<double>(p, 0.0));
  opt.set_upper_bounds(std::vector<double>(p, 1.0));
  opt.set_min_objective(&Search::Objective, search);
  opt.set_maxeval(options.max_evaluations);
  opt.set_maxtime(std::max(1e-3, seconds_left));
  opt.set_xtol_abs(options.x_tolerance);
  opt.set_ftol_rel(1e-12);
  opt.set_initial_step(step);
  double f = 0;
  try {
    switch (opt.optimize(u, f)) {
      case nlopt::MAXEVAL_REACHED: return "evaluation cap";
      case nlopt::MAXTIME_REACHED: return "time cap";
      default: return "converged";
    }
  } catch (const nlopt::roundoff_limited&) {
    return "roundoff";  // as far as doubles allow: the best point stands
  } catch (const nlopt::forced_stop&) {
    return "interrupted";
  } catch (const std::exception& e) {
    return std::string("search failed: ") + e.what();
  }
}

// The search in stages of growing horizon when there are tracked shots (see
// fit.h), each from the best point of the one before, sharing the caps.
std::string RunStages(Search* search, Residuals* residuals, bool tracked, const FitOptions& options,
                      double seconds) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<double> horizons = {kInf};
  if (tracked) horizons = options.horizons;
  if (horizons.empty() || horizons.back() != kInf) horizons.push_back(kInf);
  std::string status;
  int left = options.max_evaluations;
  for (std::size_t k = 0; k < horizons.size(); ++k) {
    residuals->set_horizon(horizons[k]);
    // The best point so far, judged at this stage's horizon.
    search->best_cost = SumOfSquares(search->eval(search->best));
    const int stages_left = static_cast<int>(horizons.size() - k);
    FitOptions stage = options;
    stage.max_evaluations = std::max(1, left / stages_left);
    const int before = search->eval.count;
    const double used = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    status = RunSearch(search, search->best, stage, seconds - used);
    left -= search->eval.count - before;
    if (status == "time cap" || status == "interrupted" || status.rfind("search failed", 0) == 0) break;
  }
  residuals->set_horizon(kInf);
  return status;
}

void Summarise(const Residuals& r, const std::vector<double>& before, const std::vector<double>& after,
               FitResult* out) {
  struct Acc {
    int n = 0;
    double before = 0, after = 0;
  } acc[4];
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Kind k = r.kind(i);
    // Back to the kind's unit (angles in degrees for the report).
    const double unit = r.Sigma(k) * (k == Kind::kThrow || k == Kind::kReboundAngle ? physics::kDegPerRad : 1.0);
    Acc& a = acc[static_cast<int>(k)];
    ++a.n;
    a.before += std::pow(before[i] * unit, 2);
    a.after += std::pow(after[i] * unit, 2);
  }
  KindResiduals* kinds[4] = {&out->throw_deg, &out->rebound_speed, &out->rebound_angle_deg, &out->position};
  for (int k = 0; k < 4; ++k) {
    kinds[k]->count = acc[k].n;
    if (acc[k].n == 0) continue;
    kinds[k]->rms_before = std::sqrt(acc[k].before / acc[k].n);
    kinds[k]->rms_after = std::sqrt(acc[k].after / acc[k].n);
  }
}

// cov = s^2 (J^T J)^-1 in scale units, back to each parameter's unit.
void Uncertainties(const Eigen::MatrixXd& j, double s2, const std::vector<Param>& params, FitResult* out) {
  const Eigen::MatrixXd jtj = j.transpose() * j;
  const bool singular = !Unidentified(j, params).empty();
  const Eigen::MatrixXd cov = singular ? Eigen::MatrixXd() : Eigen::MatrixXd(s2 * jtj.inverse());
  for (std::size_t k = 0; k < params.size(); ++k) {
    const Eigen::Index e = static_cast<Eigen::Index>(k);
    out->parameters[k].uncertainty =
        singular ? std::numeric_limits<double>::quiet_NaN() : std::sqrt(std::max(0.0, cov(e, e))) * params[k].spec.scale;
  }
  if (singular) out->status += "; J^T J singular at the optimum: no uncertainties";
}

}  // namespace

FitResult Fit(const Observations& observations, std::span<const Group> groups, const physics::Model& start,
              const FitOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  FitResult out;
  out.model = start;
  out.error = Refusal(observations, groups, start, options);
  if (!out.error.empty()) return out;
  const Model m0 = StartModel(groups, start);
  const std::vector<Param> params = ParamsOf(groups, observations, m0);
  Residuals residuals(observations, options);
  if (residuals.size() < params.size()) {
    out.error = std::to_string(residuals.size()) + " residuals for " + std::to_string(params.size()) +
                " parameters (a fit needs at least as many residuals as parameters)";
    return out;
  }
  std::vector<double> v0;
  for (const Param& p : params) {
    Model m = m0;
    v0.push_back(std::clamp(*p.ref(m, p.index), p.spec.lo, p.spec.hi));
  }
  Evaluator eval{residuals, params, m0, options.position_outlier_scale};
  // The interrupt ends the fit wherever it comes due: the start's Jacobian, the
  // search, the optimum's Jacobian.
  auto interrupted = [&] {
    out.interrupted = true;
    out.error = "interrupted (the caller's deadline or cancellation) after " + std::to_string(eval.count) +
                " evaluations";
    out.evaluations = eval.count;
    out.model = start;
    out.parameters.clear();
    return out;
  };
  std::string failed;
  const std::vector<double> r0 = eval(v0, &failed);
  if (residuals.stopped()) return interrupted();
  if (!failed.empty()) {
    out.error = "start model: a prediction failed: " + failed;
    return out;
  }
  const Eigen::MatrixXd j0 = Jacobian(eval, v0, r0);
  if (residuals.stopped()) return interrupted();
  const std::string unidentified = Unidentified(j0, params);
  if (!unidentified.empty()) {
    out.error = "the data do not identify " + unidentified;
    return out;
  }
  Search search{eval, v0, SumOfSquares(r0), &options.interrupt};
  out.status = RunStages(&search, &residuals, !observations.shots.empty(), options, options.max_seconds - elapsed());
  if (search.interrupted || residuals.stopped()) return interrupted();
  const std::vector<double> r1 = eval(search.best);
  out.model = WithValues(m0, params, search.best);
  for (std::size_t k = 0; k < params.size(); ++k) {
    out.parameters.push_back({params[k].spec.name, params[k].spec.what, v0[k], search.best[k], 0});
  }
  const std::size_t n = r1.size(), p = params.size();
  out.reduced_chi_square = n > p ? SumOfSquares(r1) / static_cast<double>(n - p) : 0;
  Uncertainties(Jacobian(eval, search.best, r1), out.reduced_chi_square, params, &out);
  Summarise(residuals, eval.Raw(v0), eval.Raw(search.best), &out);
  if (residuals.stopped()) return interrupted();
  out.evaluations = eval.count;
  out.seconds = elapsed();
  return out;
}

const char* ToString(Group g) {
  switch (g) {
    case Group::kBallBall: return "ball-ball";
    case Group::kCushion: return "cushion";
    case Group::kCloth: return "cloth";
    case Group::kCue: return "cue";
  }
  return "unknown";
}

ParsedGroups ParseGroups(std::string_view text) {
  ParsedGroups out;
  constexpr Group kAll[] = {Group::kBallBall, Group::kCushion, Group::kCloth, Group::kCue};
  std::size_t start = 0;
  for (int words = 0; words <= static_cast<int>(text.size()); ++words) {  // capped by the text's length
    std::size_t end = text.find(',', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view word = text.substr(start, end - start);
    while (!word.empty() && word.front() == ' ') word.remove_prefix(1);
    while (!word.empty() && word.back() == ' ') word.remove_suffix(1);
    const auto known = std::find_if(std::begin(kAll), std::end(kAll), [&](Group g) { return word == ToString(g); });
    if (known == std::end(kAll)) {
      out.groups.clear();
      out.error = "unknown group \"" + std::string(word) + "\" (one of ball-ball, cushion, cloth, cue)";
      return out;
    }
    if (std::find(out.groups.begin(), out.groups.end(), *known) == out.groups.end()) out.groups.push_back(*known);
    if (end == text.size()) break;
    start = end + 1;
  }
  return out;
}

std::vector<ParameterSpec> FittedParameters(std::span<const Group> groups, const Observations& observations,
                                            const physics::Model& start, std::vector<double>* values) {
  const Model m0 = StartModel(groups, start);
  std::vector<Param> params = ParamsOf(groups, observations, m0);
  std::vector<ParameterSpec> out;
  if (values != nullptr) values->clear();
  for (Param& p : params) {
    out.push_back(p.spec);
    Model m = m0;
    if (values != nullptr) values->push_back(*p.ref(m, p.index));
  }
  return out;
}

}  // namespace snooker::calibration
