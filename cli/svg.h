// Drawing a simulated shot as SVG: the table (cushion noses, jaw walls, knuckles,
// pocket capture circles, baulk line, D, spots), each ball's path and where it ended;
// or, with no shot, the table, its balls and a caption. And a plan's answer, drawn
// and in words.
#pragma once

#include <string>

#include "physics/table/table.h"
#include "snooker/v1/plan.pb.h"
#include "snooker/v1/simulate.pb.h"
#include "snooker/v1/table.pb.h"

namespace snooker::cli {

/// `text` for an SVG text node or attribute value: &, <, > and " escaped, control
/// bytes made spaces.
std::string XmlText(const std::string& text);

/// The SVG document for a shot from `table_state` simulated into `result` (which
/// must carry paths for them to be drawn).
std::string ShotSvg(const physics::TableModel& table, const v1::TableState& table_state,
                    const v1::SimulateResponse& result, double ball_radius);

/// The SVG document of `table_state` with no shot: the table, each ball where it is,
/// and `caption` (e.g. why there is no shot) in words below the table, wrapped.
std::string TableSvg(const physics::TableModel& table, const v1::TableState& table_state, double ball_radius,
                     const std::string& caption);

/// A planned shot in words: "red-1 into top-right (pot, direct)", "red-1 into
/// top-right (pot, plant off red-2)", "safety, red-3 first", "escape, no ball hit".
std::string ShotLabel(const v1::PlannedShot& shot);

/// The drawing of a plan's answer for `table` (the request's, after any vision
/// repair): the best shot simulated again with paths (ShotSvg; a cue ball placed
/// from hand drawn among the balls, named "cue"), each alternative's cue-ball path
/// dashed; with no shot, TableSvg with "no shot: " and the answer's reason. Empty,
/// with why in `error`, when a shot cannot be simulated.
std::string PlanSvg(const v1::TableState& table, const v1::PlanResponse& plan, std::string* error);

}  // namespace snooker::cli
