// The drawing primitives of cli/svg.h's pictures: the table in page coordinates,
// balls at their start (filled, named) and end (a ring), paths with a halo under
// their colour so each reads on the cloth, the ghost ball, rings for the target
// pocket and the next ball, numbered badges, labels placed where they overlap
// least, and a panel of text and a key beside the table. Everything is written with
// one decimal, in the order drawn: the same calls give the same bytes.
//
// Colours: every path is a halo stroke (black or white, whichever contrasts more
// with the path's colour) under its core stroke in the ball's path colour; the cloth
// is a mid green that both black and white contrast with (about 4:1 and 5:1), and
// each path colour is chosen to contrast with its halo by at least 3:1 (WCAG's
// contrast for graphics). Red paths are a full red, the green ball's path a dark
// green on white.
#pragma once

#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "physics/core/types.h"
#include "physics/table/table.h"
#include "snooker/v1/simulate.pb.h"
#include "snooker/v1/table.pb.h"

namespace snooker::cli::svg {

inline constexpr const char* kCloth = "#2b7a46";
inline constexpr const char* kHighlight = "#ffd60a";  // target pocket, next ball, best shot's badge

/// WCAG's relative luminance of "#rrggbb" (0 black to 1 white), and the contrast
/// ratio of two colours (1 to 21).
double Luminance(const std::string& hex);
double Contrast(const std::string& a, const std::string& b);

/// A ball's fill, the colour of its path, and the halo under that path.
const char* BallColour(v1::BallKind kind);
const char* PathColour(v1::BallKind kind);
const char* HaloFor(const std::string& colour);

/// An enum value's name in words: "BREAK_OFF" -> "break-off".
std::string Words(std::string name);

/// "12.3": page coordinates and sizes, one decimal.
std::string Num(double x);

/// A box on the page, px.
struct Box {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double Overlap(const Box& o) const;
};

/// Where labels go: each near its anchor where it overlaps least what is already
/// taken (balls, marks, other labels), trying eight directions at three distances;
/// the first free place wins, what lies outside the bounds counting as overlap.
class LabelSpace {
 public:
  /// Labels stay inside `bounds` where they can.
  void SetBounds(const Box& bounds) { bounds_ = bounds; }
  void Take(const Box& b) { taken_.push_back(b); }
  /// The box of a `w` x `h` label near (x, y), at least `gap` px from it, taken.
  Box Place(double x, double y, double w, double h, double gap);

 private:
  std::vector<Box> taken_;
  Box bounds_{-1e9, -1e9, 1e9, 1e9};
};

/// A line of the panel beside the table.
struct PanelLine {
  std::string text;
  bool bold = false;
  int badge = 0;          // > 0: a numbered badge before the text
  bool best = false;      // the badge is the best shot's
  double gap_before = 0;  // px of space above
};

/// One picture: the table, then what is drawn on it, then the panel.
class Canvas {
 public:
  Canvas(const physics::TableModel& table, double ball_radius);

  double X(double x) const;
  double Y(double y) const;
  double BallPx() const { return radius_ * kScale; }

  /// Cloth, pockets, cushions, jaws, baulk line, D and spots.
  void Table();
  /// A ball's path: `alternative` draws it thinner and dashed. `shot` (> 0) and the
  /// ball's id go into the group's data-shot and data-ball attributes. Returns the
  /// last point's page position; nothing (and nothing drawn) for a ball that did not
  /// move (under half a millimetre).
  std::optional<physics::Vec2> Path(const v1::BallPath& path, v1::BallKind kind, bool alternative, int shot);
  /// A ball where it starts: filled, outlined, taken from the label space; its id
  /// drawn beside it by BallIds.
  void StartBall(const std::string& id, v1::BallKind kind, const physics::Vec2& at);
  /// A ball where it stops: a ring in its path colour over a halo.
  void EndBall(const std::string& id, v1::BallKind kind, const physics::Vec2& at);
  /// A cue ball placed from hand for an alternative shot: a thin ring.
  void PlacedCue(const physics::Vec2& at);
  /// The ghost ball (the cue ball at contact, dashed outline) and the aim mark (a
  /// cross at the ghost ball's centre, where the cue ball's centre is sent).
  void Ghost(const physics::Vec2& ghost);
  /// A ring around the pocket a shot aims at.
  void TargetPocket(const physics::Pocket& pocket);
  /// A ring around the ball the best shot sets up.
  void NextBall(const physics::Vec2& at);

  /// The ids of the balls StartBall drew, beside them.
  void BallIds();
  /// A row of numbered badges (shot 1's in the highlight colour) near page point
  /// (x, y), clear of a ball there.
  void Badges(const std::vector<int>& numbers, double x, double y);
  /// `title` in large letters across the middle of the cloth, `text` under it,
  /// wrapped to the table's width.
  void Caption(const std::string& title, const std::string& text);
  /// A label near page point (x, y), on the cloth.
  void Label(const std::string& text, double x, double y, double font_px, bool bold);

  /// Text and key beside the table.
  void AddPanelLine(PanelLine line) { panel_.push_back(std::move(line)); }
  /// The key of the symbols (start, end, paths, pocket, ghost, next ball).
  void AddKey(bool plan);

  /// The whole document.
  std::string Document() const;

  static constexpr double kScale = 250.0;  // px per metre
  static constexpr double kMargin = 30.0;  // px around the playing area

 private:
  struct KeyRow {
    int symbol;
    std::string text;
  };
  double PanelHeight() const;
  void DrawPanel(std::ostringstream& s, double x0) const;
  void DrawKeySymbol(std::ostringstream& s, int symbol, double x, double y) const;

  const physics::TableModel& table_;
  double radius_;
  std::ostringstream defs_, body_, marks_, balls_, labels_;
  LabelSpace space_;
  struct Named {
    std::string id;
    physics::Vec2 at;
  };
  std::vector<Named> named_;
  std::vector<PanelLine> panel_;
  std::vector<KeyRow> key_;
  int next_path_id_ = 0;
};

}  // namespace snooker::cli::svg
