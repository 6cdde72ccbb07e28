// Drawing shots and plans as SVG (self-contained: no fonts, images or scripts; the
// same input gives the same bytes). The table (cushion noses, jaw walls, knuckles,
// pocket capture circles, baulk line, D, spots), each ball where it starts (filled,
// its id beside it) and where it stops (a ring), paths in colours that read on the
// cloth (cli/svg_canvas.h), and a panel beside the table: for a plan, each shot in
// words and numbers, and a key.
#pragma once

#include <functional>
#include <string>

#include "physics/table/table.h"
#include "server/api_status.h"
#include "snooker/v1/plan.pb.h"
#include "snooker/v1/simulate.pb.h"
#include "snooker/v1/table.pb.h"

namespace snooker::cli {

/// `text` for an SVG text node or attribute value: &, <, > and " escaped, control
/// bytes made spaces.
std::string XmlText(const std::string& text);

/// The SVG document for a shot from `table_state` simulated into `result` (which
/// must carry paths for them to be drawn): every ball that moved, its path and
/// where it stopped; the status, duration and balls potted beside the table.
std::string ShotSvg(const physics::TableModel& table, const v1::TableState& table_state,
                    const v1::SimulateResponse& result, double ball_radius);

/// The SVG document of `table_state` with no shot: the table, each ball where it is
/// with its id, and "no shot" with `caption` (e.g. why there is no shot) across the
/// middle of the table and beside it, wrapped.
std::string TableSvg(const physics::TableModel& table, const v1::TableState& table_state, double ball_radius,
                     const std::string& caption);

/// A planned shot in words: "red-1 into top-right (pot, direct)", "red-1 into
/// top-right (pot, plant off red-2)", "safety, red-3 first", "escape, no ball hit",
/// "foul, red-2 first, nominating yellow". `table` is the table planned on: a foul
/// names its object ball as a nomination only when that ball is a colour (with a red
/// on there is nothing to nominate, and the object ball is the red played).
std::string ShotLabel(const v1::PlannedShot& shot, const v1::TableState& table);

/// ", nominating <colour>" for a FOUL whose object ball is a colour of `table`, else "".
std::string FoulNomination(const v1::PlannedShot& shot, const v1::TableState& table);

/// What a planned shot leaves, in words, its values to `precision` decimals: after a
/// pot the striker's position and next ball ("position 0.82, next ball black");
/// after a safety, escape or break-off the opponent's ("the opponent's position
/// 0.12, their best ball red-3", and when it leaves them snookered ", snookered
/// (P(foul) 0.50)"); "" for a foul, whose leave is not scored so.
std::string LeaveLabel(const v1::PlannedShot& shot, int precision);

/// How a drawing simulates a shot: the operation `snooker simulate` calls
/// (server::Simulate with the model in use, or a server's Simulate).
using SimulateFn = std::function<server::ApiStatus(const v1::SimulateRequest&, v1::SimulateResponse*)>;

/// The drawing of a plan's answer for `table` (the request's, after any vision
/// repair). Each shot is simulated again with paths through `simulate` (a cue ball
/// placed from hand added as "cue"). Shot 1 (the best): every ball's path, where
/// each stops, the ghost ball and aim point, the target pocket ringed with P(pot),
/// the next ball ringed. Each alternative: its object ball's path, thinner and
/// dashed, numbered at its end. Every shot numbered at its aim (or its cue ball
/// when it hits nothing), and beside the table in words: kind and route, object ball
/// -> pocket, P(pot) and P(foul), the cue, the position left and the next ball;
/// then a key. With no shot, TableSvg with "no shot: " and the answer's reason.
/// Empty, with why in `error`, when a shot cannot be simulated.
std::string PlanSvg(const v1::TableState& table, const v1::PlanResponse& plan, const SimulateFn& simulate,
                    double ball_radius, std::string* error);

/// PlanSvg with server::Simulate and the default model.
std::string PlanSvg(const v1::TableState& table, const v1::PlanResponse& plan, std::string* error);

}  // namespace snooker::cli
