// The ball-ball impact of Mathavan et al. (2014) as a hybrid model for the generic
// integrators of physics/ode/ (hybrid_integrator.h, fixed_step_integrator.h).
//
// The model supplies (the integrator does the numerics):
//  * contacts A (ball-ball), D (C on the cloth), B (O on the cloth) and their slips;
//  * witnesses: the end of compression (recorded), the end of restitution (ends the
//    impact), the vertical slip at A changing sign (the other ball is pushed onto the
//    cloth), an airborne ball landing, a stuck cloth contact leaving its cone, a
//    slaved cloth slide that may slide freely;
//  * the reset at each (which ball the cloth holds, a landing's vertical velocity) and
//    the stick law at zero slip: stick while the friction that holds the slip at zero
//    lies inside the friction cone, otherwise slide on in the direction the dynamics
//    drive it (docs/physics-notes.md section 4).
// A cloth slip leaving zero is slaved to its drive (Law::kSlideSlaved, ball_ball_impulse.h):
// its direction relaxes at a rate ~ 1/|u|, which would make the problem stiff; the
// slaved law follows the quasi-steady direction with its first-order lag until free
// sliding is accurate and no longer stiff for the step at hand (BeforeStep).
//
// Internal to physics/. The model is declared here so that the integrator of each
// Runge-Kutta pair is instantiated in a translation unit of its own: ball_ball_hybrid.cc
// (Dormand-Prince 5(4)) and ball_ball_hybrid_dop853.cc. With both in one unit the compiler
// stopped inlining the model's right-hand side (11 % more instructions a shot).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "physics/impact/ball_ball_detail.h"
#include "physics/impact/ball_ball_impulse.h"
#include "physics/ode/fixed_step_integrator.h"
#include "physics/ode/hybrid_integrator.h"

namespace snooker::physics::detail {

using impulse::Forces;
using impulse::Law;
using impulse::Model;
using impulse::State;
using impulse::kA;
using impulse::kB;
using impulse::kD;

namespace hybrid {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// A cloth slip that starts from zero slides slaved to its drive (Law::kSlideSlaved,
// quasi-steady direction with its first-order lag) until it exceeds
// kSlavedSlipLimit * slip_zero - and, where friction nearly balances the drive (the
// stiff, quasi-steady case), until free sliding is no longer stiff for the step at
// hand (friction's slip rate * h <= |u|) - or until the lag exceeds kSlavedMaxLag
// (then the quasi-steady picture fails and the direction must be integrated).
constexpr double kSlavedSlipLimit = 1e3;
constexpr double kSlavedSlipCap = 1e-6;  // ... but at most this fraction of the speed scale
constexpr double kSlavedMaxLag = 0.05;   // rad
// A turning slip is followed in tau = -ln|u| only once it is below this fraction of
// the speed scale: in tau the normal-direction quantities (P_I, W, ydot_A), trivial
// in P_I, decay like the slip and their error limits the step, which pays only close
// to the zero.
constexpr double kLogClockSlip = 2e-3;

class BallBallHybrid {
 public:
  static constexpr int kContacts = impulse::kContacts;
  static constexpr int kImpulse = impulse::kP;
  static constexpr bool kStiffSteps = false;
  enum Witness : int {
    kCompressionEnd = 0,  // ydot_A reaches 0 (eq. 10d)
    kRestitutionEnd,      // W reaches (1 - e^2) W_c (eqs. 10c, 15)
    kVerticalSlipA,       // zdot_A changes sign: the other ball is pushed down
    kLandC,               // airborne C comes back to the cloth
    kLandO,
    kConeD,               // stuck D leaves its friction cone
    kConeB,
    kReleaseD,            // a slaved slide at D (not stiff) reaches free_slip_
    kReleaseB,
    kWitnesses
  };
  using State = impulse::State;
  using Aux = Forces;
  using Jacobian = Eigen::Matrix<double, 1, 1>;  // no stiff steps

  BallBallHybrid(const ImpactState& in, const Model& model, const ImpulseSolverOptions& opt)
      : p_(model) {
    const double R = model.radius;
    const double v_scale =
        std::max({in.c.v.norm(), in.o.v.norm(), R * in.c.w.norm(), R * in.o.w.norm()});
    const double atol = opt.tolerance * v_scale;
    settings_.tolerance = opt.tolerance;
    settings_.max_steps = opt.max_steps;
    settings_.speed_scale = v_scale;
    // A slip below this counts as zero. A slip is a difference of velocities that each
    // carry up to atol of error, so it cannot be resolved below that; setting it to
    // zero changes spins by at most atol / R, within the tolerance. The floor keeps it
    // above the rounding of velocities of size v_scale.
    settings_.slip_zero = std::max(atol, 64 * kEps * v_scale);
    // The frictionless impulse, (1 + e) (M/2) ydot_A (two free balls): the scale of P_I.
    settings_.impulse_scale =
        0.5 * (1.0 + model.contact.e) * (in.c.v.y() - in.o.v.y()) / model.inv_mass;
    settings_.log_clock_slip = kLogClockSlip * v_scale;
    free_slip_ = std::max(2 * settings_.slip_zero,
                          std::min(kSlavedSlipLimit * settings_.slip_zero, kSlavedSlipCap * v_scale));
    mode_.slip_zero = settings_.slip_zero;
    weight_.setConstant(1.0 / v_scale);
    for (int i : {impulse::kWC, impulse::kWO}) weight_.segment<3>(i).setConstant(R / v_scale);
    weight_[impulse::kWork] = model.inv_mass / (v_scale * v_scale);
    weight_[impulse::kP] = model.inv_mass / v_scale;
  }

  const ode::HybridSettings& settings() const { return settings_; }
  const State& error_weights() const { return weight_; }
  ImpactResult& result() { return r_; }

  // ---- continuous part ----
  void Derivative(const State& x, State* dx, Aux* aux) const {
    impulse::Derivative(x, mode_, p_, dx, aux);
  }
  void Auxiliary(const State& x, Aux* aux) const { *aux = impulse::ComputeForces(x, mode_, p_); }
  Vec2 Slip(int c, const State& x) const { return impulse::Slip(c, x, p_.radius); }
  bool SlidingActive(int c, const Aux& f) const {
    if (c == kA) return SlidingActiveA();
    const double n = c == kD ? f.n_c : f.n_o;
    return mode_.law[c] != Law::kStick && n > 0 && p_.mu_s > 0;
  }
  // Direction of the slip at contact c; a slaved slide whose slip is still within the
  // zero threshold (rounding residue) points along its drive (-stick friction).
  Vec2 SlideDirection(int c, const State& x, const Aux& f) const {
    const Vec2 u = Slip(c, x);
    if (mode_.law[c] != Law::kSlideSlaved || mode_.frozen[c] || u.norm() > settings_.slip_zero) {
      return impulse::SlideDirection(c, u, mode_);
    }
    return -impulse::Direction(c == kD ? f.stick_d : f.stick_b);
  }
  // Sent away from zero slip by Settle (slaved, or along dir0) and still at zero.
  bool Leaving(int c, const State& x) const {
    const bool leave = mode_.law[c] == Law::kSlideSlaved ||
                       (mode_.law[c] == Law::kSlide && !mode_.dir0[c].isZero(0.0));
    return leave && Slip(c, x).norm() <= settings_.slip_zero;
  }
  // Followed in tau: a plain slide (a slaved one is growing from zero) that surely
  // reaches zero: at A always (friction at A is all that changes its slip), at D or B
  // when the cone can hold the slip (then d|u|/dP_I <= |drive| - friction < 0).
  bool CanFollow(int c, const State&, const Aux& f) const {
    if (mode_.law[c] != Law::kSlide) return false;
    if (c == kA) return true;
    const double n = c == kD ? f.n_c : f.n_o;
    return (c == kD ? f.stick_d : f.stick_b).norm() < p_.mu_s * n;
  }
  void Freeze(int c, const Vec2& d) {
    mode_.frozen[c] = true;
    mode_.hold[c] = d;
  }
  void Unfreeze() { mode_.frozen = {false, false, false}; }
  bool Frozen(int c) const { return mode_.frozen[c]; }
  Vec2 FrozenDirection(int c) const { return mode_.hold[c]; }
  double DirectionStiffness(int, const Aux&) const { return 0; }

  // ---- discrete part ----
  void Start(State* x) {
    mode_.c_on_cloth = (*x)[impulse::kVC + 2] <= 0;
    mode_.o_on_cloth = (*x)[impulse::kVO + 2] <= 0;
    az_sign_ = impulse::SlipA(*x, p_.radius).y() > 0 ? 1 : -1;
    SettleAll(x, false);
    CountLiftoff(*x);
  }
  bool BeforeStep(const State& x, const State& dx, const Aux& f, double h);
  bool WitnessActive(int w) const {
    switch (w) {
      case kCompressionEnd: return !compressed_;
      case kRestitutionEnd: return compressed_;
      // Which way zdot_A points decides which ball the cloth holds: with both balls
      // off the cloth it decides nothing, and a slip sliding along zdot_A = 0 (friction
      // at A draws it there from both sides) would switch at every step.
      case kVerticalSlipA: return mode_.law[kA] == Law::kSlide && (mode_.c_on_cloth || mode_.o_on_cloth);
      case kLandC: return !mode_.c_on_cloth;
      case kLandO: return !mode_.o_on_cloth;
      case kConeD: return mode_.law[kD] == Law::kStick && mode_.c_on_cloth;
      case kConeB: return mode_.law[kB] == Law::kStick && mode_.o_on_cloth;
      case kReleaseD: return release_watch_[kD];
      case kReleaseB: return release_watch_[kB];
      default: return false;
    }
  }
  ode::WitnessAction Action(int w) const {
    return w == kCompressionEnd   ? ode::WitnessAction::kRecord
           : w == kRestitutionEnd ? ode::WitnessAction::kTerminal
                                  : ode::WitnessAction::kSwitch;
  }
  bool WitnessNeedsAux(int w) const { return w == kConeD || w == kConeB; }
  // Each witness is > 0 before its event and <= 0 at or after it.
  double Witness(int w, const State& x, const Aux& f) const {
    switch (w) {
      case kCompressionEnd: return impulse::NormalSpeed(x);
      case kRestitutionEnd: return x[impulse::kWork] - target_;
      case kVerticalSlipA: return az_sign_ * impulse::SlipA(x, p_.radius).y();
      case kLandC: return x[impulse::kVC + 2];
      case kLandO: return x[impulse::kVO + 2];
      // A stuck contact whose cloth reaction vanishes has left its cone too.
      case kConeD: return p_.mu_s * f.n_c - f.stick_d.norm();
      case kConeB: return p_.mu_s * f.n_o - f.stick_b.norm();
      case kReleaseD: return free_slip_ - impulse::SlipD(x, p_.radius).norm();
      case kReleaseB: return free_slip_ - impulse::SlipB(x, p_.radius).norm();
      default: return 1;
    }
  }
  void OnRecord(int, const State& x) {  // the end of compression
    compressed_ = true;
    r_.impulse_compression = x[impulse::kP];
    r_.work_compression = x[impulse::kWork];
    target_ = (1.0 - p_.contact.e * p_.contact.e) * r_.work_compression;  // eq. 10c
  }
  void OnSwitch(int w, State* x);
  void Settle(State* x, const std::array<bool, kContacts>& at_zero);

  // ---- the paper's fixed-step scheme (ode::IntegrateFixedStep) ----
  static constexpr int kWork = impulse::kWork;
  void PaperDerivative(const State& x, State* dx) const {
    // The paper's rules, read off the state: sliding wherever the slip is non-zero,
    // no friction where it is exactly zero; a ball is on the cloth unless it moves up.
    impulse::Mode m;
    m.c_on_cloth = x[impulse::kVC + 2] <= 0;
    m.o_on_cloth = x[impulse::kVO + 2] <= 0;
    impulse::Derivative(x, m, p_, dx);
  }
  double NormalSpeed(const State& x) const { return impulse::NormalSpeed(x); }

 private:
  bool SlidingActiveA() const {
    return mode_.law[kA] == Law::kSlide &&
           (p_.contact.friction_law != BallBallFrictionLaw::kConstant || p_.contact.mu_bb > 0);
  }
  void SnapSlipToZero(int c, State* x) const;
  void SettleA(State* x);
  // c = kD or kB; `count` is false at the start, where a zero slip is no transition.
  void SettleCloth(int c, State* x, bool count);
  void SettleAll(State* x, bool count) {
    SettleA(x);  // the forces at A decide which ball the cloth holds
    SettleCloth(kD, x, count);
    SettleCloth(kB, x, count);
  }
  void CountLiftoff(const State& x) {
    if (mode_.law[kA] != Law::kSlide) return;
    const Vec2 f_a = impulse::FrictionA(x, mode_, p_);
    if (f_a.y() > 0 && mode_.c_on_cloth) ++r_.c_liftoffs;
    if (f_a.y() < 0 && mode_.o_on_cloth) ++r_.o_liftoffs;
  }

  const Model& p_;
  ode::HybridSettings settings_;
  State weight_;
  impulse::Mode mode_;
  ImpactResult r_;
  double free_slip_ = 0;  // a slaved slide may slide freely beyond this slip, m/s
  bool compressed_ = false;
  double target_ = 0;  // W at the end of restitution
  int az_sign_ = 1;    // sign of zdot_A in the current mode
  bool count_liftoff_ = false;  // after the next Settle (the vertical slip has switched)
  // Per cloth contact: a slaved slide whose release is the witness kRelease* (not
  // stiff), set by BeforeStep.
  std::array<bool, kContacts> release_watch_{};
};

static_assert(ode::HybridImpulseModel<BallBallHybrid>);
static_assert(ode::FixedStepImpulseModel<BallBallHybrid>);

/// The adaptive solve with the Runge-Kutta pair M.
template <ode::RkMethod M>
ImpactResult SolveWith(const ImpactState& in, const Model& model,
                       const ImpulseSolverOptions& options) {
  BallBallHybrid hybrid(in, model, options);
  ode::HybridIntegrator<BallBallHybrid, M> integrator(hybrid);
  State x = impulse::Pack(in);
  const ode::HybridStatus status = integrator.Run(&x);
  ImpactResult& r = hybrid.result();
  r.status = status == ode::HybridStatus::kFinished ? ImpactStatus::kOk : ImpactStatus::kStepLimit;
  r.out = impulse::Unpack(x);
  r.impulse_final = x[impulse::kP];
  const ode::HybridWork& w = integrator.work();
  r.work = {w.steps, w.rejected_steps, w.rhs_evals, w.events};
  return r;
}

}  // namespace hybrid

/// The adaptive solve with DOP853 steps (ball_ball_hybrid_dop853.cc: in a translation
/// unit of its own, so that the Dormand-Prince 5(4) instantiation keeps the
/// compiler's inlining budget for its hot path).
ImpactResult SolveAdaptiveDop853(const ImpactState& in, const impulse::Model& model,
                                 const ImpulseSolverOptions& options);

}  // namespace snooker::physics::detail
