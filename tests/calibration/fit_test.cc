// Tests of calibration/fit.h: each group's parameters are found again from data
// the simulator made with known, non-default values plus noise, within stated
// bounds and within a few of their own standard uncertainties; data that cannot
// identify a group are refused with the reason; Alciatore's throw data give a
// throw that falls with speed; the fit is deterministic.
#include "calibration/fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "calibration/datasets.h"
#include "calibration/record.h"
#include "physics/core/splitmix64.h"
#include "tests/support/thread_limit.h"

namespace snooker::calibration {
namespace {

constexpr double kR = 0.02625;

// Seeded Gaussian noise for the tests' own data (SplitMix64, Box-Muller).
class Noise {
 public:
  explicit Noise(std::uint64_t seed) : s_(seed) {}
  double Uniform() { return physics::UnitInterval(physics::SplitMix64(s_)); }
  double Normal(double sigma) {
    return sigma * std::sqrt(-2 * std::log(1 - Uniform())) * std::cos(2 * physics::kPi * Uniform());
  }

 private:
  std::uint64_t s_;
};

physics::Model WithLaw(double a, double b, double c) {
  physics::Model m;
  m.ball_ball = physics::WithFrictionCurve(m.ball_ball, {a, b, c});
  return m;
}

// Throws of `world` over cuts, speeds and spins, with 0.1 deg of noise.
std::vector<ThrowObservation> ThrowsOf(const physics::Model& world) {
  Noise noise(3);
  std::vector<ThrowObservation> out;
  for (double cut : {25.0, 40.0, 55.0, 70.0}) {
    for (double v : {0.4, 0.9, 1.6, 2.6, 4.0}) {
      for (double roll : {0.0, 1.0}) {
        ThrowObservation o;
        o.cut = physics::DegToRad(cut);
        o.cue_ball_speed = v;
        o.topspin = roll * v / kR;
        o.measured_throw = PredictThrow(o, world).throw_angle + noise.Normal(physics::DegToRad(0.1));
        out.push_back(o);
      }
    }
  }
  return out;
}

// Rebounds of `world` over speeds, angles and side, with 0.01 m/s and 0.5 deg of
// noise.
std::vector<CushionObservation> ReboundsOf(const physics::Model& world) {
  Noise noise(4);
  std::vector<CushionObservation> out;
  for (double v : {0.35, 0.6, 0.9, 1.3, 1.8, 2.3, 2.8, 3.3}) {
    for (double angle : {35.0, 60.0, 90.0}) {
      for (double side : {-0.5, 0.0, 0.5}) {
        CushionObservation o;
        o.speed = v;
        o.angle = physics::DegToRad(angle);
        o.topspin = v / kR;
        o.sidespin = side * v / kR;
        const ReboundPrediction p = PredictRebound(o, world);
        o.rebound_speed = p.speed + noise.Normal(0.01);
        o.rebound_angle = p.angle + noise.Normal(physics::DegToRad(0.5));
        out.push_back(o);
      }
    }
  }
  return out;
}

struct Truth {
  const char* name;  // the parameter's
  double value;
  double bound;  // the stated bound on |fitted - value|
};

struct IdentifiabilityCase {
  const char* name;
  Group group;
  std::function<physics::Model()> world;
  std::function<Observations(const physics::Model&)> data;
  FitOptions options;
  std::vector<Truth> truth;
};

// gtest prints a parameter with this (not as bytes).
void PrintTo(const IdentifiabilityCase& c, std::ostream* os) { *os << c.name; }

Observations Tracked(const physics::Model& world, int shots) {
  Observations o;
  o.shots = Record(world, shots, 17, 1e-3);
  return o;
}

physics::Model CushionWorld() {
  physics::Model m;
  m.cushion.mu_w = 0.18;
  for (double& e : m.cushion.restitution_curve.e) e = std::min(0.97, e - 0.03);
  return m;
}

physics::Model ClothWorld() {
  physics::Model m;
  m.cloth.mu_s = 0.24;
  m.cloth.mu_r = 0.0150;
  m.cloth.spin_decel = 18;
  return m;
}

physics::Model CueWorld() {
  physics::Model m;
  m.cue.end_mass = 0.009;
  m.cue.tip_restitution = 0.78;
  return m;
}

FitOptions Sigmas(double throw_deg, double speed, double angle_deg) {
  FitOptions o;
  o.throw_sigma = physics::DegToRad(throw_deg);
  o.rebound_speed_sigma = speed;
  o.rebound_angle_sigma = physics::DegToRad(angle_deg);
  return o;
}

std::vector<Truth> CushionTruth() {
  const physics::Model w = CushionWorld();
  std::vector<Truth> t = {{"cushion.mu_w", 0.18, 0.01}};
  static const char* kKnots[] = {"cushion.restitution_curve.e[0]", "cushion.restitution_curve.e[1]",
                                 "cushion.restitution_curve.e[2]", "cushion.restitution_curve.e[3]",
                                 "cushion.restitution_curve.e[4]", "cushion.restitution_curve.e[5]",
                                 "cushion.restitution_curve.e[6]"};
  for (int k = 0; k < w.cushion.restitution_curve.points; ++k) {
    t.push_back({kKnots[k], w.cushion.restitution_curve.e[static_cast<std::size_t>(k)], 0.02});
  }
  return t;
}

const IdentifiabilityCase kCases[] = {
    {"BallBallFromThrows", Group::kBallBall, [] { return WithLaw(0.01, 0.12, 0.8); },
     [](const physics::Model& w) {
       Observations o;
       o.throws = ThrowsOf(w);
       return o;
     },
     Sigmas(0.1, 0.02, 1), {{"ball_ball.mu_bb", 0.01, 0.003}, {"ball_ball.slip_gain", 0.12, 0.01},
                            {"ball_ball.slip_decay", 0.8, 0.1}}},
    {"CushionFromRebounds", Group::kCushion, CushionWorld,
     [](const physics::Model& w) {
       Observations o;
       o.rebounds = ReboundsOf(w);
       return o;
     },
     Sigmas(0.25, 0.01, 0.5), CushionTruth()},
    {"ClothFromTrackedShots", Group::kCloth, ClothWorld, [](const physics::Model& w) { return Tracked(w, 12); },
     FitOptions{}, {{"cloth.mu_s", 0.24, 0.003}, {"cloth.mu_r", 0.0150, 0.0003}, {"cloth.spin_decel", 18, 1.0}}},
    {"BallBallFromTrackedShots", Group::kBallBall, [] { return WithLaw(0.01, 0.12, 0.8); },
     [](const physics::Model& w) { return Tracked(w, 12); }, FitOptions{},
     {{"ball_ball.mu_bb", 0.01, 0.003}, {"ball_ball.slip_gain", 0.12, 0.01}, {"ball_ball.slip_decay", 0.8, 0.1}}},
    {"CueFromTrackedShots", Group::kCue, CueWorld, [](const physics::Model& w) { return Tracked(w, 12); },
     FitOptions{}, {{"cue.end_mass", 0.009, 0.0005}, {"cue.tip_restitution", 0.78, 0.01}}},
};

class Identifiability : public testing::TestWithParam<IdentifiabilityCase> {};

// From the default model, the world's values within the stated bounds and within
// 3.5 standard uncertainties (the uncertainty covers the truth), the residuals
// down to the noise.
TEST_P(Identifiability, FitFindsTheWorldAgain) {
  const IdentifiabilityCase& c = GetParam();
  const physics::Model world = c.world();
  const Observations data = c.data(world);
  const Group groups[] = {c.group};
  const FitResult r = Fit(data, groups, physics::Model{}, c.options);
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(r.parameters.size(), c.truth.size()) << r.status;
  for (std::size_t k = 0; k < c.truth.size(); ++k) {
    const ParameterEstimate& p = r.parameters[k];
    ASSERT_EQ(p.name, c.truth[k].name);
    EXPECT_NEAR(p.fitted, c.truth[k].value, c.truth[k].bound) << p.name << " +- " << p.uncertainty;
    EXPECT_TRUE(std::isfinite(p.uncertainty)) << p.name;
    EXPECT_LE(std::abs(p.fitted - c.truth[k].value), 3.5 * p.uncertainty + 1e-12) << p.name << " +- "
                                                                                   << p.uncertainty;
  }
  EXPECT_LT(r.reduced_chi_square, 1.5) << r.status;
}

INSTANTIATE_TEST_SUITE_P(Groups, Identifiability, testing::ValuesIn(kCases),
                         [](const testing::TestParamInfo<IdentifiabilityCase>& p) {
                           return std::string(p.param.name);
                         });

TEST(FitTest, AlciatoresThrowGivesThrowFallingWithSpeed) {
  Observations o;
  o.throws = AlciatoreStunThrow45();
  const Group groups[] = {Group::kBallBall};
  const FitResult r = Fit(o, groups, physics::Model{});
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.model.ball_ball.friction_law, physics::BallBallFrictionLaw::kExponential);
  EXPECT_EQ(r.throw_deg.count, 8);
  EXPECT_GT(r.throw_deg.rms_before, 1.5);  // the constant law's throw does not fall
  EXPECT_LT(r.throw_deg.rms_after, 0.4);
  auto throw_deg = [&](double object_speed) {
    ThrowObservation t = o.throws[0];
    t.object_ball_speed = object_speed;
    return physics::RadToDeg(PredictThrow(t, r.model).throw_angle);
  };
  EXPECT_GT(throw_deg(0.35) - throw_deg(1.75), 3.0);
  for (double v = 0.35; v < 1.75; v += 0.1) EXPECT_GT(throw_deg(v), throw_deg(v + 0.1)) << v;
  for (const ThrowObservation& t : o.throws) {
    EXPECT_NEAR(throw_deg(*t.object_ball_speed), physics::RadToDeg(t.measured_throw), 0.6);
  }
  // SimToRealWorld carries this law.
  EXPECT_NEAR(r.model.ball_ball.mu_bb, kSimToRealThrowLaw.a, 1e-3);
  EXPECT_NEAR(r.model.ball_ball.slip_gain, kSimToRealThrowLaw.b, 2e-3);
  EXPECT_NEAR(r.model.ball_ball.slip_decay, kSimToRealThrowLaw.c, 2e-2);
}

// Mean |predicted - measured| throw, deg, of `model` on `data`.
double MeanThrowErrorDeg(const std::vector<ThrowObservation>& data, const physics::Model& model) {
  double sum = 0;
  for (const ThrowObservation& t : data) {
    sum += std::abs(physics::RadToDeg(PredictThrow(t, model).throw_angle - t.measured_throw));
  }
  return sum / static_cast<double>(data.size());
}

// The law's two forms fitted to the 45 deg data, judged on the 30 deg curve's ends:
// both fit 45 deg, and only the impact-speed form predicts 30 deg within 1 deg on
// average (the slip form sticks at 30 deg, its fast end at the geared limit).
TEST(FitTest, TheImpactSpeedFormPredictsThirtyDegreesWithinOneDegree) {
  Observations o;
  o.throws = AlciatoreStunThrow45();
  const Group groups[] = {Group::kBallBall};
  physics::Model start;
  start.ball_ball.friction_law = physics::BallBallFrictionLaw::kExponentialImpactSpeed;
  const FitResult impact = Fit(o, groups, start);
  const FitResult slip = Fit(o, groups, physics::Model{});
  ASSERT_EQ(impact.error, "");
  ASSERT_EQ(slip.error, "");
  EXPECT_EQ(impact.model.ball_ball.friction_law, physics::BallBallFrictionLaw::kExponentialImpactSpeed);
  EXPECT_EQ(slip.model.ball_ball.friction_law, physics::BallBallFrictionLaw::kExponential);
  EXPECT_LT(impact.throw_deg.rms_after, 0.45);
  EXPECT_LT(slip.throw_deg.rms_after, 0.45);
  const std::vector<ThrowObservation> ends = AlciatoreStunThrow30Ends();
  EXPECT_LT(MeanThrowErrorDeg(ends, impact.model), 1.0);
  EXPECT_GT(MeanThrowErrorDeg(ends, slip.model), 1.0);
  // The slow end is above the geared limit atan(2 tan(cut) / (7 (1 + e))) for
  // both: no friction reaches it.
  const double geared = physics::RadToDeg(std::atan(2 * std::tan(ends[0].cut) / (7 * (1 + 0.89))));
  EXPECT_NEAR(physics::RadToDeg(PredictThrow(ends[0], impact.model).throw_angle), geared, 0.02);
  EXPECT_GT(physics::RadToDeg(ends[0].measured_throw), geared + 0.5);
}

// Throws made with an impact-speed law are fitted back to it from a start in that form.
TEST(FitTest, FindsAnImpactSpeedLawAgainFromThrows) {
  physics::Model world;
  world.ball_ball = physics::WithFrictionCurve(world.ball_ball, {0.01, 0.12, 0.8},
                                               physics::BallBallFrictionLaw::kExponentialImpactSpeed);
  Observations o;
  o.throws = ThrowsOf(world);
  physics::Model start;
  start.ball_ball.friction_law = physics::BallBallFrictionLaw::kExponentialImpactSpeed;
  const Group groups[] = {Group::kBallBall};
  const FitResult r = Fit(o, groups, start, Sigmas(0.1, 0.02, 1));
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.model.ball_ball.friction_law, physics::BallBallFrictionLaw::kExponentialImpactSpeed);
  EXPECT_NEAR(r.model.ball_ball.mu_bb, 0.01, 0.003);
  EXPECT_NEAR(r.model.ball_ball.slip_gain, 0.12, 0.01);
  EXPECT_NEAR(r.model.ball_ball.slip_decay, 0.8, 0.1);
  EXPECT_LT(r.reduced_chi_square, 1.5);
}

TEST(FitTest, SimToRealWorldIsValidAndDiffersWhereStated) {
  const physics::Model w = SimToRealWorld(), d;
  EXPECT_EQ(physics::ValidateModel(w), "");
  EXPECT_EQ(w.ball_ball.friction_law, physics::BallBallFrictionLaw::kExponential);
  EXPECT_DOUBLE_EQ(w.cloth.mu_s, 1.2 * d.cloth.mu_s);
  EXPECT_DOUBLE_EQ(w.cloth.mu_r, 1.2 * d.cloth.mu_r);
  EXPECT_EQ(w.cue.end_mass, 0.009);
  EXPECT_EQ(w.cushion.mu_w, d.cushion.mu_w);
}

// The cloth fit of six tracked shots, at most 120 evaluations, on `threads` threads.
FitResult ClothFit(int threads) {
  const Observations data = Tracked(ClothWorld(), 6);
  const Group groups[] = {Group::kCloth};
  FitOptions options;
  options.threads = threads;
  options.max_evaluations = 120;
  return Fit(data, groups, physics::Model{}, options);
}

// The same data and start give the same fit, on one thread or two.
TEST(FitTest, IsDeterministic) {
  const FitResult a = ClothFit(1), b = ClothFit(2);
  ASSERT_EQ(a.error, "");
  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  for (std::size_t k = 0; k < a.parameters.size(); ++k) {
    EXPECT_EQ(a.parameters[k].fitted, b.parameters[k].fitted);
    EXPECT_EQ(a.parameters[k].uncertainty, b.parameters[k].uncertainty);
  }
  EXPECT_EQ(a.evaluations, b.evaluations);
  EXPECT_EQ(a.position.rms_after, b.position.rms_after);
  EXPECT_LT(a.position.rms_after, a.position.rms_before);
}

// A fit asked for four threads, in a copy of this test where the system starts
// only `spare` more: every shot is predicted all the same (the caller takes the
// shares of the threads that did not start) and the fit is the one-thread fit to the
// bit. Before, the thread that could not start threw past the one running: with one
// to spare, an abort.
void ExpectTheOneThreadFitWith(int spare) {
  const test_support::LimitedRun run = test_support::RunWithSpareThreads(spare, [](std::string* out) {
    const FitResult a = ClothFit(1), b = ClothFit(4);
    bool same = a.error.empty() && b.error.empty() && a.parameters.size() == b.parameters.size() &&
                a.evaluations == b.evaluations && a.position.rms_after == b.position.rms_after;
    for (std::size_t k = 0; same && k < a.parameters.size(); ++k) {
      same = a.parameters[k].fitted == b.parameters[k].fitted;
    }
    *out = same ? "same" : "differs: " + a.error + " | " + b.error;
    return 0;
  });
  if (!run.limited) GTEST_SKIP() << run.output;
  EXPECT_EQ(run.signal, 0);
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output, "same");
}

TEST(FitTest, WithNoThreadToSpareTheFitIsTheSame) { ExpectTheOneThreadFitWith(0); }

TEST(FitTest, WithOneThreadToSpareTheFitIsTheSame) { ExpectTheOneThreadFitWith(1); }

struct RefusalCase {
  const char* name;
  std::vector<Group> groups;
  std::function<Observations()> data;
  const char* reason;  // a part of FitResult::error
};

// gtest prints a parameter with this (not as bytes).
void PrintTo(const RefusalCase& c, std::ostream* os) { *os << c.name; }

Observations Alciatore() {
  Observations o;
  o.throws = AlciatoreStunThrow45();
  return o;
}

// Recorded shots with the strike changed by `change`.
Observations ShotsWith(const std::function<void(TrackedShot*)>& change) {
  Observations o = Tracked(physics::Model{}, 3);
  for (TrackedShot& s : o.shots) change(&s);
  return o;
}

const RefusalCase kRefusals[] = {
    {"ClothFromThrowsOnly", {Group::kCloth}, Alciatore,
     "cloth: no tracked shots; throw observations do not depend on mu_s, mu_r or spin_decel"},
    {"CushionWithoutRebounds", {Group::kCushion}, Alciatore, "cushion: no rebound observations"},
    {"CueFromBallFormShots", {Group::kCue},
     [] { return ShotsWith([](TrackedShot* s) { s->strike = physics::Shot{1.0, 0.3, 0, 0, 0}; }); },
     "cue: no tracked shots struck in the cue's terms"},
    {"CueWithoutSide", {Group::kCue},
     [] { return ShotsWith([](TrackedShot* s) { std::get<physics::CueStrike>(s->strike).side = 0; }); },
     "cue: no tracked shot struck with side"},
    {"BallBallFromRebounds", {Group::kBallBall},
     [] {
       Observations o;
       o.rebounds = ReboundsOf(physics::Model{});
       return o;
     },
     "ball-ball: no throw observations and no tracked shot with an object ball"},
    {"FewerResidualsThanParameters", {Group::kBallBall},
     [] {
       Observations o = Alciatore();
       o.throws.resize(2);
       return o;
     },
     "2 residuals for 3 parameters"},
    {"OneSpeedOneCut", {Group::kBallBall},
     [] {
       // Four repeats of one collision: one number, three parameters.
       Observations o = Alciatore();
       o.throws.resize(4);
       for (ThrowObservation& t : o.throws) t.object_ball_speed = 1.0;
       return o;
     },
     "the data do not identify"},
    {"FullBallThrows", {Group::kBallBall},
     [] {
       // A full-ball hit throws nothing whatever the friction.
       Observations o = Alciatore();
       for (ThrowObservation& t : o.throws) {
         t.cut = 0;
         t.measured_throw = 0;
       }
       return o;
     },
     "the data do not identify"},
    {"InvalidObservations", {Group::kBallBall},
     [] {
       Observations o = Alciatore();
       o.throws[3].object_ball_speed = NAN;
       return o;
     },
     "observations: throw[3].object_ball_speed = nan"},
    {"NoGroup", {}, Alciatore, "no group to fit"},
};

class Refusal : public testing::TestWithParam<RefusalCase> {};

TEST_P(Refusal, SaysWhyAndFitsNothing) {
  const RefusalCase& c = GetParam();
  const physics::Model start;
  const FitResult r = Fit(c.data(), c.groups, start);
  EXPECT_NE(r.error.find(c.reason), std::string::npos) << r.error;
  EXPECT_TRUE(r.parameters.empty());
  EXPECT_TRUE(physics::SameModel(r.model, start));
}

INSTANTIATE_TEST_SUITE_P(Cases, Refusal, testing::ValuesIn(kRefusals),
                         [](const testing::TestParamInfo<RefusalCase>& p) { return std::string(p.param.name); });

TEST(FitTest, BadOptionsAreNamed) {
  const Group groups[] = {Group::kBallBall};
  FitOptions o;
  o.throw_sigma = 0;
  EXPECT_NE(Fit(Alciatore(), groups, physics::Model{}, o).error.find("options.throw_sigma = 0"), std::string::npos);
  o = FitOptions{};
  o.horizons = {1.0, 0.5};
  EXPECT_NE(Fit(Alciatore(), groups, physics::Model{}, o).error.find("options.horizons[1] = 0.5"), std::string::npos);
}

TEST(FitTest, TheUnidentifiedDirectionIsNamed) {
  Observations o = Alciatore();
  for (ThrowObservation& t : o.throws) t.cut = 0;
  const Group groups[] = {Group::kBallBall};
  const FitResult r = Fit(o, groups, physics::Model{});
  EXPECT_NE(r.error.find("ball_ball."), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("smallest eigenvalue"), std::string::npos) << r.error;
}

TEST(ParseGroupsTest, NamesAreReadAndBadOnesNamed) {
  const ParsedGroups a = ParseGroups("ball-ball,cloth");
  EXPECT_EQ(a.error, "");
  EXPECT_EQ(a.groups, (std::vector<Group>{Group::kBallBall, Group::kCloth}));
  const ParsedGroups b = ParseGroups(" cue , cushion,cue");
  EXPECT_EQ(b.error, "");
  EXPECT_EQ(b.groups, (std::vector<Group>{Group::kCue, Group::kCushion}));
  const ParsedGroups c = ParseGroups("ball-ball,clth");
  EXPECT_NE(c.error.find("\"clth\""), std::string::npos) << c.error;
  EXPECT_TRUE(c.groups.empty());
  EXPECT_NE(ParseGroups("").error.find("unknown group \"\""), std::string::npos);
  for (Group g : {Group::kBallBall, Group::kCushion, Group::kCloth, Group::kCue}) {
    EXPECT_EQ(ParseGroups(ToString(g)).groups, std::vector<Group>{g});
  }
}

// The parameters a fit would take, with their start values: the constant law
// starts as Marlow's; cushion knots only where rebounds are.
TEST(FittedParametersTest, ListsWhatTheDataCover) {
  std::vector<double> values;
  const Group bb[] = {Group::kBallBall};
  const std::vector<ParameterSpec> law = FittedParameters(bb, Alciatore(), physics::Model{}, &values);
  ASSERT_EQ(law.size(), 3u);
  EXPECT_EQ(values, (std::vector<double>{9.951e-3, 0.108, 1.088}));
  Observations slow;
  for (double v : {0.3, 0.35, 0.4}) slow.rebounds.push_back({v, physics::kPi / 2, v / kR, 0, 0.8 * v, {}});
  const Group cushion[] = {Group::kCushion};
  const std::vector<ParameterSpec> knots = FittedParameters(cushion, slow, physics::Model{});
  ASSERT_EQ(knots.size(), 3u);  // mu_w, and the knots at 0.3 and 0.5 m/s
  EXPECT_EQ(knots[0].name, "cushion.mu_w");
  EXPECT_EQ(knots[1].name, "cushion.restitution_curve.e[0]");
  EXPECT_EQ(knots[2].name, "cushion.restitution_curve.e[1]");
  for (const ParameterSpec& p : knots) EXPECT_LT(p.lo, p.hi);
}

}  // namespace
}  // namespace snooker::calibration
