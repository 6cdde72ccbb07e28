// Validation of a plan request against the ranges of limits.h and snooker's counts,
// with structured errors: each names PlanRequest's field, the bad value in SI units,
// the range it breaks and that range's unit, so that an API above can rename the
// field and convert the units without restating a rule (server/plan_convert.cc does).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "physics/table/table.h"
#include "planner/planner.h"

namespace snooker::planner {

/// The unit of a checked value (and of its range), SI.
enum class Unit : std::uint8_t {
  kNone,             ///< a count, or no number (ball_on)
  kMetre,
  kSecond,
  kRadian,
  kMetrePerSecond,
  kRadPerSecond,
  kFraction,         ///< a dimensionless ratio
  kRollingSpin,      ///< a fraction of the rolling spin v/R
  kPoints,           ///< snooker points (the break value)
};
/// "m", "s", "rad", "m/s", "rad/s", "", "of the rolling spin", "points".
const char* ToString(Unit u);

/// One bad value of a PlanRequest.
struct FieldError {
  /// PlanRequest's member: "limits.max_speed", "noise.heading", "position_sigma",
  /// "time_budget", "max_shots", "table.balls", "ball_on", ...
  std::string field;
  /// The ball the error is about (index in table.balls; position_sigma's entries
  /// are per ball too), or -1.
  int ball = -1;
  /// The bad value, in `unit`; none when the error is not about one number (then
  /// `value_text` may name it, e.g. the ball on).
  std::optional<double> value;
  std::string value_text;
  Unit unit = Unit::kNone;
  /// The range the value must lie in, in `unit`, when the rule is a range.
  std::optional<physics::Range> range;
  /// The rule in words when it is not a plain range ("must exceed limits.min_speed
  /// (0.3 m/s)", "at most 15 reds"), else empty.
  std::string rule;
};

/// The table: at most physics::limits::kMaxBalls balls, exactly one cue ball (none
/// when the cue ball is in hand: PlanRequest::cue_in_hand), at most 15 reds and one
/// ball of each colour, finite centres placed legally on `model`
/// (TableModel::ValidatePlacement), and a ball on (when given) that has a ball of
/// its kind on the table.
std::vector<FieldError> ValidateTable(const TableState& table, bool cue_in_hand,
                                      const std::optional<BallOn>& ball_on, const physics::TableModel& model);

/// Everything but the table: the robot's limits, the noise (position_sigma: none, or
/// one per ball of the table), the time budget and the counts, each in its
/// limits.h range.
std::vector<FieldError> ValidateSettings(const PlanRequest& request);

/// ValidateTable and ValidateSettings.
std::vector<FieldError> ValidatePlanRequest(const PlanRequest& request, const physics::TableModel& model);

/// "field = value (must be in [lo, hi] unit); ..." in SI units, for the library's own
/// callers (the API writes its own, in its field names and units).
std::string Describe(const std::vector<FieldError>& errors);

}  // namespace snooker::planner
