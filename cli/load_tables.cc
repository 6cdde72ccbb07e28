#include "cli/load_tables.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "cli/json_input.h"
#include "physics/core/params.h"
#include "physics/core/splitmix64.h"
#include "physics/core/types.h"
#include "physics/table/table.h"
#include "planner/builtin_tables.h"
#include "planner/rules.h"
#include "server/convert.h"
#include "server/limits.h"
#include "server/plan_convert.h"
#include "server/read_file.h"

namespace snooker::cli {

std::uint64_t LoadRandom::Next() { return physics::SplitMix64(state_); }

double LoadRandom::Uniform(double lo, double hi) { return lo + (hi - lo) * physics::UnitInterval(Next()); }

int LoadRandom::Below(int n) { return static_cast<int>(Next() % static_cast<std::uint64_t>(n)); }

namespace {

constexpr double kCushionMargin = 0.06;  // m from a cushion nose line
constexpr double kGap = 0.001;           // m between balls
constexpr int kMaxTries = 2000;          // placements tried per ball

void Add(v1::TableState* t, const std::string& id, v1::BallKind kind, const physics::Vec2& p) {
  v1::Ball* b = t->add_balls();
  b->set_id(id);
  b->set_kind(kind);
  b->mutable_position()->set_x(p.x());
  b->mutable_position()->set_y(p.y());
}

physics::Vec2 At(const v1::Ball& b) { return {b.position().x(), b.position().y()}; }

// A free spot at least 2R + kGap from every ball of `t`, or false after kMaxTries.
bool FreeSpot(const v1::TableState& t, LoadRandom& random, physics::Vec2* out) {
  const physics::TableModel& table = physics::DefaultTable();
  const double r2 = 2 * table.ball_radius();
  for (int k = 0; k < kMaxTries; ++k) {
    const physics::Vec2 p(random.Uniform(kCushionMargin, table.spec().width - kCushionMargin),
                          random.Uniform(kCushionMargin, table.spec().length - kCushionMargin));
    bool free = true;
    for (const v1::Ball& b : t.balls()) free = free && (At(b) - p).norm() >= r2 + kGap;
    if (free) {
      *out = p;
      return true;
    }
  }
  return false;
}

}  // namespace

std::vector<v1::TableState> VariedTables(std::uint64_t seed, int count, double overlap_mm) {
  const physics::TableModel& table = physics::DefaultTable();
  LoadRandom random(seed);
  std::vector<v1::TableState> tables;
  while (static_cast<int>(tables.size()) < count) {
    v1::TableState t;
    physics::Vec2 p;
    FreeSpot(t, random, &p);
    Add(&t, "cue", v1::CUE, p);
    const int reds = random.Below(16);
    for (int i = 0; i < reds && FreeSpot(t, random, &p); ++i) {
      Add(&t, "red-" + std::to_string(i + 1), v1::RED, p);
    }
    for (int c = 0; c < physics::kColourCount; ++c) {
      const planner::BallKind kind = planner::KindOf(static_cast<physics::Colour>(c));
      if ((random.Below(10) < 7 || t.balls_size() == 1) && FreeSpot(t, random, &p)) {
        Add(&t, planner::ToString(kind), server::ToProto(kind), p);
      }
    }
    if (t.balls_size() < 2) continue;  // no object ball: draw again
    if (overlap_mm > 0 && tables.size() % 4 == 3) {
      // Move the last ball against the one before it, overlapping by overlap_mm (the
      // pair stays clear of the cushions: both are 6 cm in).
      const int n = t.balls_size();
      const physics::Vec2 a = At(t.balls(n - 2));
      const double angle = random.Uniform(0, 2 * physics::kPi);
      const physics::Vec2 b =
          a + (2 * table.ball_radius() - overlap_mm * 1e-3) * physics::Vec2(std::cos(angle), std::sin(angle));
      bool clear = b.x() > kCushionMargin && b.x() < table.spec().width - kCushionMargin &&
                   b.y() > kCushionMargin && b.y() < table.spec().length - kCushionMargin;
      for (int i = 0; i < n - 2 && clear; ++i) {
        clear = (At(t.balls(i)) - b).norm() >= 2 * table.ball_radius() + kGap;
      }
      if (!clear) continue;  // draw this table again
      t.mutable_balls(n - 1)->mutable_position()->set_x(b.x());
      t.mutable_balls(n - 1)->mutable_position()->set_y(b.y());
    }
    tables.push_back(std::move(t));
  }
  return tables;
}

v1::Shot ShotAtABall(const v1::TableState& table, LoadRandom& random) {
  const double radius = physics::BallParams{}.radius;
  const int cue = server::CueIndex(table);
  const physics::Vec2 from = At(table.balls(cue));
  int target = random.Below(std::max(1, table.balls_size() - 1));
  if (target >= cue) ++target;
  if (target >= table.balls_size()) target = cue == 0 ? 1 : 0;
  const physics::Vec2 d = At(table.balls(target)) - from;
  v1::Shot shot;
  const double speed = random.Uniform(0.5, 5.0);
  const double rolling = speed / radius;
  shot.set_speed(speed);
  shot.set_heading_deg(physics::RadToDeg(std::atan2(d.y(), d.x())) + random.Uniform(-1.5, 1.5));
  shot.set_topspin(random.Uniform(-rolling, rolling));
  shot.set_sidespin(random.Uniform(-0.5 * rolling, 0.5 * rolling));
  return shot;
}

bool BuiltinTable(const std::string& name, v1::TableState* t) {
  t->Clear();
  const auto balls = planner::BuiltinTable(name);
  if (!balls) return false;
  server::ToProto(*balls, t);
  return true;
}

const char* BuiltinTableNames() { return planner::BuiltinTableNames(); }

bool ReadTables(const std::string& dir, std::vector<v1::TableState>* tables, std::string* error) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    *error = "'" + dir + "' is not a directory";
    return false;
  }
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    if (e.path().extension() == ".json") files.push_back(e.path());
  }
  if (ec) {
    *error = "cannot list '" + dir + "': " + ec.message();
    return false;
  }
  std::sort(files.begin(), files.end());
  constexpr std::size_t kMaxFiles = 100'000;
  if (files.empty() || files.size() > kMaxFiles) {
    *error = "'" + dir + "' holds " + std::to_string(files.size()) + " *.json files (1 to " +
             std::to_string(kMaxFiles) + " are used)";
    return false;
  }
  for (const fs::path& f : files) {
    std::string text, why;
    if (!server::ReadInputFile(f.string(), &text, &why)) {
      *error = "cannot read '" + f.string() + "': " + why;
      return false;
    }
    v1::TableState t;
    if (!ReadJsonMessage(text, &t, &why)) {
      *error = "'" + f.string() + "' is not a valid TableState JSON: " + server::BoundMessage(why);
      return false;
    }
    if (server::CueIndex(t) < 0 || t.balls_size() < 2) {
      *error = "'" + f.string() + "' needs a CUE ball and another ball";
      return false;
    }
    // What a server would refuse on any settings (the ids, kinds, positions; overlaps
    // beyond the largest vision repair a server may make), so that a load test does
    // not send a table every call of which fails.
    const server::TableCheck check =
        server::CheckTable(t, physics::DefaultTable(), server::limits::kVisionToleranceMm.hi * 1e-3);
    if (!check.errors.empty()) {
      *error = "'" + f.string() + "' is not a table a server takes: " + server::BoundMessage(server::Describe(check.errors));
      return false;
    }
    tables->push_back(std::move(t));
  }
  return true;
}

}  // namespace snooker::cli
