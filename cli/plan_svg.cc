// PlanSvg (cli/svg.h): a plan's answer drawn over the table, each shot simulated
// again with paths, and in words beside it.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/svg.h"
#include "cli/svg_canvas.h"
#include "physics/core/params.h"
#include "server/api.h"
#include "server/convert.h"
#include "server/plan_convert.h"

namespace snooker::cli {
namespace {

// One shot of the plan simulated again, with paths.
struct Drawn {
  v1::SimulateRequest request;
  v1::SimulateResponse result;
  std::string cue_id;                   // the cue ball's id in `request`
  std::optional<physics::Vec2> ghost;   // the cue ball's centre when it first meets a ball
  std::map<std::string, v1::BallKind> kind_of;
};

physics::Vec2 At(const v1::Vec2& v) { return {v.x(), v.y()}; }

// Ball `id`'s centre at time `t` on its sampled path (linear between samples; the
// samples include every impact), or nothing when it has no path.
std::optional<physics::Vec2> PathAt(const v1::SimulateResponse& r, const std::string& id, double t) {
  for (const v1::BallPath& p : r.paths()) {
    if (p.id() != id || p.points_size() == 0 || p.t_size() != p.points_size()) continue;
    for (int i = 1; i < p.points_size(); ++i) {
      if (p.t(i) < t) continue;
      const double span = p.t(i) - p.t(i - 1), u = span > 0 ? (t - p.t(i - 1)) / span : 1;
      return At(p.points(i - 1)) + std::clamp(u, 0.0, 1.0) * (At(p.points(i)) - At(p.points(i - 1)));
    }
    return At(p.points(p.points_size() - 1));
  }
  return std::nullopt;
}

// The ghost ball of `d`: the cue ball's centre at its first ball-ball contact, put
// exactly 2R from the ball it meets.
std::optional<physics::Vec2> GhostOf(const Drawn& d, double radius) {
  for (const v1::Event& e : d.result.events()) {
    if (e.kind() != v1::BALL_BALL || e.balls_size() != 2) continue;
    if (e.balls(0) != d.cue_id && e.balls(1) != d.cue_id) continue;
    const std::string& other = e.balls(0) == d.cue_id ? e.balls(1) : e.balls(0);
    const std::optional<physics::Vec2> cue = PathAt(d.result, d.cue_id, e.time());
    const std::optional<physics::Vec2> ball = PathAt(d.result, other, e.time());
    if (!cue || !ball) return cue;
    const physics::Vec2 gap = *cue - *ball;
    return gap.norm() > 0 ? *ball + 2 * radius * gap.normalized() : *cue;
  }
  return std::nullopt;
}

// Shot `s` simulated again from `table` with paths into `d`.
server::ApiStatus Resimulate(const v1::TableState& table, const v1::PlannedShot& s, const SimulateFn& simulate,
                             double radius, Drawn* d) {
  *d->request.mutable_table() = table;
  if (s.has_cue_ball_start()) {
    v1::Ball* cue = d->request.mutable_table()->add_balls();
    cue->set_id(server::kPlacedCueId);
    cue->set_kind(v1::CUE);
    *cue->mutable_position() = s.cue_ball_start();
  }
  v1::Shot* shot = d->request.mutable_shot();
  shot->set_speed(s.speed());
  shot->set_heading_deg(s.heading_deg());
  shot->set_topspin(s.topspin());
  shot->set_sidespin(s.sidespin());
  shot->set_swerve_spin(s.swerve_spin());
  d->request.mutable_options()->set_include_paths(true);
  const server::ApiStatus st = simulate(d->request, &d->result);
  if (!st.ok()) return st;
  const int cue = server::CueIndex(d->request.table());
  if (cue >= 0) d->cue_id = d->request.table().balls(cue).id();
  for (const v1::Ball& b : d->request.table().balls()) d->kind_of[b.id()] = b.kind();
  d->ghost = GhostOf(*d, radius);
  return st;
}

v1::BallKind KindOf(const Drawn& d, const std::string& id) {
  const auto it = d.kind_of.find(id);
  return it == d.kind_of.end() ? v1::BALL_KIND_UNSPECIFIED : it->second;
}

// Where a shot's number goes: its ghost ball, or its cue ball when it meets none.
physics::Vec2 AimOf(const Drawn& d) {
  if (d.ghost) return *d.ghost;
  const int cue = server::CueIndex(d.request.table());
  return cue >= 0 ? At(d.request.table().balls(cue).position()) : physics::Vec2::Zero();
}

std::string Percent(double p) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << 100 * p << " %";
  return s.str();
}

// "pot, direct: red-1 -> top-right", "safety: red-3 first", "escape: no ball hit",
// "foul: red-2 first, nominating yellow".
std::string Headline(const v1::PlannedShot& s, const v1::TableState& table) {
  const std::string kind = svg::Words(v1::ShotKind_Name(s.kind())), route = svg::Words(v1::PotRoute_Name(s.route()));
  if (s.kind() != v1::POT) {
    return kind + ": " + (s.first_ball().empty() ? "no ball hit" : s.first_ball() + " first") +
           FoulNomination(s, table);
  }
  std::string line = "pot, " + route;
  if (s.route() == v1::PLANT && !s.first_ball().empty()) line += " off " + s.first_ball();
  return line + ": " + s.object_ball() + " -> " + s.pocket();
}

// The shot's lines of the panel, under its number.
void AddShotLines(svg::Canvas& c, const v1::PlannedShot& s, const v1::TableState& table, int number) {
  c.AddPanelLine({Headline(s, table), true, number, number == 1, 8});
  std::ostringstream odds, cue;
  if (s.kind() == v1::POT) odds << "P(pot) " << Percent(s.pot_probability()) << ", ";
  odds << "P(foul) " << Percent(s.foul_probability()) << ", worth " << std::fixed << std::setprecision(1)
       << s.expected_points() << " pts";
  c.AddPanelLine({odds.str()});
  const v1::CueStrike& k = s.cue();
  cue << std::fixed << std::setprecision(2) << "cue " << k.speed() << " m/s, elevation " << std::setprecision(1)
      << k.elevation_deg() << " deg";
  c.AddPanelLine({cue.str()});
  std::ostringstream tip;
  tip << std::fixed << std::setprecision(2) << "tip " << std::abs(k.tip_side()) << " R "
      << (k.tip_side() < 0 ? "left" : "right") << ", " << std::abs(k.tip_height()) << " R "
      << (k.tip_height() < 0 ? "down" : "up");
  c.AddPanelLine({tip.str()});
  if (s.has_cue_ball_start()) {
    std::ostringstream place;
    place << std::fixed << std::setprecision(3) << "cue ball in hand, placed at (" << s.cue_ball_start().x() << ", "
          << s.cue_ball_start().y() << ") m";
    c.AddPanelLine({place.str()});
  }
  if (const std::string leave = LeaveLabel(s, 2); !leave.empty()) c.AddPanelLine({"leaves " + leave});
}

const physics::Pocket* PocketNamed(const physics::TableModel& table, const std::string& name) {
  for (const physics::Pocket& p : table.pockets()) {
    if (name == physics::ToString(p.id)) return &p;
  }
  return nullptr;
}

// Shot 1: every ball's path and end, the ghost ball, the target pocket with P(pot)
// and the next ball, each marked.
void DrawBest(svg::Canvas& c, const physics::TableModel& table, const Drawn& d, const v1::PlannedShot& s) {
  std::map<std::string, bool> moved;
  for (const v1::BallPath& p : d.result.paths()) moved[p.id()] = c.Path(p, KindOf(d, p.id()), false, 1).has_value();
  for (const v1::FinalBall& f : d.result.final_balls()) {
    if (!f.pocketed() && moved[f.id()]) c.EndBall(f.id(), f.kind(), At(f.position()));
    if (f.id() == s.next_ball()) c.NextBall(At(f.position()));
  }
  if (d.ghost) c.Ghost(*d.ghost);
  if (const physics::Pocket* p = s.kind() == v1::POT ? PocketNamed(table, s.pocket()) : nullptr) c.TargetPocket(*p);
}

// Shot 1's labels: P(pot) by its pocket, the next ball's name by its ring.
void LabelBest(svg::Canvas& c, const physics::TableModel& table, const Drawn& d, const v1::PlannedShot& s) {
  if (const physics::Pocket* p = s.kind() == v1::POT ? PocketNamed(table, s.pocket()) : nullptr) {
    const physics::Vec2 at = p->mouth_centre - 0.05 * p->axis;
    c.Label("P(pot) " + Percent(s.pot_probability()), c.X(at.x()), c.Y(at.y()), 12, true);
  }
  for (const v1::FinalBall& f : d.result.final_balls()) {
    if (f.id() == s.next_ball() && !f.pocketed()) {
      c.Label((s.kind() == v1::POT ? "next: " : "theirs: ") + f.id(), c.X(f.position().x()), c.Y(f.position().y()),
              9, false);
    }
  }
}

// An alternative's object ball's path (its cue ball's when it names none), thinner
// and dashed: where it ends on the page, or nothing when that ball did not move.
std::optional<physics::Vec2> DrawAlternative(svg::Canvas& c, const Drawn& d, const v1::PlannedShot& s, int number) {
  const std::string& ball = s.object_ball().empty() ? d.cue_id : s.object_ball();
  std::optional<physics::Vec2> end;
  for (const v1::BallPath& p : d.result.paths()) {
    if (p.id() == ball) end = c.Path(p, KindOf(d, p.id()), true, number);
  }
  if (s.has_cue_ball_start()) c.PlacedCue(At(s.cue_ball_start()));
  return end;
}

// Shot numbers at page points, those within `near` px of a group's first point
// together (shots aimed alike, or ending in the same pocket): each group's point and
// numbers, in the order of their first shots.
struct Numbered {
  physics::Vec2 at;
  std::vector<int> numbers;
};
std::vector<Numbered> Grouped(const std::vector<std::pair<int, physics::Vec2>>& points, double near) {
  std::vector<Numbered> groups;
  for (const auto& point : points) {
    // Named copies, not a structured binding: a lambda may not capture one before C++20
    // compilers such as clang 14 (the sanitizer build's).
    const int number = point.first;
    const physics::Vec2 at = point.second;
    auto it = std::find_if(groups.begin(), groups.end(), [&](const Numbered& g) { return (g.at - at).norm() < near; });
    if (it == groups.end()) {
      groups.push_back({at, {number}});
    } else {
      it->numbers.push_back(number);
    }
  }
  return groups;
}

}  // namespace

std::string PlanSvg(const v1::TableState& table, const v1::PlanResponse& plan, const SimulateFn& simulate,
                    double ball_radius, std::string* error) {
  const physics::TableModel& model = physics::DefaultTable();
  if (plan.shots_size() == 0) return TableSvg(model, table, ball_radius, "no shot: " + plan.reason());
  std::vector<Drawn> drawn(static_cast<std::size_t>(plan.shots_size()));
  for (int k = 0; k < plan.shots_size(); ++k) {
    const server::ApiStatus st = Resimulate(table, plan.shots(k), simulate, ball_radius, &drawn[k]);
    if (!st.ok()) {
      *error = "cannot draw shot " + std::to_string(k + 1) + ": " + st.message;
      return "";
    }
  }
  svg::Canvas c(model, ball_radius);
  c.Table();
  for (const v1::Ball& b : drawn[0].request.table().balls()) c.StartBall(b.id(), b.kind(), At(b.position()));
  // The alternatives under the best shot, the last under all; labels the other way
  // round, the best shot's first, so they take the clearest places.
  std::vector<std::optional<physics::Vec2>> ends(drawn.size());
  for (int k = plan.shots_size() - 1; k >= 1; --k) ends[k] = DrawAlternative(c, drawn[k], plan.shots(k), k + 1);
  DrawBest(c, model, drawn[0], plan.shots(0));
  // Every shot's number at its aim, shot 1's labels, the alternatives' numbers at
  // their paths' ends, then the balls' ids: the first placed get the clearest places.
  const double near = 2 * c.BallPx();
  std::vector<std::pair<int, physics::Vec2>> aims, path_ends;
  for (int k = 0; k < plan.shots_size(); ++k) {
    const physics::Vec2 aim = AimOf(drawn[k]);
    aims.emplace_back(k + 1, physics::Vec2(c.X(aim.x()), c.Y(aim.y())));
    if (ends[k]) path_ends.emplace_back(k + 1, *ends[k]);
  }
  for (const Numbered& g : Grouped(aims, near)) c.Badges(g.numbers, g.at.x(), g.at.y());
  LabelBest(c, model, drawn[0], plan.shots(0));
  for (const Numbered& g : Grouped(path_ends, near)) c.Badges(g.numbers, g.at.x(), g.at.y());
  c.BallIds();
  std::ostringstream head;
  head << "Plan: " << plan.shots_size() << (plan.shots_size() == 1 ? " shot" : " shots") << ", best first";
  c.AddPanelLine({head.str(), true});
  for (const v1::Warning& w : plan.warnings()) c.AddPanelLine({"warning: " + w.message()});
  for (int k = 0; k < plan.shots_size(); ++k) AddShotLines(c, plan.shots(k), table, k + 1);
  c.AddKey(true);
  return c.Document();
}

std::string PlanSvg(const v1::TableState& table, const v1::PlanResponse& plan, std::string* error) {
  const SimulateFn simulate = [](const v1::SimulateRequest& request, v1::SimulateResponse* response) {
    return server::Simulate(request, response);
  };
  return PlanSvg(table, plan, simulate, physics::BallParams{}.radius, error);
}

}  // namespace snooker::cli
