#include "physics/core/params.h"

#include <cmath>
#include <sstream>

#include "physics/core/limits.h"

namespace snooker::physics {
namespace {

// Appends "name = value (must be ...)" when `ok` is false.
void Check(std::ostringstream& out, bool ok, const char* name, double value, const char* rule) {
  if (ok) return;
  if (out.tellp() > 0) out << "; ";
  out << name << " = " << value << " (must be " << rule << ")";
}

}  // namespace

std::string ValidateBallParams(const BallParams& p) {
  std::ostringstream out;
  if (!limits::kBallMass.Contains(p.mass)) {
    if (out.tellp() > 0) out << "; ";
    out << "mass = " << p.mass << " (must be in [" << limits::kBallMass.lo << ", " << limits::kBallMass.hi
        << "] kg)";
  }
  if (!limits::kBallRadius.Contains(p.radius)) {
    if (out.tellp() > 0) out << "; ";
    out << "radius = " << p.radius << " (must be in [" << limits::kBallRadius.lo << ", "
        << limits::kBallRadius.hi << "] m)";
  }
  return out.str();
}

bool BallParamsValid(const BallParams& p) {
  return limits::kBallMass.Contains(p.mass) && limits::kBallRadius.Contains(p.radius);
}

std::string ValidateClothParams(const ClothParams& p) {
  std::ostringstream out;
  Check(out, limits::kClothSlideFriction.Contains(p.mu_s), "mu_s", p.mu_s, "in [0.01, 1]");
  Check(out, limits::kRollingResistance.Contains(p.mu_r), "mu_r", p.mu_r, "in [0.001, 1]");
  Check(out, limits::kSpinDecel.Contains(p.spin_decel), "spin_decel", p.spin_decel, "in [0, 10000] rad/s^2");
  Check(out, limits::kGravity.Contains(p.g), "g", p.g, "in [0.1, 100] m/s^2");
  return out.str();
}

std::string ValidateBallBallParams(const BallBallParams& p) {
  std::ostringstream out;
  // limits.h: mu_bb <= 1 with mu_s <= 1 bounds the impulse and the step count.
  Check(out, limits::kFrictionCoefficient.Contains(p.mu_bb), "mu_bb", p.mu_bb, "in [0, 1]");
  Check(out, limits::kRestitution.Contains(p.e), "e", p.e, "in [0, 1]");
  if (IsExponentialLaw(p.friction_law)) {
    // mu(0) = a + b <= 1 keeps the same bound on the impulse as mu_bb <= 1.
    Check(out,
          limits::kSlipGain.Contains(p.slip_gain) && limits::kFrictionCoefficient.Contains(p.mu_bb + p.slip_gain),
          "slip_gain", p.slip_gain, "finite, >= 0, with mu_bb + slip_gain <= 1");
    Check(out, limits::kSlipDecay.Contains(p.slip_decay), "slip_decay", p.slip_decay, "in [0, 100] s/m");
  }
  const int law = static_cast<int>(p.friction_law);
  Check(out, law >= 0 && law <= static_cast<int>(BallBallFrictionLaw::kExponentialImpactSpeed),
        "friction_law", law, "constant, marlow, exponential or exponential in the impact speed");
  return out.str();
}

}  // namespace snooker::physics
