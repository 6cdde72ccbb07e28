#include "cli/svg.h"

#include <iomanip>
#include <map>
#include <sstream>
#include <string>

#include "cli/svg_canvas.h"

namespace snooker::cli {

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
  svg::Canvas c(table, ball_radius);
  c.Table();
  std::map<std::string, v1::BallKind> kind_of;
  for (const v1::Ball& b : table_state.balls()) kind_of[b.id()] = b.kind();
  std::map<std::string, bool> moved;
  for (const v1::BallPath& p : result.paths()) moved[p.id()] = c.Path(p, kind_of[p.id()], false, 0).has_value();
  std::ostringstream status;
  status << std::fixed << std::setprecision(2) << "simulated: " << result.status() << ", " << result.duration_s()
         << " s, " << result.events_size() << " events";
  c.AddPanelLine({"The shot", true});
  c.AddPanelLine({status.str()});
  for (const v1::FinalBall& f : result.final_balls()) {
    if (f.pocketed()) {
      c.AddPanelLine({"potted: " + f.id() + " in " + f.pocket()});
    } else if (moved[f.id()]) {
      c.EndBall(f.id(), f.kind(), {f.position().x(), f.position().y()});
    }
  }
  for (const v1::Ball& b : table_state.balls()) c.StartBall(b.id(), b.kind(), {b.position().x(), b.position().y()});
  c.BallIds();
  c.AddKey(false);
  return c.Document();
}

std::string TableSvg(const physics::TableModel& table, const v1::TableState& table_state, double ball_radius,
                     const std::string& caption) {
  svg::Canvas c(table, ball_radius);
  c.Table();
  for (const v1::Ball& b : table_state.balls()) c.StartBall(b.id(), b.kind(), {b.position().x(), b.position().y()});
  c.Caption("no shot", caption);
  c.BallIds();
  c.AddPanelLine({caption});
  return c.Document();
}

std::string FoulNomination(const v1::PlannedShot& s, const v1::TableState& table) {
  if (s.kind() != v1::FOUL) return "";
  for (const v1::Ball& b : table.balls()) {
    if (b.id() == s.object_ball()) return b.kind() == v1::CUE || b.kind() == v1::RED ? "" : ", nominating " + b.id();
  }
  return "";
}

std::string ShotLabel(const v1::PlannedShot& s, const v1::TableState& table) {
  const std::string kind = svg::Words(v1::ShotKind_Name(s.kind())), route = svg::Words(v1::PotRoute_Name(s.route()));
  if (s.kind() != v1::POT) {
    return kind + ", " + (s.first_ball().empty() ? "no ball hit" : s.first_ball() + " first") +
           FoulNomination(s, table);
  }
  std::string label = s.object_ball() + " into " + s.pocket() + " (pot, " + route;
  if (s.route() == v1::PLANT && !s.first_ball().empty()) label += " off " + s.first_ball();
  return label + ")";
}

std::string LeaveLabel(const v1::PlannedShot& s, int precision) {
  if (s.kind() == v1::FOUL) return "";
  const bool pot = s.kind() == v1::POT;
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision) << (pot ? "position " : "the opponent's position ")
      << s.position_value() << (pot ? ", next ball " : ", their best ball ")
      << (s.next_ball().empty() ? "none" : s.next_ball());
  if (s.opponent().snookered()) out << ", snookered (P(foul) " << s.opponent().foul_probability() << ")";
  return out.str();
}

}  // namespace snooker::cli
