// Drawing a simulated shot as SVG: the table (cushion noses, jaw walls, knuckles,
// pocket capture circles, baulk line, D, spots), each ball's path and where it ended.
#pragma once

#include <string>

#include "physics/table/table.h"
#include "snooker/v1/simulate.pb.h"
#include "snooker/v1/table.pb.h"

namespace snooker::cli {

/// The SVG document for a shot from `table_state` simulated into `result` (which
/// must carry paths for them to be drawn).
std::string ShotSvg(const physics::TableModel& table, const v1::TableState& table_state,
                    const v1::SimulateResponse& result, double ball_radius);

}  // namespace snooker::cli
