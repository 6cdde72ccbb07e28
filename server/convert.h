// The one place where API messages (proto/) and library types (physics/, planner/)
// meet: conversions in both directions and request validation. Validation names
// each bad value by its API field name, with the rule it breaks.
#pragma once

#include <string>
#include <vector>

#include "physics/impact/ball_ball.h"
#include "physics/core/ball_state.h"
#include "physics/core/shot.h"
#include "physics/core/params.h"
#include "physics/sim/simulate.h"
#include "physics/table/table.h"
#include "snooker/v1/collide.pb.h"
#include "snooker/v1/simulate.pb.h"
#include "snooker/v1/table.pb.h"

namespace snooker::server {

/// One bad value in a request: the field's API name (proto field path), the value
/// as given, and the rule it breaks.
struct FieldError {
  std::string field;
  std::string value;
  std::string rule;
};

/// "field = value (rule); ..." for a list of errors.
std::string Describe(const std::vector<FieldError>& errors);

std::vector<FieldError> ValidateCollideRequest(const v1::CollideRequest& request);

/// Library parameters from the request; unset fields take the paper's defaults.
physics::BallParams BallParamsFrom(const v1::CollisionParameters& p);
physics::ClothParams ClothParamsFrom(const v1::CollisionParameters& p);
physics::BallBallParams BallBallParamsFrom(const v1::CollisionParameters& p);
physics::ImpulseSolverOptions SolverOptionsFrom(const v1::ImpulseSolverOptions& o);

/// Checks the table (ids, kinds, one cue ball, placement on `table`), the shot and
/// the options; each error names the ball id or field and its value.
std::vector<FieldError> ValidateSimulateRequest(const v1::SimulateRequest& request,
                                                const physics::TableModel& table);

/// The balls of a (validated) table state, in its order, all at rest; the cue ball
/// gets the shot: v = speed (cos h, sin h), w = topspin (z x heading) + sidespin z.
std::vector<physics::BallState> BallStatesFrom(const v1::TableState& table, const v1::Shot& shot);

/// The shot in library units (heading in rad).
physics::Shot ShotFrom(const v1::Shot& shot);

/// Simulation parameters from the request's options (defaults where unset).
physics::SimParams SimParamsFrom(const v1::SimulationOptions& options);

/// Index of the CUE ball in a table state, or -1.
int CueIndex(const v1::TableState& table);

void ToProto(const physics::Vec2& v, v1::Vec2* out);
void ToProto(const physics::Vec3& v, v1::Vec3* out);

}  // namespace snooker::server
