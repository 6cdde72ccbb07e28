// Physical parameters, kept apart from state (MuJoCo's mjModel/mjData split).
// Defaults are the snooker values of Mathavan, Jackson & Parkin (2014) and the
// sources listed in docs/physics-notes.md sections 7 and 9.
#pragma once

#include <cmath>
#include <string>

#include "physics/core/limits.h"

namespace snooker::physics {

/// A snooker ball: a uniform solid sphere.
struct BallParams {
  /// Mass. kg. Paper section 2.4.3.
  double mass = 0.1406;
  /// Radius. m. Paper section 2.4.3 (52.5 mm diameter).
  double radius = 0.02625;
  /// Moment of inertia about a diameter, 2 M R^2 / 5. kg m^2.
  double Inertia() const { return 0.4 * mass * radius * radius; }
};

/// The cloth under the balls.
struct ClothParams {
  /// Ball-cloth sliding friction coefficient. Paper section 2.4.2 (measured 0.178-0.245).
  double mu_s = 0.21;
  /// Rolling resistance coefficient: rolling deceleration is mu_r * g
  /// (about 0.125 m/s^2 measured on snooker cloth, Mathavan et al. 2009).
  double mu_r = 0.0128;
  /// Deceleration of spin about the vertical axis. rad/s^2. Paper eq. 21.
  double spin_decel = 22.0;
  /// Gravitational acceleration. m/s^2.
  double g = 9.81;
};

/// How the ball-ball sliding friction coefficient is obtained.
enum class BallBallFrictionLaw {
  /// mu_bb is the constant `mu_bb` (paper: 0.05, fitted to its Fig. 4).
  kConstant,
  /// mu_bb = 9.951e-3 + 0.108 exp(-1.088 s), s the slip speed at A in m/s
  /// (Marlow 1994, quoted in paper section 2.4.2), evaluated along the impact.
  kMarlow,
  /// mu_bb = a + b exp(-c s) with a = `mu_bb`, b = `slip_gain`, c = `slip_decay`:
  /// the family both laws above belong to (constant: b = 0; Marlow: its three
  /// numbers), for a law fitted to a table's measured throw (calibration).
  kExponential,
  /// mu_bb = a + b exp(-c v_n), the same three numbers, with v_n the normal
  /// approach speed at first contact (m/s) in place of the slip speed: one
  /// coefficient for the whole impact, lower the harder the balls meet. The two
  /// forms agree on a stun shot at a 45 deg cut, where slip and normal speeds are
  /// equal at first contact, and differ at other cuts (docs/calibration.md).
  kExponentialImpactSpeed,
};

/// Ball-ball contact.
struct BallBallParams {
  /// Ball-ball sliding friction coefficient (kConstant law). Paper: 0.05.
  double mu_bb = 0.05;
  /// Energetic coefficient of restitution (Stronge). Paper: 0.89.
  double e = 0.89;
  BallBallFrictionLaw friction_law = BallBallFrictionLaw::kConstant;
  /// kExponential's and kExponentialImpactSpeed's b (dimensionless) and c (s/m).
  double slip_gain = 0;
  double slip_decay = 0;
};

/// The ball-ball friction law as mu(s) = a + b exp(-c s), whichever law is chosen
/// (s the impact speed for kExponentialImpactSpeed, the slip speed otherwise).
struct FrictionCurve {
  double a = 0, b = 0, c = 0;
};

inline FrictionCurve FrictionCurveOf(const BallBallParams& p) {
  switch (p.friction_law) {
    case BallBallFrictionLaw::kMarlow: return {9.951e-3, 0.108, 1.088};
    case BallBallFrictionLaw::kExponential:
    case BallBallFrictionLaw::kExponentialImpactSpeed: return {p.mu_bb, p.slip_gain, p.slip_decay};
    case BallBallFrictionLaw::kConstant: break;
  }
  return {p.mu_bb, 0, 0};
}

/// Is `law` one of the two exponential forms, whose three numbers are free?
inline bool IsExponentialLaw(BallBallFrictionLaw law) {
  return law == BallBallFrictionLaw::kExponential || law == BallBallFrictionLaw::kExponentialImpactSpeed;
}

/// Whether an exponential law's b and c are in their ranges (limits::kSlipGain,
/// kSlipDecay) with mu at zero speed, mu_bb + b, a friction coefficient; mu_bb's own
/// range is checked apart. No allocation: the impact solver asks on every call.
inline bool ExponentialLawInRange(double mu_bb, double slip_gain, double slip_decay) {
  return limits::kSlipGain.Contains(slip_gain) && limits::kFrictionCoefficient.Contains(mu_bb + slip_gain) &&
         limits::kSlipDecay.Contains(slip_decay);
}

/// `p` with the law mu = f.a + f.b exp(-f.c s) in the form `law` (kExponential, or
/// kExponentialImpactSpeed), the inverse of FrictionCurveOf; e is kept.
inline BallBallParams WithFrictionCurve(BallBallParams p, const FrictionCurve& f,
                                        BallBallFrictionLaw law = BallBallFrictionLaw::kExponential) {
  p.friction_law = IsExponentialLaw(law) ? law : BallBallFrictionLaw::kExponential;
  p.mu_bb = f.a;
  p.slip_gain = f.b;
  p.slip_decay = f.c;
  return p;
}

/// The law an impact that starts at normal approach speed `v_n` (m/s) integrates:
/// kExponentialImpactSpeed becomes the constant coefficient it gives at v_n; the
/// others are returned as they are.
inline BallBallParams AtImpactSpeed(BallBallParams p, double v_n) {
  if (p.friction_law != BallBallFrictionLaw::kExponentialImpactSpeed) return p;
  p.mu_bb += p.slip_gain * std::exp(-p.slip_decay * v_n);
  p.friction_law = BallBallFrictionLaw::kConstant;
  p.slip_gain = 0;
  p.slip_decay = 0;
  return p;
}

/// Ball-ball friction coefficient at slip speed `s` (m/s); for
/// kExponentialImpactSpeed, `s` is the impact speed (see AtImpactSpeed).
inline double BallBallFriction(const BallBallParams& p, double s) {
  if (p.friction_law == BallBallFrictionLaw::kConstant) return p.mu_bb;
  const FrictionCurve f = FrictionCurveOf(p);
  return f.a + f.b * std::exp(-f.c * s);
}

/// d mu / d s at slip speed `s` (s/m): 0 for the constant law.
inline double BallBallFrictionSlope(const BallBallParams& p, double s) {
  if (p.friction_law == BallBallFrictionLaw::kConstant) return 0;
  const FrictionCurve f = FrictionCurveOf(p);
  return -f.b * f.c * std::exp(-f.c * s);
}

/// Checks parameters where they enter the library. Returns an empty string when
/// valid, otherwise a message that names the bad value.
std::string ValidateBallParams(const BallParams& p);
/// ValidateBallParams' rule without its message, for the solvers' every call: mass and
/// radius in limits::kBallMass and kBallRadius (beyond them an impact's impulse, M v,
/// and its inverse mass can overflow).
bool BallParamsValid(const BallParams& p);
std::string ValidateClothParams(const ClothParams& p);
std::string ValidateBallBallParams(const BallBallParams& p);

}  // namespace snooker::physics
