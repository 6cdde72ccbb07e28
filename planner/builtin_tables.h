// The built-in tables: a few named scenes on the default table that the command line
// (`snooker plan --table builtin:NAME`, `snooker demo`), the README's demonstration
// and the tests all play. They are defined here once, with the ids their balls carry
// in an answer, so that a figure quoted for "the demo's table" means one table.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "planner/rules.h"

namespace snooker::planner {

/// A ball of a built-in table and the id it is known by ("cue", "black", "red-5").
struct NamedBall {
  std::string id;
  Ball ball;
};

/// The built-in table `name`, on physics::DefaultTable(), its balls in a fixed order:
/// - "black": the cue ball at the black spot + (0.45, -0.30) m, the black on its
///   spot, and reds 1, 5 and 10 of the rack (ids "red-1", "red-5", "red-10");
/// - "red": a red near the top-right pocket, the black, a red in baulk;
/// - "colours": the reds gone, the six colours on their spots, the cue ball at the
///   brown spot + (0.12, 0.35) m;
/// - "break-off": the 15 reds racked and the colours on their spots, with no cue
///   ball (it is in hand).
/// nullopt for any other name.
std::optional<std::vector<NamedBall>> BuiltinTable(std::string_view name);

/// A built-in table's name and a one-line description of it, for a menu.
struct BuiltinTableEntry {
  std::string_view name;
  std::string_view description;
};

/// Every name BuiltinTable knows, with its description, in a fixed order ("black"
/// first: the demonstration's table).
std::vector<BuiltinTableEntry> BuiltinTableList();

/// The names BuiltinTable knows, comma-separated (for messages).
const char* BuiltinTableNames();

/// The balls without their ids, in the same order.
TableState TableOf(const std::vector<NamedBall>& balls);

}  // namespace snooker::planner
