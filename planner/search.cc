#include "planner/search.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <exception>
#include <limits>
#include <nlopt.hpp>
#include <vector>

#include "physics/motion/motion.h"
#include "physics/sim/resolve.h"
#include "planner/geometry.h"
#include "planner/layout.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

// Objective of a shot that cannot be played at all (no heading realises the cut,
// or the cue has no room): below every simulated failure (-1 + P/2 >= -1).
constexpr double kUnplayable = -2.0;
// Objective of a safety, escape or break-off that fouls, or of one that cannot be
// played: below every legal stroke's (whose worst is the opponent's best
// position, some tens of points).
constexpr double kFailedSafety = -200.0;

// The cue ball's state when it has travelled `distance` (m) along its heading, or
// nullopt if it stops (or draws back) first. Straight-line motion (geometry.h).
std::optional<physics::BallState> CueAfter(const physics::BallState& start, double distance,
                                           const physics::SimParams& params) {
  const Vec2 u = Vec2(start.v.x(), start.v.y()).normalized();
  physics::BallState s = physics::Settle(start, params.ball);  // classify the struck ball
  double remaining = distance;
  for (int phase = 0; phase < 3; ++phase) {  // sliding, rolling, (spinning: stopped)
    if (s.s != physics::MotionState::kSliding && s.s != physics::MotionState::kRolling) break;
    const physics::PositionPoly p = physics::PositionPolynomial(s, params.ball, params.cloth);
    const double T = physics::TransitionTime(s, params.ball, params.cloth);
    const double b = p.b.dot(u), a = p.a.dot(u);
    // Distance along u: f(t) = b t + a t^2, largest at t* = -b / (2a) when a < 0.
    const double t_peak = a < 0 ? -b / (2 * a) : std::numeric_limits<double>::infinity();
    const double t_max = std::min(T, t_peak);
    const double f_max = std::isfinite(t_max) ? b * t_max + a * t_max * t_max
                                              : std::numeric_limits<double>::infinity();
    if (f_max >= remaining) {
      const double disc = b * b + 4 * a * remaining;
      if (disc < 0 || b <= 0) return std::nullopt;
      const double t = 2 * remaining / (b + std::sqrt(disc));
      return physics::Evolve(s, t, params.ball, params.cloth);
    }
    if (!std::isfinite(T) || t_peak < T) return std::nullopt;  // drew back or stopped
    remaining -= b * T + a * T * T;
    s = physics::Evolve(s, T, params.ball, params.cloth);
  }
  return std::nullopt;
}

// The object ball's rolling direction after a cut `cut` from `cue` along `heading`
// (rad), the cue ball struck with `shot`'s speed and spins; nullopt when the cue
// ball does not arrive or the impact fails.
std::optional<double> ObjectDirection(const Vec2& cue, const Vec2& object, double heading,
                                      double cut, const physics::Shot& shot,
                                      const physics::SimParams& params) {
  const double r = params.ball.radius;
  const Vec2 u(std::cos(heading), std::sin(heading));
  const double travel = u.dot(object - cue) - 2 * r * std::cos(cut);
  if (!(travel >= 0)) return std::nullopt;
  physics::Shot s = shot;
  s.heading = heading;
  const auto at = CueAfter(physics::StruckBall(s, cue), travel, params);
  if (!at) return std::nullopt;
  physics::BallState c = *at;
  const Vec2 n(std::cos(heading + cut), std::sin(heading + cut));
  c.r = object - 2 * r * n;
  physics::BallState o;
  o.r = object;
  const physics::BallBallResolution res = physics::ResolveBallBallOnTable(
      c, o, params.ball, params.ball_ball, params.cloth, params.ball_ball_solver);
  if (res.status != physics::ImpactStatus::kOk) return std::nullopt;
  physics::BallState ob = res.b;
  if (ob.s == physics::MotionState::kSliding) {
    ob = physics::Evolve(ob, physics::TransitionTime(ob, params.ball, params.cloth), params.ball,
                         params.cloth);
  }
  const Vec2 v(ob.v.x(), ob.v.y());
  if (!(v.norm() > 0)) return std::nullopt;
  return Direction(v);
}

class Search {
 public:
  Search(const TableState& table, BallOn on, const Candidate& cand, const PotContext& ctx,
         const SearchSettings& settings, ShotSimulator& sim, const StopControl& stop, LeaveScratch* scratch)
      : table_(table), on_(on), cand_(cand), ctx_(ctx), settings_(settings), sim_(sim),
        stop_(stop), interrupt_(stop.AsInterrupt()),
        own_(scratch == nullptr ? std::make_unique<LeaveScratch>() : nullptr),
        scratch_(scratch != nullptr ? *scratch : *own_) {
    cue_ = table.cue_index();
    setup_ = {&table_, cue_, cand.object, cand.pocket, on, cand.kind, cand.first, TouchingBallOn(table, on, *ctx.table)};
    if (cand.speed_hi > 0) {
      v_lo_ = std::clamp(cand.speed_lo, settings.limits.min_speed, settings.limits.max_speed);
      v_hi_ = std::clamp(cand.speed_hi, v_lo_, settings.limits.max_speed);
    } else {
      std::tie(v_lo_, v_hi_) = SpeedRange(table, cue_, cand, settings.limits, sim.params());
    }
    // The next shot is seen afresh by vision: every ball with the default sigma
    // (the balls' indices change once some drop).
    after_ctx_ = ctx;
    after_ctx_.position_sigma.clear();
    final_positions_.reserve(table.balls.size());
    scratch_.after.balls.reserve(table.balls.size());
    scratch_.origin.reserve(table.balls.size());
    // Another route's own spread at the mouth, and its chance centred in the window it
    // planned for: constants of the candidate that PotProbability scales by.
    if (cand.route != PotRoute::kDirect) {
      route_sigma_ = std::max(cand.estimate.sigma, 1e-4);
      route_centred_ = WindowProbability(cand.estimate.window.centre(), route_sigma_, cand.estimate.window);
    }
    // A cue ball touching a ball plays away from it (no push): the directions in
    // which the cue ball may not set off.
    const Vec2 c = table.balls[static_cast<size_t>(cue_)].position;
    for (const int i : TouchingCueBall(table, *ctx.table)) {
      touching_.push_back((table.balls[static_cast<size_t>(i)].position - c).normalized());
    }
    // Where a level cue has no room along the candidate's line, only a tip high
    // enough lets a raised cue clear within the robot's elevation: the tip's range
    // starts there.
    const double max_height = std::min(kMaxTipOffset, settings.limits.max_topspin_fraction / 2.5);
    height_lo_ = -max_height;
    height_hi_ = max_height;
    const double nominal = cand.aim == AimMode::kHeading ? cand.aim_base : cand.estimate.aim.heading;
    const CueClearance& room = settings.limits.cue;
    if (std::isfinite(nominal) && CueMarginAt(table, cue_, nominal, 0, 0, room, *ctx.table) < 0) {
      constexpr int kSteps = 18;
      for (int i = 0; i <= kSteps; ++i) {
        const double h = -max_height + 2 * max_height * i / kSteps;
        if (CueElevation(table, cue_, nominal, h, room, *ctx.table)) {
          height_lo_ = h;
          break;
        }
      }
    }
  }

  SearchResult Run() {
    // Global stage over (speed, topspin, sidespin), a pot's cut at its prediction;
    // over the aim too where the aim is not predicted (safeties, routes off a
    // cushion), whose range is wide.
    std::vector<double> x = {0.5, 0.5, 0.5, 0.5};
    if (settings_.global_evaluations > 0 && !Stopped()) {
      const unsigned dims = cand_.aim == AimMode::kPredictedCut ? 3 : 4;
      nlopt::opt opt(nlopt::GN_DIRECT_L, dims);
      Configure(opt, settings_.global_evaluations);
      std::vector<double> xg(dims, 0.5);
      Optimize(opt, xg, "global");
      if (best_x_valid_) std::copy(best_x_.begin(), best_x_.begin() + dims, x.begin());
    }
    // Local stage over all four from the best point so far.
    if (settings_.local_evaluations > 0 && settings_.local != LocalAlgorithm::kNone && !Stopped()) {
      if (best_x_valid_) x = best_x_;
      const nlopt::algorithm alg = settings_.local == LocalAlgorithm::kSubplex ? nlopt::LN_SBPLX
                                   : settings_.local == LocalAlgorithm::kCobyla ? nlopt::LN_COBYLA
                                                                                 : nlopt::LN_BOBYQA;
      nlopt::opt opt(alg, 4);
      Configure(opt, settings_.local_evaluations);
      // First steps: a tenth of the speed and spin ranges, a quarter of the cut's.
      opt.set_initial_step(std::vector<double>{0.1, 0.1, 0.1, 0.25});
      Optimize(opt, x, "local");
    }
    result_.status = interrupted_ ? SearchStatus::kInterrupted
                     : failed_    ? SearchStatus::kFailed
                                  : SearchStatus::kConverged;
    return result_;
  }

 private:
  bool Stopped() { return interrupted_ || (interrupted_ = stop_.Due()); }

  void Configure(nlopt::opt& opt, int max_evaluations) {
    opt.set_lower_bounds(std::vector<double>(opt.get_dimension(), 0.0));
    opt.set_upper_bounds(std::vector<double>(opt.get_dimension(), 1.0));
    opt.set_max_objective(&Search::Trampoline, this);
    opt.set_maxeval(max_evaluations);
    opt.set_xtol_abs(settings_.x_tolerance);
    opt.set_ftol_abs(1e-6);
    const auto left = stop_.deadline - std::chrono::steady_clock::now();
    if (stop_.deadline != std::chrono::steady_clock::time_point::max()) {
      opt.set_maxtime(std::max(1e-4, std::chrono::duration<double>(left).count()));
    }
    opt_ = &opt;
  }

  void Optimize(nlopt::opt& opt, std::vector<double>& x, const char* stage) {
    double f = 0;
    std::string what = stage;
    try {
      const nlopt::result r = opt.optimize(x, f);
      what += " " + std::to_string(static_cast<int>(r));
      // NLopt keeps its own clock for the time left (Configure): it may see the
      // deadline pass a moment before Stopped() does.
      if (r == nlopt::MAXTIME_REACHED) interrupted_ = true;
    } catch (const nlopt::forced_stop&) {
      what += " stopped";
    } catch (const nlopt::roundoff_limited&) {
      what += " roundoff";  // converged as far as doubles allow: not a failure
    } catch (const std::exception& e) {
      failed_ = true;
      what += std::string(" error: ") + e.what();
    }
    opt_ = nullptr;
    if (!result_.detail.empty()) result_.detail += "; ";
    result_.detail += what;
    if (pending_) {  // an exception of ours, caught in the trampoline
      std::exception_ptr p = pending_;
      pending_ = nullptr;
      std::rethrow_exception(p);
    }
  }

  // NLopt 2.7's C++ API takes a function pointer and void* (no lambda): this
  // trampoline catches every exception, stops the optimiser and keeps the
  // exception for Optimize to rethrow once NLopt has unwound.
  static double Trampoline(unsigned n, const double* x, double* grad, void* data) {
    (void)grad;  // derivative-free algorithms only
    auto* self = static_cast<Search*>(data);
    try {
      return self->Objective(n, x);
    } catch (...) {
      self->pending_ = std::current_exception();
      if (self->opt_ != nullptr) self->opt_->force_stop();
      return -std::numeric_limits<double>::max();
    }
  }

  double Objective(unsigned n, const double* x) {
    if (Stopped()) {
      if (opt_ != nullptr) opt_->force_stop();
      return Unplayable();
    }
    ++result_.evaluations;
    std::array<double, 4> u = {x[0], x[1], x[2], n > 3 ? x[3] : 0.5};
    for (double& c : u) c = std::clamp(c, 0.0, 1.0);
    const auto stroke = StrokeFor(u);
    if (!stroke) return Keep(u, Unplayable());
    const physics::Shot& shot = stroke->shot;
    const Aim& aim = stroke->aim;
    ++result_.simulations;
    const ShotOutcome& out = sim_.Run(setup_, shot, {}, ShotSimulator::Mode::kDecide, interrupt_);
    if (out.status == physics::SimStatus::kInterrupted) {
      interrupted_ = true;
      if (opt_ != nullptr) opt_->force_stop();
      return Unplayable();
    }
    const bool pot = cand_.kind == ShotKind::kPot;
    const double p = pot ? PotProbability(out, *aim.heading, aim.cut, stroke->squirt) : 1.0;
    if (!out.success) return Keep(u, pot ? -1 + 0.5 * p : kFailedSafety);
    // The table the shot leaves, by the rules, and the ball on then.
    final_positions_.clear();
    for (const physics::BallState& b : sim_.final_balls()) final_positions_.push_back(b.r);
    const Leave leave = pot ? ScoreLeave(table_, on_, cand_.object, final_positions_, out.potted, p, after_ctx_,
                                         settings_, &scratch_, CueSpread(out))
                            : ScoreSafety(table_, on_, out.first_hit, final_positions_, out.potted, after_ctx_,
                                          settings_, &scratch_);
    const double score = leave.score - SpeedCost(shot.speed);
    std::optional<ShotCandidate>& best_of_class =
        result_.by_spin[static_cast<size_t>(SpinClassOf(shot, ctx_.table->ball_radius()))];
    if (!result_.best || score > result_.best->score || !best_of_class || score > best_of_class->score) {
      ShotCandidate c;
      c.cue = stroke->cue;
      c.shot = shot;
      c.cut = aim.cut;
      c.score = score;
      c.pot_estimate = p;
      c.position = leave.position;
      c.cue_end = final_positions_[static_cast<size_t>(cue_)];
      if (!best_of_class || score > best_of_class->score) best_of_class = c;
      if (!result_.best || score > result_.best->score) result_.best = std::move(c);
    }
    return Keep(u, score);
  }

  // The objective of a shot that cannot be played, below every simulated failure.
  double Unplayable() const { return cand_.kind == ShotKind::kPot ? kUnplayable : 1.5 * kFailedSafety; }

  struct Aim {
    std::optional<double> heading;
    double cut = 0;
  };

  struct Stroke {
    physics::CueStrike cue;
    physics::Shot shot;
    Aim aim;
    double squirt = 0;  ///< the strike's squirt, rad
  };

  // The stroke at the unit-cube point u: the cue's strength and tip offsets from
  // u[0..2], its heading from the aim (u[3]) with the squirt taken off, its
  // elevation the lowest that clears. nullopt when the robot cannot play it (no
  // aim, no room for the cue at any elevation, a cue speed beyond its range, a
  // miscue or a hop).
  std::optional<Stroke> StrokeFor(const std::array<double, 4>& u) const {
    const RobotLimits& lim = settings_.limits;
    const physics::CueParams& cue = ctx_.cue_params();
    const physics::BallParams& ball = sim_.params().ball;
    const double g = sim_.params().cloth.g;
    const double max_side = std::min(kMaxTipOffset, lim.max_sidespin_fraction / 2.5);
    Stroke k;
    k.cue.height = height_lo_ + u[1] * (height_hi_ - height_lo_);
    k.cue.side = (2 * u[2] - 1) * max_side;
    k.cue.speed = physics::CueSpeedFor(v_lo_ + u[0] * (v_hi_ - v_lo_), k.cue.side, k.cue.height, cue, ball);
    if (k.cue.speed < lim.min_cue_speed || k.cue.speed > lim.max_cue_speed) return std::nullopt;
    // Aim the ball for a level strike, then raise the cue if it must be, and aim
    // again with that strike's spins.
    for (int pass = 0; pass < 2; ++pass) {
      physics::StrikeResult res = physics::Strike(k.cue, cue, ball, g);
      k.aim = AimFor(res.shot, u[3]);
      if (!k.aim.heading) return std::nullopt;
      k.cue.heading = WrapAngle(*k.aim.heading - res.squirt);
      if (pass == 0) {
        const auto elevation = CueElevation(table_, cue_, k.cue.heading, k.cue.height, lim.cue, *ctx_.table);
        if (!elevation) return std::nullopt;
        if (*elevation == 0) {
          res = physics::Strike(k.cue, cue, ball, g);
          if (!Playable(res) || !AwayFromTouching(res.shot.heading)) return std::nullopt;
          k.shot = res.shot;
          k.squirt = res.squirt;
          return k;
        }
        k.cue.elevation = *elevation;
      }
    }
    if (CueMarginAt(table_, cue_, k.cue.heading, k.cue.elevation, k.cue.height, lim.cue, *ctx_.table) < 0) {
      return std::nullopt;
    }
    const physics::StrikeResult res = physics::Strike(k.cue, cue, ball, g);
    if (!Playable(res) || !AwayFromTouching(res.shot.heading)) return std::nullopt;
    k.shot = res.shot;
    k.squirt = res.squirt;
    return k;
  }

  // No push: the cue ball sets off away from (or along) every ball it touches.
  bool AwayFromTouching(double heading) const {
    const Vec2 u(std::cos(heading), std::sin(heading));
    return std::all_of(touching_.begin(), touching_.end(), [&](const Vec2& t) { return u.dot(t) <= 0; });
  }

  // A strike the robot can play and whose spins keep within the request's limits
  // (a raised cue spins the ball more per unit of speed than a level one).
  bool Playable(const physics::StrikeResult& res) const {
    return res.status == physics::StrikeStatus::kOk &&
           WithinLimits(res.shot, settings_.limits, ctx_.table->ball_radius());
  }

  // The heading (and cut on the aim ball) for the fourth search variable u in [0, 1].
  Aim AimFor(const physics::Shot& shot, double u) const {
    const double r = ctx_.table->ball_radius();
    const Vec2 cue = table_.balls[static_cast<size_t>(cue_)].position;
    const double range = cand_.aim_range > 0 ? cand_.aim_range : settings_.max_cut_correction;
    const double offset = (2 * u - 1) * range;
    Aim aim;
    if (cand_.aim == AimMode::kHeading) {
      aim.heading = WrapAngle(cand_.aim_base + offset);
      return aim;
    }
    const Vec2 ball = table_.balls[static_cast<size_t>(cand_.AimBall())].position;
    double base = cand_.aim_base;
    if (cand_.aim == AimMode::kPredictedCut) {
      const double direction = cand_.aim_direction.value_or(cand_.estimate.object_direction);
      const auto predicted = settings_.predict_throw
                                 ? PredictCut(cue, ball, direction, shot.speed, shot.topspin, shot.sidespin,
                                              sim_.params())
                                 : std::nullopt;
      base = predicted.value_or(cand_.aim_direction ? cand_.aim_base : cand_.estimate.aim.cut);
    }
    aim.cut = base + offset;
    aim.heading = HeadingForCut(cue, ball, aim.cut, r);
    return aim;
  }

  // A small cost of speed beyond what a shot needs: of two shots that score alike the
  // softer is kinder to the table and to the robot (points per m/s above 3 m/s).
  double SpeedCost(double speed) const { return settings_.speed_cost * std::max(0.0, speed - 3.0); }

  // One standard deviation of the cue ball's end along its last move
  // (SearchSettings::position_spread): the speed's noise, the cue's and the
  // ball's own, scales a path after contact by twice its fraction.
  Vec2 CueSpread(const ShotOutcome& out) const {
    if (!(settings_.position_spread > 0)) return Vec2::Zero();
    const NoiseModel& n = ctx_.execution;
    const double sigma = std::hypot(n.cue_speed_fraction, n.speed_fraction);
    return settings_.position_spread * 2 * sigma * out.cue_travel * out.cue_last_direction;
  }

  // The pot probability of this shot from its simulated object-ball line. The
  // model's uncertainty adds what the Monte Carlo samples: the stroke's squirt,
  // known to the noise's squirt fraction, a heading error of that fraction of it
  // (side costs what it costs); the throw of the potted ball's contact, known to the
  // throw fraction, that fraction of it over the line to the mouth.
  double PotProbability(const ShotOutcome& out, double heading, double cut, double squirt) const {
    if (!out.line.valid) return 0;
    const Vec2 cue = table_.balls[static_cast<size_t>(cue_)].position;
    const Vec2 object = table_.balls[static_cast<size_t>(cand_.object)].position;
    const PocketWindow w =
        ctx_.pockets->Window(cand_.pocket, out.line.direction, out.line.arrival_speed);
    if (cand_.route != PotRoute::kDirect) {
      // Another route's estimate (routes.h) is its chance with the line centred in
      // the window it planned for (at kTypicalArrivalSpeed), with its own spread at
      // the mouth. This stroke's chance scales it by how its simulated line falls in
      // the window at the speed it arrives (a fast ball's is narrower), with the
      // spread the squirt and the throw add to the route's.
      const double sigma =
          std::hypot(route_sigma_, SquirtSigma(squirt, cand_.estimate.heading_gain, ctx_.noise),
                     ThrowSigma(out.first_line.throw_angle, cand_.estimate.distance, ctx_.noise));
      return route_centred_ > 0 ? std::min(1.0, cand_.estimate.probability *
                                                    WindowProbability(out.line.offset, sigma, w) / route_centred_)
                                : 0;
    }
    const Vec2 u(std::cos(out.line.direction), std::sin(out.line.direction));
    const double distance =
        std::max(0.0, (ctx_.table->pocket(cand_.pocket).mouth_centre - object).dot(u));
    const double r = ctx_.table->ball_radius();
    const double sigma = std::hypot(
        LateralSigma(cue, object, heading, cut, distance, out.line.contact_speed, ctx_.sigma_of(cue_),
                     ctx_.sigma_of(cand_.object), ctx_.noise, *ctx_.throws, r),
        SquirtSigma(squirt, HeadingGain(cue, object, heading, cut, distance, r), ctx_.noise),
        ThrowSigma(out.first_line.throw_angle, distance, ctx_.noise));
    return WindowProbability(out.line.offset, sigma, w);
  }

  double Keep(const std::array<double, 4>& u, double f) {
    if (!best_x_valid_ || f > best_f_) {
      best_f_ = f;
      best_x_ = {u[0], u[1], u[2], u[3]};
      best_x_valid_ = true;
    }
    return f;
  }

  const TableState& table_;
  BallOn on_;
  const Candidate& cand_;
  const PotContext& ctx_;
  const SearchSettings& settings_;
  ShotSimulator& sim_;
  const StopControl& stop_;
  physics::Interrupt interrupt_;
  ShotSetup setup_;
  std::vector<Vec2> touching_;
  double height_lo_ = 0, height_hi_ = 0;  // the tip's range, fraction of R
  int cue_ = -1;
  double v_lo_ = 0, v_hi_ = 0;
  double route_sigma_ = 0, route_centred_ = 0;  // another route's (PotProbability)
  nlopt::opt* opt_ = nullptr;
  std::exception_ptr pending_;
  bool interrupted_ = false, failed_ = false;
  std::vector<double> best_x_ = std::vector<double>(4, 0.5);
  double best_f_ = 0;
  bool best_x_valid_ = false;
  SearchResult result_;
  PotContext after_ctx_;
  std::vector<Vec2> final_positions_;
  std::unique_ptr<LeaveScratch> own_;  // when the caller keeps none
  LeaveScratch& scratch_;              // the table each evaluation leaves
};

}  // namespace

const char* ToString(LocalAlgorithm a) {
  switch (a) {
    case LocalAlgorithm::kBobyqa: return "LN_BOBYQA";
    case LocalAlgorithm::kSubplex: return "LN_SBPLX";
    case LocalAlgorithm::kCobyla: return "LN_COBYLA";
    case LocalAlgorithm::kNone: return "none";
  }
  return "unknown";
}

bool WithinLimits(const physics::Shot& shot, const RobotLimits& limits, double radius) {
  const double rolling = shot.speed / radius;
  return std::abs(shot.topspin) <= limits.max_topspin_fraction * rolling &&
         std::abs(shot.sidespin) <= limits.max_sidespin_fraction * rolling && shot.speed >= limits.min_speed &&
         shot.speed <= limits.max_speed;
}

bool CueWithinLimits(const physics::CueStrike& cue, const RobotLimits& limits) {
  return cue.speed >= limits.min_cue_speed && cue.speed <= limits.max_cue_speed &&
         cue.elevation <= limits.cue.max_elevation;
}

SpinClass SpinClassOf(const physics::Shot& shot, double radius) {
  const double rolling = shot.speed / radius;
  const double f = rolling > 0 ? shot.topspin / rolling : 0.0;
  return f < -kSpinClass ? SpinClass::kScrew : f > kSpinClass ? SpinClass::kFollow : SpinClass::kStun;
}

bool StopControl::Due() const {
  if (cancelled != nullptr && cancelled->load(std::memory_order_relaxed)) return true;
  return deadline != std::chrono::steady_clock::time_point::max() &&
         std::chrono::steady_clock::now() >= deadline;
}

physics::Interrupt StopControl::AsInterrupt() const {
  physics::Interrupt i;
  i.deadline = deadline;
  i.cancelled = cancelled;
  return i;
}

std::pair<double, double> SpeedRange(const TableState& table, int cue, const Candidate& cand,
                                     const RobotLimits& limits, const physics::SimParams& params) {
  const double decel = params.cloth.mu_r * params.cloth.g;
  const Vec2 c = table.balls[static_cast<size_t>(cue)].position;
  const double travel = (cand.estimate.aim.ghost - c).norm();
  // The object ball leaves sliding and rolls on at 5/7 of its speed; it should
  // reach the mouth at a crawl (0.05 m/s) at least. It gets about 0.9 cos(cut) of
  // the cue ball's speed at contact.
  const double object_start =
      std::sqrt(0.05 * 0.05 + 2 * decel * cand.estimate.distance) / (5.0 / 7.0);
  const double contact = object_start / (0.9 * std::max(std::cos(cand.estimate.aim.cut), 0.2));
  const double lo = std::clamp(0.9 * std::sqrt(contact * contact + 2 * decel * travel),
                               limits.min_speed, limits.max_speed);
  const double hi = std::clamp(lo + 3.0, lo, limits.max_speed);
  return {lo, hi};
}

std::optional<double> PredictCut(const Vec2& cue, const Vec2& object, double object_direction,
                                 double speed, double topspin, double sidespin,
                                 const physics::SimParams& params) {
  const double r = params.ball.radius;
  const auto aim = AimAlong(cue, object, object_direction, r);
  if (!aim) return std::nullopt;
  double cut = aim->cut;
  const double d = (object - cue).norm();
  const physics::Shot shot{speed, 0, topspin, sidespin};
  for (int iter = 0; iter < 3; ++iter) {
    const auto h = HeadingForCut(cue, object, cut, r);
    if (!h) return std::nullopt;
    const auto dir = ObjectDirection(cue, object, *h, cut, shot, params);
    if (!dir) return std::nullopt;
    const double err = WrapAngle(object_direction - *dir);
    // d(direction)/d(cut) = 1 + dh/dc, dh/dc = -2R cos c / (d cos(phi0 - h)).
    const double phi = WrapAngle(Direction(object - cue) - *h);
    const double slope = 1 - 2 * r * std::cos(cut) / (d * std::max(std::cos(phi), 1e-3));
    cut += err / std::max(slope, 0.1);
    if (std::abs(err) < 1e-7) break;
  }
  if (!(std::abs(cut) < physics::kPi / 2)) return std::nullopt;
  return cut;
}

std::optional<physics::Shot> RollingPotShot(const Vec2& cue, const Vec2& object,
                                            const PotEstimate& estimate,
                                            const physics::SimParams& params) {
  const double r = params.ball.radius;
  const double decel = params.cloth.mu_r * params.cloth.g;
  const double contact = TypicalContactSpeed(estimate.distance, estimate.aim.cut);
  const double travel = (estimate.aim.ghost - cue).norm();
  physics::Shot shot;
  shot.speed = std::sqrt(contact * contact + 2 * decel * travel);
  shot.topspin = shot.speed / r;
  const auto cut = PredictCut(cue, object, estimate.object_direction, shot.speed, shot.topspin, 0, params);
  if (!cut) return std::nullopt;
  const auto heading = HeadingForCut(cue, object, *cut, r);
  if (!heading) return std::nullopt;
  shot.heading = *heading;
  return shot;
}

double ShotScore(double pot_probability, int value, const PositionValue& position,
                 bool position_play) {
  return pot_probability * (value + (position_play ? position.expected_points : 0.0));
}

namespace {
// The table a fair shot leaves, by the rules, built in `buf`.
LeaveScratch& TableLeft(const TableState& table, BallOn on, std::span<const Vec2> finals,
                        std::span<const int> potted, const PotContext& after_ctx, LeaveScratch& buf) {
  ApplyShotInto(table, on, finals, potted, false, *after_ctx.table, &buf.after, &buf.origin);
  return buf;
}

// The position at the cue ball's nominal end (`at_end`) averaged with two more
// along its spread (ScoreLeave); `after` is restored before it returns. The next
// ball keeps the nominal end's: the one the stroke plays for.
PositionValue MeanOverSpread(TableState& after, int cue, BallOn next_on, const Vec2& spread,
                             const PositionValue& at_end, const PotContext& after_ctx,
                             const PositionOptions& options, PocketLineCache& lines) {
  // The sides are added as v / 6, not (1 / 6) v: the last bit differs, and this is
  // the form whose matches docs/whole-frame-planner.md records, stroke for stroke.
  constexpr double kCentreWeight = 2.0 / 3, kSideShare = 6;
  const physics::TableModel& model = *after_ctx.table;
  const double d = model.cushion_contact_distance();
  Vec2& ball = after.balls[static_cast<size_t>(cue)].position;
  const Vec2 end = ball;
  PositionValue mean = at_end;
  mean.value *= kCentreWeight;
  mean.expected_points *= kCentreWeight;
  for (const double s : {-std::sqrt(3.0), std::sqrt(3.0)}) {
    const Vec2 p = end + s * spread;
    ball = Vec2(std::clamp(p.x(), d, model.spec().width - d), std::clamp(p.y(), d, model.spec().length - d));
    const PositionValue v = EvaluatePosition(after, next_on, after_ctx, options, &lines);
    mean.value += v.value / kSideShare;
    mean.expected_points += v.expected_points / kSideShare;
  }
  ball = end;
  return mean;
}
}  // namespace

Leave ScoreLeave(const TableState& table, BallOn on, int object, std::span<const Vec2> finals,
                 std::span<const int> potted, double pot_probability, const PotContext& after_ctx,
                 const SearchSettings& settings, LeaveScratch* scratch, const Vec2& cue_spread) {
  if (scratch == nullptr) {  // buffers of its own, cleared only here: 25 kB, most of it the line cache
    LeaveScratch own;
    return ScoreLeave(table, on, object, finals, potted, pot_probability, after_ctx, settings, &own, cue_spread);
  }
  LeaveScratch& buf = TableLeft(table, on, finals, potted, after_ctx, *scratch);
  TableState& after = buf.after;
  const std::vector<int>& origin = buf.origin;
  const BallKind object_kind = table.balls[static_cast<size_t>(object)].kind;
  Leave leave;
  if (const auto next_on = NextBallOn(on, object_kind, after)) {
    leave.position = EvaluatePosition(after, *next_on, after_ctx, settings.position, &buf.lines);
    const int cue = after.cue_index();
    if (cue >= 0 && settings.position_play && cue_spread.squaredNorm() > 0) {
      leave.position = MeanOverSpread(after, cue, *next_on, cue_spread, leave.position, after_ctx, settings.position,
                                      buf.lines);
    }
  }
  if (leave.position.next_ball >= 0) leave.next_ball = origin[static_cast<size_t>(leave.position.next_ball)];
  leave.score = ShotScore(pot_probability, Value(object_kind), leave.position, settings.position_play);
  if (settings.position_play && after_ctx.layout != nullptr) {
    // What the shot did to the rest of the table: colours' places, reds tied up.
    LayoutOptions layout;
    layout.pockets = after_ctx.pockets;
    leave.layout = LayoutChange(table, *after_ctx.layout, after, *after_ctx.table, layout);
    leave.score += pot_probability * leave.layout;
  }
  return leave;
}

Outlook OpponentOutlook(const TableState& after, BallOn on, const PotContext& after_ctx,
                        const SearchSettings& settings, TableState* placed, PocketLineCache* lines) {
  OutlookOptions options;
  options.position = settings.position;
  return EvaluateOutlook(after, on, after_ctx, options, placed, lines);
}

Leave ScoreSafety(const TableState& table, BallOn on, int first_hit, std::span<const Vec2> finals,
                  std::span<const int> potted, const PotContext& after_ctx, const SearchSettings& settings,
                  LeaveScratch* scratch) {
  if (scratch == nullptr) {  // as ScoreLeave
    LeaveScratch own;
    return ScoreSafety(table, on, first_hit, finals, potted, after_ctx, settings, &own);
  }
  LeaveScratch& work = *scratch;
  const LeaveScratch& buf = TableLeft(table, on, finals, potted, after_ctx, work);
  const TableState& after = buf.after;
  const std::vector<int>& origin = buf.origin;
  Leave leave;
  const std::optional<BallKind> nominated =
      first_hit >= 0 ? std::optional<BallKind>(table.balls[static_cast<size_t>(first_hit)].kind) : std::nullopt;
  const ShotJudgement j = JudgeShot(table, on, nominated, first_hit, potted);
  if (j.legal_pots > 0 && j.potted_kind) {
    // A ball on dropped after all: the visit goes on, scored as a pot.
    if (const auto next_on = NextBallOn(on, *j.potted_kind, after)) {
      leave.position = EvaluatePosition(after, *next_on, after_ctx, settings.position, &work.lines);
    }
    leave.score = j.points + (settings.position_play ? leave.position.expected_points : 0.0);
  } else if (const auto opponent_on = OpeningBallOn(after)) {
    // The opponent plays the table left: what they can expect, in the same points,
    // less what a snooker makes them give away.
    const Outlook outlook = OpponentOutlook(after, *opponent_on, after_ctx, settings, &work.placed, &work.lines);
    leave.position.value = outlook.position_value;
    leave.position.expected_points = outlook.expected_points;
    leave.position.next_ball = outlook.pot_ball;
    leave.opponent = outlook;
    leave.score = -(outlook.expected_points - outlook.expected_penalty);
  }
  if (leave.position.next_ball >= 0) leave.next_ball = origin[static_cast<size_t>(leave.position.next_ball)];
  return leave;
}

SearchResult SearchCandidate(const TableState& table, BallOn on, const Candidate& cand,
                             const PotContext& ctx, const SearchSettings& settings,
                             ShotSimulator& sim, const StopControl& stop, LeaveScratch* scratch) {
  Search search(table, on, cand, ctx, settings, sim, stop, scratch);
  return search.Run();
}

}  // namespace snooker::planner
