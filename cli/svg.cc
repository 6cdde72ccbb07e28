#include "cli/svg.h"

#include <map>
#include <sstream>

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

}  // namespace

std::string ShotSvg(const physics::TableModel& table, const v1::TableState& table_state,
                    const v1::SimulateResponse& result, double ball_radius) {
  const physics::TableSpec& spec = table.spec();
  const double w = spec.width * kScale + 2 * kMargin, h = spec.length * kScale + 2 * kMargin;
  // Table frame to SVG: x right, y up the page (the top cushion at the top).
  auto X = [&](double x) { return kMargin + x * kScale; };
  auto Y = [&](double y) { return kMargin + (spec.length - y) * kScale; };
  std::ostringstream s;
  s.precision(5);
  s << std::fixed;
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
      << "\" fill-opacity=\"0.25\" stroke=\"none\"/>\n";
  }
  for (const v1::FinalBall& f : result.final_balls()) {
    if (f.pocketed()) continue;
    s << "<circle cx=\"" << X(f.position().x()) << "\" cy=\"" << Y(f.position().y()) << "\" r=\""
      << ball_radius * kScale << "\" fill=\"" << Colour(f.kind())
      << "\" stroke=\"#000\" stroke-width=\"0.8\"><title>" << f.id() << "</title></circle>\n";
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace snooker::cli
