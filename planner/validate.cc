#include "planner/validate.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "physics/core/limits.h"
#include "planner/limits.h"

namespace snooker::planner {
namespace {

constexpr std::nullopt_t kNoNumber = std::nullopt;

std::string Num(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

void CheckRange(std::vector<FieldError>* errors, const std::string& field, double value,
                physics::Range range, Unit unit, int ball = -1) {
  if (range.Contains(value)) return;
  errors->push_back({field, ball, value, "", unit, range, ""});
}

void CheckCount(std::vector<FieldError>* errors, const std::string& field, std::int64_t value,
                limits::IntRange range) {
  if (range.Contains(value)) return;
  errors->push_back({field, -1, static_cast<double>(value), "", Unit::kNone,
                     physics::Range{static_cast<double>(range.lo), static_cast<double>(range.hi)}, ""});
}

void CheckCounts(const TableState& t, bool cue_in_hand, std::vector<FieldError>* errors) {
  const int cues = t.Count(BallKind::kCue);
  if (cues != (cue_in_hand ? 0 : 1)) {
    errors->push_back({"table.balls", -1, static_cast<double>(cues), "", Unit::kNone, std::nullopt,
                       cue_in_hand ? "cue balls: none with cue_in_hand" : "cue balls: exactly one"});
  }
  if (t.reds() > physics::kRedCount) {
    errors->push_back({"table.balls", -1, static_cast<double>(t.reds()), "", Unit::kNone, std::nullopt,
                       "reds: at most " + std::to_string(physics::kRedCount)});
  }
  for (int c = 0; c < physics::kColourCount; ++c) {
    const BallKind k = KindOf(static_cast<physics::Colour>(c));
    if (t.Count(k) > 1) {
      errors->push_back({"table.balls", -1, static_cast<double>(t.Count(k)), "", Unit::kNone, std::nullopt,
                         std::string(ToString(k)) + " balls: at most one"});
    }
  }
}

}  // namespace

const char* ToString(Unit u) {
  switch (u) {
    case Unit::kNone: return "";
    case Unit::kMetre: return "m";
    case Unit::kSecond: return "s";
    case Unit::kRadian: return "rad";
    case Unit::kMetrePerSecond: return "m/s";
    case Unit::kRadPerSecond: return "rad/s";
    case Unit::kFraction: return "";
    case Unit::kRollingSpin: return "of the rolling spin";
    case Unit::kPoints: return "points";
  }
  return "";
}

std::vector<FieldError> ValidateTable(const TableState& t, bool cue_in_hand,
                                      const std::optional<BallOn>& ball_on, const physics::TableModel& model) {
  std::vector<FieldError> errors;
  const int n = static_cast<int>(t.balls.size());
  if (n > physics::limits::kMaxBalls) {
    // Refused before anything that grows with the count.
    errors.push_back({"table.balls", -1, static_cast<double>(n), "", Unit::kNone,
                      physics::Range{0, static_cast<double>(physics::limits::kMaxBalls)}, ""});
    return errors;
  }
  CheckCounts(t, cue_in_hand, &errors);
  bool finite = true;
  for (int i = 0; i < n; ++i) {
    const physics::Vec2& p = t.balls[static_cast<size_t>(i)].position;
    if (!p.allFinite()) {
      finite = false;
      errors.push_back({"table.balls", i, kNoNumber, "", Unit::kMetre, std::nullopt,
                        "position must be finite"});
    }
  }
  if (finite && n > 0) {
    std::vector<std::string> names;
    names.reserve(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      names.push_back(std::string(ToString(t.balls[static_cast<size_t>(i)].kind)) + " (ball " +
                      std::to_string(i) + ")");
    }
    std::vector<physics::BallPlacement> placed;
    placed.reserve(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) placed.push_back({names[static_cast<size_t>(i)], t.balls[static_cast<size_t>(i)].position});
    if (std::string msg = model.ValidatePlacement(placed); !msg.empty()) {
      errors.push_back({"table.balls", -1, kNoNumber, "", Unit::kNone, std::nullopt, std::move(msg)});
    }
  }
  if (ball_on) {
    bool present = false;
    for (const Ball& b : t.balls) present = present || IsLegalTarget(*ball_on, b.kind);
    if (!present) {
      errors.push_back({"ball_on", -1, kNoNumber, ToString(*ball_on), Unit::kNone, std::nullopt,
                        "no such ball on the table"});
    }
  }
  return errors;
}

std::vector<FieldError> ValidateSettings(const PlanRequest& r) {
  namespace lim = limits;
  std::vector<FieldError> errors;
  const RobotLimits& l = r.limits;
  CheckRange(&errors, "limits.min_speed", l.min_speed, lim::kMinSpeed, Unit::kMetrePerSecond);
  CheckRange(&errors, "limits.max_speed", l.max_speed, lim::kMaxSpeed, Unit::kMetrePerSecond);
  if (std::isfinite(l.min_speed) && std::isfinite(l.max_speed) && !(l.max_speed > l.min_speed)) {
    errors.push_back({"limits.max_speed", -1, l.max_speed, "", Unit::kMetrePerSecond, std::nullopt,
                      "must exceed limits.min_speed (" + Num(l.min_speed) + " m/s)"});
  }
  CheckRange(&errors, "limits.max_topspin_fraction", l.max_topspin_fraction, lim::kSpinFraction,
             Unit::kRollingSpin);
  CheckRange(&errors, "limits.max_sidespin_fraction", l.max_sidespin_fraction, lim::kSpinFraction,
             Unit::kRollingSpin);
  CheckRange(&errors, "limits.cue.length", l.cue.length, lim::kCueClearance, Unit::kMetre);
  CheckRange(&errors, "limits.cue.radius", l.cue.radius, lim::kCueRadius, Unit::kMetre);
  CheckRange(&errors, "limits.cue.max_elevation", l.cue.max_elevation, lim::kMaxElevation, Unit::kRadian);
  CheckRange(&errors, "limits.min_cue_speed", l.min_cue_speed, lim::kCueSpeed, Unit::kMetrePerSecond);
  CheckRange(&errors, "limits.max_cue_speed", l.max_cue_speed, lim::kCueSpeed, Unit::kMetrePerSecond);
  if (std::isfinite(l.min_cue_speed) && std::isfinite(l.max_cue_speed) && !(l.max_cue_speed > l.min_cue_speed)) {
    errors.push_back({"limits.max_cue_speed", -1, l.max_cue_speed, "", Unit::kMetrePerSecond, std::nullopt,
                      "must exceed limits.min_cue_speed (" + Num(l.min_cue_speed) + " m/s)"});
  }
  const NoiseModel& z = r.noise;
  CheckRange(&errors, "noise.heading", z.heading, lim::kHeadingSigma, Unit::kRadian);
  CheckRange(&errors, "noise.speed_fraction", z.speed_fraction, lim::kSpeedSigmaFraction, Unit::kFraction);
  CheckRange(&errors, "noise.topspin", z.topspin, lim::kSpinSigma, Unit::kRadPerSecond);
  CheckRange(&errors, "noise.sidespin", z.sidespin, lim::kSpinSigma, Unit::kRadPerSecond);
  CheckRange(&errors, "noise.position", z.position, lim::kPositionSigma, Unit::kMetre);
  CheckRange(&errors, "noise.aim", z.aim, lim::kHeadingSigma, Unit::kRadian);
  CheckRange(&errors, "noise.cue_speed_fraction", z.cue_speed_fraction, lim::kSpeedSigmaFraction, Unit::kFraction);
  CheckRange(&errors, "noise.tip_offset", z.tip_offset, lim::kTipOffsetSigma, Unit::kMetre);
  CheckRange(&errors, "noise.elevation", z.elevation, lim::kElevationSigma, Unit::kRadian);
  CheckRange(&errors, "noise.squirt_fraction", z.squirt_fraction, lim::kModelUncertainty, Unit::kFraction);
  CheckRange(&errors, "noise.throw_fraction", z.throw_fraction, lim::kModelUncertainty, Unit::kFraction);
  const size_t balls = r.table.balls.size();
  if (!r.position_sigma.empty() && r.position_sigma.size() != balls) {
    errors.push_back({"position_sigma", -1, static_cast<double>(r.position_sigma.size()), "", Unit::kNone,
                      std::nullopt, "entries: none or one per ball (" + std::to_string(balls) + ")"});
  }
  for (size_t i = 0; i < r.position_sigma.size(); ++i) {
    CheckRange(&errors, "position_sigma", r.position_sigma[i], lim::kPositionSigma, Unit::kMetre,
               static_cast<int>(i));
  }
  CheckRange(&errors, "time_budget", r.time_budget, lim::kTimeBudget, Unit::kSecond);
  CheckCount(&errors, "max_shots", r.max_shots, lim::kMaxShots);
  CheckCount(&errors, "threads", r.threads, lim::kThreads);
  CheckCount(&errors, "max_simulations", r.max_simulations, lim::kMaxSimulations);
  CheckCount(&errors, "monte_carlo_samples", r.monte_carlo_samples, lim::kMonteCarloSamples);
  if (r.break_value) CheckRange(&errors, "break_value", *r.break_value, lim::kBreakValue, Unit::kPoints);
  if (r.position_spread) {
    CheckRange(&errors, "position_spread", *r.position_spread, lim::kPositionSpread, Unit::kNone);
  }
  return errors;
}

std::vector<FieldError> ValidatePlanRequest(const PlanRequest& request, const physics::TableModel& model) {
  std::vector<FieldError> errors = ValidateTable(request.table, request.cue_in_hand, request.ball_on, model);
  std::vector<FieldError> more = ValidateSettings(request);
  errors.insert(errors.end(), more.begin(), more.end());
  return errors;
}

std::string Describe(const std::vector<FieldError>& errors) {
  std::ostringstream out;
  for (const FieldError& e : errors) {
    if (out.tellp() > 0) out << "; ";
    out << e.field;
    if (e.ball >= 0) out << "[" << e.ball << "]";
    if (e.value) {
      out << " = " << Num(*e.value);
    } else if (!e.value_text.empty()) {
      out << " = " << e.value_text;
    }
    const std::string unit = ToString(e.unit);
    if (e.range) {
      out << " (must be in [" << Num(e.range->lo) << ", " << Num(e.range->hi) << "]"
          << (unit.empty() ? "" : " " + unit) << ")";
    } else if (!e.rule.empty()) {
      out << " (" << e.rule << ")";
    }
  }
  return out.str();
}

}  // namespace snooker::planner
