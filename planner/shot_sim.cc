#include "planner/shot_sim.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "physics/motion/motion.h"
#include "planner/geometry.h"

namespace snooker::planner {

using physics::EventKind;
using physics::SimStatus;
using physics::Vec2;

int TouchingBallOn(const TableState& table, BallOn on, const physics::TableModel& model) {
  for (const int i : TouchingCueBall(table, model)) {
    if (IsLegalTarget(on, table.balls[static_cast<size_t>(i)].kind)) return i;
  }
  return -1;
}

ShotSimulator::ShotSimulator(const physics::TableModel& table, const physics::SimParams& params)
    : table_(table), params_(params), sim_(table, params) {
  balls_.reserve(physics::Simulator::kMaxBalls);
  out_.potted.reserve(physics::Simulator::kMaxBalls);
}

void ShotSimulator::MeasureLine(const ShotSetup& setup, const physics::BallState& object, const Vec2* partner) {
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
  line.throw_angle = 0;
  if (partner != nullptr) {
    const Vec2 centres = object.r - *partner;
    if (centres.norm() > 0) line.throw_angle = WrapAngle(line.direction - Direction(centres));
  }
  if (!out_.first_line.valid) out_.first_line = line;
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
  // A fresh outcome that keeps the potted list's buffer: no allocation per run.
  std::vector<int> potted = std::move(out_.potted);
  potted.clear();
  out_ = ShotOutcome{};
  out_.potted = std::move(potted);
  out_.first_hit = setup.touching_on;
  ++runs_;
  // The full mode keeps events and paths for the answer; the others neither (the
  // object ball's state right after its contact comes from StateNow).
  physics::RunOptions options = mode == Mode::kFull ? physics::RunOptions{} : physics::RunOptions::Lean();
  options.interrupt = interrupt;
  const SimStatus status = Loop(setup, sim_.Start(balls_, options), mode == Mode::kDecide);
  out_.status = status;
  out_.events = sim_.event_count();
  out_.object_pocket = setup.object >= 0 ? sim_.pocket_of(setup.object) : -1;
  Judge(setup, status);
  return out_;
}

SimStatus ShotSimulator::Loop(const ShotSetup& setup, SimStatus status, bool decide) {
  const TableState& table = *setup.table;
  const bool pot = setup.kind == ShotKind::kPot;
  const int first = setup.FirstBall();
  // With any colour on, the colour nominated: the object ball's, else the first hit's.
  auto legal = [&](int i) {
    const BallKind k = table.balls[static_cast<size_t>(i)].kind;
    if (setup.on != BallOn::kAnyColour) return IsLegalTarget(setup.on, k);
    const int named = setup.object >= 0 ? setup.object : out_.first_hit;
    return named >= 0 ? k == table.balls[static_cast<size_t>(named)].kind : IsColour(k);
  };
  auto stop = [&]() {
    out_.stopped_early = true;
    return true;
  };
  // The cue ball's path from its first contact: a chord from each of its events to
  // the next.
  bool tracking = false;
  Vec2 mark = Vec2::Zero();
  auto track = [&](const Vec2& p) {
    if (tracking) {
      const Vec2 chord = p - mark;
      const double length = chord.norm();
      if (length > 1e-6) {
        out_.cue_travel += length;
        out_.cue_last_direction = chord / length;
      }
    }
    tracking = true;
    mark = p;
  };
  // Touching a ball on, the cue ball's contact is where it starts.
  if (out_.first_hit >= 0) track(sim_.StateNow(setup.cue).r);
  while (status == SimStatus::kRunning) {
    status = sim_.Step();
    if (status != SimStatus::kRunning) break;
    const physics::SimEvent& ev = sim_.last_event();
    const bool cue_involved = ev.ball == setup.cue || ev.other == setup.cue;
    if (ev.kind == EventKind::kBallBall && out_.first_hit < 0 && cue_involved) {
      out_.first_hit = ev.ball == setup.cue ? ev.other : ev.ball;
      const bool wrong = first >= 0 ? out_.first_hit != first : !legal(out_.first_hit);
      if (decide && wrong && stop()) break;
    } else if (ev.kind == EventKind::kCushion && ev.ball == setup.cue && out_.first_hit < 0) {
      ++out_.cue_cushions_first;
    } else if (ev.kind == EventKind::kPocket) {
      out_.potted.push_back(ev.ball);
      if (decide && (ev.ball == setup.cue || !legal(ev.ball)) && stop()) break;
    }
    if (cue_involved && out_.first_hit >= 0 && sim_.pocket_of(setup.cue) < 0) track(sim_.StateNow(setup.cue).r);
    // The object ball's line from its latest contact (the cue ball's, for a direct pot).
    if (setup.object >= 0 && out_.first_hit >= 0 && sim_.pocket_of(setup.object) < 0 &&
        (ev.ball == setup.object || ev.other == setup.object) &&
        (ev.kind == EventKind::kBallBall || ev.kind == EventKind::kCushion)) {
      if (ev.kind == EventKind::kCushion) ++out_.object_cushions;
      // A ball's contact: the other ball's centre, for the line's throw.
      const bool ball = ev.kind == EventKind::kBallBall;
      const Vec2 partner = ball ? sim_.StateNow(ev.ball == setup.object ? ev.other : ev.ball).r : Vec2::Zero();
      MeasureLine(setup, sim_.StateNow(setup.object), ball ? &partner : nullptr);
    }
    if (!decide) continue;
    // A miss: a pot's object ball at rest after contact, or the cue ball at rest
    // before touching anything.
    if (pot && out_.first_hit >= 0 && sim_.pocket_of(setup.object) < 0 && sim_.Decided(setup.object) &&
        stop()) {
      break;
    }
    if (out_.first_hit < 0 && sim_.Decided(setup.cue) && stop()) break;
  }
  if (tracking && status == SimStatus::kAtRest && sim_.pocket_of(setup.cue) < 0) {
    track(sim_.final_balls()[static_cast<size_t>(setup.cue)].r);
  }
  return status;
}

void ShotSimulator::Judge(const ShotSetup& setup, SimStatus status) {
  const TableState& table = *setup.table;
  if (status != SimStatus::kRunning && status != SimStatus::kAtRest) {
    out_.foul = Foul::kSimulationFailed;
    return;
  }
  // For the judgement the colour nominated is the object ball's (or, with none, the
  // first ball's).
  const int named = setup.object >= 0 ? setup.object : out_.first_hit;
  const std::optional<BallKind> nominated =
      named >= 0 ? std::optional<BallKind>(table.balls[static_cast<size_t>(named)].kind) : std::nullopt;
  const int touching[] = {setup.touching_on};
  out_.foul = JudgeShot(table, setup.on, nominated, out_.first_hit, out_.potted,
                        setup.touching_on >= 0 ? std::span<const int>(touching) : std::span<const int>())
                  .foul;
  const bool at_rest = status == SimStatus::kAtRest && !out_.stopped_early && out_.foul == Foul::kNone;
  if (setup.kind != ShotKind::kPot) {
    out_.success = at_rest;
    return;
  }
  const bool first_ok = setup.touching_on >= 0 || out_.first_hit == setup.FirstBall();
  out_.success = at_rest && first_ok && out_.object_pocket >= 0;
}

}  // namespace snooker::planner
