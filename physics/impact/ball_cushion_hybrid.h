// The ball-cushion impact of Mathavan et al. (2010) as a hybrid model for the generic
// integrators of physics/ode/ (hybrid_integrator.h, fixed_step_integrator.h).
//
// The model supplies (the integrator does the numerics):
//  * contacts I (cushion) and C (cloth) and their slips;
//  * witnesses: the end of compression (recorded), the end of restitution (ends the
//    impact) and a stuck contact's cone margin mu N - |f|;
//  * the stick law at zero slip, for both contacts together because each one's stick
//    friction depends on the other's law (and the cloth reaction on the friction at
//    I): stick while the friction that holds the slip at zero lies in the cone (with a
//    margin, so that a contact released at a cone exit does not stick again at once);
//    otherwise slide away from zero along the stable ray u = r d with d x du/dP_I = 0
//    and d . du/dP_I >= 0, found by a scan over the circle and a root finder (at I,
//    and at C while I sticks, that is not simply opposite the stick friction); when
//    both leave zero, a scan over C's ray with I's solved inside (docs/physics-notes.md
//    section 4). Both stuck at once is excluded by the parameters;
//  * for stiff stretches (a slip leaving zero grows from nothing - from zero rate at a
//    cone exit - and its direction relaxes at ~ 1/|u|), the relaxation rate and a
//    Jacobian built from the friction directions (the forces depend on the state only
//    through them), so that the integrator can take Rosenbrock steps there.
//
// Internal to physics/. The model is declared here so that the integrator of each
// Runge-Kutta pair is instantiated in a translation unit of its own: ball_cushion_hybrid.cc
// (Dormand-Prince 5(4)) and ball_cushion_hybrid_dop853.cc. With both in one unit the compiler
// stopped inlining the model's right-hand side (11 % more instructions a shot).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "physics/impact/ball_cushion_impulse.h"
#include "physics/ode/fixed_step_integrator.h"
#include "physics/ode/hybrid_integrator.h"

namespace snooker::physics::cushion {
namespace hybrid {

// A slip below this many tolerances (times the speed scale) counts as zero: it is a
// difference of velocities that each carry the local error, accumulated over the
// steps of a tau clock (measured: a followed slip stalls at a few), so it cannot be
// resolved below a few tens; zeroing it changes spins by at most slip_zero / R.
constexpr double kSlipZeroInTolerances = 32.0;
// ... and never above this fraction of the speed scale. At loose tolerances 32
// tolerances approach the speed itself, and zeroing such a slip rewrites the spins:
// over 10^5 random impacts at tolerance 1e-3, with the threshold uncapped the kinetic
// energy rose by up to 0.8 % and the outgoing state missed a converged one by 18.6
// tolerances at the 99th percentile; capped here (the threshold of tolerance 1e-4),
// the energy never rose and the 99th percentile was 5.0, for 11 % more steps.
constexpr double kSlipZeroMaxOfSpeed = 3.2e-3;
// Directions tried around the circle when a slip leaves zero, root-finder evaluations
// per root, and the angle (rad) probed either side of a candidate ray.
constexpr int kDirectionGrid = 36;
constexpr int kDirectionIterations = 60;
constexpr double kDirectionProbe = 1e-3;
// A ray along which the slip's rate makes at most this sine with it.
constexpr double kRayTurn = 1e-9;
// Rotation (rad) of a friction direction for its finite-difference Jacobian.
constexpr double kJacobianAngle = 1e-6;
constexpr double kEps = std::numeric_limits<double>::epsilon();

class CushionHybrid {
 public:
  static constexpr int kContacts = cushion::kContacts;
  static constexpr int kImpulse = cushion::kP;
  static constexpr bool kStiffSteps = true;
  enum Witness : int {
    kCompressionEnd = 0,  // normal speed reaches 0
    kRestitutionEnd,      // W reaches (1 - e_e^2) W_c
    kConeI,               // stuck I leaves its friction cone
    kConeC,               // stuck C leaves its friction cone
    kWitnesses
  };
  using State = cushion::State;
  using Aux = Forces;
  using Jacobian = Eigen::Matrix<double, 7, 7>;

  CushionHybrid(const BallMotion& in, const Model& model, const ImpulseSolverOptions& opt)
      : p_(model) {
    const double R = model.radius;
    const double v_scale = CushionSpeedScale(in, R);
    // Looser tolerances are solved at kLoosestCushionTolerance (ball_cushion.h).
    const double tolerance = std::min(opt.tolerance, kLoosestCushionTolerance);
    const double atol = tolerance * v_scale;
    settings_.tolerance = tolerance;
    settings_.max_steps = opt.max_steps;
    settings_.speed_scale = v_scale;
    settings_.slip_zero = std::max(std::min(kSlipZeroInTolerances * atol, kSlipZeroMaxOfSpeed * v_scale),
                                   64 * kEps * v_scale);
    // The frictionless impulse, (1 + e) M ydot / cos th: the scale of P_I.
    settings_.impulse_scale = (1.0 + model.e) * in.v.y() / (model.inv_mass * model.c);
    mode_.slip_zero = settings_.slip_zero;
    weight_.setConstant(1.0 / v_scale);
    weight_.segment<3>(kWx).setConstant(R / v_scale);
    weight_[kWork] = model.inv_mass / (v_scale * v_scale);
    weight_[kP] = model.inv_mass / v_scale;
    // A contact sticks only with this margin inside its cone, so that a contact
    // released at a cone exit (located to ~1e-3 of the tolerance) does not stick again
    // at once.
    hold_margin_ = 2e-3 * tolerance;
    for (int c = 0; c < kContacts; ++c) {  // the slip maps, d u_c / d y
      slip_map_[c].setZero();
      for (int i = 0; i < kWork; ++i) slip_map_[c].col(i) = cushion::Slip(c, State::Unit(i), p_);
    }
  }

  const ode::HybridSettings& settings() const { return settings_; }
  const State& error_weights() const { return weight_; }
  CushionImpactResult& result() { return r_; }
  std::int32_t extra_rhs_evals() const { return extra_rhs_; }

  // ---- continuous part ----
  void Derivative(const State& x, State* dx, Aux* aux) const {
    cushion::Derivative(x, mode_, p_, dx, aux);
  }
  void Auxiliary(const State& x, Aux* aux) const { *aux = ComputeForces(x, mode_, p_); }
  Vec2 Slip(int c, const State& x) const { return cushion::Slip(c, x, p_); }
  bool SlidingActive(int c, const Aux&) const { return SlidingActive(c); }
  Vec2 SlideDirection(int c, const State& x, const Aux&) const {
    return cushion::SlideDirection(c, Slip(c, x), mode_);
  }
  // Just sent away from zero slip along dir0 by Settle and still below slip_zero.
  bool Leaving(int c, const State& x) const {
    return !mode_.dir0[c].isZero(0.0) && Norm(Slip(c, x)) <= settings_.slip_zero;
  }
  bool CanFollow(int c, const State& x, const Aux&) const { return CanHold(c, x); }
  void Freeze(int c, const Vec2& d) {
    mode_.frozen[c] = true;
    mode_.hold[c] = d;
  }
  void Unfreeze() { mode_.frozen = {false, false}; }
  bool Frozen(int c) const { return mode_.frozen[c]; }
  Vec2 FrozenDirection(int c) const { return mode_.hold[c]; }
  // Relaxation rate of a sliding slip's direction times |u|: mu N (1 + k) / M.
  double DirectionStiffness(int c, const Aux& f) const {
    return p_.mu[c] * f.Normal(c) * (1 + p_.k) * p_.inv_mass;
  }
  // df/dx at x in P_I; returns the derivative evaluations it took. Forces depend on
  // the state only through the friction directions, so it is the sum over sliding
  // contacts of (df / d angle) (t^T du/dx) / |u|, t normal to u, plus dW/dydot;
  // df / d angle by central differences with the direction held.
  int JacobianAt(const State& x, const Aux&, Jacobian* jac) const;

  // ---- discrete part ----
  void Start(State* x) { Settle(x, false, {}); }
  bool BeforeStep(const State&, const State&, const Aux&, double) { return false; }
  bool WitnessActive(int w) const {
    switch (w) {
      case kCompressionEnd: return !compressed_;
      case kRestitutionEnd: return compressed_;
      case kConeI: return mode_.law[kI] == Law::kStick;
      case kConeC: return mode_.law[kC] == Law::kStick;
      default: return false;
    }
  }
  ode::WitnessAction Action(int w) const {
    return w == kCompressionEnd   ? ode::WitnessAction::kRecord
           : w == kRestitutionEnd ? ode::WitnessAction::kTerminal
                                  : ode::WitnessAction::kSwitch;
  }
  bool WitnessNeedsAux(int w) const { return w == kConeI || w == kConeC; }
  // Each witness is > 0 before its event and <= 0 at or after it.
  double Witness(int w, const State& x, const Aux& f) const {
    switch (w) {
      case kCompressionEnd: return cushion::NormalSpeed(x, p_);
      case kRestitutionEnd: return x[kWork] - target_;
      case kConeI: return ConeMargin(kI, f, p_);
      case kConeC: return ConeMargin(kC, f, p_);
      default: return 1;
    }
  }
  void OnRecord(int, const State& x) {  // the end of compression
    compressed_ = true;
    r_.impulse_compression = x[kP];
    r_.work_compression = x[kWork];
    target_ = (1.0 - p_.e * p_.e) * r_.work_compression;
  }
  void OnSwitch(int, State*) {}  // cones: Settle releases the contact
  void Settle(State* x, const std::array<bool, kContacts>& at_zero) { Settle(x, true, at_zero); }

  // ---- the paper's fixed-step scheme (ode::IntegrateFixedStep) ----
  static constexpr int kWork = cushion::kWork;
  void PaperDerivative(const State& x, State* dx) const {
    const Mode paper;  // both sliding, no friction at exactly zero slip (the paper's rule)
    cushion::Derivative(x, paper, p_, dx);
  }
  double NormalSpeed(const State& x) const { return cushion::NormalSpeed(x, p_); }

 private:
  bool SlidingActive(int c) const { return mode_.law[c] == Law::kSlide && p_.mu[c] > 0; }
  Forces ForcesAt(const State& x, const Mode& m) const { return ComputeForces(x, m, p_); }
  void SnapSlipToZero(int c, State* x) const;
  // Can contact c's cone hold its slip at zero, the other contact keeping its law?
  bool CanHold(int c, const State& x) const {
    const int other = 1 - c;
    if (mode_.law[other] == Law::kStick) return false;  // both stuck: excluded
    Mode m = mode_;
    m.law[c] = Law::kStick;
    return ConeMargin(c, ForcesAt(x, m), p_) > hold_margin_;
  }
  // Direction in which contact c (at zero slip, sliding in `m`) leaves zero, the other
  // contact's law and direction held; false if there is no such ray (then dir0 is the
  // drive without friction at c, a fallback). `dot`: the slip's rate along it.
  bool LeaveDirection(const State& x, int c, Mode* m, double* dot = nullptr);
  // Both slips leave zero: the pair of rays, by a scan over C's direction with I's
  // ray solved for each. False if there is none (then a best effort is left in m).
  bool BothLeave(const State& x, Mode* m);
  // Decides the law of every contact at zero slip (`forced`: contacts known to be
  // there). `count`: record the transitions (not at the start).
  void Settle(State* x, bool count, const std::array<bool, kContacts>& forced);

  const Model& p_;
  ode::HybridSettings settings_;
  State weight_;
  Mode mode_;
  CushionImpactResult r_;
  std::array<Eigen::Matrix<double, 2, 7>, kContacts> slip_map_;
  double hold_margin_ = 0;
  bool compressed_ = false;
  double target_ = 0;  // W at the end of restitution
  std::int32_t extra_rhs_ = 0;  // derivative evaluations of the stick law
};

static_assert(ode::HybridImpulseModel<CushionHybrid>);
static_assert(ode::FixedStepImpulseModel<CushionHybrid>);

/// The adaptive solve with the Runge-Kutta pair M.
template <ode::RkMethod M>
CushionImpactResult SolveWith(const BallMotion& in, const Model& model,
                              const ImpulseSolverOptions& options) {
  CushionHybrid hybrid(in, model, options);
  ode::HybridIntegrator<CushionHybrid, M> integrator(hybrid);
  State x = Pack(in);
  const ode::HybridStatus status = integrator.Run(&x);
  CushionImpactResult& r = hybrid.result();
  r.status = status == ode::HybridStatus::kFinished ? ImpactStatus::kOk : ImpactStatus::kStepLimit;
  r.out = Unpack(x);
  r.impulse_final = x[kP];
  const ode::HybridWork& w = integrator.work();
  r.work = {w.steps, w.rejected_steps, w.rhs_evals + hybrid.extra_rhs_evals(), w.events};
  return r;
}

}  // namespace hybrid

/// The adaptive solve with DOP853 steps (ball_cushion_hybrid_dop853.cc: in a
/// translation unit of its own, so that the Dormand-Prince 5(4) instantiation keeps
/// the compiler's inlining budget for its hot path).
CushionImpactResult SolveAdaptiveDop853(const BallMotion& in, const Model& model,
                                        const ImpulseSolverOptions& options);

}  // namespace snooker::physics::cushion
