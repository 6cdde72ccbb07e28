// The one place where API messages (proto/) and library types (physics/, planner/)
// meet: conversions in both directions and request validation. Validation names
// each bad value by its API field name, with the rule it breaks.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "physics/impact/ball_ball.h"
#include "physics/core/ball_state.h"
#include "physics/core/shot.h"
#include "physics/core/params.h"
#include "physics/cue/strike.h"
#include "physics/model/model.h"
#include "physics/sim/simulate.h"
#include "physics/table/table.h"
#include "snooker/v1/collide.pb.h"
#include "snooker/v1/model.pb.h"
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

/// "field = value (rule); ..." for the first limits::kMaxReportedProblems errors,
/// then "and N more problems"; never longer than limits::kMaxMessageBytes.
std::string Describe(const std::vector<FieldError>& errors);

/// The shortest text that reads back as x ("1e-06", "0.1", "nan", "-inf").
std::string FormatNumber(double x);

/// `message` cut (at a UTF-8 boundary, marked) to at most limits::kMaxMessageBytes.
std::string BoundMessage(std::string message);

/// A ball id for a message: in quotes, quotes, backslashes and control bytes escaped,
/// cut after limits::kMaxQuotedIdBytes bytes with its length given
/// ("abc..." (1048576 bytes)).
std::string QuoteId(std::string_view id);

/// Every field within its range (server/limits.h, physics/core/limits.h) and every
/// enum one of its declared values; each error names the field and its value.

std::vector<FieldError> ValidateCollideRequest(const v1::CollideRequest& request);

/// Library parameters from the request; unset fields take `base`'s values (the
/// default model: the paper's).
physics::BallParams BallParamsFrom(const v1::CollisionParameters& p, const physics::Model& base = {});
physics::ClothParams ClothParamsFrom(const v1::CollisionParameters& p, const physics::Model& base = {});
physics::BallBallParams BallBallParamsFrom(const v1::CollisionParameters& p, const physics::Model& base = {});
physics::ImpulseSolverOptions SolverOptionsFrom(const v1::ImpulseSolverOptions& o);

/// What CheckTable found, and what it changed.
struct TableCheck {
  std::vector<FieldError> errors;
  /// Set when the vision repair moved a ball: the table state with the moved
  /// positions (everything else as given).
  std::optional<v1::TableState> repaired;
  /// One per moved ball, in table order.
  std::vector<v1::Warning> warnings;
};

/// Where the cue ball of a table state is: on the table (exactly one CUE ball:
/// Simulate), on the table where the request could have put it in hand (Plan
/// without cue_in_hand: a missing cue ball's error names that choice), or in hand
/// (no CUE ball: Plan with cue_in_hand, where the planner places it).
enum class CueBall : std::uint8_t { kOnTable, kOnTableUnlessInHand, kInHand };

/// Checks a table state: the ball count first, before anything that grows with it;
/// ids not empty, unique and at most limits::kMaxIdBytes; kinds; one cue ball (none
/// when it is in hand); finite positions; then the placement on `table`. With
/// vision_tolerance_m > 0, overlaps and cushion overshoots up to it are repaired
/// (physics::RepairPlacement: the least displacement) and reported as warnings,
/// larger ones are errors naming the balls; with 0, every overlap and overshoot is
/// an error (ValidatePlacement).
TableCheck CheckTable(const v1::TableState& state, const physics::TableModel& table,
                      double vision_tolerance_m, CueBall cue = CueBall::kOnTable);

/// The vision tolerance a request asks for (`requested_mm`, unset: the server's), m;
/// an error naming `field` when it is outside [0, server_mm].
std::optional<double> VisionTolerance(std::optional<double> requested_mm, double server_mm,
                                      const char* field, std::vector<FieldError>* errors);

/// The shot and the options of a Simulate request (its table is CheckTable's); each
/// error names the field and its value.
std::vector<FieldError> ValidateShotAndOptions(const v1::SimulateRequest& request);

/// The balls of a (validated) table state, in its order, all at rest; the cue ball
/// gets the shot: v = speed (cos h, sin h), w = topspin (z x heading) + sidespin z.
std::vector<physics::BallState> BallStatesFrom(const v1::TableState& table, const v1::Shot& shot);

/// A heading in degrees (finite) normalised into [0, 360).
double NormalizedHeadingDeg(double heading_deg);

/// The shot in library units (heading normalised, in rad).
physics::Shot ShotFrom(const v1::Shot& shot);
/// The shot a CueStrike gives the cue ball (`model`'s cue and ball,
/// physics/cue/strike.h), or nullopt with the reasons in `errors` (a value out of
/// range, a miscue, a hop).
std::optional<physics::Shot> ShotFromCue(const v1::CueStrike& cue, std::vector<FieldError>* errors,
                                         const physics::Model& model = {});
void ToProto(const physics::Shot& shot, v1::Shot* out);

/// Simulation parameters from the request's options (defaults where unset), with
/// `model`'s physics.
physics::SimParams SimParamsFrom(const v1::SimulationOptions& options, const physics::Model& model = {});

/// Index of the CUE ball in a table state, or -1.
int CueIndex(const v1::TableState& table);

/// The API's name of an event kind (simulate.proto's EventKind).
v1::EventKind EventKindToProto(physics::EventKind kind);

/// One simulation event in API form: ball indices become the ids of `table` (the
/// state the simulation started from), `where` the cushion, jaw or pocket name of
/// `model`.
void ToProto(const physics::SimEvent& event, const v1::TableState& table,
             const physics::TableModel& model, v1::Event* out);

void ToProto(const physics::Vec2& v, v1::Vec2* out);
void ToProto(const physics::Vec3& v, v1::Vec3* out);

/// The table's geometry in API form (GetModel): cushion segments, knuckles, pockets,
/// spots and the red triangle.
void ToProto(const physics::TableModel& table, v1::TableGeometry* out);

/// The physics model in API form (GetModel): ball, cloth, ball-ball, cushion (its
/// contact height the table's), the cue, the simulation defaults, with
/// `path_sample_s` the paths' default sampling interval, s, and the same model in
/// model-file form (`physics`).
void ModelToProto(const physics::Model& model, const physics::TableModel& table, double path_sample_s,
                  v1::GetModelResponse* out);

}  // namespace snooker::server
