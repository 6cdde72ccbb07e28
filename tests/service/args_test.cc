// The command's flag parser on its own: each form a flag may take, and each error
// with the flag and the text it names (the messages a user sees from every command).
#include "cli/args.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace snooker::cli {
namespace {

Args Parse(const std::vector<std::string>& argv) {
  return Args(argv, {"speed", "frames", "seed", "table"}, {"json", "svg"});
}

TEST(ArgsTest, ReadsSpacedAndInlineValuesAndSwitches) {
  Args a = Parse({"--speed", "1.5", "--frames=12", "--json", "--table=builtin:black"});
  ASSERT_EQ(a.error(), "");
  EXPECT_TRUE(a.Has("speed"));
  EXPECT_FALSE(a.Has("seed"));
  EXPECT_TRUE(a.Switch("json"));
  EXPECT_FALSE(a.Switch("svg"));
  EXPECT_EQ(a.Number("speed", std::nullopt), 1.5);
  EXPECT_EQ(a.Integer("frames", std::nullopt, 1, 100), 12);
  EXPECT_EQ(a.Text("table", std::nullopt), "builtin:black");
  EXPECT_EQ(a.Unsigned64("seed", 7), 7u);  // unset: the fallback
  EXPECT_EQ(a.error(), "");
}

// A value may itself begin with "--" or "-" when it follows its flag: it is the value.
TEST(ArgsTest, TheWordAfterAValuedFlagIsItsValue) {
  Args a = Parse({"--table", "--json", "--speed", "-2"});
  ASSERT_EQ(a.error(), "");
  EXPECT_EQ(a.Text("table", std::nullopt), "--json");
  EXPECT_FALSE(a.Switch("json"));
  EXPECT_EQ(a.Number("speed", std::nullopt), -2.0);
}

TEST(ArgsTest, ParseErrorsNameTheFlagOrTheWord) {
  EXPECT_EQ(Parse({"plan"}).error(), "unexpected argument 'plan'");
  EXPECT_EQ(Parse({"--"}).error(), "unexpected argument '--'");
  EXPECT_EQ(Parse({"-speed", "1"}).error(), "unexpected argument '-speed'");
  EXPECT_EQ(Parse({"--colour", "pink"}).error(), "unknown option --colour");
  EXPECT_EQ(Parse({"--json=yes"}).error(), "--json takes no value (got 'yes')");
  EXPECT_EQ(Parse({"--json", "--speed"}).error(), "--speed needs a value");
  // The first error is kept.
  EXPECT_EQ(Parse({"--colour", "--json=1"}).error(), "unknown option --colour");
}

TEST(ArgsTest, NumbersMustBeWholeAndFinite) {
  for (const char* bad : {"1.5x", " 1", "abc", "0x10"}) {
    Args a = Parse({"--speed", bad});
    EXPECT_EQ(a.Number("speed", std::nullopt), std::nullopt) << bad;
    EXPECT_EQ(a.error(), "--speed '" + std::string(bad) + "' is not a number") << bad;
  }
  for (const char* bad : {"nan", "inf", "-inf"}) {
    Args a = Parse({"--speed", bad});
    EXPECT_EQ(a.Number("speed", std::nullopt), std::nullopt) << bad;
    EXPECT_EQ(a.error(), "--speed '" + std::string(bad) + "' is not a finite number") << bad;
  }
  // Beyond a double's range from_chars reports out of range: not a number.
  Args big = Parse({"--speed", "1e400"});
  EXPECT_EQ(big.Number("speed", std::nullopt), std::nullopt);
  EXPECT_EQ(big.error(), "--speed '1e400' is not a number");
  Args sci = Parse({"--speed=2.5e-1"});
  EXPECT_EQ(sci.Number("speed", std::nullopt), 0.25);
}

TEST(ArgsTest, IntegersKeepToTheirRange) {
  Args a = Parse({"--frames", "0"});
  EXPECT_EQ(a.Integer("frames", std::nullopt, 1, 100), std::nullopt);
  EXPECT_EQ(a.error(), "--frames 0 is out of range [1, 100]");
  Args edge = Parse({"--frames", "100"});
  EXPECT_EQ(edge.Integer("frames", std::nullopt, 1, 100), 100);
  for (const char* bad : {"1.0", "1e2", "+5", "12 "}) {
    Args b = Parse({"--frames", bad});
    EXPECT_EQ(b.Integer("frames", std::nullopt, 1, 100), std::nullopt) << bad;
    EXPECT_EQ(b.error(), "--frames '" + std::string(bad) + "' is not a whole number") << bad;
  }
  // A whole number beyond a long is out of range, not "not a whole number".
  for (const char* huge : {"9223372036854775808", "-9223372036854775809"}) {
    Args h = Parse({"--frames", huge});
    EXPECT_EQ(h.Integer("frames", std::nullopt, 1, 100), std::nullopt) << huge;
    EXPECT_EQ(h.error(), "--frames " + std::string(huge) + " is out of range [1, 100]") << huge;
  }
}

TEST(ArgsTest, SeedsTakeTheWholeUnsignedRange) {
  Args top = Parse({"--seed", "18446744073709551615"});
  EXPECT_EQ(top.Unsigned64("seed", std::nullopt), std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(top.error(), "");
  for (const char* bad : {"-1", "18446744073709551616", "1.5"}) {
    Args a = Parse({"--seed", bad});
    EXPECT_EQ(a.Unsigned64("seed", std::nullopt), std::nullopt) << bad;
    EXPECT_EQ(a.error(), "--seed '" + std::string(bad) + "' is not a whole number in [0, 18446744073709551615]")
        << bad;
  }
}

TEST(ArgsTest, AFlagWithoutAFallbackIsRequired) {
  Args a = Parse({"--json"});
  EXPECT_EQ(a.Text("table", std::nullopt), std::nullopt);
  EXPECT_EQ(a.error(), "--table is required");
  // The later lookups keep the first error.
  EXPECT_EQ(a.Integer("frames", std::nullopt, 1, 10), std::nullopt);
  EXPECT_EQ(a.error(), "--table is required");
}

// An empty path or address (an unset shell variable) is an error, not the flag left out.
TEST(ArgsTest, AnEmptyTextIsRefused) {
  for (const std::vector<std::string>& argv :
       {std::vector<std::string>{"--table", ""}, {"--table="}, {"--speed", ""}}) {
    const Args a = Parse(argv);
    EXPECT_EQ(a.error(), argv[0].substr(0, argv[0].find('=')) + " needs a value; it was given an empty one");
  }
}

}  // namespace
}  // namespace snooker::cli
