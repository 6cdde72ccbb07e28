#include "cli/svg_canvas.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>

#include "cli/svg.h"

namespace snooker::cli::svg {
namespace {

constexpr double kPanelWidth = 380;  // px, the panel beside the table
constexpr double kPanelPad = 10;
constexpr double kFontPx = 11;
constexpr double kLineHeight = 15;
constexpr double kKeyRowHeight = 20;
constexpr double kIdFontPx = 9;
constexpr double kBadgeRadius = 7.5;
// Average advance of a sans-serif character, as a fraction of the font size: the
// estimate labels are placed and the panel wrapped with.
constexpr double kCharWidth = 0.54;

double Channel(unsigned value) {
  const double c = value / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// A text node with a halo (on the cloth): white letters over a black outline.
void HaloText(std::ostringstream& s, const std::string& cls, double x, double y, double font_px, bool bold,
              const std::string& text, const char* anchor = "start") {
  s << "<text class=\"" << cls << "\" x=\"" << Num(x) << "\" y=\"" << Num(y) << "\" font-size=\"" << Num(font_px)
    << "\"" << (bold ? " font-weight=\"bold\"" : "") << " text-anchor=\"" << anchor
    << "\" fill=\"#ffffff\" stroke=\"#000000\" stroke-width=\"2.4\" stroke-linejoin=\"round\" "
       "paint-order=\"stroke\">"
    << XmlText(text) << "</text>\n";
}

// `text` in lines of at most `width` characters, broken at spaces where it can be.
std::vector<std::string> Wrapped(const std::string& text, std::size_t width) {
  std::vector<std::string> lines;
  std::istringstream words(text);
  std::string line;
  for (std::string word; words >> word;) {
    if (!line.empty() && line.size() + 1 + word.size() > width) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    while (line.size() > width) {  // a word longer than a line
      lines.push_back(line.substr(0, width));
      line.erase(0, width);
    }
  }
  if (!line.empty()) lines.push_back(line);
  if (lines.empty()) lines.emplace_back();
  return lines;
}

// True when the path's ball went more than half a millimetre from its start.
bool Moved(const v1::BallPath& path) {
  if (path.points_size() < 2) return false;
  const v1::Vec2& a = path.points(0);
  for (const v1::Vec2& q : path.points()) {
    if (std::hypot(q.x() - a.x(), q.y() - a.y()) > 5e-4) return true;
  }
  return false;
}

std::size_t PanelChars() { return static_cast<std::size_t>((kPanelWidth - 2 * kPanelPad - 22) / (kFontPx * kCharWidth)); }

}  // namespace

double Luminance(const std::string& hex) {
  unsigned r = 0, g = 0, b = 0;
  if (hex.size() != 7 || std::sscanf(hex.c_str(), "#%2x%2x%2x", &r, &g, &b) != 3) return 0;
  return 0.2126 * Channel(r) + 0.7152 * Channel(g) + 0.0722 * Channel(b);
}

double Contrast(const std::string& a, const std::string& b) {
  const double la = Luminance(a), lb = Luminance(b);
  return (std::max(la, lb) + 0.05) / (std::min(la, lb) + 0.05);
}

const char* BallColour(v1::BallKind kind) {
  switch (kind) {
    case v1::CUE: return "#ffffff";
    case v1::RED: return "#c0161c";
    case v1::YELLOW: return "#f2d21b";
    case v1::GREEN: return "#1a7f37";
    case v1::BROWN: return "#7a4a1d";
    case v1::BLUE: return "#1f4fd1";
    case v1::PINK: return "#f29bc1";
    case v1::BLACK: return "#111111";
    default: return "#888888";
  }
}

const char* PathColour(v1::BallKind kind) {
  switch (kind) {
    case v1::CUE: return "#ffffff";
    case v1::RED: return "#d10f16";
    case v1::YELLOW: return "#ffd60a";
    case v1::GREEN: return "#0b4d1f";
    case v1::BROWN: return "#7a4519";
    case v1::BLUE: return "#1c4fe0";
    case v1::PINK: return "#ff80c0";
    case v1::BLACK: return "#111111";
    default: return "#bbbbbb";
  }
}

const char* HaloFor(const std::string& colour) {
  return Contrast(colour, "#000000") >= Contrast(colour, "#ffffff") ? "#000000" : "#ffffff";
}

std::string Words(std::string name) {
  for (char& c : name) c = c == '_' ? '-' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

std::string Num(double x) {
  char s[32];
  std::snprintf(s, sizeof s, "%.1f", std::abs(x) < 0.05 ? 0.0 : x);
  return s;
}

double Box::Overlap(const Box& o) const {
  const double w = std::min(x1, o.x1) - std::max(x0, o.x0), h = std::min(y1, o.y1) - std::max(y0, o.y0);
  return w > 0 && h > 0 ? w * h : 0;
}

Box LabelSpace::Place(double x, double y, double w, double h, double gap) {
  static constexpr std::array<std::array<double, 2>, 8> kDirections = {
      {{1, -1}, {1, 0}, {0, -1}, {-1, -1}, {-1, 0}, {1, 1}, {0, 1}, {-1, 1}}};
  constexpr double kFree = 1e-6;  // px^2: no overlap
  Box best;
  double best_overlap = std::numeric_limits<double>::infinity();
  for (const double extra : {0.0, 8.0, 18.0}) {
    for (const auto& [dx, dy] : kDirections) {
      const double cx = x + dx * (gap + extra + w / 2), cy = y + dy * (gap + extra + h / 2);
      const Box b{cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2};
      // What lies outside the bounds counts twice what covers another label.
      double overlap = 2 * std::max(0.0, w * h - b.Overlap(bounds_));
      for (const Box& t : taken_) overlap += b.Overlap(t);
      if (overlap < best_overlap) {
        best = b;
        best_overlap = overlap;
      }
      if (best_overlap < kFree) break;
    }
    if (best_overlap < kFree) break;
  }
  taken_.push_back(best);
  return best;
}

Canvas::Canvas(const physics::TableModel& table, double ball_radius) : table_(table), radius_(ball_radius) {
  space_.SetBounds({kMargin, kMargin, kMargin + table.spec().width * kScale, kMargin + table.spec().length * kScale});
  for (std::ostringstream* s : {&defs_, &body_, &marks_, &balls_, &labels_}) {
    s->precision(1);
    *s << std::fixed;
  }
}

double Canvas::X(double x) const { return kMargin + x * kScale; }
double Canvas::Y(double y) const { return kMargin + (table_.spec().length - y) * kScale; }

void Canvas::Table() {
  const physics::TableSpec& spec = table_.spec();
  std::ostringstream& s = body_;
  s << "<rect class=\"cloth\" x=\"" << Num(X(0)) << "\" y=\"" << Num(Y(spec.length)) << "\" width=\""
    << Num(spec.width * kScale) << "\" height=\"" << Num(spec.length * kScale) << "\" fill=\"" << kCloth << "\"/>\n";
  for (const physics::Pocket& p : table_.pockets()) {
    s << "<circle cx=\"" << Num(X(p.capture_centre.x())) << "\" cy=\"" << Num(Y(p.capture_centre.y()))
      << "\" r=\"" << Num(p.capture_radius * kScale) << "\" fill=\"#000000\"/>\n";
  }
  s << "<g stroke=\"#174d2b\" fill=\"none\">\n";
  for (const physics::CushionSegment& seg : table_.segments()) {
    s << "<line x1=\"" << Num(X(seg.p0.x())) << "\" y1=\"" << Num(Y(seg.p0.y())) << "\" x2=\"" << Num(X(seg.p1.x()))
      << "\" y2=\"" << Num(Y(seg.p1.y())) << "\" stroke-width=\"3\"/>\n";
  }
  for (const physics::JawCircle& j : table_.jaws()) {
    s << "<circle cx=\"" << Num(X(j.centre.x())) << "\" cy=\"" << Num(Y(j.centre.y())) << "\" r=\""
      << Num(j.radius * kScale) << "\" stroke-width=\"2\"/>\n";
  }
  s << "</g>\n";
  // Baulk line, the D and the spots.
  const double cx = spec.width / 2, r = spec.d_radius;
  s << "<g stroke=\"#cfe3d3\" stroke-width=\"1\" fill=\"none\">\n<line x1=\"" << Num(X(0)) << "\" y1=\""
    << Num(Y(spec.baulk_line)) << "\" x2=\"" << Num(X(spec.width)) << "\" y2=\"" << Num(Y(spec.baulk_line))
    << "\"/>\n<path d=\"M " << Num(X(cx - r)) << " " << Num(Y(spec.baulk_line)) << " A " << Num(r * kScale) << " "
    << Num(r * kScale) << " 0 0 0 " << Num(X(cx + r)) << " " << Num(Y(spec.baulk_line)) << "\"/>\n</g>\n";
  for (int c = 0; c < physics::kColourCount; ++c) {
    const physics::Vec2 at = table_.spot(static_cast<physics::Colour>(c));
    s << "<circle cx=\"" << Num(X(at.x())) << "\" cy=\"" << Num(Y(at.y())) << "\" r=\"1.2\" fill=\"#cfe3d3\"/>\n";
  }
}

std::optional<physics::Vec2> Canvas::Path(const v1::BallPath& path, v1::BallKind kind, bool alternative, int shot) {
  if (!Moved(path)) return std::nullopt;
  const int id = ++next_path_id_;
  std::string last;
  defs_ << "<polyline id=\"p" << id << "\" fill=\"none\" points=\"";
  for (const v1::Vec2& q : path.points()) {
    const std::string point = Num(X(q.x())) + "," + Num(Y(q.y()));
    if (point == last) continue;  // a ball at rest: one point
    defs_ << (last.empty() ? "" : " ") << point;
    last = point;
  }
  defs_ << "\"/>\n";
  const std::string core = PathColour(kind), halo = HaloFor(core);
  const double width = alternative ? 1.3 : 2.2;
  body_ << "<g class=\"path " << (alternative ? "alt" : "best") << "\" data-shot=\"" << shot << "\" data-ball=\""
        << XmlText(path.id()) << "\" fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\""
        << (alternative ? " stroke-dasharray=\"7 4\"" : "") << "><title>"
        << (shot > 0 ? "shot " + std::to_string(shot) + ": " : "") << XmlText(path.id()) << "</title>"
        << "<use class=\"halo\" xlink:href=\"#p" << id << "\" stroke=\"" << halo << "\" stroke-width=\""
        << Num(width + 2.2) << "\"/><use class=\"core\" xlink:href=\"#p" << id << "\" stroke=\"" << core
        << "\" stroke-width=\"" << Num(width) << "\"/></g>\n";
  const v1::Vec2& end = path.points(path.points_size() - 1);
  return physics::Vec2(X(end.x()), Y(end.y()));
}

void Canvas::StartBall(const std::string& id, v1::BallKind kind, const physics::Vec2& at) {
  if (!std::isfinite(at.x()) || !std::isfinite(at.y())) return;
  const std::string fill = BallColour(kind);
  // The outline that reads against both the ball and the cloth.
  const auto worst = [&](const char* c) { return std::min(Contrast(fill, c), Contrast(kCloth, c)); };
  const char* outline = worst("#000000") >= worst("#ffffff") ? "#000000" : "#ffffff";
  const double x = X(at.x()), y = Y(at.y()), r = BallPx();
  balls_ << "<circle class=\"start\" data-ball=\"" << XmlText(id) << "\" cx=\"" << Num(x) << "\" cy=\"" << Num(y)
         << "\" r=\"" << Num(r) << "\" fill=\"" << fill << "\" stroke=\"" << outline
         << "\" stroke-width=\"1.2\"><title>" << XmlText(id) << " (start)</title></circle>\n";
  space_.Take({x - r, y - r, x + r, y + r});
  named_.push_back({id, {x, y}});
}

void Canvas::EndBall(const std::string& id, v1::BallKind kind, const physics::Vec2& at) {
  const std::string core = PathColour(kind);
  const double x = X(at.x()), y = Y(at.y()), r = BallPx() - 1;
  marks_ << "<g class=\"end\" data-ball=\"" << XmlText(id) << "\" fill=\"none\"><title>" << XmlText(id)
         << " (end)</title><circle cx=\"" << Num(x) << "\" cy=\"" << Num(y) << "\" r=\"" << Num(r) << "\" stroke=\""
         << HaloFor(core) << "\" stroke-width=\"4\"/><circle cx=\"" << Num(x) << "\" cy=\"" << Num(y) << "\" r=\""
         << Num(r) << "\" stroke=\"" << core << "\" stroke-width=\"2\"/></g>\n";
  space_.Take({x - r, y - r, x + r, y + r});
}

void Canvas::PlacedCue(const physics::Vec2& at) {
  const double x = X(at.x()), y = Y(at.y()), r = BallPx();
  marks_ << "<circle class=\"placed\" cx=\"" << Num(x) << "\" cy=\"" << Num(y) << "\" r=\"" << Num(r)
         << "\" fill=\"none\" stroke=\"#ffffff\" stroke-width=\"1\" stroke-dasharray=\"2 2\"/>\n";
  space_.Take({x - r, y - r, x + r, y + r});
}

void Canvas::Ghost(const physics::Vec2& ghost) {
  const double x = X(ghost.x()), y = Y(ghost.y()), r = BallPx(), c = 3.5;
  marks_ << "<g class=\"ghost\" fill=\"none\"><title>ghost ball and aim point</title>";
  for (const auto& [colour, width] : {std::pair{"#000000", "2.6"}, std::pair{"#ffffff", "1.2"}}) {
    marks_ << "<circle cx=\"" << Num(x) << "\" cy=\"" << Num(y) << "\" r=\"" << Num(r) << "\" stroke=\"" << colour
           << "\" stroke-width=\"" << width << "\" stroke-dasharray=\"3 2\"/><path d=\"M " << Num(x - c) << " "
           << Num(y) << " H " << Num(x + c) << " M " << Num(x) << " " << Num(y - c) << " V " << Num(y + c)
           << "\" stroke=\"" << colour << "\" stroke-width=\"" << width << "\"/>";
  }
  marks_ << "</g>\n";
  space_.Take({x - r, y - r, x + r, y + r});
}

void Canvas::TargetPocket(const physics::Pocket& pocket) {
  const double x = X(pocket.capture_centre.x()), y = Y(pocket.capture_centre.y());
  const double r = pocket.capture_radius * kScale + 3;
  marks_ << "<g class=\"target\" fill=\"none\"><title>" << physics::ToString(pocket.id)
         << " (target pocket)</title><circle cx=\"" << Num(x) << "\" cy=\"" << Num(y) << "\" r=\"" << Num(r)
         << "\" stroke=\"#000000\" stroke-width=\"5.5\"/><circle cx=\"" << Num(x) << "\" cy=\"" << Num(y)
         << "\" r=\"" << Num(r) << "\" stroke=\"" << kHighlight << "\" stroke-width=\"3\"/></g>\n";
}

void Canvas::NextBall(const physics::Vec2& at) {
  const double x = X(at.x()), y = Y(at.y()), r = BallPx() + 4;
  marks_ << "<g class=\"next\" fill=\"none\" stroke-dasharray=\"4 2.5\"><title>the next ball</title>"
         << "<circle cx=\"" << Num(x) << "\" cy=\"" << Num(y) << "\" r=\"" << Num(r)
         << "\" stroke=\"#000000\" stroke-width=\"3.6\"/><circle cx=\"" << Num(x) << "\" cy=\"" << Num(y)
         << "\" r=\"" << Num(r) << "\" stroke=\"" << kHighlight << "\" stroke-width=\"1.8\"/></g>\n";
  space_.Take({x - r, y - r, x + r, y + r});
}

void Canvas::BallIds() {
  for (const Named& n : named_) {
    const double w = kCharWidth * kIdFontPx * static_cast<double>(n.id.size()) + 2, h = kIdFontPx + 2;
    const Box b = space_.Place(n.at.x(), n.at.y(), w, h, BallPx() + 1);
    HaloText(labels_, "id", b.x0 + 1, b.y1 - 3, kIdFontPx, false, n.id);
  }
}

void Canvas::Badges(const std::vector<int>& numbers, double x, double y) {
  if (numbers.empty()) return;
  const double d = 2 * kBadgeRadius, n = static_cast<double>(numbers.size());
  const Box b = space_.Place(x, y, n * d + (n - 1), d, BallPx() + 1);
  double cx = b.x0 + kBadgeRadius;
  const double cy = (b.y0 + b.y1) / 2;
  for (const int number : numbers) {
    labels_ << "<circle class=\"badge\" cx=\"" << Num(cx) << "\" cy=\"" << Num(cy) << "\" r=\""
            << Num(kBadgeRadius) << "\" fill=\"" << (number == 1 ? kHighlight : "#ffffff")
            << "\" stroke=\"#000000\" stroke-width=\"1\"/><text class=\"num\" x=\"" << Num(cx) << "\" y=\""
            << Num(cy + 3.6) << "\" font-size=\"10\" font-weight=\"bold\" text-anchor=\"middle\" fill=\"#000000\">"
            << number << "</text>\n";
    cx += d + 1;
  }
}

void Canvas::Label(const std::string& text, double x, double y, double font_px, bool bold) {
  const double w = kCharWidth * font_px * static_cast<double>(text.size()) + 4, h = font_px + 3;
  const Box b = space_.Place(x, y, w, h, 4);
  HaloText(labels_, "label", b.x0 + 2, b.y1 - 0.28 * font_px, font_px, bold, text);
}

void Canvas::Caption(const std::string& title, const std::string& text) {
  constexpr double kTitlePx = 22, kTextPx = 13;
  const physics::TableSpec& spec = table_.spec();
  const double x = X(spec.width / 2);
  double y = Y(spec.length / 2) - 30;
  HaloText(labels_, "label", x, y, kTitlePx, true, title, "middle");
  const auto chars = static_cast<std::size_t>((spec.width * kScale - 20) / (kTextPx * kCharWidth));
  for (const std::string& line : Wrapped(text, chars)) {
    y += kTextPx + 5;
    HaloText(labels_, "caption", x, y, kTextPx, false, line, "middle");
  }
}

void Canvas::AddKey(bool plan) {
  key_.push_back({0, "a ball where it starts, its id beside it"});
  key_.push_back({1, "where a ball stops"});
  key_.push_back({2, plan ? "shot 1: every ball's path" : "each ball's path"});
  if (!plan) return;
  key_.push_back({3, "shots 2 on: the object ball's path, its number at the end"});
  key_.push_back({4, "shot 1's pocket, with P(pot) beside it"});
  key_.push_back({5, "ghost ball (the cue ball at contact); + the aim point"});
  key_.push_back({6, "shot 1's next ball (after a pot; else the opponent's best)"});
}

double Canvas::PanelHeight() const {
  double h = 2 * kPanelPad;
  for (const PanelLine& l : panel_) {
    h += l.gap_before + kLineHeight * static_cast<double>(Wrapped(l.text, PanelChars()).size());
  }
  if (!key_.empty()) h += 8 + kKeyRowHeight * static_cast<double>(key_.size());
  return h;
}

void Canvas::DrawKeySymbol(std::ostringstream& s, int symbol, double x, double y) const {
  const double r = BallPx();
  s << "<rect x=\"" << Num(x - 14) << "\" y=\"" << Num(y - 8) << "\" width=\"28\" height=\"16\" fill=\"" << kCloth
    << "\"/>";
  const std::string at = "cx=\"" + Num(x) + "\" cy=\"" + Num(y) + "\" r=\"" + Num(r - 1) + "\"";
  const std::string line = "<path d=\"M " + Num(x - 12) + " " + Num(y) + " H " + Num(x + 12) + "\" ";
  switch (symbol) {
    case 0: s << "<circle " << at << " fill=\"" << BallColour(v1::RED) << "\" stroke=\"#000000\"/>"; break;
    case 1:
      s << "<circle " << at << " fill=\"none\" stroke=\"#ffffff\" stroke-width=\"4\"/><circle " << at
        << " fill=\"none\" stroke=\"" << PathColour(v1::RED) << "\" stroke-width=\"2\"/>";
      break;
    case 2:
      s << line << "stroke=\"#ffffff\" stroke-width=\"4.4\"/>" << line << "stroke=\"" << PathColour(v1::RED)
        << "\" stroke-width=\"2.2\"/>";
      break;
    case 3:
      s << line << "stroke=\"#ffffff\" stroke-width=\"3.5\" stroke-dasharray=\"7 4\"/>" << line << "stroke=\""
        << PathColour(v1::RED) << "\" stroke-width=\"1.3\" stroke-dasharray=\"7 4\"/>";
      break;
    case 4:
      s << "<circle " << at << " fill=\"#000000\" stroke=\"" << kHighlight << "\" stroke-width=\"3\"/>";
      break;
    case 5:
      s << "<circle " << at << " fill=\"none\" stroke=\"#ffffff\" stroke-dasharray=\"3 2\"/><path d=\"M "
        << Num(x - 3) << " " << Num(y) << " H " << Num(x + 3) << " M " << Num(x) << " " << Num(y - 3) << " V "
        << Num(y + 3) << "\" stroke=\"#ffffff\"/>";
      break;
    default:
      s << "<circle " << at << " fill=\"" << BallColour(v1::BLACK) << "\"/><circle cx=\"" << Num(x) << "\" cy=\""
        << Num(y) << "\" r=\"" << Num(r + 3) << "\" fill=\"none\" stroke=\"" << kHighlight
        << "\" stroke-width=\"1.8\" stroke-dasharray=\"4 2.5\"/>";
  }
  s << "\n";
}

void Canvas::DrawPanel(std::ostringstream& s, double x0) const {
  const double y0 = kMargin;
  s << "<g class=\"legend\" font-size=\"" << Num(kFontPx) << "\" fill=\"#1a1a1a\">\n<rect x=\"" << Num(x0)
    << "\" y=\"" << Num(y0) << "\" width=\"" << Num(kPanelWidth) << "\" height=\"" << Num(PanelHeight())
    << "\" rx=\"4\" fill=\"#f4efe6\" stroke=\"#000000\"/>\n";
  double y = y0 + kPanelPad;
  const double text_x = x0 + kPanelPad + 22;
  for (const PanelLine& l : panel_) {
    y += l.gap_before;
    if (l.badge > 0) {
      s << "<circle cx=\"" << Num(x0 + kPanelPad + kBadgeRadius) << "\" cy=\"" << Num(y + kLineHeight / 2)
        << "\" r=\"" << Num(kBadgeRadius) << "\" fill=\"" << (l.best ? kHighlight : "#ffffff")
        << "\" stroke=\"#000000\"/><text class=\"legend-num\" x=\"" << Num(x0 + kPanelPad + kBadgeRadius)
        << "\" y=\"" << Num(y + kLineHeight / 2 + 3.6) << "\" font-size=\"10\" font-weight=\"bold\" "
           "text-anchor=\"middle\">"
        << l.badge << "</text>\n";
    }
    for (const std::string& part : Wrapped(l.text, PanelChars())) {
      s << "<text class=\"line\" x=\"" << Num(l.badge > 0 || !l.bold ? text_x : x0 + kPanelPad) << "\" y=\""
        << Num(y + kLineHeight - 4) << "\"" << (l.bold ? " font-weight=\"bold\"" : "") << ">" << XmlText(part)
        << "</text>\n";
      y += kLineHeight;
    }
  }
  if (!key_.empty()) y += 8;
  for (const KeyRow& row : key_) {
    DrawKeySymbol(s, row.symbol, x0 + kPanelPad + 14, y + kKeyRowHeight / 2);
    s << "<text class=\"key\" x=\"" << Num(x0 + kPanelPad + 34) << "\" y=\"" << Num(y + kKeyRowHeight / 2 + 4)
      << "\" font-size=\"10\">" << XmlText(row.text) << "</text>\n";
    y += kKeyRowHeight;
  }
  s << "</g>\n";
}

std::string Canvas::Document() const {
  const physics::TableSpec& spec = table_.spec();
  const double table_w = spec.width * kScale + 2 * kMargin, table_h = spec.length * kScale + 2 * kMargin;
  const bool panel = !panel_.empty() || !key_.empty();
  const double w = table_w + (panel ? kPanelWidth + kMargin : 0);
  const double h = std::max(table_h, panel ? PanelHeight() + 2 * kMargin : 0);
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"" << Num(w)
    << "\" height=\"" << Num(h) << "\" viewBox=\"0 0 " << Num(w) << " " << Num(h)
    << "\" font-family=\"sans-serif\">\n<defs>\n"
    << defs_.str() << "</defs>\n<rect class=\"frame\" x=\"0\" y=\"0\" width=\"" << Num(w) << "\" height=\"" << Num(h)
    << "\" fill=\"#3b2a1a\"/>\n"
    << body_.str() << marks_.str() << balls_.str() << labels_.str();
  if (panel) DrawPanel(s, table_w);
  s << "</svg>\n";
  return s.str();
}

}  // namespace snooker::cli::svg
