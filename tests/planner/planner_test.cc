// Tests of the planner facade (planner/planner.h) on hand-made and seeded tables:
// the obvious pot is found and leaves a pottable next ball, no pot gives an empty
// answer with a reason, every shot is within the robot's limits and pots in the
// planner's own full simulation, the same seed gives the same answer, progress,
// cancellation, deadlines and the budget, and bad requests are refused.
#include "planner/planner.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "planner/position.h"
#include "planner/selfplay.h"
#include "tests/planner/demo_plans.h"

namespace snooker::planner {
namespace {

using physics::PocketId;
using physics::Vec2;

const physics::TableModel& Table() { return physics::DefaultTable(); }
constexpr double kR = 0.02625;

// Deterministic work: a simulation cap that binds long before the (generous) time
// budget, even under the sanitizers.
PlanRequest Request(const TableState& t, std::int64_t sims = 400) {
  PlanRequest r;
  r.table = t;
  r.time_budget = 30;
  r.max_simulations = sims;
  r.monte_carlo_samples = 16;
  return r;
}

// A red 40 cm in front of the top-right pocket with the cue ball 40 cm straight
// behind it, the black on its spot, a red near the blue spot.
TableState ObviousPot() {
  const physics::Pocket& p = Table().pocket(PocketId::kTopRight);
  const Vec2 red = p.mouth_centre - 0.4 * p.axis;
  TableState t;
  t.balls = {{BallKind::kCue, red - 0.4 * p.axis},
             {BallKind::kRed, red},
             {BallKind::kBlack, Table().spot(physics::Colour::kBlack)},
             {BallKind::kPink, Table().spot(physics::Colour::kPink)},
             {BallKind::kRed, Vec2(0.4, 1.5)}};
  return t;
}

// Simulates a planned shot on the table exactly as planned (no noise, full
// fidelity, a fresh simulator): the planner's promise.
ShotOutcome Replay(const TableState& t, BallOn on, const PlannedShot& s, std::vector<Vec2>* finals = nullptr) {
  ShotSimulator sim(Table(), physics::SimParams{});
  const ShotSetup setup{&t, t.cue_index(), s.object_ball, s.pocket, on, s.kind,
                        s.route == PotRoute::kPlant ? s.first_ball : -1};
  ShotOutcome out = sim.Run(setup, s.shot, {}, ShotSimulator::Mode::kFull, {});
  if (finals != nullptr) {
    finals->clear();
    for (const auto& b : sim.final_balls()) finals->push_back(b.r);
  }
  return out;
}

TEST(PlannerTest, PotsTheObviousRedAndLeavesAColour) {
  const TableState t = ObviousPot();
  const PlanAnswer a = Planner::Default().Plan(Request(t));
  ASSERT_EQ(a.status, PlanStatus::kOk) << a.reason;
  ASSERT_FALSE(a.shots.empty());
  const PlannedShot& best = a.shots.front();
  EXPECT_EQ(best.object_ball, 1);
  EXPECT_EQ(best.pocket, PocketId::kTopRight);
  std::vector<Vec2> finals;
  const ShotOutcome out = Replay(t, BallOn::kRed, best, &finals);
  EXPECT_TRUE(out.success);
  EXPECT_EQ(out.object_pocket, static_cast<int>(PocketId::kTopRight));
  EXPECT_EQ(finals[0], best.cue_ball_end);
  // The cue ball ends where the next ball on (a colour) is pottable.
  ASSERT_GE(best.next_ball, 0);
  EXPECT_TRUE(IsColour(t.balls[static_cast<size_t>(best.next_ball)].kind));
  EXPECT_GT(best.position_value, 0.6);
  TableState after = ApplyShot(t, BallOn::kRed, finals, out.potted, false, Table());
  const PositionValue v = EvaluatePosition(after, BallOn::kAnyColour,
                                           Planner::Default().ContextFor(Request(after)), {});
  EXPECT_GT(v.next_probability, 0.6);
  EXPECT_GT(best.pot_probability, 0.9);
  EXPECT_GT(a.simulations, 0);
  EXPECT_GT(a.evaluations, 0);
}

// With the Gaussian fit of the pot lines in the Monte Carlo's score (off by default)
// the plan is the same kind of answer: the obvious red potted, every score finite.
TEST(PlannerTest, TheFittedPotLinesStillPotTheObviousRed) {
  const TableState t = ObviousPot();
  Planner::Config config;
  config.pot_tail_min_samples = 16;
  const PlanAnswer a = Planner(config).Plan(Request(t));
  ASSERT_EQ(a.status, PlanStatus::kOk) << a.reason;
  const PlannedShot& best = a.shots.front();
  EXPECT_EQ(best.object_ball, 1);
  EXPECT_EQ(best.pocket, PocketId::kTopRight);
  for (const PlannedShot& s : a.shots) EXPECT_TRUE(std::isfinite(s.score));
  std::vector<Vec2> finals;
  EXPECT_TRUE(Replay(t, BallOn::kRed, best, &finals).success);
}

TEST(PlannerTest, NoPossiblePotGivesAnEmptyAnswerWithAReason) {
  // The only red is surrounded by colours: every path to it is blocked.
  const Vec2 red(0.9, 2.0);
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(0.9, 0.5)}, {BallKind::kRed, red}};
  const BallKind ring[] = {BallKind::kYellow, BallKind::kGreen, BallKind::kBrown,
                           BallKind::kBlue, BallKind::kPink, BallKind::kBlack};
  for (int k = 0; k < 6; ++k) {
    const double a = k * physics::kPi / 3 + physics::kPi / 6;
    t.balls.push_back({ring[k], red + (2 * kR + 0.0005) * Vec2(std::cos(a), std::sin(a))});
  }
  // Asked for legal strokes only, the answer is empty and says why.
  PlanRequest legal = Request(t);
  legal.kinds = ShotKinds::Of(ShotKind::kPot).With(ShotKind::kSafety).With(ShotKind::kEscape);
  const PlanAnswer a = Planner::Default().Plan(legal);
  EXPECT_EQ(a.status, PlanStatus::kNoPot);
  EXPECT_TRUE(a.shots.empty());
  EXPECT_NE(a.reason.find("no pot"), std::string::npos) << a.reason;
  EXPECT_NE(a.reason.find("path blocked"), std::string::npos) << a.reason;
  // By default the robot still gets a stroke: the least costly foul, the same reason
  // leading its explanation.
  const PlanAnswer f = Planner::Default().Plan(Request(t));
  EXPECT_EQ(f.status, PlanStatus::kOk);
  ASSERT_FALSE(f.shots.empty());
  EXPECT_EQ(f.shots.front().kind, ShotKind::kFoul);
  EXPECT_NE(f.reason.find("path blocked"), std::string::npos) << f.reason;
  EXPECT_NE(f.reason.find("the foul that costs least"), std::string::npos) << f.reason;
}

// Seeded random mid-frame tables (the self-play's), one per test: every returned
// shot is within the robot's (tightened) limits and pots in a fresh full simulation.
class PlannerTableTest : public testing::TestWithParam<int> {};

TEST_P(PlannerTableTest, ShotsAreWithinLimitsAndPotWhenReplayed) {
  Rng rng(DeriveSeed(1234, static_cast<std::uint64_t>(GetParam())));
  const TableState t = RandomFrame(rng, 6 + GetParam() % 5, Table());
  PlanRequest r = Request(t, 300);
  r.limits.min_speed = 0.5;
  r.limits.max_speed = 3.0;
  r.limits.max_topspin_fraction = 0.6;
  r.limits.max_sidespin_fraction = 0.3;
  r.max_shots = 4;
  const PlanAnswer a = Planner::Default().Plan(r);
  ASSERT_TRUE(a.status == PlanStatus::kOk || a.status == PlanStatus::kNoPot) << a.reason;
  EXPECT_EQ(a.shots.empty(), a.status == PlanStatus::kNoPot);
  EXPECT_LE(static_cast<int>(a.shots.size()), r.max_shots);
  for (const PlannedShot& s : a.shots) {
    const double rolling = s.shot.speed / kR;
    EXPECT_GE(s.shot.speed, r.limits.min_speed);
    EXPECT_LE(s.shot.speed, r.limits.max_speed);
    EXPECT_LE(std::abs(s.shot.topspin), r.limits.max_topspin_fraction * rolling * (1 + 1e-12));
    EXPECT_LE(std::abs(s.shot.sidespin), r.limits.max_sidespin_fraction * rolling * (1 + 1e-12));
    EXPECT_GE(CueMargin(t, t.cue_index(), s.shot.heading, r.limits.cue, Table()), 0);
    EXPECT_TRUE(IsLegalTarget(BallOn::kRed, t.balls[static_cast<size_t>(s.object_ball)].kind));
    EXPECT_TRUE(Replay(t, BallOn::kRed, s).success);
    EXPECT_GE(s.pot_probability, 0);
    EXPECT_LE(s.pot_probability, 1);
    EXPECT_FALSE(s.events.empty());
  }
  for (size_t i = 1; i < a.shots.size(); ++i) EXPECT_GE(a.shots[i - 1].score, a.shots[i].score);
}

INSTANTIATE_TEST_SUITE_P(SeededFrames, PlannerTableTest, testing::Range(0, 6),
                         [](const testing::TestParamInfo<int>& param) {
                           return "frame_" + std::to_string(param.param);
                         });

// The same shots, to the bit, and the same work.
void ExpectSameAnswer(const PlanAnswer& a, const PlanAnswer& b) {
  ASSERT_EQ(a.shots.size(), b.shots.size());
  EXPECT_EQ(a.simulations, b.simulations);
  for (size_t i = 0; i < a.shots.size(); ++i) {
    EXPECT_EQ(a.shots[i].shot.speed, b.shots[i].shot.speed);
    EXPECT_EQ(a.shots[i].shot.heading, b.shots[i].shot.heading);
    EXPECT_EQ(a.shots[i].shot.topspin, b.shots[i].shot.topspin);
    EXPECT_EQ(a.shots[i].shot.sidespin, b.shots[i].shot.sidespin);
    EXPECT_EQ(a.shots[i].pot_probability, b.shots[i].pot_probability);
  }
}

TEST(PlannerTest, TheSameSeedGivesTheSameAnswer) {
  Rng rng(77);
  const TableState t = RandomFrame(rng, 8, Table());
  PlanRequest r = Request(t, 300);
  r.max_shots = 3;
  const PlanAnswer a = Planner::Default().Plan(r);
  const PlanAnswer b = Planner::Default().Plan(r);
  r.threads = 1;  // the work partition does not depend on the threads
  const PlanAnswer c = Planner::Default().Plan(r);
  ASSERT_FALSE(a.shots.empty());
  EXPECT_EQ(a.simulation_cap, 300);
  for (const PlanAnswer* other : {&a, &b, &c}) EXPECT_FALSE(other->cut_short);
  ExpectSameAnswer(a, b);
  ExpectSameAnswer(a, c);
}

// A plan whose budget buys its simulations, and which the clock did not cut short, is
// the answer of the same request capped at its simulation_cap instead, whatever the
// budget: how a client replays a plan it was given. A budget too small for its work
// says that it cut it.
TEST(PlannerTest, AnAnswerNotCutShortComesAgainFromItsSimulationCap) {
  Planner::Config slow;  // a budget that buys few simulations, so 20 s hold them
  slow.simulations_per_ms = 0.0201;
  Rng rng(77);
  PlanRequest r;
  r.table = RandomFrame(rng, 8, Table());
  r.monte_carlo_samples = 16;
  r.time_budget = 20;
  const PlanAnswer a = Planner(slow).Plan(r);
  ASSERT_FALSE(a.shots.empty()) << a.reason;
  EXPECT_EQ(a.simulation_cap, 804);  // 0.0201 a ms x 20 000 ms x 2 threads, rounded
  EXPECT_FALSE(a.cut_short);
  r.max_simulations = a.simulation_cap;
  r.time_budget = 30;
  const PlanAnswer b = Planner::Default().Plan(r);
  EXPECT_EQ(b.simulation_cap, a.simulation_cap);
  EXPECT_FALSE(b.cut_short);
  EXPECT_EQ(b.evaluations, a.evaluations);
  ExpectSameAnswer(a, b);
  r.max_simulations = 1'000'000;
  r.time_budget = 1e-3;
  const PlanAnswer c = Planner::Default().Plan(r);
  EXPECT_EQ(c.simulation_cap, 1'000'000);
  EXPECT_TRUE(c.cut_short);
}

struct Progress {
  std::vector<double> scores;
  std::vector<std::chrono::steady_clock::time_point> times;
};

TEST(PlannerTest, ProgressReportsEachImprovementOfTheBestShot) {
  PlanRequest r = Request(ObviousPot());
  Progress progress;
  r.progress = [](const PlannedShot& best, void* ctx) {
    auto* p = static_cast<Progress*>(ctx);
    p->scores.push_back(best.score);
    p->times.push_back(std::chrono::steady_clock::now());
    EXPECT_GE(best.object_ball, 0);
  };
  r.progress_context = &progress;
  const auto start = std::chrono::steady_clock::now();
  const PlanAnswer a = Planner::Default().Plan(r);
  const auto end = std::chrono::steady_clock::now();
  ASSERT_FALSE(a.shots.empty());
  ASSERT_FALSE(progress.scores.empty());
  for (size_t i = 1; i < progress.scores.size(); ++i) EXPECT_GT(progress.scores[i], progress.scores[i - 1]);
  EXPECT_LT(progress.times.front(), end);
  EXPECT_GT(progress.times.front(), start);
}

TEST(PlannerTest, CancellingStopsThePlan) {
  Rng rng(5);
  PlanRequest r;
  r.table = RandomFrame(rng, 10, Table());
  r.time_budget = 30;  // far more than the test will wait
  std::atomic<bool> cancel{false};
  r.cancel = &cancel;
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    cancel.store(true);
  });
  const PlanAnswer a = Planner::Default().Plan(r);
  stopper.join();
  EXPECT_EQ(a.status, PlanStatus::kCancelled) << a.reason;
  EXPECT_LT(a.elapsed, 10.0);  // far below the budget: it stopped
  EXPECT_TRUE(a.cut_short);
}

TEST(PlannerTest, ADeadlineInThePastReturnsAtOnce) {
  PlanRequest r = Request(ObviousPot());
  r.deadline = std::chrono::steady_clock::now() - std::chrono::seconds(1);
  const PlanAnswer a = Planner::Default().Plan(r);
  EXPECT_TRUE(a.shots.empty());
  EXPECT_EQ(a.status, PlanStatus::kDeadline) << a.reason;
  EXPECT_LT(a.elapsed, 5.0);
  EXPECT_TRUE(a.cut_short);
}

TEST(PlannerTest, PotOnlyAndColoursOn) {
  PlanRequest r = Request(ObviousPot());
  r.position_play = false;
  const PlanAnswer pot_only = Planner::Default().Plan(r);
  ASSERT_FALSE(pot_only.shots.empty());
  EXPECT_TRUE(Replay(r.table, BallOn::kRed, pot_only.shots.front()).success);
  // With a colour on the planner chooses (nominates) a colour.
  r.ball_on = BallOn::kAnyColour;
  r.position_play = true;
  const PlanAnswer colour = Planner::Default().Plan(r);
  ASSERT_FALSE(colour.shots.empty()) << colour.reason;
  for (const PlannedShot& s : colour.shots) {
    EXPECT_TRUE(IsColour(r.table.balls[static_cast<size_t>(s.object_ball)].kind));
    EXPECT_TRUE(Replay(r.table, BallOn::kAnyColour, s).success);
  }
}

// A real table's squirt is known to 15 % of itself (the default noise): a stroke
// with side pays for it in its pot's chance. The search must price it as the
// Monte Carlo does, or it ranks strokes with side that the Monte Carlo then finds
// poor. On the demo table (cue ball, black on its spot, three reds of the pack),
// the answer's search estimate agrees with its Monte Carlo on three seeds (200
// samples each: a binomial error of at most 0.035). Without the squirt's term the
// search rated its answer 0.74 and the Monte Carlo 0.36-0.41.
TEST(PlannerTest, TheSearchPricesTheSquirtsUncertaintyAsTheMonteCarloDoes) {
  const PlanRequest r = Request(testing_tables::DemoTable());
  ASSERT_GT(r.noise.squirt_fraction, 0);
  testing_tables::BestShotsOnThreeSeeds(r, [](const PlannedShot& s, std::uint64_t seed) {
    ASSERT_EQ(s.kind, ShotKind::kPot);
    EXPECT_NEAR(s.pot_estimate, s.pot_probability, 0.12) << "seed " << seed;
    EXPECT_GT(s.pot_probability, 0.6) << "seed " << seed;
  });
}

// The break value prices what a pot keeps alive: the leave's expected points are
// the weighted next pot probabilities times (the ball's value + the break value).
// Potting the black with reds left, the next ball is a red whatever the break value
// (every red is worth 1, so the ranking of next shots cannot change), and with the
// position ignored the search is the same: the same shot, whose leave is then worth
// exactly position_value points more for each point of break value.
TEST(PlannerTest, TheBreakValuePricesTheLeaveByWhatItKeepsAlive) {
  const physics::Pocket& p = Table().pocket(PocketId::kTopRight);
  const Vec2 black = p.mouth_centre - 0.4 * p.axis;
  TableState t;
  t.balls = {{BallKind::kCue, black - 0.4 * p.axis},
             {BallKind::kBlack, black},
             {BallKind::kRed, Vec2(0.5, 1.2)},
             {BallKind::kRed, Vec2(1.2, 2.2)}};
  PlanRequest r = Request(t);
  r.ball_on = BallOn::kBlack;
  r.position_play = false;
  r.kinds = ShotKinds::Of(ShotKind::kPot);
  r.max_shots = 1;
  r.break_value = 0;
  const PlanAnswer none = Planner::Default().Plan(r);
  r.break_value = 100;
  const PlanAnswer hundred = Planner::Default().Plan(r);
  ASSERT_EQ(none.status, PlanStatus::kOk) << none.reason;
  ASSERT_EQ(hundred.status, PlanStatus::kOk) << hundred.reason;
  const PlannedShot& a = none.shots.front();
  const PlannedShot& b = hundred.shots.front();
  ASSERT_EQ(a.shot.heading, b.shot.heading);
  ASSERT_EQ(a.shot.speed, b.shot.speed);
  ASSERT_EQ(a.position_value, b.position_value);
  ASSERT_GT(a.position_value, 0.5);  // a red is left to pot
  EXPECT_EQ(r.table.balls[static_cast<size_t>(a.next_ball)].kind, BallKind::kRed);
  EXPECT_NEAR(b.position_points - a.position_points, 100 * a.position_value, 1e-9);
  // Unset, the planner's own break value: PositionOptions' 30.
  r.break_value.reset();
  const PlanAnswer unset = Planner::Default().Plan(r);
  ASSERT_FALSE(unset.shots.empty());
  EXPECT_NEAR(unset.shots.front().position_points - a.position_points,
              PositionOptions{}.continuation * a.position_value, 1e-9);
}

// The position's spread changes only what the search prefers: 0 plays as unset, and
// on the demo's table 2 still answers pots the Monte Carlo rates likely, found by a
// different search (another count of NLopt evaluations: another optimum's path).
TEST(PlannerTest, APositionSpreadOfZeroIsTheNominalEnd) {
  PlanRequest r = Request(testing_tables::DemoTable(), 4000);
  const PlanAnswer unset = Planner::Default().Plan(r);
  ASSERT_EQ(unset.status, PlanStatus::kOk) << unset.reason;
  r.position_spread = 0;
  const PlanAnswer zero = Planner::Default().Plan(r);
  ASSERT_EQ(zero.shots.size(), unset.shots.size());
  for (size_t i = 0; i < zero.shots.size(); ++i) {
    EXPECT_EQ(zero.shots[i].score, unset.shots[i].score) << i;
    EXPECT_EQ(zero.shots[i].shot.speed, unset.shots[i].shot.speed) << i;
  }
  EXPECT_EQ(zero.evaluations, unset.evaluations);
  r.position_spread = 2;
  const PlanAnswer spread = Planner::Default().Plan(r);
  ASSERT_EQ(spread.status, PlanStatus::kOk) << spread.reason;
  EXPECT_NE(spread.evaluations, unset.evaluations);
  for (const PlannedShot& s : spread.shots) {
    ASSERT_EQ(s.kind, ShotKind::kPot);
    EXPECT_GT(s.pot_probability, 0.5);
  }
}

// Why a shot's label (kind, first ball, object ball and pocket) differs from what its
// own events show, or "" when they agree: the cue ball's first contact must be the
// first ball (the object ball but for a plant), a pot's object ball must drop in the
// named pocket, the cue ball must not drop.
std::string LabelMismatch(const PlannedShot& s, int cue) {
  int first = -1;
  bool object_in_pocket = false;
  for (const PlannedEvent& e : s.events) {
    if (e.kind == physics::EventKind::kBallBall && first < 0 && (e.ball == cue || e.other == cue)) {
      first = e.ball == cue ? e.other : e.ball;
    }
    if (e.kind == physics::EventKind::kPocket && e.ball == cue) return "the cue ball drops";
    if (e.kind == physics::EventKind::kPocket && e.ball == s.object_ball && s.kind == ShotKind::kPot) {
      if (e.where != static_cast<int>(s.pocket)) {
        return std::string("the object ball drops in ") + physics::ToString(static_cast<PocketId>(e.where)) +
               ", labelled " + physics::ToString(s.pocket);
      }
      object_in_pocket = true;
    }
  }
  if (s.kind != ShotKind::kPot) {
    // A safety names the ball it plays: the first the cue ball hits.
    return first == s.object_ball && first == s.first_ball ? "" : "a safety's first ball differs";
  }
  if (first != s.first_ball) return "the cue ball first hits ball " + std::to_string(first) + ", labelled first " + std::to_string(s.first_ball);
  if (s.route != PotRoute::kPlant && first != s.object_ball) {
    return "the cue ball first hits ball " + std::to_string(first) + ", labelled " + std::to_string(s.object_ball);
  }
  return object_in_pocket ? "" : "the object ball does not drop";
}

TEST(PlannerLabelTest, ACushionFirstShotIsLabelledWithThePocketItReallyFinds) {
  // Colours on their spots, three reds, the cue ball near the right cushion in
  // baulk: among five shots some strike a cushion first, and an object ball aimed
  // at one pocket can drop in another (red-1, aimed at top-left, into baulk-left).
  // Each shot is labelled with what its verification run did.
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(1.62, 0.85)},
             {BallKind::kRed, Vec2(1.745, 2.55)},
             {BallKind::kRed, Vec2(0.25, 3.3)},
             {BallKind::kRed, Vec2(0.6, 3.1)}};
  for (int c = 0; c < physics::kColourCount; ++c) {
    const auto colour = static_cast<physics::Colour>(c);
    t.balls.push_back({KindOf(colour), Table().spot(colour)});
  }
  PlanRequest r = Request(t, 3000);
  r.max_shots = 5;
  const PlanAnswer a = Planner::Default().Plan(r);
  ASSERT_EQ(a.status, PlanStatus::kOk) << a.reason;
  ASSERT_GE(a.shots.size(), 3u);
  for (const PlannedShot& s : a.shots) {
    EXPECT_EQ(LabelMismatch(s, 0), "") << "ball " << s.object_ball << " into " << physics::ToString(s.pocket);
    EXPECT_LE(s.pocket_probability, s.pot_probability);
  }
}

TEST(PlannerLabelTest, EveryShotsLabelMatchesItsEventsOnSeededTables) {
  int shots = 0;
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    Rng rng(seed);
    PlanRequest r = Request(RandomFrame(rng, 1 + static_cast<int>(seed % 8), Table()), 600);
    r.max_shots = 5;
    const PlanAnswer a = Planner::Default().Plan(r);
    for (const PlannedShot& s : a.shots) {
      ++shots;
      EXPECT_EQ(LabelMismatch(s, r.table.cue_index()), "")
          << "seed " << seed << ": ball " << s.object_ball << " into " << physics::ToString(s.pocket);
      EXPECT_LE(s.pocket_probability, s.pot_probability) << "seed " << seed;
    }
  }
  EXPECT_GE(shots, 30);  // the property was tried on many shots
}

TEST(PlannerTest, AnInvalidRequestIsRefusedNamingTheField) {
  PlanRequest r = Request(ObviousPot());
  r.table.balls.push_back({BallKind::kCue, Vec2(1.5, 0.3)});
  r.noise.heading = -1;
  const PlanAnswer a = Planner::Default().Plan(r);
  EXPECT_EQ(a.status, PlanStatus::kInvalidRequest);
  EXPECT_TRUE(a.shots.empty());
  EXPECT_EQ(a.simulations, 0);
  EXPECT_NE(a.reason.find("table.balls = 2 (cue balls: exactly one)"), std::string::npos) << a.reason;
  EXPECT_NE(a.reason.find("noise.heading = -1"), std::string::npos) << a.reason;
  r = Request(ObviousPot());
  r.break_value = -5;
  const PlanAnswer bad = Planner::Default().Plan(r);
  EXPECT_EQ(bad.status, PlanStatus::kInvalidRequest);
  EXPECT_NE(bad.reason.find("break_value = -5 (must be in [0, 147] points)"), std::string::npos) << bad.reason;
}

// The budget is the planner's aim, the caller's deadline a hard end: when the budget
// runs out with no shot verified, the fallback's stroke is still answered, verified
// up to the deadline. Here the only red is ringed by colours (no pot, no legal
// stroke) and the budget, 1 ms, is spent before the scan has played its strokes.
TEST(PlannerTest, WithTheBudgetSpentTheFallbackStillAnswersBeforeTheDeadline) {
  const Vec2 red(0.9, 2.0);
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(0.9, 0.5)}, {BallKind::kRed, red}};
  const BallKind ring[] = {BallKind::kYellow, BallKind::kGreen, BallKind::kBrown,
                           BallKind::kBlue, BallKind::kPink, BallKind::kBlack};
  for (int k = 0; k < 6; ++k) {
    const double a = k * physics::kPi / 3 + physics::kPi / 6;
    t.balls.push_back({ring[k], red + (2 * kR + 0.0005) * Vec2(std::cos(a), std::sin(a))});
  }
  PlanRequest r = Request(t);
  r.time_budget = 1e-3;
  r.threads = 1;
  const PlanAnswer a = Planner::Default().Plan(r);
  EXPECT_EQ(a.status, PlanStatus::kOk) << a.reason;
  ASSERT_EQ(a.shots.size(), 1u) << a.reason;
  EXPECT_EQ(a.shots.front().kind, ShotKind::kFoul);
  // A caller's deadline already past leaves no time for it: no shot, and the
  // deadline named.
  r.deadline = std::chrono::steady_clock::now();
  const PlanAnswer late = Planner::Default().Plan(r);
  EXPECT_TRUE(late.shots.empty());
  EXPECT_EQ(late.status, PlanStatus::kDeadline) << late.reason;
}

// The cue ball frozen to the left cushion, the only red straight out across the table,
// and topspin capped below what a raised cue's high tip gives: no stroke at the red can
// be played. The plan still answers a stroke, from the headings around the cue ball,
// that re-simulates to what its kind says.
TEST(PlannerTest, ACueBallTheRobotCannotPlayAtTheBallOnStillGetsAStroke) {
  const double c = Table().cushion_contact_distance();
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(c, 1.8)}, {BallKind::kRed, Vec2(1.2, 1.8)}};
  PlanRequest r = Request(t);
  r.limits.max_topspin_fraction = 0.9;
  r.max_simulations = 2000;
  r.time_budget = 30;
  const PlanAnswer a = Planner::Default().Plan(r);
  EXPECT_EQ(a.status, PlanStatus::kOk) << a.reason;
  ASSERT_FALSE(a.shots.empty()) << a.reason;
  const PlannedShot& s = a.shots.front();
  const ShotSetup setup{&t, 0, s.object_ball, s.pocket, BallOn::kRed, s.kind, -1, -1};
  ShotSimulator sim(Table(), Planner::Default().config().full);
  const ShotOutcome& out = sim.Run(setup, s.shot, {}, ShotSimulator::Mode::kToRest, physics::Interrupt{});
  ASSERT_EQ(out.status, physics::SimStatus::kAtRest);
  EXPECT_EQ(out.foul != Foul::kNone, s.kind == ShotKind::kFoul) << ToString(s.kind);
  EXPECT_TRUE(WithinLimits(s.shot, r.limits, kR));
}

// A caller's deadline before the end of the budget: the stages share out the time to
// the deadline, as they would a budget that short, so the search leaves the
// verification its part (it used to search until the deadline and verify nothing),
// and what the plan may simulate is what that time buys.
TEST(PlannerTest, ADeadlineBeforeTheBudgetsEndIsSharedOutAsTheBudgetWouldBe) {
  Rng rng(11);
  PlanRequest r;
  r.table = RandomFrame(rng, 15, Table());
  r.time_budget = 20;
  r.threads = 1;
  const auto window = std::chrono::milliseconds(1500);
  r.deadline = std::chrono::steady_clock::now() + window;
  const PlanAnswer a = Planner::Default().Plan(r);
  EXPECT_EQ(a.status, PlanStatus::kOk) << a.reason;
  EXPECT_FALSE(a.shots.empty()) << a.reason;
  EXPECT_GE(a.simulation_cap, 1);
  EXPECT_LE(a.simulation_cap, std::llround(Planner::Default().config().simulations_per_ms * 1500.0));
}

TEST(PlannerTest, TheBudgetRunningOutIsNotTheCallersDeadline) {
  // A budget far too small for a pot on a full frame, with no deadline of the
  // caller's: whatever the timing, the plan ends by its budget, never by a deadline.
  Rng rng(11);
  PlanRequest r;
  r.table = RandomFrame(rng, 15, Table());
  r.time_budget = 1e-3;
  const PlanAnswer a = Planner::Default().Plan(r);
  EXPECT_NE(a.status, PlanStatus::kDeadline) << a.reason;
  EXPECT_NE(a.status, PlanStatus::kInvalidRequest) << a.reason;
  if (a.shots.empty() && a.deadline_hit) {
    EXPECT_EQ(a.status, PlanStatus::kBudgetSpent) << a.reason;
  }
}

}  // namespace
}  // namespace snooker::planner
