// impact_stress: the adaptive impact solvers' work over seeded random impacts, for
// docs/impact-stress.md (scripts/impact-stress). Two domains: the snooker shots the
// planner meets (the default parameters, speeds to 8 m/s, spins to 300 rad/s) and
// anything the parameter checks accept (speeds to 20 m/s, spins to 1000 rad/s, any
// valid friction, restitution and cushion height, half the ball-ball impacts at the
// friction corner mu_bb = mu_s = 1). For each solver and tolerance (the planner's
// search tier and the default) it counts the impacts that reached the step cap and the
// largest step count of the others, and prints the first capped input in full so
// that it can be replayed.
//
// Usage: impact_stress [--seed S] [--impacts N]
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <system_error>
#include <vector>

#include "physics/impact/ball_ball.h"
#include "physics/impact/ball_cushion.h"

namespace {

using namespace snooker::physics;

struct Tally {
  long impacts = 0, ok = 0, capped = 0;
  int worst_steps = 0;  // accepted + rejected, over the impacts that finished
  double rhs = 0;       // right-hand sides, summed over every impact
  std::string first_cap;
};

struct Domain {
  const char* name;
  double speed, spin;  // m/s, rad/s: uniform within +-
  bool any_parameters;
};

class Sampler {
 public:
  explicit Sampler(std::uint64_t seed) : rng_(seed) {}
  double U() { return std::uniform_real_distribution<double>(0, 1)(rng_); }
  double Sym(double bound) { return bound * (2 * U() - 1); }
  // A velocity towards +y (the other ball or the cushion) of speed up to `speed`.
  Vec3 Towards(double speed) {
    const double s = speed * U(), a = 3.14159265358979 * U();
    return Vec3(s * std::cos(a), s * std::sin(a), 0);
  }
  Vec3 Spin(double bound) { return Vec3(Sym(bound), Sym(bound), Sym(bound)); }

 private:
  std::mt19937_64 rng_;
};

std::string Describe(const char* what, const Vec3& v, const Vec3& w) {
  char b[256];
  std::snprintf(b, sizeof b, "%s v (%.17g, %.17g, %.17g) w (%.17g, %.17g, %.17g)", what, v.x(), v.y(), v.z(), w.x(),
                w.y(), w.z());
  return b;
}

void Count(Tally* t, ImpactStatus status, const ImpulseWork& work, const std::string& input) {
  ++t->impacts;
  t->rhs += work.rhs_evals;
  if (status == ImpactStatus::kStepLimit) {
    if (t->capped++ == 0) t->first_cap = input;
  } else if (status == ImpactStatus::kOk) {
    ++t->ok;
    t->worst_steps = std::max(t->worst_steps, work.steps + work.rejected_steps);
  }
}

ImpulseSolverOptions Tier(int k) {
  ImpulseSolverOptions o;
  if (k == 0) o.fidelity = ImpulseFidelity::kSearch;
  return o;
}

// One domain: `n` ball-ball and `n` cushion impacts, each solved at both tiers.
void Run(const Domain& d, long n, std::uint64_t seed, Tally bb[2], Tally cu[2]) {
  Sampler s(seed);
  const BallParams ball;
  for (long i = 0; i < n; ++i) {
    ImpactState in;
    in.c.v = s.Towards(d.speed);
    in.c.w = s.Spin(d.spin);
    BallBallParams contact;
    double mu_s = 0.2;
    if (d.any_parameters) {
      const bool corner = s.U() < 0.5;
      contact.mu_bb = corner ? 1 - 1e-8 * s.U() : s.U();
      contact.e = s.U();
      mu_s = corner ? 1 - 1e-8 * s.U() : s.U();
    }
    char p[160];
    std::snprintf(p, sizeof p, "; mu_bb %.17g e %.17g mu_s %.17g", contact.mu_bb, contact.e, mu_s);
    for (int k = 0; k < 2; ++k) {
      const ImpactResult r = ResolveImpact(in, ball, contact, mu_s, Tier(k));
      Count(&bb[k], r.status, r.work, Describe("C", in.c.v, in.c.w) + p);
    }

    BallMotion m{s.Towards(d.speed), s.Spin(d.spin)};
    CushionParams cushion;
    if (d.any_parameters) {
      for (int tries = 0; tries < 100; ++tries) {  // any parameters the checks accept
        cushion.e_e = s.U();
        cushion.mu_w = 0.5 * s.U();
        cushion.mu_s = s.U();
        cushion.contact_height = ball.radius * (1 + s.U());
        if (ValidateCushionParams(ball, cushion).empty()) break;
        cushion = CushionParams{};
      }
    }
    std::snprintf(p, sizeof p, "; e_e %.17g mu_w %.17g mu_s %.17g h %.17g m", cushion.e_e, cushion.mu_w,
                  cushion.mu_s, cushion.contact_height);
    for (int k = 0; k < 2; ++k) {
      const CushionImpactResult r = ResolveCushionImpact(m, ball, cushion, Tier(k));
      Count(&cu[k], r.status, r.work, Describe("ball", m.v, m.w) + p);
    }
  }
}

}  // namespace

// The whole of `text` as an unsigned number, or false.
bool Parse(const char* text, std::uint64_t* out) {
  const char* end = text + std::strlen(text);
  const auto [p, ec] = std::from_chars(text, end, *out);
  return ec == std::errc() && p == end && p != text;
}

int main(int argc, char** argv) {
  std::uint64_t seed = 1, impacts = 200000;
  for (int i = 1; i < argc; i += 2) {
    const bool known = std::strcmp(argv[i], "--seed") == 0 || std::strcmp(argv[i], "--impacts") == 0;
    if (!known || i + 1 >= argc) {
      std::fprintf(stderr, "impact_stress: '%s' %s (usage: impact_stress [--seed S] [--impacts N])\n", argv[i],
                   known ? "needs a value" : "is not a flag");
      return 2;
    }
    std::uint64_t* target = std::strcmp(argv[i], "--seed") == 0 ? &seed : &impacts;
    if (!Parse(argv[i + 1], target) || (target == &impacts && (impacts == 0 || impacts > 1'000'000'000))) {
      std::fprintf(stderr, "impact_stress: %s '%s' is not a whole number%s\n", argv[i], argv[i + 1],
                   target == &impacts ? " in [1, 1000000000]" : "");
      return 2;
    }
  }
  const Domain domains[] = {{"snooker shots (default parameters, to 8 m/s, 300 rad/s)", 8, 300, false},
                            {"any valid parameters (to 20 m/s, 1000 rad/s)", 20, 1000, true}};
  const ImpulseSolverOptions defaults;
  std::printf("| domain | solver | tolerance | impacts | at the step cap (%d) | most steps otherwise | "
              "right-hand sides, mean |\n|---|---|---|---:|---:|---:|---:|\n",
              defaults.max_steps);
  std::vector<std::string> caps;
  std::uint64_t domain_seed = seed;
  for (const Domain& d : domains) {
    Tally bb[2], cu[2];
    Run(d, static_cast<long>(impacts), domain_seed++, bb, cu);
    for (int solver = 0; solver < 2; ++solver) {
      for (int k = 0; k < 2; ++k) {
        const Tally& t = solver == 0 ? bb[k] : cu[k];
        const char* name = solver == 0 ? "ball-ball" : "ball-cushion";
        const char* tier = k == 0 ? "search (1e-6)" : "default (1e-10)";
        std::printf("| %s | %s | %s | %ld | %ld | %d | %.1f |\n", d.name, name, tier, t.impacts, t.capped,
                    t.worst_steps, t.rhs / static_cast<double>(t.impacts));
        if (t.capped > 0) caps.push_back(std::string(name) + ", " + tier + ": " + t.first_cap);
      }
    }
  }
  if (!caps.empty()) {
    std::printf("\nThe first impact of each row that reached the cap:\n\n");
    for (const std::string& c : caps) std::printf("- %s\n", c.c_str());
  }
  return 0;
}
