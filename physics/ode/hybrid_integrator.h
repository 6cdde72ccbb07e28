// The hybrid impulse integrator: one engine for every impulse-based impact model
// (physics/impact/: ball-ball, ball-cushion, and any later one). Internal to physics/.
//
// The split (after Drake's witness functions and Boost.Odeint's stepper / observer
// split): a model supplies the continuous part - its state (with the normal impulse
// P_I as one component), the derivative in its current mode, the slips of its
// friction contacts - and the discrete part - witnesses (functions whose zeros are
// events, each with its action) and the reset or stick law at each. The integrator
// owns everything numerical: the clock, the stepper, one event locator on the dense
// output, the caps and the counters. A model is a plain class checked by the
// HybridImpulseModel concept; every call is resolved at compile time (no virtual call,
// no allocation, no exception; every loop capped).
//
// Why the integrator looks like this. The right-hand side of an impulse ODE with
// Coulomb friction is smooth only between mode switches (a slip reaching zero, a
// stuck contact leaving its friction cone, ...). A high-order method stepping across
// a switch loses its order and its error control grinds the step down. So:
//  * The mode is held during a step. Dormand-Prince 5(4) or, where it pays at tight
//    tolerances, 8(5,3) (RkMethod; FSAL, PI control capped by Gustafsson's predictive
//    controller, max-norm error weighted by the model); the first step is sized from
//    the impact (an estimate of the solution's second derivative, Hairer, Norsett &
//    Wanner II.4).
//  * Witnesses are checked at the end of every step; the first zero crossing is
//    located (Illinois) on the step's dense output - a continuous extension as
//    accurate as the step (4th order; 7th for 8(5,3), built with 3 more right-hand
//    sides) - and the step ends there: no refinement with real steps. A kRecord witness (the end of
//    compression) changes no dynamics: it is recorded and the search goes on.
//  * A sliding slip heading for zero along a fixed ray has its direction held over the
//    step (Freeze): the right-hand side stays smooth through the zero, which is then a
//    witness like the others. A slip that turns as it shrinks limits the step to a
//    fraction of the way to its predicted zero: near the zero the direction's
//    derivatives blow up like inverse powers of the distance to it, so the error
//    depends on that fraction, and the step controller adjusts the fraction instead of
//    the step's length. Once the slip is small (and where a landing fails close to
//    zero) the clock becomes tau = -ln|u| (a Sundman transformation, dP_I/dtau =
//    |u| / (-d|u|/dP_I)), in which the solution is smooth, until |u| = slip_zero.
//    Steps whose stages see a slip reversed, or a frozen slip leave its ray, are
//    rejected.
//  * At zero slip the model's stick law decides (Settle): stick while the friction
//    that holds the slip at zero lies in the cone, otherwise slide away from zero.
//  * Where a small sliding slip makes the problem stiff (its direction relaxes at a
//    rate ~ 1/|u|) and the model supplies a Jacobian, steps are taken with the
//    L-stable Rosenbrock 2(3) method instead (dense output: the cubic Hermite).
// References: Hairer, Norsett & Wanner, Solving ODEs I (II.4-II.6, IV.2); Shampine &
// Reichelt (1997) for Rosenbrock 2(3).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "physics/core/types.h"
#include "physics/ode/ode_dop853.h"
#include "physics/ode/ode_dp54.h"
#include "physics/ode/ode_rosenbrock23.h"

namespace snooker::physics::ode {

/// What a witness's zero does (its value goes from > 0 to <= 0).
enum class WitnessAction : std::uint8_t {
  /// Observed only (the end of compression): recorded where it crosses, the step and
  /// the search for other witnesses go on.
  kRecord,
  /// A mode switch: the step ends on the zero, the model's reset law and stick law
  /// apply there.
  kSwitch,
  /// The end of the impact. Fires also when the witness is already <= 0 where it
  /// becomes active (restitution that ends where compression ends, e = 0).
  kTerminal,
};

/// Numbers a model fixes for its integrator.
struct HybridSettings {
  /// Local error per step, relative to the model's error weights. Dimensionless.
  double tolerance = 1e-10;
  /// Cap on steps tried (accepted, rejected, or taken to locate nothing else).
  std::int32_t max_steps = 100'000;
  /// A slip at or below this is zero. m/s.
  double slip_zero = 0;
  /// Speed scale of the impact (largest |v|, R|w| of the input). m/s.
  double speed_scale = 1;
  /// Impulse scale of the impact: the frictionless P_I at its end (friction makes
  /// it longer). Steps in P_I are at most twice this. N s.
  double impulse_scale = 1;
  /// Only slips below this are followed in tau = -ln|u|. m/s.
  double log_clock_slip = std::numeric_limits<double>::infinity();
};

/// Work done by the integrator.
struct HybridWork {
  std::int32_t steps = 0;           ///< accepted steps
  std::int32_t rejected_steps = 0;  ///< rejected steps
  std::int32_t rhs_evals = 0;       ///< right-hand-side evaluations by the integrator
  std::int32_t events = 0;          ///< located witnesses and slips reaching zero
};

enum class HybridStatus : std::uint8_t { kFinished, kStepLimit };

/// The explicit Runge-Kutta pair of the non-stiff steps.
enum class RkMethod : std::uint8_t {
  kDp54,    ///< Dormand-Prince 5(4), 6 evaluations a step (FSAL), 4th-order dense output
  kDop853,  ///< Dormand-Prince 8(5,3), 12 a step, 7th-order dense output (3 more)
};

/// The model an impulse ODE supplies (see the top of this file). State is a
/// fixed-size Eigen column vector whose component kImpulse is P_I; Aux holds what a
/// derivative evaluation computes besides the derivative (forces), for witnesses and
/// laws.
template <class M>
concept HybridImpulseModel =
    requires(M& m, const M& cm, typename M::State& x, const typename M::State& cx,
             typename M::Aux& aux, const typename M::Aux& caux, int i, const Vec2& d,
             const std::array<bool, M::kContacts>& mask) {
      { M::kContacts } -> std::convertible_to<int>;
      { M::kWitnesses } -> std::convertible_to<int>;
      { M::kImpulse } -> std::convertible_to<int>;
      { M::kStiffSteps } -> std::convertible_to<bool>;
      { M::kWork } -> std::convertible_to<int>;
      { cm.settings() } -> std::same_as<const HybridSettings&>;
      { cm.error_weights() } -> std::same_as<const typename M::State&>;
      // Continuous part, in the current mode, per unit P_I (dx[kImpulse] = 1).
      { cm.Derivative(cx, &x, &aux) } -> std::same_as<void>;
      { cm.Auxiliary(cx, &aux) } -> std::same_as<void>;
      // Contacts: slip (linear in the state), whether its friction acts as sliding
      // friction, the direction it slides along (used for friction), whether it was
      // just sent away from zero slip, and whether it may be followed to a zero in tau.
      { cm.Slip(i, cx) } -> std::same_as<Vec2>;
      { cm.SlidingActive(i, caux) } -> std::same_as<bool>;
      { cm.SlideDirection(i, cx, caux) } -> std::same_as<Vec2>;
      { cm.Leaving(i, cx) } -> std::same_as<bool>;
      { cm.CanFollow(i, cx, caux) } -> std::same_as<bool>;
      { m.Freeze(i, d) } -> std::same_as<void>;
      { m.Unfreeze() } -> std::same_as<void>;
      { cm.Frozen(i) } -> std::same_as<bool>;
      { cm.FrozenDirection(i) } -> std::same_as<Vec2>;
      // Discrete part.
      { m.Start(&x) } -> std::same_as<void>;
      { m.BeforeStep(cx, cx, caux, 1.0) } -> std::same_as<bool>;
      { cm.WitnessActive(i) } -> std::same_as<bool>;
      { cm.Action(i) } -> std::same_as<WitnessAction>;
      { cm.WitnessNeedsAux(i) } -> std::same_as<bool>;
      { cm.Witness(i, cx, caux) } -> std::same_as<double>;
      { m.OnRecord(i, cx) } -> std::same_as<void>;
      { m.OnSwitch(i, &x) } -> std::same_as<void>;
      { m.Settle(&x, mask) } -> std::same_as<void>;
      // Stiff sliding (kStiffSteps models): the rate at which contact i's slip
      // direction relaxes times |u| (per unit P_I), and df/dx at x.
      { cm.DirectionStiffness(i, caux) } -> std::same_as<double>;
    };

template <HybridImpulseModel Model, RkMethod kMethod = RkMethod::kDp54>
class HybridIntegrator {
 public:
  using State = typename Model::State;
  using Aux = typename Model::Aux;
  static constexpr int kN = State::RowsAtCompileTime;
  static constexpr int kContacts = Model::kContacts;
  static constexpr int kP = Model::kImpulse;
  // Witness indices: the model's, then the integrator's own.
  static constexpr int kSlipZero = Model::kWitnesses;       // followed slip reaches zero
  static constexpr int kRayZero = Model::kWitnesses + 1;    // + c: frozen slip reaches zero
  static constexpr int kWitnessCount = Model::kWitnesses + 1 + kContacts;

  explicit HybridIntegrator(Model& model)
      : m_(model), s_(model.settings()), control_(kErrorOrder) {
    // A frozen slip may leave its ray by this much: then the held direction is wrong
    // by at most this over |u|, and the slip still lands below slip_zero. The floor is
    // the rounding of slips of size speed_scale.
    ray_tol_ = std::max(1e-3 * s_.slip_zero, 16 * kEps * s_.speed_scale);
    // Events are located to this fraction of a step: a location error dt moves the
    // state by about h |y'| dt, within the step's own error.
    event_resolution_ = std::max(4 * kEps, 1e-3 * s_.tolerance);
  }

  /// Integrates from *x until the impact ends or the step cap is reached: each pass
  /// plans a step (PlanStep), takes it (TakeStep), discards it if it cannot be used
  /// (Discarded), rejects it if it errs too much or reverses a slip (Rejected),
  /// otherwise accepts it (Accept, which locates and applies the witnesses) and
  /// settles the slips it brought to zero (SettleSlipsAtZero).
  HybridStatus Run(State* x);
  const HybridWork& work() const { return work_; }

 private:
  static constexpr double kEps = std::numeric_limits<double>::epsilon();
  static constexpr bool kHigh = kMethod == RkMethod::kDop853;
  // The local error is O(h^kErrorOrder) (the order of the embedded estimate + 1).
  static constexpr int kErrorOrder = kHigh ? 8 : 5;
  // A shrinking slip whose predicted zero is closer than this many steps is followed
  // in tau: that close, its direction varies too fast for steps in P_I.
  static constexpr double kLogClockReach = 8.0;
  // Largest step in tau (the slip shrinks by at most e^20 per step).
  static constexpr double kMaxLogStep = 20.0;
  // A slip whose rate makes at most this sine with it heads for zero along a ray.
  static constexpr double kRayTurn = 1e-9;
  // A step towards a slip's predicted zero covers at most this fraction of the way
  // (land_ratio_, adjusted by the step controller, starts here): a stage exactly on
  // the zero could see the slip reversed by rounding; the residual is settled as zero.
  static constexpr double kLandRatio = 1 - 1e-12;
  // A followed slip that grows in a step while under this many slip_zero has reached
  // the noise of the integration: it is taken as zero.
  static constexpr double kSlipNoiseFloor = 1e3;
  // Iterations allowed to locate one witness on the dense output.
  static constexpr int kMaxLocateIterations = 100;
  // Stiff threshold: h times a slip direction's relaxation rate above kStiffEnter
  // (Dormand-Prince 5(4) is stable to about 3.3 along the negative axis, 8(5,3) to
  // about 6) switches to Rosenbrock 2(3) until it falls below kStiffLeave.
  static constexpr double kStiffEnter = kHigh ? 5.5 : 3.0;
  static constexpr double kStiffLeave = kHigh ? 2.0 : 1.0;
  // Loop passes allowed per step tried (a pass may change the clock or the plan
  // without taking a step).
  static constexpr int kPassesPerStep = 4;
  // The first step is at most this many impulse scales (a little more than a
  // frictionless impact: one step may then cover the whole impact), later steps at
  // most kMaxStep.
  static constexpr double kFirstStepCap = 1.25;
  static constexpr double kMaxStep = 2.0;
  static constexpr int kNoContact = -1;

  using RkResult = std::conditional_t<kHigh, Dop853Result<State>, Dp54Result<State>>;
  using RkDense = std::conditional_t<kHigh, Dop853Dense<State>, Dp54Dense<State>>;
  struct StepOut {
    RkResult step;  // the Runge-Kutta step (y1 and the end derivative also for Rosenbrock)
    Ros23Result<State> ros;
    Aux aux1;  // at y1
    bool hermite = false;  // a Rosenbrock step: its dense output is the cubic Hermite
    RkDense dense;  // built on first use (Dense)
    bool dense_ready = false;
    const State& y1() const { return hermite ? ros.y1 : step.y1; }
    const State& k_end() const {  // derivative at y1
      if (hermite) return ros.k7;
      if constexpr (kHigh) {
        return step.k13;
      } else {
        return step.k7;
      }
    }
    bool valid() const { return hermite ? ros.valid : step.valid; }
    // DOP853's dense output met an undefined derivative: the cubic Hermite instead.
    bool hermite_fallback = false;
    std::array<double, kContacts> min_dot;   // min over stages of u . (start direction)
    std::array<double, kContacts> max_perp;  // max over stages of |d x u|, frozen slips
  };

  // The plan of one step (PlanStep).
  struct StepPlan {
    double h = 0;              // length, in P_I or (log_clock) in tau = -ln|u|
    bool log_clock = false;    // taken in tau (clock_ != kNoContact when planned)
    int landing = kNoContact;  // the turning slip whose predicted zero limits h
    std::array<bool, kContacts> freeze{};  // slips whose direction is held over the step
    bool frozen = false;                   // any of them
  };

  // ---- the phases of Run ----
  // Each is called from one place in Run and inlined there (always_inline): the code
  // of one function, as fast as the loop written out, with a name per phase. Left to
  // the compiler none is inlined, and a cushion impact takes 2.6 % more instructions.
  // Starts from *x: the model's start, the derivative there, the first step.
  [[gnu::always_inline]] inline void Begin(State* x);
  // Plans the next step: its clock and length, the slips held along their rays, the
  // stiff or explicit method. False when it switched to the tau clock instead (no
  // step to take: plan again).
  [[gnu::always_inline]] inline bool PlanStep(StepPlan* plan);
  // Limits plan->h to the predicted zero of a slip that turns as it shrinks and marks
  // the slips that head for zero along a ray (to be frozen). Returns the slip to
  // follow in tau, or kNoContact.
  [[gnu::always_inline]] inline int AimAtSlipZeros(StepPlan* plan) const;
  // True when step s cannot be used: a frozen slip left its ray, or a stage met an
  // undefined derivative (then the tau clock is left or the step shortened).
  [[gnu::always_inline]] inline bool Discarded(const StepPlan& plan, const StepOut& s);
  // True when step s, of weighted error err, is rejected (error above 1, or a slip
  // reversed within it); sets the next attempt's step or clock.
  [[gnu::always_inline]] inline bool Rejected(const StepPlan& plan, const StepOut& s,
                                              double err);
  // Accepts step s: locates the first witness on its dense output, advances to it or
  // to the step's end, sizes the next step and applies the event. True when the
  // impact is over.
  [[gnu::always_inline]] inline bool Accept(const StepPlan& plan, StepOut& s, double err);
  // Settles the sliding slips (other than the one followed in tau) that are at zero.
  [[gnu::always_inline]] inline void SettleSlipsAtZero();
  void Unfreeze(const StepPlan& plan) {  // after a frozen step: the free directions back
    if (!plan.frozen) return;
    m_.Unfreeze();
    Refresh();
  }

  // ---- right-hand side in the current clock ----
  bool F(const State& y, State* dy, Aux* aux) {
    ++work_.rhs_evals;
    m_.Derivative(y, dy, aux);
    if (clock_ == kNoContact) return true;
    const Vec2 u = m_.Slip(clock_, y);
    const double s = u.norm();
    const double rate = m_.SlideDirection(clock_, y, *aux).dot(m_.Slip(clock_, *dy));
    if (!(s > 0 && rate < 0)) return false;  // |u| not decreasing: tau is no clock here
    *dy *= s / -rate;
    return true;
  }
  void Refresh() {  // the derivative at y_ after a mode or clock change
    F(y_, &k1_, &a1_);
    jac_ok_ = false;
    control_.Reset();
  }
  void SetClock(int contact) {
    clock_ = contact;
    Refresh();
  }
  double ErrorNorm(const State& err) const {
    return err.cwiseProduct(m_.error_weights()).cwiseAbs().maxCoeff() / s_.tolerance;
  }
  double StepError(const StepOut& s) const {
    if (s.hermite) return ErrorNorm(s.ros.err);
    if constexpr (kHigh) {
      return ErrorNorm853(ErrorNorm(s.step.err5), ErrorNorm(s.step.err3));
    } else {
      return ErrorNorm(s.step.err);
    }
  }
  double FirstStep();
  // The first step in tau = -ln|u|: the shrink of |u| that the last steps towards
  // the zero achieved in P_I (at most a halving: 0.69).
  double FirstLogStep() const { return std::clamp(-std::log1p(-land_ratio_), 0.05, 0.69); }
  void TakeStep(double h, StepOut* out);
  bool Stiff(double h, double threshold, int except) const;
  const typename Model::Jacobian& Jacobian();

  // ---- witnesses ----
  bool Active(int w) const {
    if (w < Model::kWitnesses) return m_.WitnessActive(w);
    if (w == kSlipZero) return clock_ != kNoContact;
    return m_.Frozen(w - kRayZero);
  }
  double WitnessAt(int w, const State& y, const Aux& aux) const {
    if (w < Model::kWitnesses) return m_.Witness(w, y, aux);
    if (w == kSlipZero) return m_.Slip(clock_, y).norm() - s_.slip_zero;
    const int c = w - kRayZero;
    return m_.Slip(c, y).dot(m_.FrozenDirection(c));
  }
  bool NeedsAux(int w) const { return w < Model::kWitnesses && m_.WitnessNeedsAux(w); }
  WitnessAction ActionOf(int w) const {
    return w < Model::kWitnesses ? m_.Action(w) : WitnessAction::kSwitch;
  }
  State Dense(StepOut& s, double h, double t) {
    if (s.hermite) return HermiteAt(y_, k1_, s.ros.y1, s.ros.k7, h, t);
    if (!s.dense_ready) {
      if constexpr (kHigh) {
        // Three more evaluations, in the step's mode and clock.
        Aux aux{};
        s.dense = RkDense(y_, s.step, [&](const State& y, State* dy) { return F(y, dy, &aux); });
        if (!s.dense.valid()) s.hermite_fallback = true;
      } else {
        s.dense = RkDense(y_, s.step);
      }
      s.dense_ready = true;
    }
    if (s.hermite_fallback) return HermiteAt(y_, k1_, s.step.y1, s.k_end(), h, t);
    return s.dense.At(y_, t);
  }
  double WitnessOnStep(int w, StepOut& s, double h, double t) {
    const State y = Dense(s, h, t);
    Aux aux{};
    if (NeedsAux(w)) m_.Auxiliary(y, &aux);
    return WitnessAt(w, y, aux);
  }
  // The first witness to fire in (t0, 1] of step s (of length h), located on the
  // dense output; kRecord witnesses are recorded on the way. Returns it and its
  // fraction *t, or -1.
  int LocateEvent(StepOut& s, double h, double* t);
  bool ApplyEvent(int w);  // true when the impact is over
  void SettleAt(int c) {
    std::array<bool, kContacts> at_zero{};
    if (c != kNoContact) at_zero[c] = true;
    m_.Settle(&y_, at_zero);
  }

  Model& m_;
  const HybridSettings& s_;
  HybridWork work_;
  State y_, k1_;
  Aux a1_{};
  PiStepControl control_;
  typename Model::Jacobian jac_;
  bool jac_ok_ = false;
  bool stiff_ = false;
  double ray_tol_ = 0, event_resolution_ = 0;
  std::int32_t attempts_ = 0;
  int clock_ = kNoContact;
  // Contacts whose tau clock failed since the last step in P_I: each is followed in tau
  // again only after that step. (One remembered contact let two slips hand the clock
  // back and forth without a step: 100 000 discarded steps to the cap.)
  std::array<bool, kContacts> no_follow_{};
  int no_freeze_ = kNoContact;  // a contact that just left its ray in a frozen step
  // A step that heads for a slip's predicted zero ends at this fraction of the way.
  double land_ratio_ = kLandRatio;
  double h_impulse_ = 0;  // next step in P_I
  double h_log_ = 1.0;    // next step in tau
};

// ---------------------------------------------------------------------------

template <HybridImpulseModel Model, RkMethod kMethod>
double HybridIntegrator<Model, kMethod>::FirstStep() {
  // The first step sized from the impact (after Hairer, Norsett & Wanner II.4, made
  // consistent in the units of P_I): the change of the derivative over a trial step
  // h0 gives the scale L = |y'| / |y''| on which the solution bends, and a step of
  // length h errs by about |y'| L (h / L)^q (weighted; q = kErrorOrder), so
  // h = L (tol / (|y'| L))^(1/q). W and P_I are left out: W' is the normal speed, a
  // linear function of the velocities, and P_I' = 1. A derivative that does not change
  // (friction directions fixed) is integrated exactly: then the step is the whole
  // impulse scale.
  const State& w = m_.error_weights();
  const double h0 = 1e-2 * s_.impulse_scale;
  State k2;
  Aux aux{};
  F(y_ + h0 * k1_, &k2, &aux);
  double d1 = 0, d2 = 0;
  for (int i = 0; i < kN; ++i) {
    if (i == Model::kWork || i == kP) continue;
    d1 = std::max(d1, std::abs(k1_[i] * w[i]));
    d2 = std::max(d2, std::abs((k2[i] - k1_[i]) * w[i]) / h0);
  }
  // The estimate ignores higher derivatives (a slip direction turning faster and
  // faster): it is halved, and capped at about the impulse of the whole impact.
  const double cap = kFirstStepCap * s_.impulse_scale;
  if (!(d2 > 0 && d1 > 0)) return cap;
  const double scale = d1 / d2;
  const double h = 0.5 * scale * std::pow(s_.tolerance / (d1 * scale), 1.0 / kErrorOrder);
  return std::isfinite(h) ? std::clamp(h, 1e-6 * s_.impulse_scale, cap) : 0.05 * s_.impulse_scale;
}

template <HybridImpulseModel Model, RkMethod kMethod>
void HybridIntegrator<Model, kMethod>::TakeStep(double h, StepOut* out) {
  ++attempts_;
  std::array<Vec2, kContacts> u0dir;
  std::array<bool, kContacts> watch;
  for (int c = 0; c < kContacts; ++c) {
    // A slip just sent away from zero is not watched: its start direction is only the
    // ray it leaves along, and it may grow from zero rate (at a cone exit).
    watch[c] = m_.SlidingActive(c, a1_) && c != clock_ && !m_.Leaving(c, y_);
    u0dir[c] = m_.SlideDirection(c, y_, a1_);
    out->min_dot[c] = 1;
    out->max_perp[c] = 0;
  }
  Aux last{};
  auto rhs = [&](const State& y, State* dy) { return F(y, dy, &last); };
  auto observe = [&](const State& y) {
    for (int c = 0; c < kContacts; ++c) {
      if (!watch[c]) continue;
      const Vec2 u = m_.Slip(c, y);
      out->min_dot[c] = std::min(out->min_dot[c], u.dot(u0dir[c]));
      if (m_.Frozen(c)) {
        const double perp = std::abs(u0dir[c].x() * u.y() - u0dir[c].y() * u.x());
        out->max_perp[c] = std::max(out->max_perp[c], perp);
      }
    }
  };
  out->hermite = false;
  out->hermite_fallback = false;
  out->dense_ready = false;
  if constexpr (Model::kStiffSteps) {
    if (stiff_) {
      Ros23Step(y_, k1_, Jacobian(), h, rhs, observe, &out->ros);
      out->hermite = true;
      out->aux1 = last;
      return;
    }
  }
  if constexpr (kHigh) {
    Dop853Step(y_, k1_, h, rhs, observe, &out->step);
  } else {
    Dp54Step(y_, k1_, h, rhs, observe, &out->step);
  }
  out->aux1 = last;  // the last evaluation is at y1
}

template <HybridImpulseModel Model, RkMethod kMethod>
bool HybridIntegrator<Model, kMethod>::Stiff(double h, double threshold, int except) const {
  if constexpr (!Model::kStiffSteps) {
    return false;
  } else {
    if (clock_ != kNoContact) return false;
    for (int c = 0; c < kContacts; ++c) {
      if (!m_.SlidingActive(c, a1_) || m_.Frozen(c) || c == except) continue;
      const double r = std::max(m_.Slip(c, y_).norm(), s_.slip_zero);
      if (h * m_.DirectionStiffness(c, a1_) / r > threshold) return true;
    }
    return false;
  }
}

template <HybridImpulseModel Model, RkMethod kMethod>
const typename Model::Jacobian& HybridIntegrator<Model, kMethod>::Jacobian() {
  if constexpr (Model::kStiffSteps) {
    if (!jac_ok_) {
      work_.rhs_evals += m_.JacobianAt(y_, a1_, &jac_);
      jac_ok_ = true;
    }
  }
  return jac_;
}

template <HybridImpulseModel Model, RkMethod kMethod>
int HybridIntegrator<Model, kMethod>::LocateEvent(StepOut& s, double h, double* t_event) {
  double t0 = 0;
  State y0 = y_;
  Aux a0 = a1_;
  std::array<bool, kWitnessCount> armed{};  // active and > 0 at the step start
  for (int pass = 0; pass <= kWitnessCount; ++pass) {
    int first = -1;
    double first_t = 2;
    for (int w = 0; w < kWitnessCount; ++w) {
      if (!Active(w)) continue;
      const double glo = WitnessAt(w, y0, a0);
      if (pass == 0) armed[w] = glo > 0;
      if (!(glo > 0)) {
        // Already <= 0 where the search starts: a terminal witness has happened there
        // (e = 0, or rounding at the end of compression), and so has one that was > 0
        // at the step start (it crosses together with a recorded witness: a tie to
        // the location's resolution); others did not cross.
        const bool fired = ActionOf(w) == WitnessAction::kTerminal || armed[w];
        if (fired && t0 < first_t) first_t = t0, first = w;
        continue;
      }
      const double ghi = WitnessAt(w, s.y1(), s.aux1);
      if (ghi > 0) continue;
      const double guess = (t0 * ghi - glo) / (ghi - glo);  // regula falsi's first point
      const double t = IllinoisRoot([&](double tt) { return WitnessOnStep(w, s, h, tt); }, t0,
                                    glo, 1.0, ghi, guess, event_resolution_, 0.0,
                                    kMaxLocateIterations);
      if (t < first_t) first_t = t, first = w;
    }
    if (first < 0 || ActionOf(first) != WitnessAction::kRecord) {
      *t_event = first_t;
      return first;
    }
    // Recorded; the search goes on in the rest of the step.
    ++work_.events;
    t0 = first_t;
    y0 = Dense(s, h, t0);
    m_.Auxiliary(y0, &a0);
    m_.OnRecord(first, y0);
  }
  *t_event = 2;
  return -1;
}

template <HybridImpulseModel Model, RkMethod kMethod>
bool HybridIntegrator<Model, kMethod>::ApplyEvent(int w) {
  ++work_.events;
  const int followed = clock_;
  clock_ = kNoContact;
  m_.Unfreeze();
  if (w < Model::kWitnesses) {
    if (m_.Action(w) == WitnessAction::kTerminal) return true;
    m_.OnSwitch(w, &y_);
    SettleAt(kNoContact);
  } else {
    SettleAt(w == kSlipZero ? followed : w - kRayZero);
  }
  Refresh();
  return false;
}

template <HybridImpulseModel Model, RkMethod kMethod>
HybridStatus HybridIntegrator<Model, kMethod>::Run(State* x) {
  Begin(x);
  StepOut s;
  bool finished = false;
  const std::int64_t max_passes = kPassesPerStep * static_cast<std::int64_t>(s_.max_steps) + 16;
  for (std::int64_t pass = 0; pass < max_passes && attempts_ < s_.max_steps; ++pass) {
    StepPlan plan;
    if (!PlanStep(&plan)) continue;  // the clock changed: plan again
    TakeStep(plan.h, &s);
    if (Discarded(plan, s)) continue;
    const double err = std::max(StepError(s), 1e-10);
    if (Rejected(plan, s, err)) continue;
    if (Accept(plan, s, err)) {
      finished = true;
      break;
    }
    SettleSlipsAtZero();
  }
  work_.rejected_steps = attempts_ - work_.steps;
  *x = y_;
  return finished ? HybridStatus::kFinished : HybridStatus::kStepLimit;
}

template <HybridImpulseModel Model, RkMethod kMethod>
void HybridIntegrator<Model, kMethod>::Begin(State* x) {
  y_ = *x;
  m_.Start(&y_);
  Refresh();
  h_impulse_ = FirstStep();
  h_log_ = 1.0;
}

template <HybridImpulseModel Model, RkMethod kMethod>
bool HybridIntegrator<Model, kMethod>::PlanStep(StepPlan* plan) {
  plan->log_clock = clock_ != kNoContact;
  plan->h = plan->log_clock ? std::min(h_log_, kMaxLogStep)
                            : std::min(h_impulse_, kMaxStep * s_.impulse_scale);
  if (!plan->log_clock && m_.BeforeStep(y_, k1_, a1_, plan->h)) Refresh();
  if (!plan->log_clock) {
    const int follow = AimAtSlipZeros(plan);
    // Not while another slip is stiff: the tau clock has no stiff integrator.
    if (follow != kNoContact && !Stiff(plan->h, kStiffEnter, follow)) {
      h_impulse_ = plan->h;
      h_log_ = FirstLogStep();
      SetClock(follow);
      return false;
    }
  }
  for (int c = 0; c < kContacts; ++c) {
    if (plan->freeze[c]) m_.Freeze(c, m_.SlideDirection(c, y_, a1_));  // k1_ unchanged
  }
  plan->frozen = std::any_of(plan->freeze.begin(), plan->freeze.end(), [](bool f) { return f; });
  stiff_ = Stiff(plan->h, stiff_ ? kStiffLeave : kStiffEnter, kNoContact);
  return true;
}

template <HybridImpulseModel Model, RkMethod kMethod>
int HybridIntegrator<Model, kMethod>::AimAtSlipZeros(StepPlan* plan) const {
  double reach = kLogClockReach * plan->h;
  int follow = kNoContact;
  for (int c = 0; c < kContacts; ++c) {
    if (!m_.SlidingActive(c, a1_) || m_.Leaving(c, y_)) continue;
    const Vec2 u = m_.Slip(c, y_);
    const double size = u.norm();
    if (size <= s_.slip_zero) continue;  // at zero already: settled, not landing
    const Vec2 ud = m_.SlideDirection(c, y_, a1_);
    const Vec2 du = m_.Slip(c, k1_);
    const double rate = ud.dot(du);
    if (!(rate < 0)) continue;
    const double to_zero = size / -rate;
    const double turn = std::abs(ud.x() * du.y() - ud.y() * du.x()) / du.norm();
    if (turn <= kRayTurn && c != no_freeze_) {
      plan->freeze[c] = to_zero < plan->h;  // along a ray: hold the direction, locate the zero
      continue;
    }
    if (land_ratio_ * to_zero < plan->h) plan->h = land_ratio_ * to_zero, plan->landing = c;
    // A turning slip is followed in tau if it surely reaches zero (the cone can hold
    // it there); otherwise it passes by zero.
    if (to_zero < reach && size < s_.log_clock_slip && !no_follow_[c] &&
        m_.CanFollow(c, y_, a1_)) {
      reach = to_zero, follow = c;
    }
  }
  return follow;
}

template <HybridImpulseModel Model, RkMethod kMethod>
bool HybridIntegrator<Model, kMethod>::Discarded(const StepPlan& plan, const StepOut& s) {
  bool left_ray = false;
  for (int c = 0; c < kContacts; ++c) {
    if (plan.freeze[c] && !(s.max_perp[c] <= ray_tol_)) left_ray = true, no_freeze_ = c;
  }
  if (left_ray) {  // the held direction was wrong: plan again without it
    Unfreeze(plan);
    return true;
  }
  if (s.valid()) return false;
  Unfreeze(plan);
  if (plan.log_clock) {  // the followed slip stopped shrinking: back to P_I
    no_follow_[clock_] = true;
    SetClock(kNoContact);
  } else {
    h_impulse_ = 0.2 * plan.h;
  }
  return true;
}

template <HybridImpulseModel Model, RkMethod kMethod>
bool HybridIntegrator<Model, kMethod>::Rejected(const StepPlan& plan, const StepOut& s,
                                                double err) {
  double shrink = err > 1 ? (stiff_ ? Ros23StepFactor(err) : control_.Rejected(err)) : 1.0;
  bool reversed = false;
  for (int c = 0; c < kContacts; ++c) {
    // A reversal beyond the noise level of a slip (half the zero threshold).
    if (plan.freeze[c] || !m_.SlidingActive(c, a1_) || c == clock_ || m_.Leaving(c, y_) ||
        s.min_dot[c] > -0.5 * s_.slip_zero) {
      continue;
    }
    reversed = true;  // secant guess of where the slip along its start direction hits 0
    const double sp = m_.Slip(c, y_).norm();
    const double guess = 0.99 * sp / (sp - s.min_dot[c]);
    shrink = std::min(shrink, std::isfinite(guess) ? std::clamp(guess, 0.1, 0.9) : 0.5);
  }
  if (err <= 1 && !reversed) return false;
  Unfreeze(plan);
  if (plan.landing != kNoContact && !Stiff(plan.h, kStiffEnter, plan.landing) &&
      m_.Slip(plan.landing, y_).norm() < s_.log_clock_slip) {
    // The landing on a zero failed: follow that slip in tau = -ln|u| instead.
    h_impulse_ = plan.h;
    h_log_ = FirstLogStep();
    SetClock(plan.landing);
  } else if (plan.log_clock) {
    h_log_ = plan.h * shrink;
  } else if (plan.landing != kNoContact) {
    // A failed landing far from zero: the step is held to a fraction of the distance
    // to the predicted zero, which shrinks with it (near a turning zero the error
    // depends on that ratio, not on the step's length).
    land_ratio_ *= std::min(shrink, 0.5);
  } else {
    h_impulse_ = plan.h * shrink;
  }
  return true;
}

template <HybridImpulseModel Model, RkMethod kMethod>
bool HybridIntegrator<Model, kMethod>::Accept(const StepPlan& plan, StepOut& s, double err) {
  // Witnesses on the dense output; the step ends on the first that fires.
  const Vec2 u_start = plan.log_clock ? m_.Slip(clock_, y_) : Vec2::Zero();
  double t_event = 2;
  int event = LocateEvent(s, plan.h, &t_event);
  ++work_.steps;
  if (!plan.log_clock) no_follow_.fill(false);
  no_freeze_ = kNoContact;
  if (event >= 0) {
    y_ = Dense(s, plan.h, t_event);  // ApplyEvent refreshes k1_ and a1_
  } else {
    y_ = s.y1();
    k1_ = s.k_end();
    a1_ = s.aux1;
    jac_ok_ = false;
  }
  // Rosenbrock steps have their own control; in tau the error follows the slip, not a
  // trend the predictive factor could extrapolate.
  if (stiff_ || plan.log_clock) control_.Reset();
  const double grow = stiff_ ? Ros23StepFactor(err) : control_.Accepted(err, plan.h);
  (plan.log_clock ? h_log_ : h_impulse_) = plan.h * grow;
  land_ratio_ =
      plan.landing != kNoContact ? std::min(land_ratio_ * grow, kLandRatio) : kLandRatio;
  if (event < 0 && plan.log_clock) {
    const double before = u_start.norm();
    const double after = m_.Slip(clock_, y_).norm();
    if (after >= before && after < kSlipNoiseFloor * s_.slip_zero) {
      // In tau the slip shrinks like exp(-tau); one that does not is at the noise of
      // the integration: it has reached zero.
      event = kSlipZero;
    }
  }
  if (event >= 0) return ApplyEvent(event);
  Unfreeze(plan);
  return false;
}

template <HybridImpulseModel Model, RkMethod kMethod>
void HybridIntegrator<Model, kMethod>::SettleSlipsAtZero() {
  // A sliding slip (other than the one followed in tau) that has reached zero.
  std::array<bool, kContacts> at_zero{};
  bool any = false;
  for (int c = 0; c < kContacts; ++c) {
    if (!m_.SlidingActive(c, a1_) || c == clock_ || m_.Leaving(c, y_)) continue;
    if (m_.Slip(c, y_).norm() <= s_.slip_zero) at_zero[c] = any = true, ++work_.events;
  }
  if (!any) return;
  clock_ = kNoContact;
  m_.Unfreeze();
  m_.Settle(&y_, at_zero);
  Refresh();
}

}  // namespace snooker::physics::ode
