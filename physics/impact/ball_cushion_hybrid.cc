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
//    both leave zero, a scan over C's ray with I's solved inside (physics-notes
//    section 3). Both stuck at once is excluded by the parameters;
//  * for stiff stretches (a slip leaving zero grows from nothing - from zero rate at a
//    cone exit - and its direction relaxes at ~ 1/|u|), the relaxation rate and a
//    Jacobian built from the friction directions (the forces depend on the state only
//    through them), so that the integrator can take Rosenbrock steps there.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "physics/impact/ball_cushion_impulse.h"
#include "physics/ode/fixed_step_integrator.h"
#include "physics/ode/hybrid_integrator.h"

namespace snooker::physics::cushion {
namespace {

// A slip below this many tolerances (times the speed scale) counts as zero: it is a
// difference of velocities that each carry the local error, accumulated over the
// steps of a tau clock (measured: a followed slip stalls at a few), so it cannot be
// resolved below a few tens; zeroing it changes spins by at most slip_zero / R.
constexpr double kSlipZeroInTolerances = 32.0;
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
    const double v_scale = std::max(Vec2(in.v.x(), in.v.y()).norm(), R * in.w.norm());
    const double atol = opt.tolerance * v_scale;
    settings_.tolerance = opt.tolerance;
    settings_.max_steps = opt.max_steps;
    settings_.speed_scale = v_scale;
    settings_.slip_zero = std::max(kSlipZeroInTolerances * atol, 64 * kEps * v_scale);
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
    hold_margin_ = 2e-3 * opt.tolerance;
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

}  // namespace

CushionImpactResult SolveAdaptive(const BallMotion& in, const Model& model,
                                  const ImpulseSolverOptions& options) {
  CushionHybrid hybrid(in, model, options);
  ode::HybridIntegrator<CushionHybrid> integrator(hybrid);
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
