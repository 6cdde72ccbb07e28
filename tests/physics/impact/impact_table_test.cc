// The impact tables (physics/impact/impact_table.h): the compiled-in tables agree
// with the exact solvers, decline what they do not cover, keep the model's symmetry
// and scaling; building, writing and reading a table; the simulator's use of them.
#include "physics/impact/impact_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "physics/sim/fidelity.h"
#include "tests/physics/impact/impact_test_support.h"
#include "tests/support/scenarios.h"

namespace snooker::physics {
namespace {

// The default tables' cells are checked to 3e-6 V at their centres (docs/impact-tables.md:
// measured at most 3.2e-6 V for the cushion, 1.9e-6 V for ball-ball over 5000
// random impacts, like the exact solvers at the shot tolerance).
constexpr double kTableError = 5e-6;

CushionParams TableCushion() {
  CushionParams c = SimParams{}.cushion;
  c.contact_height = TableSpec{}.cushion_height;
  return c;
}

ImpulseSolverOptions Converged() {
  return test::Adaptive(1e-12, ImpulseMethod::kDormandPrince853);
}

BallMotion Mirrored(const BallMotion& m) {
  return {Vec3(-m.v.x(), m.v.y(), m.v.z()), Vec3(m.w.x(), -m.w.y(), -m.w.z())};
}

TEST(ImpactTableTest, DefaultTablesAreBuiltForTheSimulatorsParameters) {
  const SimParams sim;
  ASSERT_NE(DefaultCushionTable(), nullptr);
  ASSERT_NE(DefaultBallBallTable(), nullptr);
  EXPECT_TRUE(DefaultCushionTable()->Matches(sim.ball, TableCushion()));
  EXPECT_TRUE(DefaultBallBallTable()->Matches(sim.ball, sim.ball_ball, sim.cloth.mu_s));
  // Other parameters get no table.
  CushionParams other = TableCushion();
  other.mu_w = 0.15;
  EXPECT_FALSE(DefaultCushionTable()->Matches(sim.ball, other));
  other = TableCushion();
  other.restitution_curve.e[0] = 0.5;  // below the table's restitution range
  EXPECT_FALSE(DefaultCushionTable()->Matches(sim.ball, other));
  BallBallParams marlow = sim.ball_ball;
  marlow.friction_law = BallBallFrictionLaw::kMarlow;
  EXPECT_FALSE(DefaultBallBallTable()->Matches(sim.ball, marlow, sim.cloth.mu_s));
  EXPECT_FALSE(DefaultBallBallTable()->Matches(sim.ball, sim.ball_ball, 0.3));
  // A fitted friction law depends on the slip speed: the table (one speed, scaled)
  // cannot answer it, even when its constant part is the table's mu_bb.
  BallBallParams fitted = sim.ball_ball;
  fitted.friction_law = BallBallFrictionLaw::kExponential;
  fitted.slip_gain = 0.1;
  fitted.slip_decay = 0.6;
  EXPECT_FALSE(DefaultBallBallTable()->Matches(sim.ball, fitted, sim.cloth.mu_s));
  BallBallParams restitution = sim.ball_ball;
  restitution.e = 0.9;
  EXPECT_FALSE(DefaultBallBallTable()->Matches(sim.ball, restitution, sim.cloth.mu_s));
}

TEST(ImpactTableTest, CushionTableAgreesWithTheSolver) {
  const CushionTable& t = *DefaultCushionTable();
  const BallParams ball;
  const CushionParams cushion = TableCushion();
  const double R = ball.radius;
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> angle(0.05, 1.5707), side(-1.9, 1.9), speed(0.2, 4.0);
  int answered = 0;
  constexpr int kSamples = 300;
  for (int i = 0; i < kSamples; ++i) {
    const double v = speed(rng);
    BallMotion in = CushionIncidentState(v, angle(rng), v / R, side(rng) * v / R);
    if (i % 2 == 1) in = Mirrored(in);
    const CushionImpactResult exact = ResolveCushionImpact(in, ball, cushion, Converged());
    ASSERT_EQ(exact.status, ImpactStatus::kOk);
    BallMotion out;
    if (!t.Lookup(in, R, CushionRestitution(cushion, in.v.y()), &out)) continue;
    ++answered;
    EXPECT_LE(test::MaxDifference(out, exact.out, R), kTableError * v) << "sample " << i;
  }
  EXPECT_GE(answered, kSamples * 9 / 10);  // measured 96 %
}

TEST(ImpactTableTest, BallBallTableAgreesWithTheSolver) {
  const BallBallTable& t = *DefaultBallBallTable();
  const SimParams sim;
  const double R = sim.ball.radius;
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> cut(-1.5, 1.5), side(-1.9, 1.9), speed(0.2, 4.0);
  int answered = 0;
  constexpr int kSamples = 300;
  for (int i = 0; i < kSamples; ++i) {
    const double v = speed(rng);
    const ImpactState in = PaperIncidentState(v, v / R, side(rng) * v / R, cut(rng));
    const ImpactResult exact = ResolveImpact(in, sim.ball, sim.ball_ball, sim.cloth.mu_s, Converged());
    ASSERT_EQ(exact.status, ImpactStatus::kOk);
    ImpactState out;
    if (!t.Lookup(in, R, &out)) continue;
    ++answered;
    EXPECT_LE(test::MaxDifference(out, exact.out, R), kTableError * v) << "sample " << i;
  }
  EXPECT_GE(answered, kSamples * 95 / 100);  // measured 99.5 %
}

TEST(ImpactTableTest, OutcomesScaleWithSpeedAndMirror) {
  const CushionTable& t = *DefaultCushionTable();
  const double R = BallParams{}.radius;
  const double e = 0.95;
  const BallMotion in = CushionIncidentState(1.0, 1.0, 1.0 / R, 0.3 / R);
  BallMotion a, b, m;
  ASSERT_TRUE(t.Lookup(in, R, e, &a));
  BallMotion twice = in;
  twice.v *= 2.5;
  twice.w *= 2.5;
  ASSERT_TRUE(t.Lookup(twice, R, e, &b));
  EXPECT_LE(test::MaxDifference(b, {a.v * 2.5, a.w * 2.5}, R), 1e-14);
  ASSERT_TRUE(t.Lookup(Mirrored(in), R, e, &m));
  EXPECT_LE(test::MaxDifference(m, Mirrored(a), R), 1e-15);
}

TEST(ImpactTableTest, TablesDeclineWhatTheyDoNotCover) {
  const CushionTable& ct = *DefaultCushionTable();
  const double R = BallParams{}.radius;
  const BallMotion rolling = CushionIncidentState(1.0, 1.0, 1.0 / R, 0.0);
  BallMotion out;
  ASSERT_TRUE(ct.Lookup(rolling, R, 0.95, &out));
  BallMotion sliding = rolling;
  sliding.w.x() += 1e-6 / R;  // a cloth slip of 1e-6 V
  EXPECT_FALSE(ct.Lookup(sliding, R, 0.95, &out));
  EXPECT_FALSE(ct.Lookup(CushionIncidentState(1.0, 0.01, 1.0 / R, 0.0), R, 0.95, &out));  // grazing
  EXPECT_FALSE(ct.Lookup(CushionIncidentState(1.0, 1.0, 1.0 / R, 2.5 / R), R, 0.95, &out));  // spin
  EXPECT_FALSE(ct.Lookup(CushionIncidentState(1.0, -1.0, 1.0 / R, 0.0), R, 0.95, &out));  // leaving
  EXPECT_FALSE(ct.Lookup(rolling, R, 0.5, &out));  // restitution outside the table
  BallMotion nan = rolling;
  nan.v.x() = std::nan("");
  EXPECT_FALSE(ct.Lookup(nan, R, 0.95, &out));

  const BallBallTable& bt = *DefaultBallBallTable();
  const ImpactState hit = PaperIncidentState(1.0, 1.0 / R, 0.0, 0.3);
  ImpactState res;
  ASSERT_TRUE(bt.Lookup(hit, R, &res));
  ImpactState moving = hit;
  moving.o.v.x() = 1e-3;
  EXPECT_FALSE(bt.Lookup(moving, R, &res));
  ImpactState spinning = hit;
  spinning.o.w.z() = 1.0;
  EXPECT_FALSE(bt.Lookup(spinning, R, &res));
  EXPECT_FALSE(bt.Lookup(PaperIncidentState(1.0, 0.5 / R, 0.0, 0.3), R, &res));  // sliding
  ImpactState jumping = hit;
  jumping.c.v.z() = 0.01;
  EXPECT_FALSE(bt.Lookup(jumping, R, &res));
  EXPECT_FALSE(bt.Lookup(PaperIncidentState(1.0, 1.0 / R, 0.0, 1.56), R, &res));  // thin cut
}

// A small ball-ball table: building marks cells where the map is not smooth, and the
// bytes it writes read back to the same table; damaged bytes are refused by name.
TEST(ImpactTableTest, BuildWriteAndReadBack) {
  const SimParams sim;
  BallBallTableGrid grid;
  grid.cuts = 24;
  grid.sides = 17;
  grid.cell_tolerance = 1e-4;  // coarse grid: some cells fail the check (65 of 368)
  const BallBallTable built = BallBallTable::Build(sim.ball, sim.ball_ball, sim.cloth.mu_s, grid);
  EXPECT_EQ(built.grid().cells(), 23 * 16);
  EXPECT_GT(built.grid().marked_cells(), 0);
  EXPECT_LT(built.grid().marked_cells(), built.grid().cells());
  EXPECT_TRUE(built.Matches(sim.ball, sim.ball_ball, sim.cloth.mu_s));

  const std::vector<std::uint8_t> bytes = built.Serialize();
  std::vector<std::uint64_t> aligned((bytes.size() + 7) / 8);  // for the borrowing read
  std::memcpy(aligned.data(), bytes.data(), bytes.size());
  const auto* data = reinterpret_cast<const std::uint8_t*>(aligned.data());
  for (bool borrow : {false, true}) {
    BallBallTable read;
    ASSERT_EQ(BallBallTable::Deserialize(data, bytes.size(), borrow, &read), "");
    EXPECT_EQ(read.grid().marked_cells(), built.grid().marked_cells());
    const double R = sim.ball.radius;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> cut(-1.5, 1.5), side(-1.9, 1.9);
    for (int i = 0; i < 200; ++i) {
      const ImpactState in = PaperIncidentState(1.0, 1.0 / R, side(rng) / R, cut(rng));
      ImpactState a, b;
      const bool ha = built.Lookup(in, R, &a), hb = read.Lookup(in, R, &b);
      ASSERT_EQ(ha, hb);
      if (ha) {
        EXPECT_EQ(test::MaxDifference(a, b, R), 0.0);
      }
    }
  }
  // Damaged bytes: each refused with a message, the output untouched.
  auto refuse = [&](std::vector<std::uint8_t> b, const char* what) {
    BallBallTable out;
    const std::string error = BallBallTable::Deserialize(b.data(), b.size(), false, &out);
    EXPECT_NE(error, "") << what;
    EXPECT_TRUE(out.grid().empty()) << what;
  };
  refuse({}, "empty");
  refuse(std::vector<std::uint8_t>(bytes.begin(), bytes.end() - 1), "truncated");
  std::vector<std::uint8_t> magic = bytes;
  magic[0] = 'X';
  refuse(magic, "magic");
  std::vector<std::uint8_t> nan = bytes;
  const double bad = std::nan("");
  std::memcpy(nan.data() + nan.size() - built.grid().cells() - sizeof(double), &bad, sizeof bad);
  refuse(nan, "NaN value");
  std::vector<std::uint8_t> grid_size = bytes;
  grid_size[8 + 8 * 8 + 16] ^= 1;  // the first axis's node count
  refuse(grid_size, "grid");
  // A ball-ball table is not a cushion table.
  CushionTable wrong;
  EXPECT_NE(CushionTable::Deserialize(data, bytes.size(), false, &wrong), "");
}

// The simulator answers rolling impacts from the tables (unless told not to), and
// stays within the solvers' accuracy: a rolling ball sent into a cushion and then
// onto a ball at rest ends within 0.1 mm of the same shot with every impact solved.
TEST(ImpactTableTest, SimulatorUsesTheTablesWhereTheyApply) {
  EXPECT_TRUE(SimParams{}.impact_tables);
  // The tables carry the precision of the adaptive solvers at the shot tolerance:
  // a tighter tolerance, or the fixed-step scheme, solves every impact.
  ImpulseSolverOptions solver = SimParams::ShotImpactOptions();
  EXPECT_TRUE(TablesCarry(solver));
  solver.tolerance = 1e-8;
  EXPECT_FALSE(TablesCarry(solver));
  solver.fidelity = ImpulseFidelity::kSearch;  // 1e-6 whatever the tolerance says
  EXPECT_TRUE(TablesCarry(solver));
  solver = SimParams::ShotImpactOptions();
  solver.integrator = ImpulseIntegrator::kFixedStep;
  EXPECT_FALSE(TablesCarry(solver));
  solver.fidelity = static_cast<ImpulseFidelity>(99);
  EXPECT_FALSE(TablesCarry(solver));
  EXPECT_FALSE(FidelityParams(Fidelity::kReference).impact_tables);
  EXPECT_TRUE(FidelityParams(Fidelity::kSearch).impact_tables);
  const TableModel& table = DefaultTable();
  const Vec2 centre = table.spot(Colour::kBlue);
  const std::vector<BallState> balls = {
      scenarios::Rolling(centre, Vec2(0.6, -0.8).normalized(), 2.0),
      scenarios::AtRest(centre + Vec2(-0.4, -0.5))};
  SimParams off;
  off.impact_tables = false;
  Simulator with(table, SimParams{}), without(table, off);
  RunOptions o;
  o.record_paths = false;
  ASSERT_EQ(with.Run(balls, o), SimStatus::kAtRest);
  EXPECT_GT(with.impact_work().table_lookups, 0);
  ASSERT_EQ(without.Run(balls, o), SimStatus::kAtRest);
  EXPECT_EQ(without.impact_work().table_lookups, 0);
  SimParams tight;
  tight.ball_ball_solver.tolerance = tight.cushion_solver.tolerance = 1e-10;
  Simulator precise(table, tight);
  ASSERT_EQ(precise.Run(balls, o), SimStatus::kAtRest);
  EXPECT_EQ(precise.impact_work().table_lookups, 0);
  for (size_t i = 0; i < balls.size(); ++i) {
    EXPECT_LE((with.final_balls()[i].r - without.final_balls()[i].r).norm(), 1e-4) << "ball " << i;
  }
}

}  // namespace
}  // namespace snooker::physics
