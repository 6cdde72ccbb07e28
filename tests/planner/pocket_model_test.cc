// Tests of the pockets' acceptance windows (planner/pocket_model.h): plausible
// widths, the jaws' mirror symmetry, closed middle pockets at shallow angles, and
// agreement with fresh simulations from other distances than the table's.
#include "planner/pocket_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "planner/geometry.h"
#include "tests/support/thread_limit.h"

namespace snooker::planner {
namespace {

using physics::PocketId;
using physics::Vec2;

const PocketModel& Model() { return PocketModel::Default(); }

// The bisection leaves each edge within scan_step / 2^bisections = 0.08 mm; the
// mirror image of a cell is measured independently, so both can err. m.
constexpr double kEdgeTolerance = 2 * 0.0025 / 32;

TEST(PocketModelTest, StraightInWindowsAreCentredNarrowerThanTheMouthAndShrinkWithSpeed) {
  for (const bool corner : {true, false}) {
    const int mid = Model().angle_count(corner) / 2;
    ASSERT_NEAR(Model().angle_at(corner, mid), 0, 1e-12);
    const double mouth = corner ? physics::kCornerPocketShape.mouth_width
                                : physics::kMiddlePocketShape.mouth_width;
    double last = 1;
    for (int s = 0; s < static_cast<int>(Model().options().arrival_speeds.size()); ++s) {
      const PocketWindow w = Model().Cell(corner, mid, s);
      ASSERT_FALSE(w.empty);
      EXPECT_NEAR(w.lo, -w.hi, kEdgeTolerance);
      // A centre line more than half the mouth off cannot drop; 1 cm off does.
      EXPECT_LT(w.hi, mouth / 2) << (corner ? "corner" : "middle");
      EXPECT_GT(w.hi, 0.010) << (corner ? "corner" : "middle");
      // Faster balls bounce off the knuckles that slower ones roll in off.
      EXPECT_LE(w.hi, last + kEdgeTolerance);
      last = w.hi;
    }
  }
}

TEST(PocketModelTest, WindowsAreMirrorSymmetric) {
  for (const bool corner : {true, false}) {
    const int n = Model().angle_count(corner);
    for (int s = 0; s < static_cast<int>(Model().options().arrival_speeds.size()); ++s) {
      for (int a = 0; a < n; ++a) {
        const PocketWindow w = Model().Cell(corner, a, s);
        const PocketWindow m = Model().Cell(corner, n - 1 - a, s);
        ASSERT_EQ(w.empty, m.empty);
        if (w.empty) continue;
        EXPECT_NEAR(w.lo, -m.hi, kEdgeTolerance) << corner << " " << a << " " << s;
        EXPECT_NEAR(w.hi, -m.lo, kEdgeTolerance) << corner << " " << a << " " << s;
      }
    }
  }
}

TEST(PocketModelTest, MiddlePocketsRefuseShallowAngles) {
  // Along its cushion nothing drops into a middle pocket; 60 deg off the axis is
  // already closed, 30 deg is open.
  const double axis = Direction(physics::DefaultTable().pocket(PocketId::kMiddleLeft).axis);
  EXPECT_TRUE(Model().Window(PocketId::kMiddleLeft, axis + physics::DegToRad(85), 1.0).empty);
  EXPECT_TRUE(Model().Window(PocketId::kMiddleLeft, axis + physics::DegToRad(60), 1.0).empty);
  EXPECT_FALSE(Model().Window(PocketId::kMiddleLeft, axis + physics::DegToRad(30), 1.0).empty);
  // A corner takes a ball along its cushion (45 deg off its axis).
  const double corner = Direction(physics::DefaultTable().pocket(PocketId::kTopRight).axis);
  EXPECT_FALSE(Model().Window(PocketId::kTopRight, corner + physics::DegToRad(45), 1.0).empty);
}

// A ball rolled at the pocket from 0.8 m (the table used 0.5 m) on the window's
// centre line drops; 1.5 mm outside either edge it does not.
struct ProbeCase {
  PocketId pocket;
  double approach_deg;
  double speed;
};

// Readable in test listings (ctest shows the parameter).
void PrintTo(const ProbeCase& c, std::ostream* os) {
  *os << physics::ToString(c.pocket) << " " << c.approach_deg << " deg " << c.speed << " m/s";
}

class WindowProbeTest : public testing::TestWithParam<ProbeCase> {};

bool Drops(PocketId id, double direction, double offset, double speed) {
  const physics::TableModel& table = physics::DefaultTable();
  const physics::Pocket& p = table.pocket(id);
  const Vec2 u(std::cos(direction), std::sin(direction));
  const double d = 0.8;
  physics::BallState b;
  b.r = p.mouth_centre - d * u + offset * Left(u);
  const physics::SimParams params;
  const double v0 = std::sqrt(speed * speed + 2 * params.cloth.mu_r * params.cloth.g * d);
  b.v = physics::Vec3(v0 * u.x(), v0 * u.y(), 0);
  b.w = physics::Vec3(-u.y(), u.x(), 0) * (v0 / table.ball_radius());
  physics::Simulator sim(table, params);
  sim.Run(std::span<const physics::BallState>(&b, 1), physics::RunOptions::Lean());
  return sim.pocket_of(0) == static_cast<int>(id);
}

TEST_P(WindowProbeTest, CentreDropsAndOutsideMisses) {
  const ProbeCase& c = GetParam();
  const double dir = Direction(physics::DefaultTable().pocket(c.pocket).axis) +
                     physics::DegToRad(c.approach_deg);
  const PocketWindow w = Model().Window(c.pocket, dir, c.speed);
  ASSERT_FALSE(w.empty);
  EXPECT_TRUE(Drops(c.pocket, dir, w.centre(), c.speed));
  EXPECT_FALSE(Drops(c.pocket, dir, w.hi + 0.0015, c.speed));
  EXPECT_FALSE(Drops(c.pocket, dir, w.lo - 0.0015, c.speed));
}

INSTANTIATE_TEST_SUITE_P(
    Pockets, WindowProbeTest,
    testing::Values(ProbeCase{PocketId::kTopRight, 0, 1.0}, ProbeCase{PocketId::kBaulkLeft, 20, 1.0},
                    ProbeCase{PocketId::kTopLeft, -30, 2.5}, ProbeCase{PocketId::kMiddleRight, 0, 1.0},
                    ProbeCase{PocketId::kMiddleLeft, 40, 1.0}),
    [](const testing::TestParamInfo<ProbeCase>& param) {
      std::string name = physics::ToString(param.param.pocket);
      for (char& ch : name) {
        if (ch == '-') ch = '_';
      }
      const int a = static_cast<int>(param.param.approach_deg);
      return name + "_" + (a < 0 ? "minus" + std::to_string(-a) : std::to_string(a)) + "deg";
    });

// Every window of a coarse model, to the bit, as text.
std::string Windows(const PocketModel& m) {
  std::string text;
  char cell[64];
  for (const bool corner : {true, false}) {
    for (int a = 0; a < m.angle_count(corner); ++a) {
      for (int s = 0; s < static_cast<int>(m.options().arrival_speeds.size()); ++s) {
        const PocketWindow w = m.Cell(corner, a, s);
        std::snprintf(cell, sizeof cell, "%d %a %a;", w.empty ? 1 : 0, w.lo, w.hi);
        text += cell;
      }
    }
  }
  return text + " " + std::to_string(m.simulations());
}

// The default model is made from the windows compiled in (pocket_model_default.cc),
// with no simulation. Measured again here, they must be the same to the bit: when the
// physics moves a window, scripts/pocket-windows writes them again.
TEST(PocketModelTest, TheCompiledInDefaultWindowsAreWhatTheSimulatorMeasures) {
  EXPECT_EQ(Model().simulations(), 0) << "the default model simulated: its compiled-in windows do not fit its grid";
  const PocketModel measured(physics::DefaultTable(), physics::SimParams{}, PocketModel::Options{});
  EXPECT_GT(measured.simulations(), 1000);
  const std::vector<PocketWindow> saved = Model().Cells(), now = measured.Cells();
  ASSERT_EQ(saved.size(), now.size());
  for (std::size_t i = 0; i < saved.size(); ++i) {
    EXPECT_TRUE(saved[i].empty == now[i].empty && saved[i].lo == now[i].lo && saved[i].hi == now[i].hi)
        << "cell " << i << ": compiled in " << saved[i].lo << " .. " << saved[i].hi << (saved[i].empty ? " (empty)" : "")
        << ", measured " << now[i].lo << " .. " << now[i].hi << (now[i].empty ? " (empty)" : "")
        << "; run scripts/pocket-windows";
  }
}

// Windows of another grid than the options' are not taken: the model measures its own.
TEST(PocketModelTest, WindowsOfAnotherGridAreMeasuredAgain) {
  PocketModel::Options coarse;
  coarse.angle_step = 15.0 * physics::kPi / 180;
  coarse.arrival_speeds = {0.5, 2.0};
  coarse.bisections = 2;
  const PocketModel measured(physics::DefaultTable(), physics::SimParams{}, coarse);
  const PocketModel given(physics::DefaultTable(), physics::SimParams{}, coarse, Model().Cells());
  EXPECT_EQ(given.simulations(), measured.simulations());
  EXPECT_EQ(Windows(given), Windows(measured));
  const PocketModel copied(physics::DefaultTable(), physics::SimParams{}, coarse, measured.Cells());
  EXPECT_EQ(copied.simulations(), 0);
  EXPECT_NE(copied.serial(), measured.serial());
  // The same windows (Windows' last word is the count of simulations).
  const std::string a = Windows(copied), b = Windows(measured);
  EXPECT_EQ(a.substr(0, a.rfind(' ')), b.substr(0, b.rfind(' ')));
}

// The model measures its cells on a second thread where the system has one; where it
// has none (a process or container limit) it measures them all on the caller's and
// builds the same windows. Before, the second thread's failure threw out of the
// constructor, and out of the first plan that needed the model.
TEST(PocketModelTest, WithoutASecondThreadTheWindowsAreTheSame) {
  PocketModel::Options coarse;
  coarse.angle_step = 15.0 * physics::kPi / 180;
  coarse.arrival_speeds = {0.5, 2.0};
  coarse.bisections = 2;
  const std::string expected = Windows(PocketModel(physics::DefaultTable(), physics::SimParams{}, coarse));
  const test_support::LimitedRun run = test_support::RunWithSpareThreads(0, [&](std::string* out) {
    *out = Windows(PocketModel(physics::DefaultTable(), physics::SimParams{}, coarse));
    return 0;
  });
  if (!run.limited) GTEST_SKIP() << run.output;
  EXPECT_EQ(run.signal, 0);
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output, expected);
}

}  // namespace
}  // namespace snooker::planner
