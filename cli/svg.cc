#include "cli/svg.h"

#include <cctype>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "server/api.h"
#include "server/convert.h"
#include "server/plan_convert.h"

namespace snooker::cli {
namespace {

constexpr double kScale = 250.0;  // px per metre
constexpr double kMargin = 30.0;  // px around the playing area

const char* Colour(v1::BallKind k) {
  switch (k) {
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

// The document's start and the table (bed, pockets, cushions, jaws, baulk line and
// D) on `s`, `extra_height` px taller than the table for what goes below it.
void DrawTable(const physics::TableModel& table, double extra_height, std::ostringstream& s) {
  const physics::TableSpec& spec = table.spec();
  const double w = spec.width * kScale + 2 * kMargin, h = spec.length * kScale + 2 * kMargin + extra_height;
  // Table frame to SVG: x right, y up the page (the top cushion at the top).
  auto X = [&](double x) { return kMargin + x * kScale; };
  auto Y = [&](double y) { return kMargin + (spec.length - y) * kScale; };
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w << "\" height=\"" << h
    << "\" viewBox=\"0 0 " << w << " " << h << "\">\n";
  s << "<rect x=\"0\" y=\"0\" width=\"" << w << "\" height=\"" << h << "\" fill=\"#3b2a1a\"/>\n";
  s << "<rect x=\"" << X(0) << "\" y=\"" << Y(spec.length) << "\" width=\"" << spec.width * kScale
    << "\" height=\"" << spec.length * kScale << "\" fill=\"#1f6b3a\"/>\n";
  for (const physics::Pocket& p : table.pockets()) {
    s << "<circle cx=\"" << X(p.capture_centre.x()) << "\" cy=\"" << Y(p.capture_centre.y())
      << "\" r=\"" << p.capture_radius * kScale << "\" fill=\"#000\"/>\n";
  }
  for (const physics::CushionSegment& seg : table.segments()) {
    s << "<line x1=\"" << X(seg.p0.x()) << "\" y1=\"" << Y(seg.p0.y()) << "\" x2=\""
      << X(seg.p1.x()) << "\" y2=\"" << Y(seg.p1.y()) << "\" stroke=\"#0e3d20\" stroke-width=\"3\"/>\n";
  }
  for (const physics::JawCircle& j : table.jaws()) {
    s << "<circle cx=\"" << X(j.centre.x()) << "\" cy=\"" << Y(j.centre.y()) << "\" r=\""
      << j.radius * kScale << "\" fill=\"none\" stroke=\"#0e3d20\" stroke-width=\"2\"/>\n";
  }
  // Baulk line and the D.
  s << "<line x1=\"" << X(0) << "\" y1=\"" << Y(spec.baulk_line) << "\" x2=\"" << X(spec.width)
    << "\" y2=\"" << Y(spec.baulk_line) << "\" stroke=\"#cfe3d3\" stroke-width=\"1\"/>\n";
  const double cx = spec.width / 2, r = spec.d_radius;
  s << "<path d=\"M " << X(cx - r) << " " << Y(spec.baulk_line) << " A " << r * kScale << " "
    << r * kScale << " 0 0 0 " << X(cx + r) << " " << Y(spec.baulk_line)
    << "\" fill=\"none\" stroke=\"#cfe3d3\" stroke-width=\"1\"/>\n";
}

// `text` in lines of at most `width` bytes, broken at spaces where it can be.
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
  return lines;
}

}  // namespace

std::string XmlText(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += static_cast<unsigned char>(c) < 0x20 ? ' ' : c;
    }
  }
  return out;
}

std::string ShotSvg(const physics::TableModel& table, const v1::TableState& table_state,
                    const v1::SimulateResponse& result, double ball_radius) {
  const physics::TableSpec& spec = table.spec();
  auto X = [&](double x) { return kMargin + x * kScale; };
  auto Y = [&](double y) { return kMargin + (spec.length - y) * kScale; };
  std::ostringstream s;
  s.precision(5);
  s << std::fixed;
  DrawTable(table, 0, s);
  std::map<std::string, v1::BallKind> kind_of;
  for (const v1::Ball& b : table_state.balls()) kind_of[b.id()] = b.kind();
  for (const v1::BallPath& p : result.paths()) {
    if (p.points_size() < 2) continue;
    s << "<polyline fill=\"none\" stroke=\"" << Colour(kind_of[p.id()])
      << "\" stroke-opacity=\"0.8\" stroke-width=\"1.5\" points=\"";
    for (const v1::Vec2& q : p.points()) s << X(q.x()) << "," << Y(q.y()) << " ";
    s << "\"/>\n";
  }
  for (const v1::Ball& b : table_state.balls()) {  // starting positions, faint
    s << "<circle cx=\"" << X(b.position().x()) << "\" cy=\"" << Y(b.position().y()) << "\" r=\""
      << ball_radius * kScale << "\" fill=\"" << Colour(b.kind())
      << "\" fill-opacity=\"0.25\" stroke=\"none\"><title>" << XmlText(b.id()) << " (start)</title></circle>\n";
  }
  for (const v1::FinalBall& f : result.final_balls()) {
    if (f.pocketed()) continue;
    s << "<circle cx=\"" << X(f.position().x()) << "\" cy=\"" << Y(f.position().y()) << "\" r=\""
      << ball_radius * kScale << "\" fill=\"" << Colour(f.kind())
      << "\" stroke=\"#000\" stroke-width=\"0.8\"><title>" << XmlText(f.id()) << "</title></circle>\n";
  }
  s << "</svg>\n";
  return s.str();
}

std::string TableSvg(const physics::TableModel& table, const v1::TableState& table_state, double ball_radius,
                     const std::string& caption) {
  constexpr double kLineHeight = 16;
  const physics::TableSpec& spec = table.spec();
  auto X = [&](double x) { return kMargin + x * kScale; };
  auto Y = [&](double y) { return kMargin + (spec.length - y) * kScale; };
  // About 7 px a character at 12 px: the lines fit the table's width.
  const std::vector<std::string> lines =
      Wrapped(caption, static_cast<std::size_t>(spec.width * kScale / 7));
  std::ostringstream s;
  s.precision(5);
  s << std::fixed;
  DrawTable(table, kLineHeight * static_cast<double>(lines.size()), s);
  for (const v1::Ball& b : table_state.balls()) {
    s << "<circle cx=\"" << X(b.position().x()) << "\" cy=\"" << Y(b.position().y()) << "\" r=\""
      << ball_radius * kScale << "\" fill=\"" << Colour(b.kind())
      << "\" stroke=\"#000\" stroke-width=\"0.8\"><title>" << XmlText(b.id()) << "</title></circle>\n";
  }
  double y = Y(0) + kMargin + 4;
  for (const std::string& line : lines) {
    s << "<text x=\"" << X(0) << "\" y=\"" << y << "\" fill=\"#f4efe6\" font-family=\"sans-serif\" "
      << "font-size=\"12\">" << XmlText(line) << "</text>\n";
    y += kLineHeight;
  }
  s << "</svg>\n";
  return s.str();
}

std::string ShotLabel(const v1::PlannedShot& s) {
  std::string kind = v1::ShotKind_Name(s.kind()), route = v1::PotRoute_Name(s.route());
  for (std::string* name : {&kind, &route}) {
    for (char& c : *name) c = c == '_' ? '-' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  if (s.kind() != v1::POT) {
    return kind + ", " + (s.first_ball().empty() ? "no ball hit" : s.first_ball() + " first");
  }
  std::string label = s.object_ball() + " into " + s.pocket() + " (pot, " + route;
  if (s.route() == v1::PLANT && !s.first_ball().empty()) label += " off " + s.first_ball();
  return label + ")";
}

std::string PlanSvg(const v1::TableState& table, const v1::PlanResponse& plan, std::string* error) {
  const physics::TableModel& model = physics::DefaultTable();
  const double r = physics::BallParams{}.radius;
  if (plan.shots_size() == 0) return TableSvg(model, table, r, "no shot: " + plan.reason());
  auto X = [&](double x) { return kMargin + x * kScale; };
  auto Y = [&](double y) { return kMargin + (model.spec().length - y) * kScale; };
  std::string doc;
  std::ostringstream extra;
  extra.precision(5);
  extra << std::fixed;
  for (int k = 0; k < plan.shots_size(); ++k) {
    const v1::PlannedShot& s = plan.shots(k);
    v1::SimulateRequest sim;
    *sim.mutable_table() = table;
    if (s.has_cue_ball_start()) {
      v1::Ball* cue = sim.mutable_table()->add_balls();
      cue->set_id(server::kPlacedCueId);
      cue->set_kind(v1::CUE);
      *cue->mutable_position() = s.cue_ball_start();
    }
    sim.mutable_shot()->set_speed(s.speed());
    sim.mutable_shot()->set_heading_deg(s.heading_deg());
    sim.mutable_shot()->set_topspin(s.topspin());
    sim.mutable_shot()->set_sidespin(s.sidespin());
    sim.mutable_options()->set_include_paths(true);
    v1::SimulateResponse result;
    const server::ApiStatus st = server::Simulate(sim, &result);
    if (!st.ok()) {
      *error = "cannot draw shot " + std::to_string(k + 1) + ": " + st.message;
      return "";
    }
    if (k == 0) {
      doc = ShotSvg(model, sim.table(), result, r);
      continue;
    }
    const std::string& cue_id = sim.table().balls(server::CueIndex(sim.table())).id();
    for (const v1::BallPath& p : result.paths()) {
      if (p.id() != cue_id || p.points_size() < 2) continue;
      extra << "<polyline fill=\"none\" stroke=\"#ffffff\" stroke-opacity=\"0.6\" stroke-width=\"1\" "
               "stroke-dasharray=\"6 4\" points=\"";
      for (const v1::Vec2& q : p.points()) extra << X(q.x()) << "," << Y(q.y()) << " ";
      extra << "\"><title>#" << k + 1 << ": " << XmlText(ShotLabel(s)) << "</title></polyline>\n";
    }
  }
  const size_t end = doc.rfind("</svg>");
  if (end != std::string::npos) doc.insert(end, extra.str());
  return doc;
}

}  // namespace snooker::cli
