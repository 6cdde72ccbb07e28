#include "planner/shot_sim.h"

#include <algorithm>
#include <cmath>

#include "physics/motion/motion.h"
#include "planner/geometry.h"

namespace snooker::planner {

using physics::EventKind;
using physics::SimStatus;
using physics::Vec2;

ShotSimulator::ShotSimulator(const physics::TableModel& table, const physics::SimParams& params)
    : table_(table), params_(params), sim_(table, params) {
  balls_.reserve(physics::Simulator::kMaxBalls);
  out_.potted.reserve(physics::Simulator::kMaxBalls);
}

void ShotSimulator::MeasureLine(const ShotSetup& setup, const physics::BallState& object) {
  physics::BallState o = object;
  if (o.s == physics::MotionState::kSliding) {
    o = physics::Evolve(o, physics::TransitionTime(o, params_.ball, params_.cloth), params_.ball,
                        params_.cloth);
  }
  const Vec2 v(o.v.x(), o.v.y());
  const double speed = v.norm();
  if (!(speed > 0)) return;
  const Vec2 u = v / speed;
  const Vec2 mouth = table_.pocket(setup.pocket).mouth_centre;
  ObjectLine& line = out_.line;
  line.valid = true;
  line.direction = Direction(u);
  line.offset = (o.r - mouth).dot(Left(u));
  line.distance = std::max(0.0, (mouth - o.r).dot(u));
  const double decel = params_.cloth.mu_r * params_.cloth.g;
  line.arrival_speed = std::sqrt(std::max(0.0, speed * speed - 2 * decel * line.distance));
  // The cue ball gave the object ball about 0.9 cos(cut) of its speed.
  const Vec2 vo(object.v.x(), object.v.y());
  const Vec2 cue = (*setup.table).balls[static_cast<size_t>(setup.cue)].position;
  const Vec2 to_object = object.r - cue;
  const double cos_cut = std::clamp(to_object.norm() > 0 ? std::abs(to_object.normalized().dot(vo.normalized())) : 1.0, 0.2, 1.0);
  line.contact_speed = vo.norm() / (0.9 * cos_cut);
}

const ShotOutcome& ShotSimulator::Run(const ShotSetup& setup, const physics::Shot& shot,
                                      std::span<const Vec2> positions, Mode mode,
                                      const physics::Interrupt& interrupt) {
  const TableState& table = *setup.table;
  const int n = static_cast<int>(table.balls.size());
  balls_.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const Vec2 r = positions.empty() ? table.balls[static_cast<size_t>(i)].position
                                     : positions[static_cast<size_t>(i)];
    if (i == setup.cue) {
      balls_[static_cast<size_t>(i)] = physics::StruckBall(shot, r);
    } else {
      balls_[static_cast<size_t>(i)] = physics::BallState{};
      balls_[static_cast<size_t>(i)].r = r;
    }
  }
  out_ = ShotOutcome{};
  out_.potted.clear();
  ++runs_;
  // The full mode keeps events and paths for the answer; the others neither (the
  // object ball's state right after its contact comes from StateNow).
  physics::RunOptions options = mode == Mode::kFull ? physics::RunOptions{} : physics::RunOptions::Lean();
  options.interrupt = interrupt;
  SimStatus status = sim_.Start(balls_, options);
  const bool decide = mode == Mode::kDecide;
  auto legal = [&](int i) {
    const BallKind k = table.balls[static_cast<size_t>(i)].kind;
    if (setup.on == BallOn::kAnyColour) return k == table.balls[static_cast<size_t>(setup.object)].kind;
    return IsLegalTarget(setup.on, k);
  };
  while (status == SimStatus::kRunning) {
    status = sim_.Step();
    if (status != SimStatus::kRunning) break;
    const physics::SimEvent& ev = sim_.last_event();
    if (ev.kind == EventKind::kBallBall && out_.first_hit < 0 &&
        (ev.ball == setup.cue || ev.other == setup.cue)) {
      out_.first_hit = ev.ball == setup.cue ? ev.other : ev.ball;
      if (out_.first_hit == setup.object) {
        MeasureLine(setup, sim_.StateNow(setup.object));
      } else if (decide) {
        out_.stopped_early = true;
        break;
      }
    } else if (ev.kind == EventKind::kPocket) {
      out_.potted.push_back(ev.ball);
      if (decide && (ev.ball == setup.cue || !legal(ev.ball))) {
        out_.stopped_early = true;
        break;
      }
    }
    if (decide) {
      // A miss: the object ball (after contact) or the cue ball (before) at rest.
      if (out_.first_hit == setup.object && sim_.pocket_of(setup.object) < 0 &&
          sim_.Decided(setup.object)) {
        out_.stopped_early = true;
        break;
      }
      if (out_.first_hit < 0 && sim_.Decided(setup.cue)) {
        out_.stopped_early = true;
        break;
      }
    }
  }
  out_.status = status;
  out_.events = sim_.event_count();
  out_.object_pocket = sim_.pocket_of(setup.object);
  if (status == SimStatus::kRunning || status == SimStatus::kAtRest) {
    // For the judgement the intended object ball is the nominated colour.
    const BallKind object_kind = table.balls[static_cast<size_t>(setup.object)].kind;
    const ShotJudgement j = JudgeShot(table, setup.on, object_kind, out_.first_hit, out_.potted);
    out_.foul = j.foul;
    if (out_.foul == Foul::kNone && out_.first_hit != setup.object) out_.foul = Foul::kWrongBallFirst;
  } else {
    out_.foul = Foul::kSimulationFailed;
  }
  out_.success = status == SimStatus::kAtRest && !out_.stopped_early && out_.foul == Foul::kNone &&
                 out_.object_pocket >= 0;
  return out_;
}

}  // namespace snooker::planner
