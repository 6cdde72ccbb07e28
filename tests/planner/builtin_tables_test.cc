// Tests of the built-in tables (planner/builtin_tables.h): each named table is a legal
// table for a plan, its ids are unique and say what the ball is, the names listed are
// exactly the names that resolve, and the tables the docs describe are where they say.
#include "planner/builtin_tables.h"

#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "physics/table/table.h"
#include "planner/validate.h"

namespace snooker::planner {
namespace {

std::vector<std::string> ListedNames() {
  std::vector<std::string> names;
  std::stringstream in(BuiltinTableNames());
  for (std::string name; std::getline(in, name, ',');) {
    name.erase(0, name.find_first_not_of(' '));
    names.push_back(name);
  }
  return names;
}

TEST(BuiltinTablesTest, EveryListedTableIsLegalWithUniqueIdsThatNameTheKind) {
  const std::vector<std::string> names = ListedNames();
  ASSERT_EQ(names.size(), 4u);
  for (const std::string& name : names) {
    const auto balls = BuiltinTable(name);
    ASSERT_TRUE(balls.has_value()) << name;
    const TableState t = TableOf(*balls);
    ASSERT_EQ(t.balls.size(), balls->size()) << name;
    const bool in_hand = t.cue_index() < 0;
    EXPECT_EQ(in_hand, name == "break-off") << name;
    const std::vector<FieldError> errors = ValidateTable(t, in_hand, std::nullopt, physics::DefaultTable());
    EXPECT_TRUE(errors.empty()) << name << ": " << errors.front().field << " " << errors.front().rule;
    std::set<std::string> ids;
    for (const NamedBall& b : *balls) {
      EXPECT_TRUE(ids.insert(b.id).second) << name << ": id " << b.id << " twice";
      // "red-N" for a red, the kind's own name otherwise.
      const std::string kind = ToString(b.ball.kind);
      if (b.ball.kind == BallKind::kRed) {
        EXPECT_EQ(b.id.rfind("red-", 0), 0u) << name << ": " << b.id;
      } else {
        EXPECT_EQ(b.id, kind) << name;
      }
    }
  }
}

TEST(BuiltinTablesTest, TheListHasTheNamesOfTheMessageInTheirOrderEachDescribed) {
  const std::vector<BuiltinTableEntry> list = BuiltinTableList();
  const std::vector<std::string> names = ListedNames();
  ASSERT_EQ(list.size(), names.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    EXPECT_EQ(list[i].name, names[i]);
    EXPECT_TRUE(BuiltinTable(list[i].name).has_value()) << list[i].name;
    EXPECT_FALSE(list[i].description.empty()) << list[i].name;
  }
  EXPECT_EQ(list.front().name, "black");  // the demonstration's table comes first
}

TEST(BuiltinTablesTest, AnUnlistedNameHasNoTable) {
  EXPECT_FALSE(BuiltinTable("snooker").has_value());
  EXPECT_FALSE(BuiltinTable("").has_value());
  EXPECT_FALSE(BuiltinTable("Black").has_value());
}

TEST(BuiltinTablesTest, TheDemoTableIsTheBlackWithTheCueBallBelowRightAndThreeReds) {
  const physics::TableModel& model = physics::DefaultTable();
  const auto balls = BuiltinTable("black");
  ASSERT_TRUE(balls.has_value());
  ASSERT_EQ(balls->size(), 5u);
  const physics::Vec2 black = model.spot(physics::Colour::kBlack);
  EXPECT_EQ((*balls)[0].id, "cue");
  EXPECT_LT(((*balls)[0].ball.position - (black + physics::Vec2(0.45, -0.30))).norm(), 1e-12);
  EXPECT_EQ((*balls)[1].id, "black");
  EXPECT_LT(((*balls)[1].ball.position - black).norm(), 1e-12);
  const std::size_t rack[] = {0, 4, 9};
  for (std::size_t k = 0; k < 3; ++k) {
    const NamedBall& red = (*balls)[2 + k];
    EXPECT_EQ(red.id, "red-" + std::to_string(rack[k] + 1));
    EXPECT_LT((red.ball.position - model.reds()[rack[k]]).norm(), 1e-12) << red.id;
  }
}

TEST(BuiltinTablesTest, TheBreakOffIsTheFullRackAndTheColoursOnTheirSpots) {
  const physics::TableModel& model = physics::DefaultTable();
  const TableState t = TableOf(*BuiltinTable("break-off"));
  EXPECT_EQ(t.Count(BallKind::kRed), 15);
  EXPECT_EQ(t.Count(BallKind::kCue), 0);
  for (const physics::Colour c : {physics::Colour::kYellow, physics::Colour::kGreen, physics::Colour::kBrown,
                                  physics::Colour::kBlue, physics::Colour::kPink, physics::Colour::kBlack}) {
    ASSERT_EQ(t.Count(KindOf(c)), 1);
    for (const Ball& b : t.balls) {
      if (b.kind == KindOf(c)) {
        EXPECT_LT((b.position - model.spot(c)).norm(), 1e-12) << ToString(b.kind);
      }
    }
  }
}

}  // namespace
}  // namespace snooker::planner
