// The one place where API messages (proto/) and library types (physics/, planner/)
// meet: conversions in both directions and request validation. Validation names
// each bad value by its API field name, with the rule it breaks.
#pragma once

#include <string>
#include <vector>

#include "physics/ball_ball.h"
#include "physics/params.h"
#include "snooker/v1/collide.pb.h"

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

void ToProto(const physics::Vec2& v, v1::Vec2* out);
void ToProto(const physics::Vec3& v, v1::Vec3* out);

}  // namespace snooker::server
