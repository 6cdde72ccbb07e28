// Varied table states and shots for `snooker loadtest`, built in and seeded: the
// same seed gives the same tables and shots on every machine (a 64-bit generator
// and our own conversions to numbers, no std:: distributions).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "snooker/v1/table.pb.h"

namespace snooker::cli {

/// A small deterministic generator (physics/core/splitmix64.h).
class LoadRandom {
 public:
  explicit LoadRandom(std::uint64_t seed) : state_(seed) {}
  std::uint64_t Next();
  /// Uniform in [lo, hi).
  double Uniform(double lo, double hi);
  /// Uniform in [0, n).
  int Below(int n);

 private:
  std::uint64_t state_;
};

/// `count` valid table states: a cue ball, 0 to 15 reds and some of the colours
/// (at least one object ball), spread over the bed at least 1 mm apart and 6 cm from
/// the cushions. When `overlap_mm` > 0, every fourth table has two balls that overlap
/// by that much, as vision reports them: a server with a vision tolerance at least
/// that large moves them apart and warns.
std::vector<v1::TableState> VariedTables(std::uint64_t seed, int count, double overlap_mm);

/// A shot at one of the table's object balls (chosen by the generator), a little off
/// a full-ball contact: speed 0.5 to 5 m/s, topspin and sidespin within the rolling
/// spin (sidespin within half of it).
v1::Shot ShotAtABall(const v1::TableState& table, LoadRandom& random);

/// The built-in table `name` (planner/builtin_tables.h: "black", "red", "colours",
/// "break-off") as the API's table state, with its balls' ids, for `snooker plan
/// --table builtin:NAME` and the README's demonstration. False for another name.
bool BuiltinTable(const std::string& name, v1::TableState* table);
/// The names BuiltinTable knows, comma-separated.
const char* BuiltinTableNames();

/// The table states in the *.json files of `dir` (Protobuf's JSON form of
/// TableState, as `snooker simulate --table` reads), in name order. False with the
/// reason in `error` (a file that does not read or parse, or none at all).
bool ReadTables(const std::string& dir, std::vector<v1::TableState>* tables, std::string* error);

}  // namespace snooker::cli
