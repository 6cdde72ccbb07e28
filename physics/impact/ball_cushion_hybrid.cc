// Out-of-line parts of the CushionHybrid (ball_cushion_hybrid.h) and its solvers.
#include "physics/impact/ball_cushion_hybrid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace snooker::physics::cushion {
namespace hybrid {

int CushionHybrid::JacobianAt(const State& x, const Aux&, Jacobian* jac) const {
  int evals = 0;
  jac->setZero();
  (*jac)(kWork, kVy) = p_.c;  // dW/dP_I = ydot cos th
  for (int c = 0; c < kContacts; ++c) {
    if (!SlidingActive(c) || mode_.frozen[c]) continue;
    const Vec2 u = Slip(c, x);
    const double r = Norm(u);
    if (r <= settings_.slip_zero) continue;  // the direction is held at dir0 there
    const Vec2 d = u / r, t(-d.y(), d.x());
    Mode m = mode_;
    m.frozen[c] = true;
    State plus, minus;
    m.hold[c] = std::cos(kJacobianAngle) * d + std::sin(kJacobianAngle) * t;
    cushion::Derivative(x, m, p_, &plus);
    m.hold[c] = std::cos(kJacobianAngle) * d - std::sin(kJacobianAngle) * t;
    cushion::Derivative(x, m, p_, &minus);
    evals += 2;
    const State dfda = (plus - minus) / (2 * kJacobianAngle);
    *jac += dfda * (t.transpose() * slip_map_[c]) / r;
  }
  return evals;
}

void CushionHybrid::SnapSlipToZero(int c, State* x) const {
  // Removes a residual slip (below slip_zero) with the smallest spin change, so that
  // the stick law starts from zero. Changes spins by at most slip_zero / R.
  const double R = p_.radius;
  const Vec2 u = Slip(c, *x);
  State& y = *x;
  if (c == kI) {  // u_I = (xdot + R (s wy - c wz), -s ydot + R wx)
    y[kWy] -= p_.s * u.x() / R;
    y[kWz] += p_.c * u.x() / R;
    y[kWx] -= u.y() / R;
  } else {  // u_C = (xdot - R wy, ydot + R wx)
    y[kWy] += u.x() / R;
    y[kWx] -= u.y() / R;
  }
}

bool CushionHybrid::LeaveDirection(const State& x, int c, Mode* m, double* dot_out) {
  m->law[c] = Law::kSlide;
  // Rate of the slip at c when it slides along d, and the cross product d x rate
  // (> 0: a slip along d turns towards larger angles).
  auto eval = [&](const Vec2& d, Vec2* du) {
    m->dir0[c] = d;
    State dx;
    cushion::Derivative(x, *m, p_, &dx);
    ++extra_rhs_;
    *du = cushion::Slip(c, dx, p_);
    return d.x() * du->y() - d.y() * du->x();
  };
  auto at = [](double phi) { return Vec2(std::cos(phi), std::sin(phi)); };
  // Start the scan at the drive without friction at c: the mean of the rates for
  // opposite directions (exact where the rate is affine in the friction). The slip
  // leaves along it when the contact's inverse inertia is isotropic.
  Vec2 du_a, du_b;
  eval(Vec2(1, 0), &du_a);
  eval(Vec2(-1, 0), &du_b);
  const Vec2 drive = 0.5 * (du_a + du_b);
  const double scale = std::max(du_a.norm(), du_b.norm());  // size of the slip rates
  const double phi0 = drive.isZero(0.0) ? 0.0 : std::atan2(drive.y(), drive.x());
  // Stable rays: the cross product falls through zero as the angle grows.
  Vec2 du;
  const double cr_first = eval(at(phi0), &du);
  if (std::abs(cr_first) <= kRayTurn * du.norm() && at(phi0).dot(du) > 0) {
    // The drive is a ray (isotropic contact, or a one-dimensional slip): check that it
    // is a stable one and take it.
    Vec2 du_side;
    if (eval(at(phi0 - kDirectionProbe), &du_side) > 0 &&
        eval(at(phi0 + kDirectionProbe), &du_side) < 0) {
      m->dir0[c] = at(phi0);
      if (dot_out != nullptr) *dot_out = at(phi0).dot(du);
      return true;
    }
  }
  const double step = 2 * kPi / kDirectionGrid;
  double cr_lo = cr_first;
  double best = phi0, best_dist = 1e300, best_dot = 0;
  bool found = false;
  for (int i = 0; i < kDirectionGrid; ++i) {
    const double lo = phi0 + i * step, hi = lo + step;
    const double cr_hi = i + 1 == kDirectionGrid ? cr_first : eval(at(hi), &du);
    if (cr_lo > 0 && cr_hi <= 0) {
      const double root = ode::IllinoisRoot([&](double phi) { return eval(at(phi), &du); }, lo,
                                            cr_lo, hi, cr_hi, 0.5 * (lo + hi), 1e-14, 0.0,
                                            kDirectionIterations);
      eval(at(root), &du);
      const double dist = std::min(root - phi0, phi0 + 2 * kPi - root);
      // At a cone exit the slip leaves with zero rate (the stick friction is on the
      // cone): accept a rate that is zero to rounding.
      if (at(root).dot(du) > -kRayTurn * scale && dist < best_dist) {
        best = root, best_dist = dist, best_dot = at(root).dot(du), found = true;
      }
    }
    cr_lo = cr_hi;
  }
  m->dir0[c] = at(best);
  if (dot_out != nullptr) *dot_out = best_dot;
  return found;
}

bool CushionHybrid::BothLeave(const State& x, Mode* m) {
  m->law = {Law::kSlide, Law::kSlide};
  auto at = [](double phi) { return Vec2(std::cos(phi), std::sin(phi)); };
  // C's cross product d x du_C once I has found its ray for C along d (NaN if none).
  auto eval = [&](double phi, double* dot) {
    m->dir0[kC] = at(phi);
    *dot = -1;
    if (!LeaveDirection(x, kI, m)) return std::numeric_limits<double>::quiet_NaN();
    m->dir0[kC] = at(phi);
    State dx;
    cushion::Derivative(x, *m, p_, &dx);
    ++extra_rhs_;
    const Vec2 du = cushion::Slip(kC, dx, p_);
    *dot = at(phi).dot(du);
    return at(phi).x() * du.y() - at(phi).y() * du.x();
  };
  // Start at C's drive with I frictionless-ish: I along its own drive.
  m->dir0[kC] = Vec2::Zero();
  LeaveDirection(x, kI, m);
  double phi0 = 0;
  {
    State dx;
    m->dir0[kC] = Vec2(1, 0);
    cushion::Derivative(x, *m, p_, &dx);
    Vec2 drive = cushion::Slip(kC, dx, p_);
    m->dir0[kC] = Vec2(-1, 0);
    cushion::Derivative(x, *m, p_, &dx);
    drive = 0.5 * (drive + cushion::Slip(kC, dx, p_));
    extra_rhs_ += 2;
    if (!drive.isZero(0.0)) phi0 = std::atan2(drive.y(), drive.x());
  }
  const double step = 2 * kPi / kDirectionGrid;
  double dot = 0;
  double cr_lo = eval(phi0, &dot);
  const double cr_first = cr_lo;
  double best = phi0, best_dist = 1e300;
  bool found = false;
  for (int i = 0; i < kDirectionGrid; ++i) {
    const double lo = phi0 + i * step, hi = lo + step;
    const double cr_hi = i + 1 == kDirectionGrid ? cr_first : eval(hi, &dot);
    if (cr_lo > 0 && cr_hi <= 0) {  // NaN compares false: no ray for I there
      const double root = ode::IllinoisRoot(
          [&](double phi) {
            const double cr = eval(phi, &dot);
            return std::isnan(cr) ? 0.0 : cr;
          },
          lo, cr_lo, hi, cr_hi, 0.5 * (lo + hi), 1e-14, 0.0, kDirectionIterations);
      const double cr = eval(root, &dot);
      const double dist = std::min(root - phi0, phi0 + 2 * kPi - root);
      if (!std::isnan(cr) && dot > -kRayTurn && dist < best_dist) {
        best = root, best_dist = dist, found = true;
      }
    }
    cr_lo = cr_hi;
  }
  eval(best, &dot);  // leaves I's ray for C's best direction in m
  m->dir0[kC] = at(best);
  return found;
}

void CushionHybrid::Settle(State* x, bool count, const std::array<bool, kContacts>& forced) {
  std::array<bool, kContacts> zero{};
  const Mode before = mode_;
  for (int c = 0; c < kContacts; ++c) {
    zero[c] = p_.mu[c] > 0 && (mode_.law[c] == Law::kStick || forced[c] ||
                               Norm(Slip(c, *x)) <= settings_.slip_zero);
    if (!zero[c]) mode_.dir0[c] = Vec2::Zero();
  }
  if (!zero[kI] && !zero[kC]) return;
  for (int c = 0; c < kContacts; ++c) {
    if (zero[c] && mode_.law[c] == Law::kSlide) SnapSlipToZero(c, x);
  }

  // Candidate laws, most sticking first; a contact that was stuck is kept stuck in
  // preference. Both stuck at once is excluded (ball_cushion_impulse.h).
  auto holds = [&](const Mode& m, int c) {
    return ConeMargin(c, ForcesAt(*x, m), p_) > hold_margin_;
  };
  Mode m = mode_;
  bool done = false;
  if (zero[kI] != zero[kC]) {
    const int c = zero[kI] ? kI : kC;
    m.law[c] = Law::kStick;
    m.dir0[c] = Vec2::Zero();
    if (!holds(m, c)) LeaveDirection(*x, c, &m);
    done = true;
  } else {
    const int keep = mode_.law[kC] == Law::kStick ? kC : kI;
    for (int stuck : {keep, 1 - keep}) {
      Mode t = mode_;
      t.law[stuck] = Law::kStick;
      t.dir0[stuck] = Vec2::Zero();
      if (LeaveDirection(*x, 1 - stuck, &t) && holds(t, stuck)) {
        m = t;
        done = true;
        break;
      }
    }
  }
  if (!done) {  // both slide away from zero
    m = mode_;
    BothLeave(*x, &m);
  }
  mode_ = m;

  if (count) {
    for (int c = 0; c < kContacts; ++c) {
      ContactTransitions& tr = c == kI ? r_.cushion : r_.cloth;
      if (before.law[c] == Law::kSlide && mode_.law[c] == Law::kStick) ++tr.stick;
      if (before.law[c] == Law::kStick && mode_.law[c] == Law::kSlide) ++tr.unstick;
      if (before.law[c] == Law::kSlide && mode_.law[c] == Law::kSlide && zero[c]) ++tr.reverse;
    }
  }
}

}  // namespace hybrid

using hybrid::CushionHybrid;

CushionImpactResult SolveAdaptive(const BallMotion& in, const Model& model,
                                  const ImpulseSolverOptions& options) {
  if (options.method == ImpulseMethod::kDormandPrince853) {
    return SolveAdaptiveDop853(in, model, options);
  }
  return hybrid::SolveWith<ode::RkMethod::kDp54>(in, model, options);
}

// The paper's numerical scheme for the cushion impact: explicit Euler in P_I with N
// steps of dP_I = (1 + e_e) M v_n / N, v_n the initial normal speed ydot cos th. Kept
// as the reference the hybrid integrator must converge to; first order (friction
// directions frozen over each step, zero slip gives zero friction). W is integrated
// exactly on each step, so the frictionless impact is exact for any N.
CushionImpactResult SolveFixedStep(const BallMotion& in, const Model& model,
                                   const ImpulseSolverOptions& options) {
  const CushionHybrid hybrid(in, model, options);
  State x = Pack(in);
  const double dp = (1.0 + model.e) * NormalSpeed(x, model) / model.inv_mass / options.steps;
  const ode::FixedStepResult f = ode::IntegrateFixedStep(hybrid, model.e, dp, options.max_steps, &x);
  CushionImpactResult r;
  r.status = f.status == ode::HybridStatus::kFinished ? ImpactStatus::kOk : ImpactStatus::kStepLimit;
  r.out = Unpack(x);
  r.impulse_compression = f.impulse_compression;
  r.work_compression = f.work_compression;
  r.impulse_final = f.impulse_final;
  r.work = {f.work.steps, f.work.rejected_steps, f.work.rhs_evals, f.work.events};
  return r;
}

}  // namespace snooker::physics::cushion
