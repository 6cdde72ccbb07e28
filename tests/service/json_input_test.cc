// Tests of server/json_input.h: the JSON syntax scanner (the first error's line and
// column), and ReadJsonMessage (ball kinds and the ball on in any case, unknown kinds
// named with their ball and the kinds there are, Protobuf's reasons for the rest).
#include "server/json_input.h"

#include <gtest/gtest.h>

#include <cctype>
#include <string>

#include "snooker/v1/plan.pb.h"
#include "snooker/v1/table.pb.h"
#include "tests/support/text.h"

namespace snooker {
namespace {

using server::FindJsonSyntaxError;
using server::JsonSyntaxError;
using server::ReadJsonMessage;

// Test names from a case's own name.
template <typename Case>
std::string CaseName(const testing::TestParamInfo<Case>& info) {
  return info.param.name;
}

// ---- The syntax scanner ----------------------------------------------------------

struct ValidCase {
  const char* name;
  std::string text;
};

// gtest prints a parameter with this (not as bytes).
void PrintTo(const ValidCase& c, std::ostream* os) { *os << c.name; }

class JsonSyntaxValidTest : public testing::TestWithParam<ValidCase> {};

TEST_P(JsonSyntaxValidTest, HasNoError) {
  const auto error = FindJsonSyntaxError(GetParam().text);
  EXPECT_FALSE(error.has_value()) << GetParam().text << ": line " << error->line << ", column "
                                  << error->column << ": " << error->what;
}

INSTANTIATE_TEST_SUITE_P(
    Documents, JsonSyntaxValidTest,
    testing::Values(
        ValidCase{"EmptyObject", "{}"}, ValidCase{"EmptyArray", " [ ] "},
        ValidCase{"Scalars", R"({"a": [0, -1, 2.5, -0.0e+5, 1E-3, true, false, null, ""]})"},
        ValidCase{"Escapes", R"({"s": "q\" b\\ s\/ \b\f\n\r\t \u00e9 \ud83c\udfb1"})"},
        ValidCase{"TopLevelString", "\"just a string\""}, ValidCase{"TopLevelNumber", "\t\r\n42\n"},
        ValidCase{"Utf8Text", "{\"caf\xC3\xA9\": \"\xE2\x82\xAC\"}"},
        ValidCase{"ATable", R"({"balls": [{"id": "cue", "kind": "CUE", "position": {"x": 0.9, "y": 0.6}}]})"},
        ValidCase{"HundredLevels", std::string(100, '[') + std::string(100, ']')}),
    CaseName<ValidCase>);

struct ErrorCase {
  const char* name;
  std::string text;
  int line, column;
  const char* what;  // part of the message
};

// gtest prints a parameter with this (not as bytes).
void PrintTo(const ErrorCase& c, std::ostream* os) { *os << c.name; }

class JsonSyntaxErrorTest : public testing::TestWithParam<ErrorCase> {};

TEST_P(JsonSyntaxErrorTest, IsFoundAtItsLineAndColumn) {
  const ErrorCase& c = GetParam();
  const auto error = FindJsonSyntaxError(c.text);
  ASSERT_TRUE(error.has_value()) << c.text;
  EXPECT_EQ(error->line, c.line) << error->what;
  EXPECT_EQ(error->column, c.column) << error->what;
  EXPECT_TRUE(Mentions(error->what, c.what)) << error->what;
}

INSTANTIATE_TEST_SUITE_P(
    Documents, JsonSyntaxErrorTest,
    testing::Values(
        ErrorCase{"Empty", "", 1, 1, "the document is empty"},
        ErrorCase{"OnlySpace", " \n  ", 2, 3, "the document is empty"},
        ErrorCase{"MissingCommaBetweenBalls",
                  "{\"balls\": [\n  {\"id\": \"cue\"}\n  {\"id\": \"red\"}\n]}", 3, 3,
                  "expected ',' or ']' after an element of an array, found '{'"},
        ErrorCase{"MissingCommaBetweenMembers", "{\n  \"a\": 1\n  \"b\": 2\n}", 3, 3,
                  "expected ',' or '}' after a member of an object, found '\"'"},
        ErrorCase{"TrailingComma", "{\"a\": 1,}", 1, 9, "expected the name of a member"},
        ErrorCase{"SingleQuotes", "{'a': 1}", 1, 2,
                  "expected the name of a member (a string in double quotes)"},
        ErrorCase{"MissingColon", "{\"a\" 1}", 1, 6, "expected ':' after the member name \"a\", found '1'"},
        ErrorCase{"UnclosedArray", "[1, 2", 1, 6, "the document ends inside an array"},
        ErrorCase{"UnclosedObject", "{\"a\": {}", 1, 9, "the document ends inside an object"},
        ErrorCase{"UnclosedString", "{\"a\": \"x}", 1, 7, "a string that is never closed"},
        ErrorCase{"BadLiteral", "{\"a\": tru}", 1, 7, "expected true, false or null"},
        ErrorCase{"LeadingZero", "{\"a\": 01}", 1, 8, "must not start with 0"},
        ErrorCase{"BareMinus", "[-]", 1, 3, "expected a digit after '-', found ']'"},
        ErrorCase{"BareDecimalPoint", "[1.]", 1, 4, "expected a digit after the decimal point"},
        ErrorCase{"BareExponent", "[1e+]", 1, 5, "expected a digit in the exponent"},
        ErrorCase{"NotAValue", "{\"a\": @}", 1, 7, "expected a value (an object, array, string, number"},
        ErrorCase{"UnknownEscape", "[\"a\\qb\"]", 1, 4, "an unknown escape '\\q'"},
        ErrorCase{"ShortUnicodeEscape", "[\"\\u12\"]", 1, 3, "four hexadecimal digits"},
        ErrorCase{"TabInString", "[\"a\tb\"]", 1, 4, "a control character (byte 0x09) inside a string"},
        ErrorCase{"TextAfterTheDocument", "{}\n x", 2, 2,
                  "unexpected text after the end of the JSON document"},
        ErrorCase{"ColumnsCountCharacters", "{\"caf\xC3\xA9\": ]}", 1, 10, "expected a value"},
        ErrorCase{"ByteOrderMark", "\xEF\xBB\xBF{}", 1, 1, "byte order mark"},
        ErrorCase{"OverHundredLevels", std::string(101, '[') + std::string(101, ']'), 1, 101,
                  "nested more than 100 levels deep"}),
    CaseName<ErrorCase>);

// ---- Reading a message ------------------------------------------------------------

TEST(ReadJsonMessageTest, BallKindsAreTakenInAnyCase) {
  v1::TableState t;
  std::string error;
  ASSERT_TRUE(ReadJsonMessage(R"({"balls": [
      {"id": "cue", "kind": "cue", "position": {"x": 0.9, "y": 0.6}},
      {"id": "r", "kind": "Red", "position": {"x": 0.9, "y": 1.6}},
      {"id": "b", "kind": "bLaCk"},
      {"id": "p", "kind": "PINK"},
      {"id": "e", "kind": "yell\u006Fw"}]})",
                              &t, &error))
      << error;
  ASSERT_EQ(t.balls_size(), 5);
  EXPECT_EQ(t.balls(0).kind(), v1::CUE);
  EXPECT_EQ(t.balls(1).kind(), v1::RED);
  EXPECT_EQ(t.balls(2).kind(), v1::BLACK);
  EXPECT_EQ(t.balls(3).kind(), v1::PINK);
  EXPECT_EQ(t.balls(4).kind(), v1::YELLOW);
  EXPECT_EQ(t.balls(1).position().y(), 1.6);  // the rest as written
  EXPECT_EQ(t.balls(4).id(), "e");
}

TEST(ReadJsonMessageTest, AnUnknownKindNamesTheBallByIdAndListsTheKinds) {
  v1::TableState t;
  std::string error;
  EXPECT_FALSE(ReadJsonMessage("{\"balls\": [\n  {\"id\": \"cue\", \"kind\": \"CUE\"},\n"
                               "  {\"kind\": \"purple\", \"id\": \"red-3\"}]}",
                               &t, &error));
  EXPECT_EQ(error,
            "line 3, column 12: ball \"red-3\" has kind \"purple\", which is not one of CUE, RED, YELLOW, "
            "GREEN, BROWN, BLUE, PINK, BLACK (in any case)");
}

TEST(ReadJsonMessageTest, AnUnknownKindOfABallWithoutIdNamesItsIndex) {
  v1::TableState t;
  std::string error;
  EXPECT_FALSE(ReadJsonMessage(R"({"balls": [{"id": "cue", "kind": "CUE"}, {"kind": "Magenta"},
                                             {"kind": "teal"}]})",
                               &t, &error));
  EXPECT_TRUE(Mentions(error, "ball 1 (counting from 0; it has no id) has kind \"Magenta\", which is not "
                              "one of CUE, RED, YELLOW, GREEN, BROWN, BLUE, PINK, BLACK"))
      << error;
  EXPECT_TRUE(Mentions(error, "; and 1 more like it")) << error;  // teal
}

TEST(ReadJsonMessageTest, TheBallOnIsTakenInAnyCaseWithOrWithoutItsPrefix) {
  for (const char* on : {"pink", "Pink", "PINK", "ball_on_pink", "BALL_ON_PINK"}) {
    for (const char* name : {"ballOn", "ball_on"}) {
      v1::PlanRequest r;
      std::string error;
      const std::string text =
          std::string("{\"") + name + "\": \"" + on +
          R"(", "table": {"balls": [{"id": "c", "kind": "cue"}, {"id": "p", "kind": "pink"}]}})";
      ASSERT_TRUE(ReadJsonMessage(text, &r, &error)) << text << ": " << error;
      EXPECT_EQ(r.ball_on(), v1::BALL_ON_PINK) << text;
      ASSERT_EQ(r.table().balls_size(), 2);
      EXPECT_EQ(r.table().balls(0).kind(), v1::CUE);
      EXPECT_EQ(r.table().balls(1).kind(), v1::PINK);
    }
  }
}

TEST(ReadJsonMessageTest, AnUnknownBallOnListsTheValues) {
  v1::PlanRequest r;
  std::string error;
  EXPECT_FALSE(ReadJsonMessage(R"({"maxShots": 2, "ballOn": "purple"})", &r, &error));
  EXPECT_EQ(error, "line 1, column 27: ballOn \"purple\" is not one of RED, COLOUR, YELLOW, GREEN, BROWN, "
                   "BLUE, PINK, BLACK (in any case)");
}

TEST(ReadJsonMessageTest, ASyntaxErrorIsGivenByLineAndColumn) {
  v1::TableState t;
  std::string error;
  EXPECT_FALSE(ReadJsonMessage("{\"balls\": [\n  {\"id\": \"cue\", \"kind\": \"cue\"}\n  {\"id\": \"r\"}\n]}",
                               &t, &error));
  EXPECT_EQ(error, "line 3, column 3: expected ',' or ']' after an element of an array, found '{'");
}

// What Protobuf's own reader takes beyond JSON (a trailing comma, single quotes) is
// still read.
TEST(ReadJsonMessageTest, WhatProtobufTakesBeyondJsonIsStillRead) {
  v1::TableState t;
  std::string error;
  ASSERT_TRUE(ReadJsonMessage("{'balls': [{'id': 'cue', 'kind': 'CUE'}],}", &t, &error)) << error;
  ASSERT_EQ(t.balls_size(), 1);
  EXPECT_EQ(t.balls(0).id(), "cue");
}

// Protobuf's reader takes a member given twice: the last value of a single field, the
// two lists joined of a repeated one. Either would act on a table other than the one
// its sender meant, so a field may be given once, by either of its names.
TEST(ReadJsonMessageTest, AFieldGivenTwiceIsRefused) {
  v1::TableState t;
  std::string error;
  EXPECT_FALSE(ReadJsonMessage(R"({"balls": [{"id": "cue", "kind": "CUE"}], "balls": [{"id": "red-1", "kind": "RED"}]})",
                               &t, &error));
  EXPECT_EQ(error, "line 1, column 52: \"balls\" is given a second time in the same object");
  EXPECT_FALSE(ReadJsonMessage(R"({"balls": [{"id": "cue", "kind": "CUE", "id": "red-1"}]})", &t, &error));
  EXPECT_EQ(error, "line 1, column 47: \"id\" is given a second time in the same object");
  v1::PlanRequest r;
  EXPECT_FALSE(ReadJsonMessage(R"({"ballOn": "RED", "ball_on": "PINK"})", &r, &error));
  EXPECT_EQ(error, "line 1, column 30: \"ball_on\" is given a second time in the same object (first as \"ballOn\")");
  // The same name in different objects is no repeat.
  ASSERT_TRUE(ReadJsonMessage(R"({"balls": [{"id": "cue", "kind": "CUE"}, {"id": "red-1", "kind": "RED"}]})", &t,
                              &error))
      << error;
  EXPECT_EQ(t.balls_size(), 2);
}

// Protobuf's reader dropped what is not a ball in the list of balls, took one ball
// for the list, and read nesting of any depth (5 million levels in 4 s) once the
// strict reader had refused it.
TEST(ReadJsonMessageTest, AListOfBallsHoldsBallsAndNestingIsBoundedEverywhere) {
  v1::TableState t;
  std::string error;
  for (const char* other : {"[]", "null", "3", "\"red\""}) {
    const std::string json = std::string(R"({"balls": [{"id": "cue", "kind": "CUE"}, )") + other + "]}";
    EXPECT_FALSE(ReadJsonMessage(json, &t, &error)) << json;
    EXPECT_EQ(error, "line 1, column 42: element 1 (counting from 0) of \"balls\" is not an object") << json;
  }
  EXPECT_FALSE(ReadJsonMessage(R"({"balls": {"id": "cue", "kind": "CUE"}})", &t, &error));
  EXPECT_EQ(error, "line 1, column 11: \"balls\" is an object where a list [...] is expected");
  const std::string deep = R"({"balls": [{"id": "cue", "kind": "CUE"}, )" + std::string(200, '[') + std::string(200, ']') + "]}";
  EXPECT_FALSE(ReadJsonMessage(deep, &t, &error));
  EXPECT_TRUE(Mentions(error, "nested more than 100 levels deep")) << error;
  // Still read: an empty list, and null for no balls.
  EXPECT_TRUE(ReadJsonMessage(R"({"balls": []})", &t, &error)) << error;
  EXPECT_TRUE(ReadJsonMessage(R"({"balls": null})", &t, &error)) << error;
}

TEST(ReadJsonMessageTest, OtherProblemsAreProtobufsToSay) {
  v1::TableState t;
  std::string error;
  EXPECT_FALSE(ReadJsonMessage(R"({"balls": [{"id": "cue", "colour": "white"}]})", &t, &error));
  EXPECT_TRUE(Mentions(error, "colour")) << error;
  EXPECT_FALSE(Mentions(error, "line ")) << error;
  EXPECT_FALSE(ReadJsonMessage(R"({"balls": [{"id": "cue", "position": {"x": "left"}}]})", &t, &error));
  EXPECT_TRUE(Mentions(error, "left")) << error;
}

// Only the values of kinds (and of the ball on) change case: an id is as written.
TEST(ReadJsonMessageTest, OnlyKindsChangeCase) {
  v1::TableState t;
  std::string error;
  ASSERT_TRUE(ReadJsonMessage(
      R"({"balls": [{"id": "cue", "kind": "cue"}, {"kind": "red", "id": "red"}]})", &t, &error))
      << error;
  ASSERT_EQ(t.balls_size(), 2);
  EXPECT_EQ(t.balls(0).id(), "cue");
  EXPECT_EQ(t.balls(1).id(), "red");
  EXPECT_EQ(t.balls(1).kind(), v1::RED);
}

}  // namespace
}  // namespace snooker
