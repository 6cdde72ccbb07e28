// `snooker match` as a user (or scripts/frame-play) runs it: the JSON field names are a
// contract, the same seed gives the same match, and bad flags name the value.
#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <ostream>
#include <set>
#include <regex>
#include <string>

#include "tests/support/cli_support.h"

namespace snooker {
namespace {

using google::protobuf::Struct;
using cli_support::RunCli;
using cli_support::RunResult;
using cli_support::TempFile;

std::string StructJson(const Struct& s) {
  std::string out;
  EXPECT_TRUE(google::protobuf::util::MessageToJsonString(s, &out).ok());
  return out;
}

std::set<std::string> Keys(const Struct& s) {
  std::set<std::string> k;
  for (const auto& [name, value] : s.fields()) k.insert(name);
  return k;
}

// Two frames of at most 8 strokes, plans capped in simulations (not in time).
constexpr const char* kShortMatch =
    "match --frames 2 --seed 11 --json --max-simulations 60 --samples 8 --budget-ms 30000 --max-shots 8";

// A seed above 2^53 is no exact double: a JSON reader that parses numbers as doubles
// reads "seed" rounded (2^64 - 1 becomes 2^64), so "seedText" carries it exactly.
TEST(CliMatchTest, TheSeedSurvivesAsTextWhereADoubleWouldRoundIt) {
  const RunResult r = RunCli("match --frames 1 --seed 18446744073709551615 --json --max-simulations 30 --samples 4 "
                             "--budget-ms 30000 --max-shots 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Struct json;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &json).ok()) << r.out;
  EXPECT_EQ(json.fields().at("seedText").string_value(), "18446744073709551615");
  EXPECT_NE(r.out.find("\"seed\": 18446744073709551615,"), std::string::npos) << r.out;
  EXPECT_EQ(json.fields().at("seed").number_value(), 18446744073709551616.0) << "a double rounds it";
}

TEST(CliMatchTest, JsonHasTheContractedNames) {
  const RunResult r = RunCli(kShortMatch);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Struct json;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &json).ok()) << r.out;
  const std::set<std::string> contract = {"frames",     "framesWonA", "framesWonB", "pointsA",   "pointsB",
                                          "meanBreakA", "meanBreakB", "highestBreak", "centuries", "foulsA",
                                          "foulsB",     "safetiesA",  "safetiesB",  "stalls",    "shots",
                                          "planMsP50",  "planMsP99"};
  const std::set<std::string> more = {
      "playerA",      "playerB",       "seed",  "seedText",  "budgetMs",          "maxSimulations", "samples", "threads", "breakValue", "positionSpread",
      "noiseHeadingDeg", "noiseSpeed", "noiseSpin", "noiseAimDeg", "noiseCueSpeed", "noiseTipMm", "noiseElevationDeg", "noisePositionMm",   "maxShots",
      "framesCapped", "framesUndecided", "blackRespots", "simulationFailures", "thinBreakOff", "highestBreakA",
      "highestBreakB", "centuriesA",   "centuriesB",     "penaltyPointsA",    "penaltyPointsB",
      "shotsA",       "shotsB",        "stallsA",        "stallsB",           "planMsP50A",
      "planMsP50B",   "planMsP99A",    "planMsP99B",     "safetyOutlookA",    "safetyOutlookB",
      "safetyOutlookP50A", "safetyOutlookP50B", "breakOffOutlookA", "breakOffOutlookB", "breakOffOutlookP50A",
      "breakOffOutlookP50B", "kindsA", "kindsB", "routesA", "routesB", "planMsByTurn", "plansCutShort"};
  std::set<std::string> all = contract;
  all.insert(more.begin(), more.end());
  EXPECT_EQ(Keys(json), all);
  const auto& f = json.fields();
  EXPECT_EQ(f.at("frames").number_value(), 2);
  EXPECT_EQ(f.at("playerA").string_value(), "default");
  EXPECT_EQ(f.at("playerB").string_value(), "direct-pots");
  EXPECT_FALSE(f.at("thinBreakOff").bool_value());
  // The settings a rerun needs, as given (kShortMatch) or defaulted.
  EXPECT_EQ(f.at("maxSimulations").number_value(), 60);
  EXPECT_EQ(f.at("samples").number_value(), 8);
  EXPECT_EQ(f.at("threads").number_value(), 2);
  EXPECT_EQ(f.at("breakValue").number_value(), 100);  // planner/match.h kFrameBreakValue
  EXPECT_EQ(f.at("positionSpread").number_value(), 0);  // the planner's own: the nominal end
  EXPECT_EQ(f.at("seed").number_value(), 11);
  EXPECT_EQ(f.at("seedText").string_value(), "11");
  EXPECT_LE(f.at("framesWonA").number_value() + f.at("framesWonB").number_value(), 2);
  EXPECT_GT(f.at("shots").number_value(), 0);
  EXPECT_LE(f.at("shots").number_value(), 16);
  EXPECT_EQ(f.at("shotsA").number_value() + f.at("shotsB").number_value(), f.at("shots").number_value());
  EXPECT_EQ(f.at("stallsA").number_value() + f.at("stallsB").number_value(), f.at("stalls").number_value());
  EXPECT_LE(f.at("planMsP50").number_value(), f.at("planMsP99").number_value());
  EXPECT_EQ(f.at("plansCutShort").number_value(), 0);  // capped in simulations, not in time
  // The opponent's pot chance after a safety: a probability, or null when the
  // player played none.
  for (const char* key : {"safetyOutlookA", "safetyOutlookB", "safetyOutlookP50A", "safetyOutlookP50B",
                          "breakOffOutlookA", "breakOffOutlookB", "breakOffOutlookP50A", "breakOffOutlookP50B"}) {
    const auto& v = f.at(key);
    if (v.has_null_value()) continue;
    EXPECT_GE(v.number_value(), 0) << key;
    EXPECT_LE(v.number_value(), 1) << key;
  }
  if (f.at("safetiesA").number_value() == 0) {
    EXPECT_TRUE(f.at("safetyOutlookA").has_null_value());
  }
}

TEST(CliMatchTest, TheSameSeedPlaysTheSameMatch) {
  const RunResult a = RunCli(kShortMatch);
  const RunResult b = RunCli(kShortMatch);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  Struct ja, jb;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(a.out, &ja).ok()) << a.out;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(b.out, &jb).ok()) << b.out;
  // Everything but the planning times (the clock's) is equal.
  for (Struct* j : {&ja, &jb}) {
    for (const char* timing :
         {"planMsP50", "planMsP99", "planMsP50A", "planMsP50B", "planMsP99A", "planMsP99B", "planMsByTurn"}) {
      j->mutable_fields()->erase(timing);
    }
  }
  EXPECT_TRUE(google::protobuf::util::MessageDifferencer::Equals(ja, jb)) << a.out << b.out;
  EXPECT_GT(ja.fields().at("shots").number_value(), 0);
}

// --strokes: one JSON line per stroke, as many as the match's "shots", the last
// line of each frame carrying its score, a kind but for a stall and a route only for
// a pot; a path that cannot be written fails before
// any frame is played.
TEST(CliMatchTest, TheStrokeLogHasALinePerStroke) {
  const std::string path = cli_support::TempPath("match_strokes.jsonl");
  const RunResult r = RunCli(std::string(kShortMatch) + " --strokes " + path);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Struct json;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &json).ok()) << r.out;
  std::ifstream in(path);
  std::string line;
  int lines = 0;
  double points_a = 0, points_b = 0;
  const std::set<std::string> names = {"frame", "stroke", "striker", "turn", "kind", "route", "stall",
                                       "potProbability", "planScore", "potted", "foul", "points", "penalty",
                                       "scoreA", "scoreB", "planMs", "handoverPot", "planSeed", "planHandovers"};
  std::set<std::string> stall_names = names;
  stall_names.insert({"stallReason", "stallOn", "stallInHand", "stallTable"});
  Struct previous;
  int stalls = 0;
  while (std::getline(in, line)) {
    Struct s;
    ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(line, &s).ok()) << line;
    const auto& f = s.fields();
    const bool stall = f.at("stall").bool_value();
    EXPECT_EQ(Keys(s), stall ? stall_names : names) << line;
    // A stall has no plan's kind; only a pot has a route.
    const bool pot = f.at("kind").kind_case() == google::protobuf::Value::kStringValue &&
                     f.at("kind").string_value() == "POT";
    EXPECT_EQ(f.at("kind").kind_case() == google::protobuf::Value::kNullValue, stall) << line;
    EXPECT_EQ(f.at("route").kind_case() == google::protobuf::Value::kStringValue, pot) << line;
    if (stall && stalls++ == 0) {
      // A stall says why, and its table plans again through snooker plan's own input.
      EXPECT_FALSE(f.at("stallReason").string_value().empty()) << line;
      const std::string table = TempFile("stall_table.json", StructJson(f.at("stallTable").struct_value()));
      const RunResult again = RunCli("plan --table " + table + " --on " + f.at("stallOn").string_value() +
                                     (f.at("stallInHand").bool_value() ? " --cue-in-hand" : "") +
                                     " --json --max-simulations 60 --samples 8 --budget-ms 30000");
      EXPECT_EQ(again.exit_code, 0) << again.err << "\n" << line;
    }
    EXPECT_TRUE(f.at("striker").string_value() == "A" || f.at("striker").string_value() == "B") << line;
    // What the plan's Monte Carlo predicted it would hand over: none for a stall;
    // else counts of its runs, the runs that pot not among them, and a break-off
    // handing the table over in most.
    const google::protobuf::Value& predicted = f.at("planHandovers");
    EXPECT_EQ(predicted.kind_case() == google::protobuf::Value::kNullValue, stall) << line;
    if (!stall) {
      ASSERT_EQ(predicted.kind_case(), google::protobuf::Value::kStructValue) << line;
      const auto& h = predicted.struct_value().fields();
      const double samples = h.at("samples").number_value();
      const double runs = h.at("runs").number_value();
      EXPECT_EQ(samples, 8) << line;
      EXPECT_GE(runs, 0) << line;
      EXPECT_LE(runs, samples) << line;
      EXPECT_GE(h.at("snookeredRuns").number_value(), 0) << line;
      EXPECT_LE(h.at("snookeredRuns").number_value(), runs) << line;
      const double opponent_pot = h.at("meanPotProbability").number_value();
      EXPECT_GE(opponent_pot, 0) << line;
      EXPECT_LE(opponent_pot, 1) << line;
      if (pot) {
        EXPECT_LE(runs + std::round(f.at("potProbability").number_value() * samples), samples) << line;
      }
      if (f.at("turn").string_value() == "break-off") {
        EXPECT_GE(2 * runs, samples) << line;
      }
    }
    // A frame's last line holds its final score.
    if (lines > 0 && f.at("frame").number_value() != previous.fields().at("frame").number_value()) {
      points_a += previous.fields().at("scoreA").number_value();
      points_b += previous.fields().at("scoreB").number_value();
    }
    previous = s;
    ++lines;
  }
  ASSERT_GT(lines, 0);
  EXPECT_GT(stalls, 0) << "the short match was to hold a stall of direct-pots";
  points_a += previous.fields().at("scoreA").number_value();
  points_b += previous.fields().at("scoreB").number_value();
  EXPECT_EQ(lines, json.fields().at("shots").number_value());
  EXPECT_EQ(points_a, json.fields().at("pointsA").number_value());
  EXPECT_EQ(points_b, json.fields().at("pointsB").number_value());

  const RunResult bad = RunCli(std::string(kShortMatch) + " --strokes /nonexistent-dir/strokes.jsonl");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("cannot write --strokes '/nonexistent-dir/strokes.jsonl'"), std::string::npos) << bad.err;
  EXPECT_TRUE(bad.out.empty()) << bad.out;
}

// --stroke-tables: every line carries its turn's table, ball on and whether the
// cue ball was in hand; with the plan's seed, the match's flags and the player's
// own (its kinds, routes, lookahead and break value), `snooker plan` plays any
// player's turn again to the shot the log records.
struct ReplayCase {
  const char* name;
  const char* players;  // the match's --player-a and --player-b
  const char* flags_a;  // `snooker plan`'s flags for A's turns, then B's
  const char* flags_b;
  int seed;  // a match in which both players plan a stroke in the first ten
};

void PrintTo(const ReplayCase& c, std::ostream* os) { *os << c.name; }

constexpr const char* kDefaultFlags = " --break-value 100";
constexpr const char* kOnePlyFlags = " --break-value 100 --no-lookahead";
constexpr const char* kDirectPotsFlags = " --kinds POT --routes DIRECT --no-lookahead";

class CliMatchReplayTest : public testing::TestWithParam<ReplayCase> {};

TEST_P(CliMatchReplayTest, AStrokeTableReplaysTheTurnThroughSnookerPlan) {
  const ReplayCase& c = GetParam();
  const std::string noise =
      " --noise-heading-deg 0.02 --noise-speed 0.01 --noise-spin 2 --noise-aim-deg 0 --noise-cue-speed 0"
      " --noise-tip-mm 0 --noise-elevation-deg 0 --noise-position-mm 0.2";
  const std::string caps = " --max-simulations 60 --samples 8 --budget-ms 30000";
  const std::string path = cli_support::TempPath(std::string("match_stroke_tables_") + c.name + ".jsonl");
  const RunResult r = RunCli("match --frames 1 --seed " + std::to_string(c.seed) + " --max-shots 10 " + c.players + " --strokes " +
                             path + " --stroke-tables" + noise + caps);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(path);
  std::string line;
  std::array<int, 2> replayed{}, pots{};
  while (std::getline(in, line)) {
    Struct s;
    ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(line, &s).ok()) << line;
    const auto& f = s.fields();
    ASSERT_TRUE(f.count("table") && f.count("on") && f.count("inHand")) << line;
    ASSERT_FALSE(f.at("planSeed").string_value().empty()) << line;
    if (f.at("stall").bool_value()) continue;
    const int striker = f.at("striker").string_value() == "A" ? 0 : 1;
    const std::string table = TempFile("stroke_table.json", StructJson(f.at("table").struct_value()));
    const RunResult again = RunCli("plan --table " + table + " --on " + f.at("on").string_value() +
                                   (f.at("inHand").bool_value() ? " --cue-in-hand" : "") + " --seed " +
                                   f.at("planSeed").string_value() + " --shots 1" +
                                   (striker == 0 ? c.flags_a : c.flags_b) +
                                   " --squirt-uncertainty 0 --throw-uncertainty 0 --json" + noise + caps);
    ASSERT_EQ(again.exit_code, 0) << again.err << "\n" << line;
    Struct plan;
    ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(again.out, &plan).ok()) << again.out;
    const auto& shots = plan.fields().at("shots").list_value().values();
    ASSERT_EQ(shots.size(), 1) << again.out;
    const auto& shot = shots[0].struct_value().fields();
    EXPECT_EQ(shot.at("kind").string_value(), f.at("kind").string_value()) << line << "\n" << again.out;
    if (f.at("kind").string_value() == "POT") {
      ++pots[static_cast<size_t>(striker)];
      EXPECT_EQ(shot.at("route").string_value(), f.at("route").string_value()) << line << "\n" << again.out;
      EXPECT_NEAR(shot.at("potProbability").number_value(), f.at("potProbability").number_value(), 1e-9)
          << line << "\n" << again.out;
    }
    ++replayed[static_cast<size_t>(striker)];
  }
  // Both players' turns were played again, pots among them.
  EXPECT_GE(replayed[0], 1);
  EXPECT_GE(replayed[1], 1);
  EXPECT_GE(pots[0] + pots[1], 1);
}

INSTANTIATE_TEST_SUITE_P(Players, CliMatchReplayTest,
                         testing::Values(ReplayCase{"DefaultAgainstDirectPots", "", kDefaultFlags, kDirectPotsFlags, 13},
                                         ReplayCase{"OnePlyAgainstDefault", "--player-a one-ply --player-b default",
                                                    kOnePlyFlags, kDefaultFlags, 11},
                                         // The match's --position-spread is both players' here (one-ply's
                                         // too; direct-pots' never, MatchTest).
                                         ReplayCase{"DefaultAndOnePlyWithAPositionSpread",
                                                    "--player-b one-ply --position-spread 2",
                                                    " --break-value 100 --position-spread 2",
                                                    " --break-value 100 --position-spread 2 --no-lookahead", 11}),
                         [](const testing::TestParamInfo<ReplayCase>& p) { return std::string(p.param.name); });

// A seed is any uint64, as the API's: the largest plays, and the JSON gives it whole.
TEST(CliMatchTest, TheLargestSeedPlays) {
  const RunResult r = RunCli(
      "match --frames 1 --seed 18446744073709551615 --json --max-simulations 40 --samples 8 --budget-ms 30000 "
      "--max-shots 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"seed\": 18446744073709551615,"), std::string::npos) << r.out;
}

// --thin-break-off: the planners search the thin break beside the soft one, and the
// JSON says so; one frame's break-off only.
TEST(CliMatchTest, TheThinBreakOffIsAskedForByFlag) {
  const RunResult r = RunCli(
      "match --frames 1 --seed 5 --json --max-simulations 60 --samples 8 --budget-ms 30000 --max-shots 1 "
      "--thin-break-off");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Struct json;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &json).ok()) << r.out;
  EXPECT_TRUE(json.fields().at("thinBreakOff").bool_value());
  EXPECT_EQ(json.fields().at("shots").number_value(), 1);
}

TEST(CliMatchTest, ReadableOutputNamesThePlayers) {
  const RunResult r = RunCli(
      "match --frames 1 --seed 3 --player-a one-ply --player-b default --max-simulations 40 --samples 8 "
      "--budget-ms 30000 --max-shots 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("A one-ply against B default"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("frames won"), std::string::npos) << r.out;
  // A broke off, B did not: B's outlook after a break-off is "-", not "nan".
  const std::regex break_off_row(R"(\n  opponent's pot after break-off +[01]\.[0-9]{2} +-\n)");
  EXPECT_TRUE(std::regex_search(r.out, break_off_row)) << r.out;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
}

struct BadFlag {
  const char* args;
  const char* message;
};

// gtest prints a parameter with this (not as bytes).
void PrintTo(const BadFlag& c, std::ostream* os) { *os << "snooker " << c.args; }

class CliMatchBadFlagTest : public testing::TestWithParam<BadFlag> {};

TEST_P(CliMatchBadFlagTest, NamesTheValue) {
  const RunResult r = RunCli(GetParam().args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(GetParam().message), std::string::npos) << r.err;
}

INSTANTIATE_TEST_SUITE_P(
    Flags, CliMatchBadFlagTest,
    testing::Values(BadFlag{"match --seed 1", "--frames is required"},
                    BadFlag{"match --frames 0 --seed 1", "--frames 0 is out of range"},
                    BadFlag{"match --frames 1 --seed 1 --player-a grandmaster", "--player-a 'grandmaster' is not a player"},
                    BadFlag{"match --frames 1 --seed 1 --player-b ''", "--player-b needs a value; it was given an empty one"},
                    BadFlag{"match --frames 1 --seed 1 --noise-speed 2", "--noise-speed 2 is out of range"},
                    BadFlag{"match --frames 1 --seed 1 --budget-ms 0", "--budget-ms 0 is out of range"},
                    BadFlag{"match --frames 1 --seed 1 --max-shots 201", "--max-shots 201 is out of range"},
                    BadFlag{"match --frames 1 --seed 1 --break-value 148", "--break-value 148 is out of range [0, 147]"},
                    BadFlag{"match --frames 1 --seed 1 --break-value lots", "--break-value 'lots'"},
                    BadFlag{"match --frames 1 --seed 1 --position-spread 4.5",
                            "--position-spread 4.5 is out of range [0, 4]"},
                    BadFlag{"match --frames 1 --seed 1 --stroke-tables", "--stroke-tables needs --strokes"},
                    BadFlag{"match --frames 1 --seed 1 --colour pink", "unknown option --colour"},
                    BadFlag{"match --frames 1 --seed 18446744073709551616",
                            "--seed '18446744073709551616' is not a whole number in [0, 18446744073709551615]"},
                    BadFlag{"match --frames 1 --seed -1", "--seed '-1' is not a whole number"}),
    [](const testing::TestParamInfo<BadFlag>& param) {
      std::string name;
      for (const char c : std::string(param.param.args).substr(6)) {
        if (std::isalnum(static_cast<unsigned char>(c))) {
          name += c;
        } else if (!name.empty() && name.back() != '_') {
          name += '_';
        }
      }
      while (!name.empty() && name.back() == '_') name.pop_back();
      return name;
    });

}  // namespace
}  // namespace snooker
