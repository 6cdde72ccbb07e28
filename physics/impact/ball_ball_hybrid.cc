// Out-of-line parts of the BallBallHybrid (ball_ball_hybrid.h) and its solvers.
#include "physics/impact/ball_ball_hybrid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace snooker::physics::detail {
namespace hybrid {

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
      az_sign_ = impulse::SlipA(y, p_.radius).y() > 0 ? 1 : -1;  // unwatched while both flew
      break;
    case kLandO:
      y[impulse::kVO + 2] = 0;
      mode_.o_on_cloth = true;
      az_sign_ = impulse::SlipA(y, p_.radius).y() > 0 ? 1 : -1;
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

}  // namespace hybrid

using hybrid::BallBallHybrid;

ImpactResult SolveAdaptive(const ImpactState& in, const Model& model,
                           const ImpulseSolverOptions& options) {
  if (options.method == ImpulseMethod::kDormandPrince853) {
    return SolveAdaptiveDop853(in, model, options);
  }
  return hybrid::SolveWith<ode::RkMethod::kDp54>(in, model, options);
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
