#include "planner/builtin_tables.h"

#include <cstddef>
#include <utility>

#include "physics/table/table.h"

namespace snooker::planner {

namespace {

void Add(std::vector<NamedBall>& balls, std::string id, BallKind kind, const physics::Vec2& at) {
  balls.push_back({std::move(id), Ball{kind, at}});
}

// The colours on their spots, named by colour.
void AddColours(std::vector<NamedBall>& balls, const physics::TableModel& table) {
  for (int c = 0; c < physics::kColourCount; ++c) {
    const physics::Colour colour = static_cast<physics::Colour>(c);
    Add(balls, ToString(KindOf(colour)), KindOf(colour), table.spot(colour));
  }
}

// Red i of the rack (0-based) as "red-<i+1>".
void AddRed(std::vector<NamedBall>& balls, const physics::TableModel& table, std::size_t i) {
  Add(balls, "red-" + std::to_string(i + 1), BallKind::kRed, table.reds()[i]);
}

void Black(std::vector<NamedBall>& balls, const physics::TableModel& table) {
  const physics::Vec2 black = table.spot(physics::Colour::kBlack);
  Add(balls, "cue", BallKind::kCue, black + physics::Vec2(0.45, -0.30));
  Add(balls, "black", BallKind::kBlack, black);
  for (const std::size_t i : {0u, 4u, 9u}) AddRed(balls, table, i);
}

void Red(std::vector<NamedBall>& balls, const physics::TableModel&) {
  Add(balls, "cue", BallKind::kCue, {1.1819, 2.9729});
  Add(balls, "red-1", BallKind::kRed, {1.4648, 3.2558});
  Add(balls, "black", BallKind::kBlack, {0.889, 3.245});
  Add(balls, "red-2", BallKind::kRed, {0.4, 1.5});
}

void Colours(std::vector<NamedBall>& balls, const physics::TableModel& table) {
  Add(balls, "cue", BallKind::kCue, table.spot(physics::Colour::kBrown) + physics::Vec2(0.12, 0.35));
  AddColours(balls, table);
}

void BreakOff(std::vector<NamedBall>& balls, const physics::TableModel& table) {
  for (std::size_t i = 0; i < table.reds().size(); ++i) AddRed(balls, table, i);
  AddColours(balls, table);
}

// Every built-in table by name, in the order the names are listed.
struct Builder {
  BuiltinTableEntry entry;
  void (*build)(std::vector<NamedBall>&, const physics::TableModel&);
};
constexpr Builder kTables[] = {
    {{"black", "the black and three reds"}, Black},
    {{"red", "a red by the top-right pocket"}, Red},
    {{"colours", "the six colours on their spots"}, Colours},
    {{"break-off", "the reds racked, the cue ball in hand"}, BreakOff},
};

}  // namespace

std::optional<std::vector<NamedBall>> BuiltinTable(std::string_view name) {
  for (const Builder& b : kTables) {
    if (b.entry.name != name) continue;
    std::vector<NamedBall> balls;
    b.build(balls, physics::DefaultTable());
    return balls;
  }
  return std::nullopt;
}

std::vector<BuiltinTableEntry> BuiltinTableList() {
  std::vector<BuiltinTableEntry> list;
  for (const Builder& b : kTables) list.push_back(b.entry);
  return list;
}

const char* BuiltinTableNames() {
  static const std::string names = [] {
    std::string s;
    for (const Builder& b : kTables) s += (s.empty() ? "" : ", ") + std::string(b.entry.name);
    return s;
  }();
  return names.c_str();
}

TableState TableOf(const std::vector<NamedBall>& balls) {
  TableState t;
  t.balls.reserve(balls.size());
  for (const NamedBall& b : balls) t.balls.push_back(b.ball);
  return t;
}

}  // namespace snooker::planner
