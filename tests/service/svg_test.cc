// The pictures of plans and shots (cli/svg.h). A plan of a built-in table, drawn by
// `snooker plan --svg`: valid XML; every shot numbered on the table and listed
// beside it with the answer's P(pot), P(foul), pocket, cue and next ball; every ball
// of the table named; every ball that moved in the best shot with its path, each
// alternative's object ball with its own; every path's halo contrasting with the
// cloth and its colour with its halo; the same bytes from the same answer. With no
// shot, or a plan that fails, the table, its balls and why. The cue ball placed from
// hand drawn where the shot places it; each shot in words.
#include "cli/svg.h"

#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli/load_tables.h"
#include "physics/core/params.h"
#include "physics/table/table.h"
#include "server/api.h"
#include "snooker/v1/plan.pb.h"
#include "tests/service/requests.h"
#include "tests/support/cli_support.h"
#include "tests/support/text.h"

namespace snooker::cli {
namespace {

using cli_support::RunCli;
using cli_support::RunResult;
using cli_support::RunShell;

std::string ReadAll(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Every start tag `<tag ...>` of the document, whole.
std::vector<std::string> Tags(const std::string& svg, const std::string& tag) {
  std::vector<std::string> tags;
  for (size_t at = svg.find("<" + tag + " "); at != std::string::npos; at = svg.find("<" + tag + " ", at + 1)) {
    tags.push_back(svg.substr(at, svg.find('>', at) + 1 - at));
  }
  return tags;
}

// The value of attribute `name` in start tag `tag` ("" when it has none).
std::string Attr(const std::string& tag, const std::string& name) {
  const size_t at = tag.find(" " + name + "=\"");
  if (at == std::string::npos) return "";
  const size_t begin = at + name.size() + 3;
  return tag.substr(begin, tag.find('"', begin) - begin);
}

// The contents of the <text> elements of class `cls`, in order (still escaped).
std::vector<std::string> AllTexts(const std::string& svg, const std::string& cls) {
  std::vector<std::string> texts;
  const std::string mark = "<text class=\"" + cls + "\"";
  for (size_t at = svg.find(mark); at != std::string::npos; at = svg.find(mark, at + 1)) {
    const size_t begin = svg.find('>', at) + 1;
    texts.push_back(svg.substr(begin, svg.find("</text>", begin) - begin));
  }
  return texts;
}

// The panel's lines beside the table, joined by spaces.
std::string Legend(const std::string& svg) {
  std::string text;
  for (const std::string& line : AllTexts(svg, "line")) text += (text.empty() ? "" : " ") + line;
  return text;
}

bool Contains(const std::vector<std::string>& all, const std::string& one) {
  return std::find(all.begin(), all.end(), one) != all.end();
}

// WCAG 2 relative luminance of "#rrggbb", and the contrast ratio of two colours.
double Luminance(const std::string& hex) {
  EXPECT_EQ(hex.size(), 7u) << hex;
  double l = 0;
  const double weight[3] = {0.2126, 0.7152, 0.0722};
  for (int i = 0; i < 3; ++i) {
    const double c = std::stoi(hex.substr(1 + 2 * i, 2), nullptr, 16) / 255.0;
    l += weight[i] * (c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
  }
  return l;
}
double Contrast(const std::string& a, const std::string& b) {
  const double la = Luminance(a), lb = Luminance(b);
  return (std::max(la, lb) + 0.05) / (std::min(la, lb) + 0.05);
}

// WCAG's contrast for graphics, 3:1: every path of `svg` is a halo touching the
// cloth, contrasting with it, and a core inside the halo, contrasting with that; red
// paths are red (a strong red channel, little green or blue).
void ExpectPathsReadOnTheCloth(const std::string& svg) {
  constexpr double kMinContrast = 3.0;
  std::string cloth;
  for (const std::string& tag : Tags(svg, "rect")) {
    if (Attr(tag, "class") == "cloth") cloth = Attr(tag, "fill");
  }
  ASSERT_NE(cloth, "");
  const std::vector<std::string> uses = Tags(svg, "use");
  ASSERT_EQ(uses.size() % 2, 0u);
  ASSERT_GE(uses.size(), 2u * 3);
  for (size_t i = 0; i < uses.size(); i += 2) {
    ASSERT_EQ(Attr(uses[i], "class"), "halo") << uses[i];
    ASSERT_EQ(Attr(uses[i + 1], "class"), "core") << uses[i + 1];
    const std::string halo = Attr(uses[i], "stroke"), core = Attr(uses[i + 1], "stroke");
    EXPECT_GE(Contrast(halo, cloth), kMinContrast) << halo << " on the cloth " << cloth;
    EXPECT_GE(Contrast(core, halo), kMinContrast) << core << " on its halo " << halo;
    EXPECT_GT(std::stod(Attr(uses[i], "stroke-width")), std::stod(Attr(uses[i + 1], "stroke-width")));
  }
  for (const std::string& tag : Tags(svg, "g")) {
    if (Attr(tag, "class").rfind("path", 0) != 0 || Attr(tag, "data-ball").rfind("red", 0) != 0) continue;
    const std::string core = Attr(Tags(svg.substr(svg.find(tag)), "use").at(1), "stroke");
    EXPECT_GE(std::stoi(core.substr(1, 2), nullptr, 16), 0xc0) << core;
    EXPECT_LE(std::stoi(core.substr(3, 2), nullptr, 16), 0x40) << core;
    EXPECT_LE(std::stoi(core.substr(5, 2), nullptr, 16), 0x40) << core;
  }
}

std::string Percent(double p) {
  char s[32];
  std::snprintf(s, sizeof s, "%.1f %%", 100 * p);
  return s;
}

// The page coordinate of table point (x, y) (the drawing's mapping: 250 px per
// metre, a 30 px margin, y up the page; one decimal).
std::string PageX(double x) {
  char s[32];
  std::snprintf(s, sizeof s, "%.1f", 30 + x * 250);
  return s;
}
std::string PageY(double y) {
  char s[32];
  std::snprintf(s, sizeof s, "%.1f", 30 + (physics::DefaultTable().spec().length - y) * 250);
  return s;
}

// `snooker plan` of the built-in table "black" with five shots, drawn, once for the
// suite: the answer (JSON), the table and the picture.
class PlanPictureTest : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    path_ = new std::string(cli_support::TempPath("plan_picture.svg"));
    const RunResult r = RunCli("plan --table builtin:black --shots 5 --max-simulations 400 --samples 8 "
                               "--budget-ms 30000 --json --svg " + *path_);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    plan_ = new v1::PlanResponse;
    ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, plan_).ok()) << r.out;
    table_ = new v1::TableState;
    ASSERT_TRUE(BuiltinTable("black", table_));
    svg_ = new std::string(ReadAll(*path_));
  }
  static void TearDownTestSuite() {
    std::remove(path_->c_str());
    delete path_;
    delete plan_;
    delete table_;
    delete svg_;
  }
  void SetUp() override {
    ASSERT_NE(plan_, nullptr);
    ASSERT_GE(plan_->shots_size(), 2) << plan_->reason();
  }
  static std::string* path_;
  static v1::PlanResponse* plan_;
  static v1::TableState* table_;
  static std::string* svg_;
};
std::string* PlanPictureTest::path_ = nullptr;
v1::PlanResponse* PlanPictureTest::plan_ = nullptr;
v1::TableState* PlanPictureTest::table_ = nullptr;
std::string* PlanPictureTest::svg_ = nullptr;

TEST_F(PlanPictureTest, IsWellFormedXmlAndSelfContained) {
  const RunResult r =
      RunShell("python3 -c 'import sys, xml.etree.ElementTree as E; E.parse(sys.argv[1])' " + *path_);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(svg_->rfind("<svg ", 0), 0u);
  EXPECT_FALSE(Mentions(*svg_, "<image")) << "no images";
  EXPECT_FALSE(Mentions(*svg_, "@font-face")) << "no fonts";
  EXPECT_FALSE(Mentions(*svg_, "http://") && Mentions(*svg_, "href=\"http")) << "no outside links";
  EXPECT_LT(svg_->size(), 150'000u);
}

TEST_F(PlanPictureTest, TheSameAnswerDrawsTheSameBytes) {
  std::string error;
  EXPECT_EQ(PlanSvg(*table_, *plan_, &error), *svg_) << error;
}

TEST_F(PlanPictureTest, NumbersEachShotOnTheTableAndBesideIt) {
  const std::vector<std::string> on_table = AllTexts(*svg_, "num"), beside = AllTexts(*svg_, "legend-num");
  for (int k = 1; k <= plan_->shots_size(); ++k) {
    EXPECT_TRUE(Contains(on_table, std::to_string(k))) << "shot " << k << " not numbered on the table";
    EXPECT_TRUE(Contains(beside, std::to_string(k))) << "shot " << k << " not in the legend";
  }
  EXPECT_FALSE(Contains(on_table, std::to_string(plan_->shots_size() + 1)));
  EXPECT_EQ(static_cast<int>(beside.size()), plan_->shots_size());
}

TEST_F(PlanPictureTest, TheLegendGivesEachShotAsTheAnswerDoes) {
  const std::string legend = Legend(*svg_);
  for (const v1::PlannedShot& s : plan_->shots()) {
    char worth[48];
    std::snprintf(worth, sizeof worth, ", worth %.1f pts", s.expected_points());
    std::string odds = "P(foul) " + Percent(s.foul_probability()) + worth;
    if (s.kind() == v1::POT) {
      odds = "P(pot) " + Percent(s.pot_probability()) + ", " + odds;
      EXPECT_TRUE(Mentions(legend, s.object_ball() + " -&gt; " + s.pocket())) << legend;
    }
    EXPECT_TRUE(Mentions(legend, odds)) << odds << " not in: " << legend;
    char cue[96];
    std::snprintf(cue, sizeof cue, "cue %.2f m/s, elevation %.1f deg tip %.2f R %s, %.2f R %s", s.cue().speed(),
                  s.cue().elevation_deg(), std::abs(s.cue().tip_side()), s.cue().tip_side() < 0 ? "left" : "right",
                  std::abs(s.cue().tip_height()), s.cue().tip_height() < 0 ? "down" : "up");
    EXPECT_TRUE(Mentions(legend, cue)) << cue << " not in: " << legend;
    // After a pot our position and next ball; after another stroke the opponent's.
    const bool pot = s.kind() == v1::POT;
    char leaves[96];
    std::snprintf(leaves, sizeof leaves, "leaves %sposition %.2f, %s ", pot ? "" : "the opponent's ",
                  s.position_value(), pot ? "next ball" : "their best ball");
    if (s.kind() != v1::FOUL) {
      EXPECT_TRUE(Mentions(legend, leaves + (s.next_ball().empty() ? "none" : s.next_ball()))) << legend;
    }
  }
}

TEST_F(PlanPictureTest, NamesEveryBallAndMarksTheNextOne) {
  const std::vector<std::string> ids = AllTexts(*svg_, "id");
  for (const v1::Ball& b : table_->balls()) {
    EXPECT_TRUE(Contains(ids, b.id())) << b.id() << " not named on the table";
    bool drawn = false;  // at full opacity: no fill-opacity on a start
    for (const std::string& tag : Tags(*svg_, "circle")) {
      if (Attr(tag, "class") != "start" || Attr(tag, "data-ball") != b.id()) continue;
      drawn = true;
      EXPECT_EQ(Attr(tag, "fill-opacity"), "") << tag;
      EXPECT_EQ(Attr(tag, "opacity"), "") << tag;
    }
    EXPECT_TRUE(drawn) << b.id();
  }
  const std::string& next = plan_->shots(0).next_ball();
  if (!next.empty()) {
    EXPECT_TRUE(Contains(ids, next)) << next;
    EXPECT_TRUE(Mentions(*svg_, "<g class=\"next\"")) << "the next ball is not marked";
  }
}

TEST_F(PlanPictureTest, DrawsTheBestShotsPathForEveryBallThatMovedAndItsTarget) {
  const v1::PlannedShot& best = plan_->shots(0);
  std::map<std::string, v1::Vec2> start;
  for (const v1::Ball& b : table_->balls()) start[b.id()] = b.position();
  int moved = 0;
  for (const v1::BallEnd& e : best.balls_end()) {
    const v1::Vec2& a = start.at(e.ball());
    if (e.pocket().empty() && std::hypot(e.position().x() - a.x(), e.position().y() - a.y()) < 1e-3) continue;
    ++moved;
    EXPECT_TRUE(Mentions(*svg_, "<g class=\"path best\" data-shot=\"1\" data-ball=\"" + e.ball() + "\""))
        << e.ball() << " moved but has no path";
  }
  EXPECT_GE(moved, 2);
  if (best.kind() == v1::POT) {
    EXPECT_TRUE(Mentions(*svg_, "<title>" + best.pocket() + " (target pocket)</title>")) << "no target pocket";
    EXPECT_TRUE(Contains(AllTexts(*svg_, "label"), "P(pot) " + Percent(best.pot_probability())));
  }
  EXPECT_TRUE(Mentions(*svg_, "<g class=\"ghost\"")) << "no ghost ball";
}

TEST_F(PlanPictureTest, DrawsEachAlternativesObjectBallPath) {
  for (int k = 1; k < plan_->shots_size(); ++k) {
    const std::string& ball = plan_->shots(k).object_ball();
    ASSERT_NE(ball, "");
    EXPECT_TRUE(Mentions(*svg_, "<g class=\"path alt\" data-shot=\"" + std::to_string(k + 1) + "\" data-ball=\"" +
                                    ball + "\""))
        << "shot " << k + 1 << ": no path of " << ball;
  }
}

TEST_F(PlanPictureTest, EveryPathReadsOnTheCloth) { ExpectPathsReadOnTheCloth(*svg_); }

// The cue ball alone: no ball on, so no shot; the exit status and answer as without
// --svg, and a picture of the table, its ball and why.
TEST(PlanPictureNoShotTest, TheTableItsBallsAndWhy) {
  const std::string table = cli_support::TempFile("picture_alone.json", R"({"balls": [
    {"id": "cue", "kind": "CUE", "position": {"x": 0.9, "y": 0.6}}]})");
  const std::string svg = cli_support::TempPath("picture_none.svg");
  const RunResult r = RunCli("plan --table " + table + " --json --svg " + svg + " --max-simulations 50");
  const RunResult without = RunCli("plan --table " + table + " --json --max-simulations 50");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(without.exit_code, 0) << without.err;
  v1::PlanResponse plan;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &plan).ok()) << r.out;
  ASSERT_EQ(plan.shots_size(), 0);
  ASSERT_NE(plan.reason(), "");
  const std::string doc = ReadAll(svg);
  ASSERT_NE(doc, "") << "no picture written";
  EXPECT_EQ(RunShell("python3 -c 'import sys, xml.etree.ElementTree as E; E.parse(sys.argv[1])' " + svg).exit_code, 0);
  EXPECT_FALSE(Mentions(doc, "class=\"path")) << doc;
  EXPECT_TRUE(Contains(AllTexts(doc, "id"), "cue")) << doc;
  EXPECT_TRUE(Contains(AllTexts(doc, "label"), "no shot")) << doc;
  EXPECT_EQ(Legend(doc), "no shot: " + XmlText(plan.reason()));
  std::remove(table.c_str());
  std::remove(svg.c_str());
}

// A safety's leave is the opponent's: the panel, the text and the ring's label say
// so, with the position value and ball the JSON gives.
TEST(PlanPictureSafetyTest, ASafetyLeavesTheOpponentsPosition) {
  const std::string svg = cli_support::TempPath("picture_safety.svg");
  const std::string flags = " --table builtin:red --kinds SAFETY --shots 1 --max-simulations 600 --budget-ms 30000";
  const RunResult r = RunCli("plan --json --svg " + svg + flags);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  v1::PlanResponse plan;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &plan).ok()) << r.out;
  ASSERT_EQ(plan.shots_size(), 1) << r.out;
  const v1::PlannedShot& s = plan.shots(0);
  ASSERT_EQ(s.kind(), v1::SAFETY);
  ASSERT_FALSE(s.next_ball().empty()) << r.out;  // the red by the pocket is theirs
  char leave[96];
  std::snprintf(leave, sizeof leave, "the opponent's position %.2f, their best ball %s", s.position_value(),
                s.next_ball().c_str());
  const std::string doc = ReadAll(svg);
  EXPECT_TRUE(Mentions(Legend(doc), std::string("leaves ") + leave)) << Legend(doc);
  EXPECT_TRUE(Contains(AllTexts(doc, "label"), "theirs: " + s.next_ball())) << doc;
  const RunResult text = RunCli("plan" + flags);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  std::snprintf(leave, sizeof leave, "the opponent's position %.3f, their best ball %s", s.position_value(),
                s.next_ball().c_str());
  EXPECT_TRUE(Mentions(text.out, leave)) << text.out;
  // What it is worth: the opponent's table costs the striker, the runs counted.
  char worth[64];
  std::snprintf(worth, sizeof worth, "; worth %.2f points over %d runs", s.expected_points(), s.monte_carlo_samples());
  EXPECT_TRUE(Mentions(text.out, worth)) << text.out;
  EXPECT_GT(s.monte_carlo_samples(), 0);
  std::remove(svg.c_str());
}

// A plan that fails (no pink on the table) keeps its exit status and message, and
// still draws the table with the message.
TEST(PlanPictureNoShotTest, AFailedPlanIsDrawnWithItsMessage) {
  const std::string svg = cli_support::TempPath("picture_failed.svg");
  const RunResult r = RunCli("plan --table builtin:red --on PINK --max-simulations 50 --svg " + svg);
  const RunResult without = RunCli("plan --table builtin:red --on PINK --max-simulations 50");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.exit_code, without.exit_code);
  EXPECT_EQ(r.err, without.err);
  const std::string doc = ReadAll(svg);
  ASSERT_NE(doc, "");
  std::string said = without.err.substr(std::string("snooker plan: ").size());
  while (!said.empty() && said.back() == '\n') said.pop_back();
  EXPECT_EQ(Legend(doc), "no shot: " + XmlText(said));
  for (const char* id : {"cue", "red-1", "black", "red-2"}) EXPECT_TRUE(Contains(AllTexts(doc, "id"), id)) << id;
  std::remove(svg.c_str());
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
  EXPECT_EQ(svg.rfind("<svg ", 0), 0u) << svg;
  EXPECT_TRUE(Mentions(svg, "</svg>")) << svg;
  EXPECT_FALSE(Mentions(svg, "<polyline")) << svg;
  EXPECT_TRUE(Contains(AllTexts(svg, "id"), "red-1")) << svg;
  EXPECT_TRUE(Contains(AllTexts(svg, "id"), "black")) << svg;
  const std::string reason =
      "no shot: no pot: ball &quot;a&lt;b&quot; &amp; the rest of a reason long enough to need a second line "
      "of text";
  EXPECT_GE(AllTexts(svg, "line").size(), 2u) << svg;  // beside the table, wrapped
  EXPECT_EQ(Legend(svg), reason);
  std::string on_table;  // and across it
  for (const std::string& line : AllTexts(svg, "caption")) on_table += (on_table.empty() ? "" : " ") + line;
  EXPECT_EQ(on_table, reason);
  EXPECT_TRUE(Contains(AllTexts(svg, "label"), "no shot")) << svg;
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
  EXPECT_TRUE(Mentions(svg, "<circle class=\"start\" data-ball=\"cue\" cx=\"" + PageX(1.0) + "\" cy=\"" +
                                PageY(0.6) + "\""))
      << svg;
  EXPECT_TRUE(Contains(AllTexts(svg, "id"), "cue")) << svg;
  EXPECT_TRUE(Mentions(svg, "fill=\"none\" points=\"" + PageX(1.0) + "," + PageY(0.6) + " ")) << svg;
  EXPECT_TRUE(Mentions(svg, "<g class=\"path best\" data-shot=\"1\" data-ball=\"cue\"")) << svg;
  // The alternative: where it places the cue ball, and its object ball's path.
  EXPECT_TRUE(Mentions(svg, "<circle class=\"placed\" cx=\"" + PageX(0.75) + "\" cy=\"" + PageY(0.65) + "\""))
      << svg;
  EXPECT_TRUE(Mentions(svg, "<g class=\"path alt\" data-shot=\"2\" data-ball=\"red-1\"")) << svg;
  EXPECT_TRUE(Mentions(Legend(svg), "pot, direct: red-1 -&gt; top-right")) << svg;
  EXPECT_TRUE(Mentions(Legend(svg), "cue ball in hand, placed at (0.750, 0.650) m")) << svg;
  // The table itself has no cue ball: a shot without a placement cannot be drawn.
  plan.mutable_shots(0)->clear_cue_ball_start();
  EXPECT_EQ(PlanSvg(table, plan, &error), "");
  EXPECT_TRUE(Mentions(error, "cannot draw shot 1")) << error;
  EXPECT_TRUE(Mentions(error, "0 CUE balls")) << error;
}

// `snooker simulate --svg`'s picture: every ball named where it starts, at full
// opacity; each ball that moved with its path and a ring where it stopped; what was
// potted beside the table.
TEST(ShotSvgTest, StartsNamedPathsAndEnds) {
  v1::TableState t;
  testing_requests::AddBall(&t, "cue", v1::CUE, 0.9, 1.0);
  testing_requests::AddBall(&t, "green", v1::GREEN, 0.9, 1.6);
  testing_requests::AddBall(&t, "pink", v1::PINK, 0.3, 2.5);
  v1::SimulateRequest req;
  *req.mutable_table() = t;
  req.mutable_shot()->set_speed(1.5);
  req.mutable_shot()->set_heading_deg(90);
  req.mutable_options()->set_include_paths(true);
  v1::SimulateResponse result;
  ASSERT_TRUE(server::Simulate(req, &result).ok());
  const std::string svg = ShotSvg(physics::DefaultTable(), t, result, physics::BallParams{}.radius);
  for (const char* id : {"cue", "green", "pink"}) EXPECT_TRUE(Contains(AllTexts(svg, "id"), id)) << id;
  EXPECT_TRUE(Mentions(svg, "<g class=\"path best\" data-shot=\"0\" data-ball=\"cue\"")) << svg;
  EXPECT_TRUE(Mentions(svg, "<g class=\"path best\" data-shot=\"0\" data-ball=\"green\"")) << svg;
  EXPECT_FALSE(Mentions(svg, "data-ball=\"pink\" fill=\"none\"")) << "the pink did not move";
  EXPECT_TRUE(Mentions(svg, "<g class=\"end\" data-ball=\"green\"")) << svg;
  EXPECT_FALSE(Mentions(svg, "fill-opacity")) << svg;
  EXPECT_TRUE(Mentions(Legend(svg), "simulated: at rest")) << Legend(svg);
}

// Every kind of ball's path, each a short stroke across the cloth, reads on it.
TEST(ShotSvgTest, EveryBallsPathReadsOnTheCloth) {
  const std::pair<const char*, v1::BallKind> kinds[] = {{"cue", v1::CUE},     {"red", v1::RED},
                                                        {"yellow", v1::YELLOW}, {"green", v1::GREEN},
                                                        {"brown", v1::BROWN},   {"blue", v1::BLUE},
                                                        {"pink", v1::PINK},     {"black", v1::BLACK}};
  v1::TableState t;
  v1::SimulateResponse result;
  double x = 0.2;
  for (const auto& [id, kind] : kinds) {
    testing_requests::AddBall(&t, id, kind, x, 1.0);
    v1::BallPath* p = result.add_paths();
    p->set_id(id);
    for (int i = 0; i < 3; ++i) {
      p->add_t(i * 0.1);
      v1::Vec2* q = p->add_points();
      q->set_x(x);
      q->set_y(1.0 + 0.2 * i);
    }
    x += 0.2;
  }
  const std::string svg = ShotSvg(physics::DefaultTable(), t, result, physics::BallParams{}.radius);
  EXPECT_EQ(Tags(svg, "use").size(), 2u * 8);
  ExpectPathsReadOnTheCloth(svg);
}

TEST(ShotLabelTest, EachKindInWords) {
  v1::TableState t;
  for (const auto& [id, kind] : {std::pair{"red-1", v1::RED}, std::pair{"red-2", v1::RED}, std::pair{"yellow", v1::YELLOW}}) {
    v1::Ball* b = t.add_balls();
    b->set_id(id);
    b->set_kind(kind);
  }
  v1::PlannedShot s;
  s.set_kind(v1::POT);
  s.set_route(v1::PLANT);
  s.set_object_ball("red-1");
  s.set_first_ball("red-2");
  s.set_pocket("top-left");
  EXPECT_EQ(ShotLabel(s, t), "red-1 into top-left (pot, plant off red-2)");
  s.set_route(v1::DOUBLE);
  EXPECT_EQ(ShotLabel(s, t), "red-1 into top-left (pot, double)");
  s.set_kind(v1::SAFETY);
  s.clear_route();
  s.clear_pocket();
  EXPECT_EQ(ShotLabel(s, t), "safety, red-2 first");
  s.set_kind(v1::BREAK_OFF);
  EXPECT_EQ(ShotLabel(s, t), "break-off, red-2 first");
  // A foul nominates its object ball only when that is a colour.
  s.set_kind(v1::FOUL);
  EXPECT_EQ(ShotLabel(s, t), "foul, red-2 first");
  s.set_object_ball("yellow");
  EXPECT_EQ(ShotLabel(s, t), "foul, red-2 first, nominating yellow");
  s.set_object_ball("not-on-the-table");
  EXPECT_EQ(ShotLabel(s, t), "foul, red-2 first");
  s.set_kind(v1::ESCAPE);
  s.clear_first_ball();
  EXPECT_EQ(ShotLabel(s, t), "escape, no ball hit");
}

}  // namespace
}  // namespace snooker::cli
