// Adaptive integrator for the impulse ODE of Mathavan et al. (2014).
//
// Why it looks like this. The right-hand side is smooth only between mode switches:
// Coulomb friction makes it discontinuous where a slip reaches zero, where the
// vertical slip at A changes sign (the other ball is pushed onto the cloth), where
// an airborne ball lands, and where a stuck contact leaves its friction cone. A
// high-order method stepping across a switch loses its order and its error control
// grinds the step size down. So:
//  * The mode (stick/slide at A, D, B; which ball is on the cloth) is held during a
//    step and the right-hand side is evaluated for that mode.
//  * Smooth guards (end of compression, end of restitution, the vertical slip at A,
//    an airborne ball's vertical velocity, a stuck contact's cone margin) are
//    checked at the end of every step. A sign change is located (Illinois) on the
//    step's dense output, a 4th-order continuous extension as accurate as the step
//    itself, and the step ends there with the dense state: one new right-hand side
//    per event instead of refining with real steps. The end of compression changes
//    no dynamics, so it is only recorded (W_c, P_c) and the step runs on.
//  * A sliding slip heading for zero limits the step to its predicted zero (slip
//    speed over its rate of decrease). Where that landing fails - near a sticking
//    zero the slip direction behaves like |u|^(1/6) at A (unequal inverse inertia
//    along X and Z), so its derivatives blow up - the independent variable switches
//    to tau = -ln|u| (a Sundman transformation, dP_I/dtau = |u| / (-d|u|/dP_I)), in
//    which the solution is smooth and decays like exp(-tau); a guard stops it at
//    |u| = slip_zero_. Steps whose stages see a slip reversed are rejected.
//  * At zero slip the residual (below slip_zero_, far under the tolerance) is removed
//    by adjusting spins, and the stick law decides: stick while the friction that
//    holds the slip at zero lies in the friction cone, otherwise slide on in the
//    direction the dynamics drive it (physics-notes section 3).
// Method: Dormand-Prince 5(4) (Hairer, Norsett & Wanner, Solving ODEs I, II.5),
// FSAL, local extrapolation, max-norm error control in velocity units.
#include <algorithm>
#include <array>
#include <cmath>

#include "physics/impact/ball_ball_detail.h"
#include "physics/impact/ball_ball_impulse.h"
#include "physics/ode/ode_dp54.h"

namespace snooker::physics::detail {

using impulse::Forces;
using impulse::Law;
using impulse::Model;
using impulse::State;

namespace {

// A shrinking slip whose predicted zero is closer than this many steps is followed
// in tau = -ln|u|: that close, its direction varies too fast for steps in P_I.
constexpr double kLogClockReach = 8.0;
constexpr double kLandingMargin = 1e-12;
// A cloth slip that starts from zero slides slaved to its drive (Law::kSlideSlaved,
// quasi-steady direction with its first-order lag) until it exceeds
// kSlavedSlipLimit * slip_zero_ - and, where friction nearly balances the drive
// (the stiff, quasi-steady case), until free sliding is no longer stiff for the step
// at hand (friction's slip rate * h <= |u|) - or until the lag exceeds kSlavedMaxLag
// (then the quasi-steady picture fails and the direction must be integrated).
constexpr double kSlavedSlipLimit = 1e3;
constexpr double kSlavedSlipCap = 1e-6;  // ... but at most this fraction of the speed scale
constexpr double kSlavedMaxLag = 0.05;  // rad
// ... and only once the slip is below this fraction of the speed scale: in tau the
// normal-direction quantities (P_I, W, ydot_A), trivial in P_I, decay like the slip
// and their error limits the step, which pays only close to the zero.
constexpr double kLogClockSlip = 2e-3;
// Largest step in tau = -ln|u| (the slip shrinks by at most e^20 per step).
constexpr double kMaxLogStep = 20.0;
// Iterations allowed to locate one event on the dense output (Illinois).
constexpr int kMaxEventIterations = 100;
constexpr double kEps = 2.220446049250313e-16;  // machine epsilon

// Integrated vector: the impulse state and P_I itself (so that either P_I or tau
// can be the independent variable).
using Y = Eigen::Matrix<double, 14, 1>;
constexpr int kP = 13;

enum Contact { kA = 0, kD = 1, kB = 2, kContacts = 3, kNoContact = -1 };

enum Guard {
  kCompressionEnd = 0,  // ydot_A reaches 0 (eq. 10d)
  kRestitutionEnd,      // W reaches (1 - e^2) W_c (eqs. 10c, 15)
  kVerticalSlipA,       // zdot_A changes sign: the other ball is pushed down
  kLandC,               // airborne C comes back to the cloth
  kLandO,
  kConeD,               // stuck D leaves its friction cone
  kConeB,
  kSlipZero,            // the slip followed in tau reaches slip_zero_
  kReleaseD,            // a slaved slide at D (not stiff) reaches free_slip_
  kReleaseB,
  kGuards
};

struct StepOut : ode::Dp54Result<Y> {  // y1, k7 (FSAL), err, dense output, valid
  Forces forces1;  // forces at y1
  std::array<double, kContacts> min_dot;  // min over stages of u . (start direction)
};

inline State Head(const Y& y) { return y.head<13>(); }

class AdaptiveSolver {
 public:
  AdaptiveSolver(const ImpactState& in, const Model& model, const ImpulseSolverOptions& opt)
      : model_(model), opt_(opt) {
    y_.head<13>() = impulse::Pack(in);
    y_[kP] = 0;
    const double R = model.radius;
    v_scale_ = std::max({in.c.v.norm(), in.o.v.norm(), R * in.c.w.norm(), R * in.o.w.norm()});
    atol_ = opt.tolerance * v_scale_;
    // A slip below this counts as zero. A slip is a difference of velocities that
    // each carry up to atol_ of error, so it cannot be resolved below that; setting
    // it to zero changes spins by at most atol_ / R, within the tolerance. The floor
    // keeps it above the rounding of velocities of size v_scale_.
    slip_zero_ = std::max(atol_, 64 * kEps * v_scale_);
    free_slip_ = std::max(2 * slip_zero_, std::min(kSlavedSlipLimit * slip_zero_,
                                                   kSlavedSlipCap * v_scale_));
    weight_.setConstant(1.0 / v_scale_);
    for (int i : {impulse::kWC, impulse::kWO}) weight_.segment<3>(i).setConstant(R / v_scale_);
    weight_[impulse::kWork] = model.inv_mass / (v_scale_ * v_scale_);
    weight_[kP] = model.inv_mass / v_scale_;
    event_resolution_ = std::max(4 * kEps, 1e-3 * opt.tolerance);
    p_scale_ = (1.0 + model.contact.e) * impulse::NormalSpeed(Head(y_)) / model.inv_mass;
  }

  ImpactResult Run();

 private:
  // ---- right-hand side in the current clock, and one step ----
  bool F(const Y& y, Y* dy, Forces* f = nullptr);
  void TakeStep(const Y& y0, const Y& k1, double h, StepOut* out);
  double ErrorNorm(const Y& err) const {
    return err.cwiseProduct(weight_).cwiseAbs().maxCoeff() / opt_.tolerance;
  }
  Vec2 Slip(int c, const State& x) const {
    const double R = model_.radius;
    return c == kA ? impulse::SlipA(x, R) : c == kD ? impulse::SlipD(x, R) : impulse::SlipB(x, R);
  }
  Law LawOf(int c) const { return c == kA ? mode_.a : c == kD ? mode_.d : mode_.b; }
  // Direction of the slip at contact c; a slaved slide whose slip is still within
  // the zero threshold (rounding residue) points along its drive (-stick friction).
  Vec2 SlipDirection(int c, const State& x, const Forces& f) const {
    const Vec2 u = Slip(c, x);
    if (LawOf(c) != Law::kSlideSlaved || u.norm() > slip_zero_) return impulse::Direction(u);
    return -impulse::Direction(c == kD ? f.stick_d : f.stick_b);
  }
  // Rate of change of |u_c| per unit P_I, from a derivative per unit P_I.
  double SlipRate(int c, const State& x, const State& dxdp, const Forces& f) const {
    return SlipDirection(c, x, f).dot(Slip(c, dxdp));
  }
  // Is contact c sliding with friction acting, so that its slip direction matters?
  bool SlidingActive(int c, const Forces& f) const {
    if (c == kA) {
      return mode_.a == Law::kSlide &&
             (model_.contact.friction_law == BallBallFrictionLaw::kMarlow ||
              model_.contact.mu_bb > 0);
    }
    const double n = c == kD ? f.n_c : f.n_o;
    return LawOf(c) != Law::kStick && n > 0 && model_.mu_s > 0;
  }

  // ---- guards ----
  bool GuardActive(int g) const;
  double GuardValue(int g, const Y& y, const Forces& f) const;
  static bool GuardNeedsForces(int g) { return g == kConeD || g == kConeB; }
  Forces ForcesAt(const State& x) const { return impulse::ComputeForces(x, mode_, model_); }
  // The state at fraction t of the step `s` from y_ (dense output, order 4).
  Y Dense(const StepOut& s, double t) const { return ode::Dp54DenseAt(y_, s, t); }
  double GuardAt(int g, const Y& y) const {
    return GuardValue(g, y, GuardNeedsForces(g) ? ForcesAt(Head(y)) : f1_);
  }
  // The first guard to cross zero in (t0, 1] of step `s`, located on the dense
  // output; returns it and its fraction `*t`, or -1 if none crosses.
  int LocateEvent(const StepOut& s, double t0, double* t) const;

  // ---- modes ----
  void SettleA();
  // c = kD or kB; `count` is false at the start, where a zero slip is no transition.
  void SettleCloth(int c, bool count = true);
  void Settle(bool count = true) {
    SettleA();
    Refresh();  // forces at A decide which ball the cloth holds
    SettleCloth(kD, count);
    SettleCloth(kB, count);
    Refresh();
  }
  void SnapSlipToZero(int c);
  void Refresh() { F(y_, &k1_, &f1_); }  // derivative at y_ after a mode or clock change
  void CountLiftoff() {
    if (mode_.a != Law::kSlide) return;
    if (f1_.f_a.y() > 0 && mode_.c_on_cloth) ++r_.c_liftoffs;
    if (f1_.f_a.y() < 0 && mode_.o_on_cloth) ++r_.o_liftoffs;
  }
  bool ApplyGuardEvent(int g);  // true when the impact is over
  void RecordCompressionEnd(const Y& y) {
    ++r_.work.events;
    compressed_ = true;
    r_.impulse_compression = y[kP];
    r_.work_compression = y[impulse::kWork];
    target_ = (1.0 - model_.contact.e * model_.contact.e) * r_.work_compression;  // eq. 10c
  }
  // Hands slaved cloth slides over to free sliding where that is accurate and not
  // stiff for a step h. Returns true if the mode changed.
  bool ReleaseSlaved(double h);
  void SlipReachedZero(int c);
  // Can the friction cone at contact c hold its slip at zero (f1_ forces)?
  bool CanHold(int c) const {
    if (c == kA) return true;
    const double n = c == kD ? f1_.n_c : f1_.n_o;
    const Vec2& need = c == kD ? f1_.stick_d : f1_.stick_b;
    return need.norm() < model_.mu_s * n;
  }
  void SetClock(int contact) {  // kNoContact: P_I; otherwise tau = -ln|u_contact|
    clock_ = contact;
    Refresh();
  }

  const Model& model_;
  const ImpulseSolverOptions& opt_;
  ImpactResult r_;
  Y y_;
  Y k1_;
  Forces f1_;
  impulse::Mode mode_;
  Y weight_;
  double v_scale_ = 1, atol_ = 0, slip_zero_ = 0, p_scale_ = 0;
  double free_slip_ = 0;  // a slaved slide may slide freely beyond this slip, m/s
  double event_resolution_ = 0;  // events are located to this fraction of a step
  std::int32_t attempts_ = 0;  // steps tried, accepted or not
  bool compressed_ = false;
  double target_ = 0;  // W at the end of restitution
  int az_sign_ = 1;    // sign of zdot_A in the current mode
  int clock_ = kNoContact;
  int no_follow_ = kNoContact;  // a contact whose tau clock just failed
  // Per cloth contact: a slaved slide whose release is the guard kRelease*
  // (not stiff), set by ReleaseSlaved at every step start.
  std::array<bool, kContacts> release_watch_{};
};

bool AdaptiveSolver::F(const Y& y, Y* dy, Forces* f) {
  ++r_.work.rhs_evals;
  const State x = Head(y);
  State dx;
  impulse::Derivative(x, mode_, model_, &dx, f);
  dy->head<13>() = dx;
  (*dy)[kP] = 1.0;
  if (clock_ == kNoContact) return true;
  const Vec2 u = Slip(clock_, x);
  const double s = u.norm();
  const double rate = impulse::Direction(u).dot(Slip(clock_, dx));
  if (!(s > 0 && rate < 0)) return false;  // |u| not decreasing: tau is no clock here
  *dy *= s / -rate;
  return true;
}

void AdaptiveSolver::TakeStep(const Y& y0, const Y& k1, double h, StepOut* out) {
  ++attempts_;
  std::array<Vec2, kContacts> u0dir;
  std::array<bool, kContacts> watch;
  for (int c = 0; c < kContacts; ++c) {
    watch[c] = SlidingActive(c, f1_) && c != clock_;
    u0dir[c] = SlipDirection(c, Head(y0), f1_);
    out->min_dot[c] = 1;
  }
  // The last derivative evaluated is at y1: keep its forces for the guards.
  auto rhs = [&](const Y& y, Y* dy) { return F(y, dy, &out->forces1); };
  auto observe = [&](const Y& y) {  // every stage: has a watched slip reversed?
    for (int c = 0; c < kContacts; ++c) {
      if (watch[c]) out->min_dot[c] = std::min(out->min_dot[c], Slip(c, Head(y)).dot(u0dir[c]));
    }
  };
  ode::Dp54Step(y0, k1, h, rhs, observe, out);
}

bool AdaptiveSolver::GuardActive(int g) const {
  switch (g) {
    case kCompressionEnd: return !compressed_;
    case kRestitutionEnd: return compressed_;
    case kVerticalSlipA: return mode_.a == Law::kSlide;
    case kLandC: return !mode_.c_on_cloth;
    case kLandO: return !mode_.o_on_cloth;
    case kConeD: return mode_.d == Law::kStick && f1_.n_c > 0;
    case kConeB: return mode_.b == Law::kStick && f1_.n_o > 0;
    case kSlipZero: return clock_ != kNoContact;
    case kReleaseD: return release_watch_[kD];
    case kReleaseB: return release_watch_[kB];
    default: return false;
  }
}

// Each guard is > 0 before its event and <= 0 at or after it.
double AdaptiveSolver::GuardValue(int g, const Y& y, const Forces& f) const {
  const State x = Head(y);
  switch (g) {
    case kCompressionEnd: return impulse::NormalSpeed(x);
    case kRestitutionEnd: return x[impulse::kWork] - target_;
    case kVerticalSlipA: return az_sign_ * impulse::SlipA(x, model_.radius).y();
    case kLandC: return x[impulse::kVC + 2];
    case kLandO: return x[impulse::kVO + 2];
    case kConeD: return model_.mu_s * f.n_c - f.stick_d.norm();
    case kConeB: return model_.mu_s * f.n_o - f.stick_b.norm();
    case kSlipZero: return Slip(clock_, x).norm() - slip_zero_;
    case kReleaseD: return free_slip_ - impulse::SlipD(x, model_.radius).norm();
    case kReleaseB: return free_slip_ - impulse::SlipB(x, model_.radius).norm();
    default: return 1;
  }
}

int AdaptiveSolver::LocateEvent(const StepOut& s, double t0, double* t_event) const {
  const Y y0 = t0 > 0 ? Dense(s, t0) : y_;
  int first = -1;
  double first_t = 2;
  for (int g = 0; g < kGuards; ++g) {
    if (!GuardActive(g)) continue;
    double glo = GuardAt(g, y0);
    double ghi = GuardAt(g, s.y1);
    if (g == kRestitutionEnd && !(glo > 0)) {  // already reached (e ~ 0): ends at t0
      if (t0 < first_t) first_t = t0, first = g;
      continue;
    }
    if (!(glo > 0) || ghi > 0) continue;
    // Illinois on the dense output, bracket [t0, 1] with g(t0) > 0 >= g(1). A
    // location error dt moves the state by about h |y'| dt, within the step's own
    // error: the bracket needs to close to 1e-3 of the tolerance only.
    const double guess = (t0 * ghi - glo) / (ghi - glo);  // regula falsi's first point
    const double hi = ode::IllinoisRoot([&](double t) { return GuardAt(g, Dense(s, t)); }, t0,
                                        glo, 1.0, ghi, guess, event_resolution_, 0.0,
                                        kMaxEventIterations);
    if (hi < first_t) first_t = hi, first = g;
  }
  *t_event = first_t;
  return first;
}

void AdaptiveSolver::SnapSlipToZero(int c) {
  // Removes a residual slip (below slip_zero_) by adjusting spins only, so that the
  // stick law starts from an exact zero. The change is of order slip_zero_ / R.
  const double R = model_.radius;
  const Vec2 u = Slip(c, Head(y_));
  if (c == kA) {  // split equally between both balls
    y_[impulse::kWC + 2] += u.x() / (2 * R);
    y_[impulse::kWO + 2] += u.x() / (2 * R);
    y_[impulse::kWC + 0] -= u.y() / (2 * R);
    y_[impulse::kWO + 0] -= u.y() / (2 * R);
  } else {
    const int w = c == kD ? impulse::kWC : impulse::kWO;
    y_[w + 1] += u.x() / R;
    y_[w + 0] -= u.y() / R;
  }
}

// At zero slip A sticks: with no friction at A there is no cloth reaction either,
// and nothing else changes the slip at A (the normal impulse passes through both
// centres), so the friction needed to hold it, zero, lies inside any cone.
void AdaptiveSolver::SettleA() {
  if (mode_.a == Law::kStick || !SlidingActive(kA, f1_)) return;  // nothing to hold
  const Vec2 u = impulse::SlipA(Head(y_), model_.radius);
  if (u.norm() > slip_zero_) return;
  SnapSlipToZero(kA);
  mode_.a = Law::kStick;
  ++r_.a.stick;
}

void AdaptiveSolver::SettleCloth(int c, bool count) {
  Law& law = c == kD ? mode_.d : mode_.b;
  ContactTransitions& tr = c == kD ? r_.d : r_.b;
  const Vec2 u = Slip(c, Head(y_));
  const Forces f = ForcesAt(Head(y_));
  const double n = c == kD ? f.n_c : f.n_o;
  if (!(n > 0) || model_.mu_s == 0) {  // no cloth reaction: no friction to decide about
    law = Law::kSlide;
    return;
  }
  if (law != Law::kStick && u.norm() > slip_zero_) return;  // sliding away from zero
  if (law != Law::kStick) SnapSlipToZero(c);
  // Stick test: the friction that keeps the slip at zero against the cone.
  const Vec2 need = c == kD ? f.stick_d : f.stick_b;
  if (need.norm() <= model_.mu_s * n) {
    if (law != Law::kStick && count) ++tr.stick;
    law = Law::kStick;
    return;
  }
  // Cannot hold: slide from zero along the drive (the contact's inverse inertia is
  // isotropic, 7/(2M), so the slip grows along -need), slaved to it at first.
  if (law == Law::kSlideSlaved) return;  // already sliding from zero: no new transition
  if (count) ++(law == Law::kStick ? tr.unstick : tr.reverse);
  law = Law::kSlideSlaved;
}

void AdaptiveSolver::SlipReachedZero(int c) {
  ++r_.work.events;
  SnapSlipToZero(c);
  if (c == kA) {
    SettleA();
  } else {
    SettleCloth(c);
  }
}

bool AdaptiveSolver::ApplyGuardEvent(int g) {
  ++r_.work.events;
  const int followed = clock_;
  clock_ = kNoContact;
  switch (g) {
    case kCompressionEnd:  // reached here only when e = 0
      --r_.work.events;      // counted by RecordCompressionEnd
      RecordCompressionEnd(y_);
      return true;  // restitution ends where it starts
    case kRestitutionEnd: return true;
    case kVerticalSlipA:
      // The ball that was pushed down is now pushed up (it lifts off); the other
      // is pushed down, and the cloth holds it only if it is not rising.
      az_sign_ = -az_sign_;
      mode_.c_on_cloth = y_[impulse::kVC + 2] <= 0;
      mode_.o_on_cloth = y_[impulse::kVO + 2] <= 0;
      break;
    case kLandC:
      y_[impulse::kVC + 2] = 0;
      mode_.c_on_cloth = true;
      break;
    case kLandO:
      y_[impulse::kVO + 2] = 0;
      mode_.o_on_cloth = true;
      break;
    case kSlipZero:
      --r_.work.events;  // counted by SlipReachedZero
      SlipReachedZero(followed);
      break;
    case kReleaseD: mode_.d = Law::kSlide; break;
    case kReleaseB: mode_.b = Law::kSlide; break;
    default: break;  // kConeD / kConeB: Settle() unsticks
  }
  Settle();
  if (g == kVerticalSlipA) CountLiftoff();
  return false;
}

bool AdaptiveSolver::ReleaseSlaved(double h) {
  bool changed = false;
  const State x = Head(y_);
  const double k = 1.0 + model_.radius * model_.r_over_i / model_.inv_mass;   // 7/2
  const double kz = model_.radius * model_.r_over_i / model_.inv_mass;        // 5/2
  for (int c : {kD, kB}) {
    Law& law = c == kD ? mode_.d : mode_.b;
    const double n = c == kD ? f1_.n_c : f1_.n_o;
    release_watch_[c] = false;
    if (law != Law::kSlideSlaved || !(n > 0)) continue;
    const Vec2 u = Slip(c, x);
    const Vec2 stick = c == kD ? f1_.stick_d : f1_.stick_b;
    const Vec2 dfa = impulse::FrictionARate(x, Head(k1_), mode_, model_);
    const Vec2 dstick = c == kD ? Vec2(-dfa.x() / k, -kz * dfa.y() / k)
                                : Vec2(dfa.x() / k, -kz * dfa.y() / k);
    const double lag = std::abs(impulse::SlavedLag(u, stick, dstick, model_, k));
    const double friction_rate = k * model_.mu_s * n * model_.inv_mass;  // (m/s)/(N s)
    // Where friction is weak against the drive the slip grows like the integral of
    // the drive (not quasi-steady) and free sliding is not stiff: release at once.
    const bool stiff =
        impulse::SlavedStiff(n, stick, model_.mu_s) && friction_rate * h > u.norm();
    release_watch_[c] = false;
    if ((u.norm() >= free_slip_ && !stiff) || lag >= kSlavedMaxLag) {
      law = Law::kSlide;
      changed = true;
    } else if (!stiff) {
      release_watch_[c] = true;  // release where |u| reaches free_slip_, inside the step
    }
  }
  return changed;
}

ImpactResult AdaptiveSolver::Run() {
  mode_.c_on_cloth = y_[impulse::kVC + 2] <= 0;
  mode_.o_on_cloth = y_[impulse::kVO + 2] <= 0;
  az_sign_ = impulse::SlipA(Head(y_), model_.radius).y() > 0 ? 1 : -1;
  Settle(false);
  CountLiftoff();

  double h_impulse = 0.05 * p_scale_;  // step in P_I
  double h_log = 1.0;                  // step in tau
  StepOut s;
  bool finished = false;
  ode::PiStepControl control;
  while (attempts_ < opt_.max_steps) {
    if (compressed_ && !(GuardValue(kRestitutionEnd, y_, f1_) > 0)) {  // safety net
      finished = true;
      break;
    }
    const bool log_clock = clock_ != kNoContact;
    double h = log_clock ? std::min(h_log, kMaxLogStep) : std::min(h_impulse, p_scale_);
    if (!log_clock && ReleaseSlaved(h)) Refresh();
    // Limit a step in P_I to the predicted zero of every shrinking sliding slip.
    int landing = kNoContact;
    if (!log_clock) {
      double reach = kLogClockReach * h;
      int follow = kNoContact;
      for (int c = 0; c < kContacts; ++c) {
        if (!SlidingActive(c, f1_)) continue;
        const Vec2 u = Slip(c, Head(y_));
        if (u.norm() <= slip_zero_) continue;  // at zero already: settled, not landing
        const double rate = SlipRate(c, Head(y_), Head(k1_), f1_);
        const double to_zero = u.norm() / -rate;
        if (!(rate < 0)) continue;
        // Land a hair short: a stage exactly on the zero could see the slip reversed
        // by rounding; the residual (1e-12 of the slip) is then settled as zero.
        if (to_zero < h) h = to_zero * (1 - kLandingMargin), landing = c;
        // A slip that keeps its direction lands in one step; one that turns is
        // followed in tau, if it surely reaches zero: at A always (friction at A is
        // all that changes its slip), at D or B when the cone can hold the slip
        // (then d|u|/dP_I <= |drive| - friction < 0); otherwise it passes by zero.
        const Vec2 ud = impulse::Direction(u);
        const Vec2 du = Slip(c, Head(k1_));
        const double turn = std::abs(ud.x() * du.y() - ud.y() * du.x()) / du.norm();
        if (to_zero < reach && turn > 1e-9 && u.norm() < kLogClockSlip * v_scale_ &&
            LawOf(c) == Law::kSlide && c != no_follow_ && CanHold(c)) {
          reach = to_zero, follow = c;
        }
      }
      if (follow != kNoContact) {
        h_impulse = h;
        h_log = 0.5;
        SetClock(follow);
        continue;
      }
    }

    TakeStep(y_, k1_, h, &s);
    if (!s.valid) {  // the followed slip stopped shrinking: back to P_I
      no_follow_ = clock_;
      SetClock(kNoContact);
      continue;
    }
    const double err = std::max(ErrorNorm(s.err), 1e-10);
    double shrink = err > 1 ? control.Rejected(err) : 1.0;
    bool reversed = false;
    for (int c = 0; c < kContacts; ++c) {
      // A reversal beyond the noise level of a slip (half the zero threshold).
      if (!SlidingActive(c, f1_) || c == clock_ || s.min_dot[c] > -0.5 * slip_zero_) continue;
      reversed = true;  // secant guess of where the slip along its start direction hits 0
      const double sp = Slip(c, Head(y_)).norm();
      const double guess = 0.99 * sp / (sp - s.min_dot[c]);
      shrink = std::min(shrink, std::isfinite(guess) ? std::clamp(guess, 0.1, 0.9) : 0.5);
    }
    if (!(err <= 1) || reversed) {
      if (landing != kNoContact) {
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

    // Events inside the step, on its dense output. The end of compression changes no
    // dynamics: it is recorded and the search goes on in the rest of the step.
    double t_event = 1;
    int event = LocateEvent(s, 0.0, &t_event);
    if (event == kCompressionEnd && model_.contact.e > 0) {
      const Y yc = Dense(s, t_event);
      RecordCompressionEnd(yc);
      event = LocateEvent(s, t_event, &t_event);
    }
    ++r_.work.steps;
    if (!log_clock) no_follow_ = kNoContact;
    if (event >= 0) {
      y_ = Dense(s, t_event);  // the step ends on the event; Apply refreshes k1_, f1_
    } else {
      y_ = s.y1;
      k1_ = s.k7;
      f1_ = s.forces1;
    }
    const double grow = control.Accepted(err);
    if (log_clock) {
      h_log = h * grow;
    } else {
      h_impulse = h * grow;
    }

    if (event >= 0 && ApplyGuardEvent(event)) {
      finished = true;
      break;
    }
    if (clock_ != kNoContact) continue;
    // In P_I: a sliding slip that has reached zero.
    bool changed = false;
    for (int c = 0; c < kContacts; ++c) {
      if (!SlidingActive(c, f1_)) continue;
      const Vec2 u = Slip(c, Head(y_));
      const double rate = SlipRate(c, Head(y_), Head(k1_), f1_);
      if (u.norm() <= slip_zero_ && (rate < 0 || c == landing)) {
        SlipReachedZero(c);
        changed = true;
      }
    }
    if (changed) Settle();
  }
  r_.status = finished ? ImpactStatus::kOk : ImpactStatus::kStepLimit;
  r_.impulse_final = y_[kP];
  r_.out = impulse::Unpack(Head(y_));
  r_.work.rejected_steps = attempts_ - r_.work.steps;
  return r_;
}

}  // namespace

ImpactResult SolveAdaptive(const ImpactState& in, const Model& model,
                           const ImpulseSolverOptions& options) {
  AdaptiveSolver solver(in, model, options);
  return solver.Run();
}

}  // namespace snooker::physics::detail
