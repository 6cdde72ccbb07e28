// Adaptive integrator for the cushion impulse ODE (Mathavan et al. 2010), built like
// the ball-ball one (ball_ball_adaptive.cc) on the shared pieces of ode_dp54.h, plus
// a Rosenbrock method (ode_rosenbrock23.h) for stiff stretches.
//
// Why it looks like this. Coulomb friction makes the right-hand side discontinuous
// where a slip (at I or C) reaches zero and where a stuck contact leaves its friction
// cone; a high-order method stepping across a switch loses its order and its error
// control grinds the step down. And near zero a sliding slip's direction relaxes at a
// rate ~ mu N / (M |u|), which makes the problem stiff. So:
//  * The mode (stick/slide at I and C, the direction a zero slip leaves along) is held
//    during a step; the right-hand side is that mode's. Dormand-Prince 5(4), FSAL,
//    PI step control, max-norm error in velocity units.
//  * Smooth guards - end of compression (normal speed 0), end of restitution
//    (W = (1 - e_e^2) W_c), a stuck contact's cone margin mu N - |f| - are checked at
//    the end of every step; a sign change is placed on the step's Hermite interpolant,
//    then refined with real steps from the step start (Illinois), so the switch
//    happens on the event to the guard's tolerance.
//  * A sliding slip heading for zero along a fixed ray (its rate parallel to it, as in
//    every square-on shot) has its direction held over the step ("frozen"): the
//    right-hand side stays smooth up to and through the zero, which is then a guard
//    (u . d = 0) located like the others. The step is rejected if the slip leaves the
//    ray. Without the freeze the last stage sees the friction flip and the error
//    estimate rejects the landing.
//  * A slip that turns as it shrinks (the inverse inertia at I is anisotropic,
//    diag(1+k, s^2+k)/M, and the contacts are coupled) limits the step to its
//    predicted zero; where that landing fails, the independent variable becomes
//    tau = -ln|u| (Sundman transformation, dP_I/dtau = |u| / (-d|u|/dP_I)), in which
//    the solution is smooth, and a guard stops it at |u| = slip_zero_ (or where the
//    slip stops shrinking at the integration's noise). Steps whose stages see a
//    (non-frozen) slip reversed are rejected.
//  * At zero slip (residual below slip_zero_, a few tens of the tolerance, removed by
//    adjusting spins) the stick law decides, for both contacts together because each
//    one's stick friction depends on the other's law (and the cloth reaction on the
//    friction at I): stick while the friction that holds the slip at zero lies in the
//    cone (with a margin, so that a contact released at a cone exit does not stick
//    again at once); otherwise slide away from zero along the stable ray u = r d with
//    d x du/dP_I = 0 and d . du/dP_I >= 0, found by a scan over the circle and a root
//    finder (at I, and at C while I sticks, that is not simply opposite the stick
//    friction); when both leave zero, a scan over C's ray with I's solved inside
//    (physics-notes section 3). Both stuck at once is excluded by the parameters.
//  * A slip leaving zero grows from nothing - from zero rate at a cone exit - and its
//    direction relaxes at ~ 1/|u|: Dormand-Prince would be held to steps ~ |u| by
//    stability. While h times that rate exceeds ~3, steps are taken with the
//    L-stable Rosenbrock 2(3) method and a Jacobian built from the friction
//    directions (the forces depend on the state only through them).
// Hot path: no allocation, no exception, no virtual call; every loop is capped.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "physics/impact/ball_cushion_impulse.h"
#include "physics/ode/ode_dp54.h"
#include "physics/ode/ode_rosenbrock23.h"

namespace snooker::physics::cushion {
namespace {

// Integrated vector: the impulse state and P_I itself, so that either P_I or
// tau = -ln|u| can be the independent variable.
using Y = Eigen::Matrix<double, 7, 1>;
using Jac = Eigen::Matrix<double, 7, 7>;
constexpr int kP = 6;

// A shrinking slip whose predicted zero is closer than this many steps is followed in
// tau: that close, its direction varies too fast for steps in P_I.
constexpr double kLogClockReach = 8.0;
// Largest step in tau (the slip shrinks by at most e^20 per step).
constexpr double kMaxLogStep = 20.0;
// A slip below this many atol_ counts as zero (see slip_zero_).
constexpr double kSlipZeroInTolerances = 32.0;
// A followed slip that grows in a step while under this many slip_zero_ has reached
// the noise of the integration: it is taken as zero.
constexpr double kSlipNoiseFloor = 1e3;
// A slip whose rate makes at most this sine with it heads for zero along a ray.
constexpr double kRayTurn = 1e-9;
// Real steps allowed to refine one event.
constexpr int kMaxEventIterations = 40;
// Directions tried around the circle when a slip leaves zero, root-finder evaluations
// per root, and the angle (rad) probed either side of a candidate ray.
constexpr int kDirectionGrid = 36;
constexpr int kDirectionIterations = 60;
constexpr double kDirectionProbe = 1e-3;
// A sliding slip makes the problem stiff where h times its direction's relaxation
// rate, about mu N (1 + k) / (M |u|), exceeds the first number (Dormand-Prince is
// stable to about 3.3); the Rosenbrock method takes over until it falls below the
// second.
constexpr double kStiffEnter = 3.0;
constexpr double kStiffLeave = 1.0;
// Rotation (rad) of a friction direction for its finite-difference Jacobian.
constexpr double kJacobianAngle = 1e-6;
constexpr double kEps = std::numeric_limits<double>::epsilon();

enum Guard {
  kCompressionEnd = 0,  // normal speed reaches 0
  kRestitutionEnd,      // W reaches (1 - e_e^2) W_c
  kConeI,               // stuck I leaves its friction cone
  kConeC,               // stuck C leaves its friction cone
  kSlipZero,            // the slip followed in tau reaches slip_zero_
  kRayZeroI,            // the frozen slip at I reaches zero along its ray
  kRayZeroC,            // the frozen slip at C reaches zero along its ray
  kGuards
};
constexpr int kNoContact = -1;

inline State Head(const Y& y) { return y.head<6>(); }

struct StepOut {
  ode::Dp54Result<Y> step;                 // also holds a Rosenbrock step
  Forces forces1;                         // forces at step.y1
  std::array<double, kContacts> min_dot;   // min over stages of u . (start direction)
  std::array<double, kContacts> max_perp;  // max over stages of |d x u|, frozen contacts
};

class AdaptiveSolver {
 public:
  AdaptiveSolver(const BallMotion& in, const Model& model, const ImpulseSolverOptions& opt)
      : model_(model), opt_(opt) {
    y_.head<6>() = Pack(in);
    y_[kP] = 0;
    const double R = model.radius;
    const Vec2 v(in.v.x(), in.v.y());
    v_scale_ = std::max(v.norm(), R * in.w.norm());
    atol_ = opt.tolerance * v_scale_;
    // A slip below this counts as zero. It is a difference of velocities that each
    // carry up to atol_ of local error, accumulated over the steps of a tau clock
    // (measured: a followed slip stalls at a few atol_), so it cannot be resolved
    // below a few tens of atol_; zeroing it changes spins by at most slip_zero_ / R.
    slip_zero_ = std::max(kSlipZeroInTolerances * atol_, 64 * kEps * v_scale_);
    mode_.slip_zero = slip_zero_;
    weight_.setConstant(1.0 / v_scale_);
    weight_.segment<3>(kWx).setConstant(R / v_scale_);
    weight_[kWork] = model.inv_mass / (v_scale_ * v_scale_);
    weight_[kP] = model.inv_mass / v_scale_;
    // The frictionless impulse, (1 + e) M ydot / cos th: the scale of P_I.
    p_scale_ = (1.0 + model.e) * in.v.y() / (model.inv_mass * model.c);
    guard_eps_[kCompressionEnd] = 1e-3 * atol_;
    guard_eps_[kRestitutionEnd] = 1e-3 * atol_ * v_scale_ / model.inv_mass;
    guard_eps_[kConeI] = guard_eps_[kConeC] = 1e-3 * opt.tolerance;
    guard_eps_[kSlipZero] = 0.5 * slip_zero_;
    guard_eps_[kRayZeroI] = guard_eps_[kRayZeroC] = 0.5 * slip_zero_;
    // A frozen slip may leave its ray by this much: then the held direction is wrong
    // by at most this over |u|, and the slip still lands below slip_zero_. The floor
    // is the rounding of slips of size v_scale_.
    ray_tol_ = std::max(1e-3 * slip_zero_, 16 * kEps * v_scale_);
    // A contact sticks only with this margin inside its cone: twice the cone guard's
    // tolerance, so a contact released at a cone event does not stick again at once.
    hold_margin_ = 2 * guard_eps_[kConeI];
    for (int c = 0; c < kContacts; ++c) {  // the slip maps, d u_c / d y
      slip_map_[c].setZero();
      for (int i = 0; i < 6; ++i) slip_map_[c].col(i) = Slip(c, State::Unit(i), model_);
    }
  }

  CushionImpactResult Run();

 private:
  // ---- right-hand side in the current clock, and one step ----
  bool F(const Y& y, Y* dy, Forces* f = nullptr);
  void TakeStep(const Y& y0, const Y& k1, double h, StepOut* out);
  double ErrorNorm(const Y& err) const {
    return err.cwiseProduct(weight_).cwiseAbs().maxCoeff() / opt_.tolerance;
  }
  Vec2 SlipAt(int c, const Y& y) const { return Slip(c, Head(y), model_); }
  // Rate of change of |u_c| per unit of the clock, from a derivative in that clock.
  double SlipRate(int c, const Y& y, const Y& dy) const {
    return SlideDirection(c, SlipAt(c, y), mode_).dot(SlipAt(c, dy));
  }
  // Sliding with friction acting, so that the slip's direction matters.
  bool SlidingActive(int c) const { return mode_.law[c] == Law::kSlide && model_.mu[c] > 0; }
  // Just sent away from zero slip along dir0 by Settle and still below slip_zero_.
  bool Leaving(int c) const {
    const Vec2 u = SlipAt(c, y_);
    return !mode_.dir0[c].isZero(0.0) && Norm(u) <= slip_zero_;
  }
  Forces ForcesAt(const Y& y, const Mode& m) const { return ComputeForces(Head(y), m, model_); }
  // Is the step h in P_I stiff for Dormand-Prince (threshold kStiffEnter / kStiffLeave)?
  bool Stiff(double h, double threshold, int except = kNoContact) const;
  // df/dy at y_ in P_I for the Rosenbrock method, cached until y_ or the mode changes.
  // Forces depend on the state only through the friction directions, so it is
  // sum over sliding contacts of (df / d angle) (t^T du/dy) / |u|, t normal to u, plus
  // dW/dydot; df / d angle by central differences with the direction held.
  const Jac& Jacobian();

  // ---- guards ----
  bool GuardActive(int g) const;
  double GuardValue(int g, const Y& y, const Forces& f) const;
  // Shortens the step `s` (of length *h) to end on the first guard crossing in it.
  // Returns the guard, or -1 if none crosses.
  int LocateEvent(StepOut* s, double* h);

  // ---- modes ----
  void Refresh() {  // derivative at y_ after a mode or clock change
    F(y_, &k1_, &f1_);
    jac_ok_ = false;
  }
  void SetClock(int contact) {           // kNoContact: P_I; else tau = -ln|u_contact|
    clock_ = contact;
    Refresh();
  }
  void SnapSlipToZero(int c);
  // Can contact c's cone hold its slip at zero, the other contact keeping its law?
  bool CanHold(int c) const;
  // Direction in which contact c (at zero slip, sliding in `m`) leaves zero, the other
  // contact's law and direction held; false if there is no such ray (then dir0 is
  // the drive without friction at c, a fallback). `dot`: the slip's rate along it.
  bool LeaveDirection(int c, Mode* m, double* dot = nullptr);
  // Both slips leave zero: the pair of rays, by a scan over C's direction with I's
  // ray solved for each. False if there is none (then a best effort is left in m).
  bool BothLeave(Mode* m);
  // Decides the law of every contact at zero slip (`forced`: a contact known to be
  // there). `count`: record the transitions (not at the start).
  void Settle(bool count, int forced = kNoContact);
  bool ApplyGuardEvent(int g);  // true when the impact is over

  const Model& model_;
  const ImpulseSolverOptions& opt_;
  CushionImpactResult r_;
  Y y_;
  Y k1_;
  Forces f1_;
  Mode mode_;
  Y weight_;
  ode::PiStepControl control_;
  std::array<Eigen::Matrix<double, 2, 6>, kContacts> slip_map_;
  Jac jac_;
  bool jac_ok_ = false;
  bool stiff_ = false;  // the step being tried is a Rosenbrock step
  double v_scale_ = 1, atol_ = 0, slip_zero_ = 0, p_scale_ = 0, hold_margin_ = 0, ray_tol_ = 0;
  std::int32_t attempts_ = 0;  // steps tried, accepted or not
  bool compressed_ = false;
  double target_ = 0;  // W at the end of restitution
  int clock_ = kNoContact;
  int no_follow_ = kNoContact;  // a contact whose tau clock just failed
  int no_freeze_ = kNoContact;  // a contact that just left its ray in a frozen step
  std::array<double, kGuards> guard_eps_{};
};

bool AdaptiveSolver::F(const Y& y, Y* dy, Forces* f) {
  ++r_.work.rhs_evals;
  const State x = Head(y);
  State dx;
  Derivative(x, mode_, model_, &dx, f);
  dy->head<6>() = dx;
  (*dy)[kP] = 1.0;
  if (clock_ == kNoContact) return true;
  const Vec2 u = Slip(clock_, x, model_);
  const double s = Norm(u);
  const double rate = SlideDirection(clock_, u, mode_).dot(Slip(clock_, dx, model_));
  if (!(s > 0 && rate < 0)) return false;  // |u| not decreasing: tau is no clock here
  *dy *= s / -rate;
  return true;
}

void AdaptiveSolver::TakeStep(const Y& y0, const Y& k1, double h, StepOut* out) {
  ++attempts_;
  std::array<Vec2, kContacts> u0dir;
  std::array<bool, kContacts> watch;
  for (int c = 0; c < kContacts; ++c) {
    // A slip just leaving zero is not watched: its start direction is only the ray
    // it leaves along, and it may grow from zero rate (at a cone exit).
    watch[c] = SlidingActive(c) && c != clock_ && !Leaving(c);
    u0dir[c] = SlideDirection(c, SlipAt(c, y0), mode_);
    out->min_dot[c] = 1;
    out->max_perp[c] = 0;
  }
  Forces last;
  auto rhs = [&](const Y& y, Y* dy) { return F(y, dy, &last); };
  auto observe = [&](const Y& y) {
    for (int c = 0; c < kContacts; ++c) {
      if (!watch[c]) continue;
      const Vec2 u = SlipAt(c, y);
      out->min_dot[c] = std::min(out->min_dot[c], u.dot(u0dir[c]));
      const double perp = std::abs(u0dir[c].x() * u.y() - u0dir[c].y() * u.x());
      out->max_perp[c] = std::max(out->max_perp[c], perp);
    }
  };
  if (stiff_) {
    ode::Ros23Result<Y> ros;
    ode::Ros23Step(y0, k1, Jacobian(), h, rhs, observe, &ros);
    out->step.y1 = ros.y1;
    out->step.k7 = ros.k7;
    out->step.err = ros.err;
    out->step.valid = ros.valid;
  } else {
    ode::Dp54Step(y0, k1, h, rhs, observe, &out->step);
  }
  out->forces1 = last;  // the last evaluation is at y1
}

bool AdaptiveSolver::Stiff(double h, double threshold, int except) const {
  if (clock_ != kNoContact) return false;
  for (int c = 0; c < kContacts; ++c) {
    if (!SlidingActive(c) || mode_.frozen[c] || c == except) continue;
    const Vec2 u = SlipAt(c, y_);
    const double r = std::max(Norm(u), slip_zero_);
    const double rate = model_.mu[c] * f1_.Normal(c) * (1 + model_.k) * model_.inv_mass / r;
    if (h * rate > threshold) return true;
  }
  return false;
}

const Jac& AdaptiveSolver::Jacobian() {
  if (jac_ok_) return jac_;
  jac_.setZero();
  jac_(kWork, kVy) = model_.c;  // dW/dP_I = ydot cos th
  const State x = Head(y_);
  for (int c = 0; c < kContacts; ++c) {
    if (!SlidingActive(c) || mode_.frozen[c]) continue;
    const Vec2 u = SlipAt(c, y_);
    const double r = Norm(u);
    if (r <= slip_zero_) continue;  // the direction is held at dir0 there
    const Vec2 d = u / r, t(-d.y(), d.x());
    Mode m = mode_;
    m.frozen[c] = true;
    State plus, minus;
    m.dir0[c] = std::cos(kJacobianAngle) * d + std::sin(kJacobianAngle) * t;
    Derivative(x, m, model_, &plus);
    m.dir0[c] = std::cos(kJacobianAngle) * d - std::sin(kJacobianAngle) * t;
    Derivative(x, m, model_, &minus);
    r_.work.rhs_evals += 2;
    const State dfda = (plus - minus) / (2 * kJacobianAngle);
    jac_.topLeftCorner<6, 6>() += dfda * (t.transpose() * slip_map_[c]) / r;
  }
  jac_ok_ = true;
  return jac_;
}

bool AdaptiveSolver::GuardActive(int g) const {
  switch (g) {
    case kCompressionEnd: return !compressed_;
    case kRestitutionEnd: return compressed_;
    case kConeI: return mode_.law[kI] == Law::kStick;
    case kConeC: return mode_.law[kC] == Law::kStick;
    case kSlipZero: return clock_ != kNoContact;
    case kRayZeroI: return mode_.frozen[kI];
    case kRayZeroC: return mode_.frozen[kC];
    default: return false;
  }
}

// Each guard is > 0 before its event and <= 0 at or after it.
double AdaptiveSolver::GuardValue(int g, const Y& y, const Forces& f) const {
  switch (g) {
    case kCompressionEnd: return NormalSpeed(Head(y), model_);
    case kRestitutionEnd: return y[kWork] - target_;
    case kConeI: return ConeMargin(kI, f, model_);
    case kConeC: return ConeMargin(kC, f, model_);
    case kSlipZero: {
      const Vec2 u = SlipAt(clock_, y);
      return Norm(u) - slip_zero_;
    }
    case kRayZeroI: return SlipAt(kI, y).dot(mode_.dir0[kI]);
    case kRayZeroC: return SlipAt(kC, y).dot(mode_.dir0[kC]);
    default: return 1;
  }
}

int AdaptiveSolver::LocateEvent(StepOut* s, double* h) {
  std::array<double, kGuards> g0{};
  std::array<bool, kGuards> armed{};  // active and positive at the step start
  int first = -1;
  double theta = 2;
  for (int g = 0; g < kGuards; ++g) {
    armed[g] = GuardActive(g) && (g0[g] = GuardValue(g, y_, f1_)) > 0;
    if (!armed[g] || GuardValue(g, s->step.y1, s->forces1) > 0) continue;
    // Earliest crossing on the step's Hermite interpolant.
    const ode::Dp54Result<Y>& st = s->step;
    auto on_interpolant = [&](double t) {
      const Y yt = ode::HermiteAt(y_, k1_, st.y1, st.k7, *h, t);
      return GuardValue(g, yt, ForcesAt(yt, mode_));
    };
    const double g1 = std::min(GuardValue(g, st.y1, s->forces1), -1e-300);
    const double t = ode::IllinoisRoot(on_interpolant, 0.0, g0[g], 1.0, g1, 0.5, 1e-15, 0.0, 60);
    if (t < theta) theta = t, first = g;
  }
  if (first < 0) return -1;

  // Refine with real steps from y_ over the step length, in [0, hi].
  double hi = *h;
  StepOut trial_step, hi_step = *s;
  double trial_len = -1;
  auto real = [&](double len) {
    TakeStep(y_, k1_, len, &trial_step);
    trial_len = len;
    // A sub-step of a valid step cannot break the tau clock; be safe anyway.
    return trial_step.step.valid ? GuardValue(first, trial_step.step.y1, trial_step.forces1)
                                 : -1e-300;
  };
  for (int restart = 0; restart <= kGuards; ++restart) {
    const double g_hi = std::min(GuardValue(first, hi_step.step.y1, hi_step.forces1), -1e-300);
    const double x = ode::IllinoisRoot(real, 0.0, g0[first], hi, g_hi, theta * hi,
                                       4 * kEps * (std::abs(y_[kP]) + hi), guard_eps_[first],
                                       kMaxEventIterations);
    if (x == hi) {
      trial_step = hi_step;
      trial_len = hi;
    } else if (x != trial_len) {
      real(x);
    }
    if (!trial_step.step.valid) break;  // keep the whole step: the event is at its end
    // Another guard crossing earlier takes precedence.
    int earlier = -1;
    for (int g = 0; g < kGuards; ++g) {
      if (g != first && armed[g] &&
          GuardValue(g, trial_step.step.y1, trial_step.forces1) <= 0) {
        earlier = g;
      }
    }
    if (earlier < 0) {
      *s = trial_step;
      *h = trial_len;
      return first;
    }
    first = earlier;
    hi = trial_len;
    hi_step = trial_step;
    theta = 0.5;
  }
  return first;  // the whole step, the event at its end
}

void AdaptiveSolver::SnapSlipToZero(int c) {
  // Removes a residual slip (below slip_zero_) with the smallest spin change, so that
  // the stick law starts from zero. Changes spins by at most slip_zero_ / R.
  const double R = model_.radius;
  const Vec2 u = SlipAt(c, y_);
  if (c == kI) {  // u_I = (xdot + R (s wy - c wz), -s ydot + R wx)
    y_[kWy] -= model_.s * u.x() / R;
    y_[kWz] += model_.c * u.x() / R;
    y_[kWx] -= u.y() / R;
  } else {  // u_C = (xdot - R wy, ydot + R wx)
    y_[kWy] += u.x() / R;
    y_[kWx] -= u.y() / R;
  }
}

bool AdaptiveSolver::CanHold(int c) const {
  const int other = 1 - c;
  if (mode_.law[other] == Law::kStick) return false;  // both stuck: excluded
  Mode m = mode_;
  m.law[c] = Law::kStick;
  return ConeMargin(c, ForcesAt(y_, m), model_) > hold_margin_;
}

bool AdaptiveSolver::LeaveDirection(int c, Mode* m, double* dot_out) {
  m->law[c] = Law::kSlide;
  const State x = Head(y_);
  // Rate of the slip at c when it slides along d, and the cross product d x rate
  // (> 0: a slip along d turns towards larger angles).
  auto eval = [&](const Vec2& d, Vec2* du) {
    m->dir0[c] = d;
    State dx;
    Derivative(x, *m, model_, &dx);
    ++r_.work.rhs_evals;
    *du = Slip(c, dx, model_);
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
    // The drive is a ray (isotropic contact, or a one-dimensional slip): check that
    // it is a stable one and take it.
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

bool AdaptiveSolver::BothLeave(Mode* m) {
  m->law = {Law::kSlide, Law::kSlide};
  const State x = Head(y_);
  auto at = [](double phi) { return Vec2(std::cos(phi), std::sin(phi)); };
  // C's cross product d x du_C once I has found its ray for C along d (NaN if none).
  auto eval = [&](double phi, double* dot) {
    m->dir0[kC] = at(phi);
    *dot = -1;
    if (!LeaveDirection(kI, m)) return std::numeric_limits<double>::quiet_NaN();
    m->dir0[kC] = at(phi);
    State dx;
    Derivative(x, *m, model_, &dx);
    ++r_.work.rhs_evals;
    const Vec2 du = Slip(kC, dx, model_);
    *dot = at(phi).dot(du);
    return at(phi).x() * du.y() - at(phi).y() * du.x();
  };
  // Start at C's drive with I frictionless-ish: I along its own drive.
  m->dir0[kC] = Vec2::Zero();
  LeaveDirection(kI, m);
  double phi0 = 0;
  {
    State dx;
    m->dir0[kC] = Vec2(1, 0);
    Derivative(x, *m, model_, &dx);
    Vec2 drive = Slip(kC, dx, model_);
    m->dir0[kC] = Vec2(-1, 0);
    Derivative(x, *m, model_, &dx);
    drive = 0.5 * (drive + Slip(kC, dx, model_));
    r_.work.rhs_evals += 2;
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

void AdaptiveSolver::Settle(bool count, int forced) {
  std::array<bool, kContacts> zero{};
  const Mode before = mode_;
  for (int c = 0; c < kContacts; ++c) {
    const Vec2 u = SlipAt(c, y_);
    zero[c] = model_.mu[c] > 0 && (mode_.law[c] == Law::kStick || c == forced ||
                                   Norm(u) <= slip_zero_);
    if (!zero[c]) mode_.dir0[c] = Vec2::Zero();
  }
  if (!zero[kI] && !zero[kC]) {
    Refresh();
    return;
  }
  for (int c = 0; c < kContacts; ++c) {
    if (zero[c] && mode_.law[c] == Law::kSlide) SnapSlipToZero(c);
  }

  // Candidate laws, most sticking first; a contact that was stuck is kept stuck in
  // preference. Both stuck at once is excluded (ball_cushion_impulse.h).
  auto holds = [&](const Mode& m, int c) {
    return ConeMargin(c, ForcesAt(y_, m), model_) > hold_margin_;
  };
  Mode m = mode_;
  bool done = false;
  if (zero[kI] != zero[kC]) {
    const int c = zero[kI] ? kI : kC;
    m.law[c] = Law::kStick;
    m.dir0[c] = Vec2::Zero();
    if (!holds(m, c)) LeaveDirection(c, &m);
    done = true;
  } else {
    const int keep = mode_.law[kC] == Law::kStick ? kC : kI;
    for (int stuck : {keep, 1 - keep}) {
      Mode t = mode_;
      t.law[stuck] = Law::kStick;
      t.dir0[stuck] = Vec2::Zero();
      if (LeaveDirection(1 - stuck, &t) && holds(t, stuck)) {
        m = t;
        done = true;
        break;
      }
    }
  }
  if (!done) {  // both slide away from zero
    m = mode_;
    BothLeave(&m);
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
  Refresh();
}

bool AdaptiveSolver::ApplyGuardEvent(int g) {
  ++r_.work.events;
  const int followed = clock_;
  clock_ = kNoContact;
  mode_.frozen = {false, false};
  switch (g) {
    case kCompressionEnd:
      compressed_ = true;
      r_.impulse_compression = y_[kP];
      r_.work_compression = y_[kWork];
      target_ = (1.0 - model_.e * model_.e) * r_.work_compression;
      if (model_.e == 0) return true;  // restitution ends where it starts
      break;
    case kRestitutionEnd: return true;
    default: break;  // cones: Settle releases the contact; kSlipZero: it is at zero
  }
  const int at_zero = g == kSlipZero ? followed
                      : g == kRayZeroI ? kI
                      : g == kRayZeroC ? kC
                                       : kNoContact;
  Settle(true, at_zero);
  return false;
}

CushionImpactResult AdaptiveSolver::Run() {
  Settle(false);
  double h_impulse = 0.05 * p_scale_;  // step in P_I
  double h_log = 1.0;                  // step in tau
  StepOut s;
  bool finished = false;
  while (attempts_ < opt_.max_steps) {
    const bool log_clock = clock_ != kNoContact;
    double h = log_clock ? std::min(h_log, kMaxLogStep) : std::min(h_impulse, p_scale_);
    // Limit a step in P_I to the predicted zero of every shrinking sliding slip.
    int landing = kNoContact;
    std::array<bool, kContacts> freeze{false, false};
    if (!log_clock) {
      double reach = kLogClockReach * h;
      int follow = kNoContact;
      for (int c = 0; c < kContacts; ++c) {
        if (!SlidingActive(c) || Leaving(c)) continue;
        const Vec2 u = SlipAt(c, y_);
        const double rate = SlipRate(c, y_, k1_);
        if (!(rate < 0)) continue;
        const double to_zero = Norm(u) / -rate;
        const Vec2 ud = SlideDirection(c, u, mode_);
        const Vec2 du = SlipAt(c, k1_);
        const double turn = std::abs(ud.x() * du.y() - ud.y() * du.x()) / du.norm();
        if (turn <= kRayTurn && c != no_freeze_) {
          // Along a ray: hold the direction; the zero, if in this step, is an event.
          freeze[c] = to_zero < h;
          continue;
        }
        if (to_zero < h) h = to_zero, landing = c;
        // A turning slip is followed in tau if the cone can hold it at zero (then it
        // surely reaches zero); otherwise it passes by zero.
        if (to_zero < reach && c != no_follow_ && CanHold(c)) reach = to_zero, follow = c;
      }
      // Not while the other slip is stiff: the tau clock has no stiff integrator.
      if (follow != kNoContact && !Stiff(h, kStiffEnter, follow)) {
        h_impulse = h;
        h_log = 0.5;
        SetClock(follow);
        continue;
      }
    }
    for (int c = 0; c < kContacts; ++c) {
      if (!freeze[c]) continue;
      mode_.dir0[c] = SlideDirection(c, SlipAt(c, y_), mode_);
      mode_.frozen[c] = true;  // k1_ is unchanged: the held direction is the current one
    }
    auto unfreeze = [&] {
      if (!freeze[kI] && !freeze[kC]) return;
      mode_.frozen = {false, false};
      Refresh();
    };

    // Stiff while a sliding slip is so small that its direction's relaxation, not
    // accuracy, would limit an explicit step (with hysteresis).
    stiff_ = Stiff(h, stiff_ ? kStiffLeave : kStiffEnter);

    TakeStep(y_, k1_, h, &s);
    bool left_ray = false;
    for (int c = 0; c < kContacts; ++c) {
      if (freeze[c] && !(s.max_perp[c] <= ray_tol_)) left_ray = true, no_freeze_ = c;
    }
    if (left_ray) {  // the held direction was wrong: plan again without it
      unfreeze();
      continue;
    }
    if (!s.step.valid) {
      unfreeze();
      if (log_clock) {  // the followed slip stopped shrinking: back to P_I
        no_follow_ = clock_;
        SetClock(kNoContact);
      } else {
        h_impulse = 0.2 * h;
      }
      continue;
    }
    const double err = ErrorNorm(s.step.err);
    double shrink = err > 1 ? (stiff_ ? ode::Ros23StepFactor(err) : control_.Rejected(err)) : 1.0;
    bool reversed = false;
    for (int c = 0; c < kContacts; ++c) {
      if (!SlidingActive(c) || c == clock_ || freeze[c] || s.min_dot[c] > 0) continue;
      reversed = true;  // secant guess of where the slip along its start direction hits 0
      const Vec2 u = SlipAt(c, y_);
      const double sp = Norm(u);
      shrink = std::min(shrink, std::clamp(0.99 * sp / (sp - s.min_dot[c]), 0.1, 0.9));
    }
    if (!(err <= 1) || reversed) {
      unfreeze();
      if (landing != kNoContact && !Stiff(h, kStiffEnter, landing)) {
        // The landing on a zero failed: follow that slip in tau = -ln|u| instead.
        h_impulse = h;
        h_log = 1.0;
        SetClock(landing);
      } else if (log_clock) {
        h_log = h * shrink;
      } else {
        h_impulse = h * shrink;
      }
      continue;
    }

    double h_taken = h;
    const Vec2 u_start = log_clock ? SlipAt(clock_, y_) : Vec2::Zero();
    int event = LocateEvent(&s, &h_taken);
    ++r_.work.steps;
    if (!log_clock) no_follow_ = kNoContact;
    no_freeze_ = kNoContact;
    y_ = s.step.y1;
    k1_ = s.step.k7;
    f1_ = s.forces1;
    jac_ok_ = false;
    const double grow = stiff_ ? ode::Ros23StepFactor(err) : control_.Accepted(err);
    (log_clock ? h_log : h_impulse) = h * grow;

    if (event < 0 && log_clock) {
      const double before = Norm(u_start);
      const Vec2 u = SlipAt(clock_, y_);
      const double after = Norm(u);
      if (after >= before && after < kSlipNoiseFloor * slip_zero_) {
        // In tau the slip shrinks like exp(-tau); one that does not is at the noise
        // of the integration: it has reached zero.
        event = kSlipZero;
      }
    }
    if (event >= 0 && ApplyGuardEvent(event)) {
      finished = true;
      break;
    }
    if (event < 0) unfreeze();  // an event has settled the modes already
    // A sliding slip (other than the one followed in tau) that has reached zero.
    bool changed = false;
    for (int c = 0; c < kContacts; ++c) {
      if (!SlidingActive(c) || Leaving(c) || c == clock_) continue;
      // Leaving() has excluded the slips that Settle has just sent away from zero.
      const Vec2 u = SlipAt(c, y_);
      if (Norm(u) <= slip_zero_) {
        ++r_.work.events;
        changed = true;
      }
    }
    if (changed) {
      clock_ = kNoContact;  // Settle refreshes the derivative in P_I
      Settle(true);
    }
  }
  r_.status = finished ? ImpactStatus::kOk : ImpactStatus::kStepLimit;
  r_.impulse_final = y_[kP];
  r_.out = Unpack(Head(y_));
  r_.work.rejected_steps = attempts_ - r_.work.steps;
  return r_;
}

}  // namespace

CushionImpactResult SolveAdaptive(const BallMotion& in, const Model& model,
                                  const ImpulseSolverOptions& options) {
  AdaptiveSolver solver(in, model, options);
  return solver.Run();
}

}  // namespace snooker::physics::cushion
