// The drawing of a plan's answer (cli/svg.h): with no shot the table, its balls and
// the reason in words (escaped); with the cue ball in hand the placed cue ball among
// the balls, where the shot says, and its path; and each shot in words.
#include "cli/svg.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "physics/table/table.h"
#include "tests/service/requests.h"

namespace snooker::cli {
namespace {

bool Mentions(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// How many times `part` occurs in `text`.
int Count(const std::string& text, const std::string& part) {
  int n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// The text of the document's <text> elements, joined by spaces (still escaped).
std::string Caption(const std::string& svg) {
  std::string text;
  for (size_t at = svg.find("<text"); at != std::string::npos; at = svg.find("<text", at + 1)) {
    const size_t begin = svg.find('>', at) + 1, end = svg.find("</text>", begin);
    text += (text.empty() ? "" : " ") + svg.substr(begin, end - begin);
  }
  return text;
}

// The page coordinate of table point (x, y), as "X.XXXXX" text (cli/svg.cc's mapping:
// 250 px per metre, a 30 px margin, y up the page).
std::string PageX(double x) {
  char s[32];
  std::snprintf(s, sizeof s, "%.5f", 30 + x * 250);
  return s;
}
std::string PageY(double y) {
  char s[32];
  std::snprintf(s, sizeof s, "%.5f", 30 + (physics::DefaultTable().spec().length - y) * 250);
  return s;
}

// A red 40 cm before the top-right pocket on its axis, the black on its spot; no cue
// ball (it is in hand).
v1::TableState RedAndBlack() {
  const physics::TableModel& table = physics::DefaultTable();
  const physics::Pocket& p = table.pocket(physics::PocketId::kTopRight);
  const physics::Vec2 red = p.mouth_centre - 0.4 * p.axis;
  const physics::Vec2 black = table.spot(physics::Colour::kBlack);
  v1::TableState t;
  testing_requests::AddBall(&t, "red-1", v1::RED, red.x(), red.y());
  testing_requests::AddBall(&t, "black", v1::BLACK, black.x(), black.y());
  return t;
}

// A shot from `from` (in the D) at red-1's centre at 2 m/s.
v1::PlannedShot FromHand(const v1::TableState& t, double x, double y) {
  v1::PlannedShot s;
  s.set_kind(v1::POT);
  s.set_route(v1::DIRECT);
  s.set_object_ball("red-1");
  s.set_first_ball("red-1");
  s.set_pocket("top-right");
  s.mutable_cue_ball_start()->set_x(x);
  s.mutable_cue_ball_start()->set_y(y);
  const v1::Vec2& red = t.balls(0).position();
  s.set_speed(2);
  s.set_heading_deg(std::atan2(red.y() - y, red.x() - x) * 180 / physics::kPi);
  return s;
}

TEST(PlanSvgTest, WithNoShotTheTableTheBallsAndTheReasonInWords) {
  v1::PlanResponse plan;
  plan.set_reason("no pot: ball \"a<b\" & the rest of a reason long enough to need a second line of text");
  std::string error;
  const std::string svg = PlanSvg(RedAndBlack(), plan, &error);
  EXPECT_EQ(error, "");
  EXPECT_TRUE(Mentions(svg, "<svg")) << svg;
  EXPECT_TRUE(Mentions(svg, "</svg>")) << svg;
  EXPECT_FALSE(Mentions(svg, "<polyline")) << svg;
  EXPECT_TRUE(Mentions(svg, "<title>red-1</title>")) << svg;
  EXPECT_TRUE(Mentions(svg, "<title>black</title>")) << svg;
  EXPECT_GE(Count(svg, "<text"), 2) << svg;  // wrapped to the table's width
  EXPECT_EQ(Caption(svg),
            "no shot: no pot: ball &quot;a&lt;b&quot; &amp; the rest of a reason long enough to need a second "
            "line of text");
  EXPECT_FALSE(Mentions(svg, "a<b")) << svg;
}

TEST(PlanSvgTest, TheCueBallPlacedFromHandIsDrawnWhereTheShotPlacesIt) {
  const v1::TableState table = RedAndBlack();
  v1::PlanResponse plan;
  *plan.add_shots() = FromHand(table, 1.0, 0.6);
  *plan.add_shots() = FromHand(table, 0.75, 0.65);  // an alternative from elsewhere
  std::string error;
  const std::string svg = PlanSvg(table, plan, &error);
  ASSERT_NE(svg, "") << error;
  // The best shot's cue ball, placed at (1.0, 0.6), is among the balls, with its path.
  EXPECT_TRUE(Mentions(svg, "<circle cx=\"" + PageX(1.0) + "\" cy=\"" + PageY(0.6) + "\"")) << svg;
  EXPECT_TRUE(Mentions(svg, "<title>cue (start)</title>")) << svg;
  EXPECT_TRUE(Mentions(svg, "points=\"" + PageX(1.0) + "," + PageY(0.6) + " ")) << svg;
  // The alternative's dashed path starts where it places the cue ball.
  EXPECT_TRUE(Mentions(svg, "stroke-dasharray=\"6 4\" points=\"" + PageX(0.75) + "," + PageY(0.65) + " ")) << svg;
  EXPECT_TRUE(Mentions(svg, "<title>#2: red-1 into top-right (pot, direct)</title>")) << svg;
  // The table itself has no cue ball: a shot without a placement cannot be drawn.
  plan.mutable_shots(0)->clear_cue_ball_start();
  EXPECT_EQ(PlanSvg(table, plan, &error), "");
  EXPECT_TRUE(Mentions(error, "cannot draw shot 1")) << error;
  EXPECT_TRUE(Mentions(error, "0 CUE balls")) << error;
}

TEST(ShotLabelTest, EachKindInWords) {
  v1::PlannedShot s;
  s.set_kind(v1::POT);
  s.set_route(v1::PLANT);
  s.set_object_ball("red-1");
  s.set_first_ball("red-2");
  s.set_pocket("top-left");
  EXPECT_EQ(ShotLabel(s), "red-1 into top-left (pot, plant off red-2)");
  s.set_route(v1::DOUBLE);
  EXPECT_EQ(ShotLabel(s), "red-1 into top-left (pot, double)");
  s.set_kind(v1::SAFETY);
  s.clear_route();
  s.clear_pocket();
  EXPECT_EQ(ShotLabel(s), "safety, red-2 first");
  s.set_kind(v1::BREAK_OFF);
  EXPECT_EQ(ShotLabel(s), "break-off, red-2 first");
  s.set_kind(v1::ESCAPE);
  s.clear_first_ball();
  EXPECT_EQ(ShotLabel(s), "escape, no ball hit");
}

}  // namespace
}  // namespace snooker::cli
