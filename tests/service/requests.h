// Requests shared by the service tests (and the planner's service tests): a ball
// added to a table, the paper's first collision, a full table, and a heavy (but
// valid) break-off.
#pragma once

#include <cmath>
#include <string>

#include "physics/core/params.h"
#include "physics/core/types.h"
#include "physics/table/table.h"
#include "snooker/v1/collide.pb.h"
#include "snooker/v1/simulate.pb.h"
#include "snooker/v1/table.pb.h"

namespace snooker::testing_requests {

/// Mathavan et al. (2014) Table 1, shot 1: a rolling cue ball at 1.539 m/s, cut 33.83 deg.
inline v1::CollideRequest PaperCollide() {
  v1::CollideRequest r;
  r.set_speed(1.539);
  r.set_topspin(1.539 / physics::BallParams{}.radius);
  r.set_cut_angle_deg(33.83);
  return r;
}

/// Adds a ball at (x, y), m, table frame.
inline void AddBall(v1::TableState* t, const std::string& id, v1::BallKind kind, double x, double y) {
  v1::Ball* b = t->add_balls();
  b->set_id(id);
  b->set_kind(kind);
  b->mutable_position()->set_x(x);
  b->mutable_position()->set_y(y);
}
/// The same to a request's table (SimulateRequest, PlanRequest).
template <typename Request>
void AddBall(Request* r, const std::string& id, v1::BallKind kind, double x, double y) {
  AddBall(r->mutable_table(), id, kind, x, y);
}

/// The full table (15 reds in the triangle, six colours on their spots) and the cue
/// ball in the D, struck at `speed` m/s at the apex red with `topspin` and
/// `sidespin` rad/s.
inline v1::SimulateRequest BreakOff(double speed, double topspin, double sidespin) {
  const physics::TableModel& table = physics::DefaultTable();
  v1::SimulateRequest r;
  const physics::Vec2 cue(table.spot(physics::Colour::kBrown).x() + 0.15,
                          table.spot(physics::Colour::kBrown).y() - 0.1);
  AddBall(&r, "cue", v1::CUE, cue.x(), cue.y());
  const auto reds = table.reds();
  for (std::size_t i = 0; i < reds.size(); ++i) {
    AddBall(&r, "red-" + std::to_string(i + 1), v1::RED, reds[i].x(), reds[i].y());
  }
  const std::pair<physics::Colour, v1::BallKind> colours[] = {
      {physics::Colour::kYellow, v1::YELLOW}, {physics::Colour::kGreen, v1::GREEN},
      {physics::Colour::kBrown, v1::BROWN},   {physics::Colour::kBlue, v1::BLUE},
      {physics::Colour::kPink, v1::PINK},     {physics::Colour::kBlack, v1::BLACK}};
  for (const auto& [colour, kind] : colours) {
    const physics::Vec2 p = table.spot(colour);
    AddBall(&r, v1::BallKind_Name(kind), kind, p.x(), p.y());
  }
  const physics::Vec2 aim = reds[0] + physics::Vec2(0.02, 0.0) - cue;
  r.mutable_shot()->set_speed(speed);
  r.mutable_shot()->set_heading_deg(physics::RadToDeg(std::atan2(aim.y(), aim.x())));
  r.mutable_shot()->set_topspin(topspin);
  r.mutable_shot()->set_sidespin(sidespin);
  return r;
}

/// A valid request that costs as much as a request can reasonably cost: the
/// hardest break-off (20 m/s, the largest spins), the tightest tolerance, the
/// largest caps, with paths. About 200 events; tens of milliseconds.
inline v1::SimulateRequest Heavy() {
  v1::SimulateRequest r = BreakOff(20, -1000, 1000);
  r.mutable_options()->set_tolerance(1e-15);
  r.mutable_options()->set_max_events(1'000'000);
  r.mutable_options()->set_max_time_s(3600);
  r.mutable_options()->set_include_paths(true);
  return r;
}

}  // namespace snooker::testing_requests
