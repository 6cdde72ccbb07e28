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
//    drive it (physics-notes section 3).
// A cloth slip leaving zero is slaved to its drive (Law::kSlideSlaved, ball_ball_impulse.h):
// its direction relaxes at a rate ~ 1/|u|, which would make the problem stiff; the
// slaved law follows the quasi-steady direction with its first-order lag until free
// sliding is accurate and no longer stiff for the step at hand (BeforeStep).
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

namespace {

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
      case kVerticalSlipA: return mode_.law[kA] == Law::kSlide;
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
           (p_.contact.friction_law == BallBallFrictionLaw::kMarlow || p_.contact.mu_bb > 0);
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

void BallBallHybrid::SnapSlipToZero(int c, State* x) const {
  // Removes a residual slip (below slip_zero) by adjusting spins only, so that the
  // stick law starts from an exact zero. The change is of order slip_zero / R.
  const double R = p_.radius;
  const Vec2 u = Slip(c, *x);
  State& y = *x;
  if (c == kA) {  // split equally between both balls
    y[impulse::kWC + 2] += u.x() / (2 * R);
    y[impulse::kWO + 2] += u.x() / (2 * R);
    y[impulse::kWC + 0] -= u.y() / (2 * R);
    y[impulse::kWO + 0] -= u.y() / (2 * R);
  } else {
    const int w = c == kD ? impulse::kWC : impulse::kWO;
    y[w + 1] += u.x() / R;
    y[w + 0] -= u.y() / R;
  }
}

// At zero slip A sticks: with no friction at A there is no cloth reaction either, and
// nothing else changes the slip at A (the normal impulse passes through both
// centres), so the friction needed to hold it, zero, lies inside any cone.
void BallBallHybrid::SettleA(State* x) {
  if (mode_.law[kA] == Law::kStick || !SlidingActiveA()) return;  // nothing to hold
  if (impulse::SlipA(*x, p_.radius).norm() > settings_.slip_zero) return;
  SnapSlipToZero(kA, x);
  mode_.law[kA] = Law::kStick;
  ++r_.a.stick;
}

void BallBallHybrid::SettleCloth(int c, State* x, bool count) {
  Law& law = mode_.law[c];
  ContactTransitions& tr = c == kD ? r_.d : r_.b;
  const Forces f = impulse::ComputeForces(*x, mode_, p_);
  const double n = c == kD ? f.n_c : f.n_o;
  if (!(n > 0) || p_.mu_s == 0) {  // no cloth reaction: no friction to decide about
    law = Law::kSlide;
    return;
  }
  const bool was_leaving =
      law == Law::kSlideSlaved || (law == Law::kSlide && !mode_.dir0[c].isZero(0.0));
  if (law != Law::kStick && Slip(c, *x).norm() > settings_.slip_zero) {  // sliding on
    mode_.dir0[c] = Vec2::Zero();
    return;
  }
  if (law != Law::kStick) SnapSlipToZero(c, x);
  // Stick test: the friction that keeps the slip at zero against the cone.
  const Vec2 need = c == kD ? f.stick_d : f.stick_b;
  mode_.dir0[c] = Vec2::Zero();
  if (need.norm() <= p_.mu_s * n) {
    if (law != Law::kStick && count) ++tr.stick;
    law = Law::kStick;
    return;
  }
  // Cannot hold: slide from zero along the drive (the contact's inverse inertia is
  // isotropic, 7/(2M), so the slip grows along -need). Where friction nearly balances
  // the drive the slip's direction is stiff while it is small: slaved to the drive at
  // first. Otherwise the slip grows like the drive's integral: free sliding, along
  // the drive while it is within slip_zero (only a step's first stage sees it there).
  if (law == Law::kSlideSlaved) return;  // already sliding from zero: no new transition
  if (count && !was_leaving) ++(law == Law::kStick ? tr.unstick : tr.reverse);
  if (impulse::SlavedStiff(n, need, p_.mu_s)) {
    law = Law::kSlideSlaved;
  } else {
    law = Law::kSlide;
    mode_.dir0[c] = -impulse::Direction(need);
  }
}

void BallBallHybrid::Settle(State* x, const std::array<bool, kContacts>& at_zero) {
  for (int c = 0; c < kContacts; ++c) {
    if (!at_zero[c]) continue;
    SnapSlipToZero(c, x);
    if (c == kA) {
      SettleA(x);
    } else {
      SettleCloth(c, x, true);
    }
  }
  SettleAll(x, true);
  if (count_liftoff_) CountLiftoff(*x);
  count_liftoff_ = false;
}

void BallBallHybrid::OnSwitch(int w, State* x) {
  State& y = *x;
  switch (w) {
    case kVerticalSlipA:
      // The ball that was pushed down is now pushed up (it lifts off); the other is
      // pushed down, and the cloth holds it only if it is not rising.
      az_sign_ = -az_sign_;
      mode_.c_on_cloth = y[impulse::kVC + 2] <= 0;
      mode_.o_on_cloth = y[impulse::kVO + 2] <= 0;
      count_liftoff_ = true;
      break;
    case kLandC:
      y[impulse::kVC + 2] = 0;
      mode_.c_on_cloth = true;
      break;
    case kLandO:
      y[impulse::kVO + 2] = 0;
      mode_.o_on_cloth = true;
      break;
    case kReleaseD: mode_.law[kD] = Law::kSlide; break;
    case kReleaseB: mode_.law[kB] = Law::kSlide; break;
    default: break;  // kConeD / kConeB: Settle unsticks
  }
}

// Hands slaved cloth slides over to free sliding where that is accurate and not stiff
// for a step h. Returns true if the mode changed.
bool BallBallHybrid::BeforeStep(const State& x, const State& dx, const Aux& f, double h) {
  bool changed = false;
  for (int c : {kD, kB}) {
    Law& law = mode_.law[c];
    const double n = c == kD ? f.n_c : f.n_o;
    release_watch_[c] = false;
    if (law != Law::kSlideSlaved || !(n > 0)) continue;
    const Vec2 u = Slip(c, x);
    const Vec2 stick = c == kD ? f.stick_d : f.stick_b;
    const Vec2 dfa = impulse::FrictionARate(x, dx, mode_, p_);
    const double lag = std::abs(impulse::SlavedLag(u, stick, impulse::StickRate(c, dfa, p_), p_));
    const double friction_rate = p_.mu_s * n * p_.inv_mass / p_.inv_k;  // (m/s)/(N s)
    // Where friction is weak against the drive the slip grows like the integral of the
    // drive (not quasi-steady) and free sliding is not stiff: release at once.
    const bool stiff = impulse::SlavedStiff(n, stick, p_.mu_s) && friction_rate * h > u.norm();
    if ((u.norm() >= free_slip_ && !stiff) || lag >= kSlavedMaxLag) {
      law = Law::kSlide;
      changed = true;
    } else if (!stiff) {
      release_watch_[c] = true;  // release where |u| reaches free_slip_, inside the step
    }
  }
  return changed;
}

}  // namespace

ImpactResult SolveAdaptive(const ImpactState& in, const Model& model,
                           const ImpulseSolverOptions& options) {
  BallBallHybrid hybrid(in, model, options);
  ode::HybridIntegrator<BallBallHybrid> integrator(hybrid);
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

// The paper's numerical scheme (section 2.4.3): explicit Euler in P_I with the step of
// eq. 14, dP_I = (1 + e) M ydot_A(0) / N. Kept as the reference that reproduces the
// paper; first order (a slip that reaches zero chatters around it with an amplitude
// of one step).
ImpactResult SolveFixedStep(const ImpactState& in, const Model& model,
                            const ImpulseSolverOptions& options) {
  const BallBallHybrid hybrid(in, model, options);
  State x = impulse::Pack(in);
  const double e = model.contact.e;
  const double dp = (1.0 + e) * impulse::NormalSpeed(x) / model.inv_mass / options.steps;  // eq. 14
  const ode::FixedStepResult f = ode::IntegrateFixedStep(hybrid, e, dp, options.max_steps, &x);
  ImpactResult r;
  r.status = f.status == ode::HybridStatus::kFinished ? ImpactStatus::kOk : ImpactStatus::kStepLimit;
  r.out = impulse::Unpack(x);
  r.impulse_compression = f.impulse_compression;
  r.work_compression = f.work_compression;
  r.impulse_final = f.impulse_final;
  r.work = {f.work.steps, f.work.rejected_steps, f.work.rhs_evals, f.work.events};
  return r;
}

}  // namespace snooker::physics::detail
