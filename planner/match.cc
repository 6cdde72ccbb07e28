#include "planner/match.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "physics/sim/fidelity.h"
#include "physics/table/placement_repair.h"
#include "planner/geometry.h"
#include "planner/robustness.h"
#include "planner/selfplay.h"
#include "planner/validate.h"

namespace snooker::planner {

using physics::Vec2;

namespace {

// A frame's random streams: DeriveSeed(seed, frame) for vision and execution noise,
// (seed, frame, stroke + 1) for the plans, and this one for the tie's coin.
constexpr std::uint64_t kTieCoinStream = std::uint64_t{1} << 32;

// The fallback's placement grid over the D: its centre, then rings at 1/4 .. 4/4
// of the radius, each at kDSectors + 1 angles over the half circle; if no point of
// it is free, a square grid of kFineStep.
constexpr int kDRings = 4;
constexpr int kDSectors = 12;
constexpr double kFineStep = 0.01;  // m
// Air the fallback's placement leaves to every ball, m.
constexpr double kPlacementAir = 1e-3;
// A placement vision put on a ball is moved clear by this much more than 2R, m, in
// at most kSettleSweeps sweeps.
constexpr double kSettleAir = 1e-7;
constexpr int kSettleSweeps = 8;
constexpr int kCentury = 100;

// A straight shot at a ball on: the ball it meets first, and whether that is a ball
// on (the path is clear of balls not on).
struct Aim {
  int target = -1;
  int first = -1;
  bool clear = false;
  double distance = std::numeric_limits<double>::infinity();
  bool Better(const Aim& o) const {
    if (target < 0) return false;
    if (o.target < 0) return true;
    if (clear != o.clear) return clear;
    return distance < o.distance;
  }
};

// The nearest ball on from the cue ball whose straight shot is clear, else the
// nearest ball on; balls touching the cue ball are not aimed at.
Aim NearestOn(const TableState& t, int cue, BallOn on, const std::vector<int>& touching, double radius) {
  Aim best;
  const Vec2 c = t.balls[static_cast<size_t>(cue)].position;
  for (size_t i = 0; i < t.balls.size(); ++i) {
    const int index = static_cast<int>(i);
    if (index == cue || !IsLegalTarget(on, t.balls[i].kind)) continue;
    if (std::find(touching.begin(), touching.end(), index) != touching.end()) continue;
    Aim a;
    a.target = index;
    a.distance = (t.balls[i].position - c).norm();
    a.first = FirstBallMet(t, c, Direction(t.balls[i].position - c), radius, cue);
    a.clear = a.first >= 0 && IsLegalTarget(on, t.balls[static_cast<size_t>(a.first)].kind);
    if (a.Better(best)) best = a;
  }
  return best;
}

bool FreeFor(const TableState& t, const Vec2& p, double air, const physics::TableModel& model) {
  for (const Ball& b : t.balls) {
    if ((b.position - p).norm() < 2 * model.ball_radius() + air) return false;
  }
  return InTheD(p, model);
}

// The fallback's candidate placements in the D that leave kPlacementAir to every ball.
std::vector<Vec2> DPlacements(const TableState& t, const physics::TableModel& model) {
  const physics::TableSpec& spec = model.spec();
  const Vec2 centre(spec.width / 2, spec.baulk_line);
  const double inside = spec.d_radius - 1e-6;
  std::vector<Vec2> out;
  if (FreeFor(t, centre, kPlacementAir, model)) out.push_back(centre);
  for (int ring = 1; ring <= kDRings; ++ring) {
    const double r = inside * ring / kDRings;
    for (int s = 0; s <= kDSectors; ++s) {
      const double a = physics::kPi * s / kDSectors;
      const Vec2 p = centre + r * Vec2(std::cos(a), -std::sin(a));
      if (FreeFor(t, p, kPlacementAir, model)) out.push_back(p);
    }
  }
  if (!out.empty()) return out;
  const int steps = static_cast<int>(std::ceil(spec.d_radius / kFineStep));
  for (int i = -steps; i <= steps; ++i) {
    for (int j = 0; j <= steps; ++j) {
      const Vec2 p = centre + Vec2(i * kFineStep, -j * kFineStep);
      if (FreeFor(t, p, 0, model)) out.push_back(p);
    }
  }
  return out;
}

// The planner's placement on the true table: moved clear of any ball it overlaps
// (vision misplaced that ball), or nullopt when that does not give a legal placement.
std::optional<Vec2> SettlePlacement(const TableState& truth, Vec2 p, const physics::TableModel& model) {
  const double reach = 2 * model.ball_radius() + kSettleAir;
  for (int sweep = 0; sweep < kSettleSweeps; ++sweep) {
    if (CuePlacementError(truth, p, model).empty()) return p;
    bool moved = false;
    for (const Ball& b : truth.balls) {
      const Vec2 d = p - b.position;
      const double dist = d.norm();
      if (dist >= reach) continue;
      p = b.position + (dist > 0 ? Vec2(d / dist) : Vec2(0, -1)) * reach;
      moved = true;
    }
    if (!moved) return std::nullopt;
  }
  if (CuePlacementError(truth, p, model).empty()) return p;
  return std::nullopt;
}

// A stroke played on the true table.
struct Played {
  physics::SimStatus status = physics::SimStatus::kAtRest;
  int first_hit = -1;
  std::vector<int> potted;
  std::vector<Vec2> ends;
};

Played Simulate(physics::Simulator& sim, const TableState& t, int cue, const physics::Shot& shot) {
  std::vector<physics::BallState> balls(t.balls.size());
  for (size_t i = 0; i < t.balls.size(); ++i) {
    if (static_cast<int>(i) == cue) {
      balls[i] = physics::StruckBall(shot, t.balls[i].position);
    } else {
      balls[i].r = t.balls[i].position;
    }
  }
  physics::RunOptions options;
  options.record_paths = false;
  Played out;
  out.status = sim.Run(balls, options);
  for (const physics::SimEvent& ev : sim.events()) {
    // A contact with nothing to resolve (playing away from a touching ball) is no hit.
    if (ev.kind == physics::EventKind::kBallBall && out.first_hit < 0 && (ev.ball == cue || ev.other == cue) &&
        ev.contact != physics::ContactStart::kTouching) {
      out.first_hit = ev.ball == cue ? ev.other : ev.ball;
    } else if (ev.kind == physics::EventKind::kPocket) {
      out.potted.push_back(ev.ball);
    }
  }
  for (const physics::BallState& b : sim.final_balls()) out.ends.push_back(b.r);
  return out;
}

// A turn's request but for its table: the striker's settings and the match's.
void FillTurnRequest(const MatchOptions& o, PlayerKind player, bool cue_in_hand, BallOn on, std::uint64_t seed,
                     PlanRequest* req) {
  req->cue_in_hand = cue_in_hand;
  req->ball_on = on;
  req->limits = o.limits;
  req->noise = o.noise;
  req->time_budget = o.time_budget;
  req->max_shots = 1;
  req->seed = seed;
  req->threads = o.threads;
  req->max_simulations = o.max_simulations;
  req->monte_carlo_samples = o.monte_carlo_samples;
  ConfigureRequest(player, req, o.break_value, o.position_spread);
  req->thin_break_off = o.thin_break_off;
}

// What the striker plays this turn.
struct TurnChoice {
  std::optional<Vec2> cue_start;
  physics::CueStrike cue;
  std::optional<BallKind> nominated;
  ShotKind kind = ShotKind::kPot;
  PotRoute route = PotRoute::kDirect;
  bool stall = false;
  double plan_ms = 0;
  bool cut_short = false;  // the plan's PlanAnswer::cut_short
  double pot_probability = std::numeric_limits<double>::quiet_NaN();
  double plan_score = std::numeric_limits<double>::quiet_NaN();
  int samples = 0;
  Handovers handovers;
  std::string stall_reason;
  TableState seen;
  std::uint64_t plan_seed = 0;
};

// The colour a shot plays first, as its nomination when a colour is on.
std::optional<BallKind> NominationFor(const FrameState& f, int ball) {
  if (f.ball_on != BallOn::kAnyColour || ball < 0 || ball >= static_cast<int>(f.table.balls.size())) {
    return std::nullopt;
  }
  const BallKind k = f.table.balls[static_cast<size_t>(ball)].kind;
  return IsColour(k) ? std::optional<BallKind>(k) : std::nullopt;
}

// The vision repair's tolerance, m: the service's default (1 mm).
constexpr double kVisionTolerance = 1e-3;

class MatchRunner {
 public:
  MatchRunner(const Planner& planner, const MatchOptions& o)
      : planner_(planner),
        o_(o),
        model_(*planner.config().table),
        world_(o.world.value_or(planner.config().model())),
        sim_(model_, world_.Apply(physics::FidelityParams(physics::Fidelity::kDefault))) {
    vision_.table = &model_;
    vision_.noise = o.noise;
  }

  FrameSummary PlayFrame(int frame);
  MatchReport Finish();

 private:
  TurnChoice Choose(const FrameState& f, int frame, Rng& rng) const;
  void Play(int frame, FrameState& f, const TurnChoice& c, Rng& rng, FrameSummary& summary);

  const Planner& planner_;
  const MatchOptions& o_;
  const physics::TableModel& model_;
  const physics::Model world_;  // the table the strokes are played on
  physics::Simulator sim_;
  PotContext vision_;
  MatchReport report_;
  std::vector<double> plan_ms_;
  std::array<std::vector<double>, 3> plan_ms_by_turn_;
};

TurnChoice MatchRunner::Choose(const FrameState& f, int frame, Rng& rng) const {
  PlanRequest req;
  req.table = f.table;
  std::vector<Vec2> seen;
  SampleTruePositions(f.table, vision_, rng, &seen);
  // What the service does with vision's positions: balls that overlap by a hair
  // (a rack seen through the noise) moved apart by the least distance.
  std::vector<physics::BallPlacement> placed;
  for (const Vec2& p : seen) placed.push_back({"", p});
  if (physics::RepairPlacement(model_, placed, kVisionTolerance).error.empty()) {
    for (size_t i = 0; i < seen.size(); ++i) seen[i] = placed[i].r;
  }
  for (size_t i = 0; i < seen.size(); ++i) req.table.balls[i].position = seen[i];
  const std::uint64_t seed =
      DeriveSeed(o_.seed, static_cast<std::uint64_t>(frame), static_cast<std::uint64_t>(f.shots) + 1);
  FillTurnRequest(o_, o_.players[static_cast<size_t>(f.striker)], f.cue_in_hand, f.ball_on, seed, &req);
  const PlanAnswer answer = planner_.Plan(req);
  TurnChoice c;
  c.plan_ms = answer.elapsed * 1e3;
  c.cut_short = answer.cut_short;
  c.seen = req.table;
  c.plan_seed = seed;
  if (!answer.shots.empty()) {
    const PlannedShot& p = answer.shots.front();
    std::optional<Vec2> start;
    if (f.cue_in_hand && p.cue_start) start = SettlePlacement(f.table, *p.cue_start, model_);
    if (!f.cue_in_hand || start) {
      c.cue_start = start;
      c.cue = p.cue;
      c.kind = p.kind;
      c.route = p.route;
      if (p.kind == ShotKind::kPot) c.pot_probability = p.pot_probability;
      c.plan_score = p.score;
      c.samples = p.monte_carlo_samples;
      c.handovers = p.handovers;
      // A foul stroke names the colour it nominates as its object ball.
      c.nominated = NominationFor(f, p.first_ball >= 0 && p.kind != ShotKind::kFoul ? p.first_ball : p.object_ball);
      return c;
    }
  }
  const std::string status = ToString(answer.status);
  c.stall_reason = answer.reason.empty()                ? status
                   : answer.reason.starts_with(status) ? answer.reason
                                                        : status + ": " + answer.reason;
  if (!answer.shots.empty()) c.stall_reason = "the plan's placement in the D could not be settled on the table";
  const FallbackShot fb = NearestBallOnShot(f.table, f.cue_in_hand, f.ball_on, o_.limits, model_);
  c.cue_start = fb.cue_start;
  c.cue = LevelStrikeFor(fb.shot, planner_.config().cue, planner_.config().full.ball,
                         planner_.config().full.cloth.g);
  c.nominated = NominationFor(f, fb.first_ball >= 0 ? fb.first_ball : fb.target);
  c.stall = true;
  return c;
}

void MatchRunner::Play(int frame, FrameState& f, const TurnChoice& c, Rng& rng, FrameSummary& summary) {
  Stroke s;
  s.cue_start = c.cue_start;
  s.nominated = c.nominated;
  const TableState table = StrokeTable(f, c.cue_start);
  s.touching = TouchingCueBall(table, model_);
  // The robot's cue, with its execution noise, striking in the world.
  const PlayedStroke played = SampleStroke(c.cue, world_.cue, world_.ball, world_.cloth.g, o_.noise, false, rng);
  const Played out = Simulate(sim_, table, table.cue_index(), played.shot);
  if (out.status == physics::SimStatus::kAtRest) {
    s.first_hit = out.first_hit;
    s.potted = out.potted;
    s.ends = out.ends;
  } else {
    s.simulation_failed = true;
    ++report_.simulation_failures;
  }
  const TurnType turn = !f.cue_in_hand ? TurnType::kOnTable : f.shots == 0 ? TurnType::kBreakOff : TurnType::kInHand;
  const BallOn on_before = f.ball_on;
  const StrokeResult r = ApplyStroke(f, s, model_);
  // The incoming player's outlook, when the stroke handed the table over.
  double handover = std::numeric_limits<double>::quiet_NaN();
  if (o_.outlook && !f.over && f.striker != r.striker) handover = o_.outlook(f.table, f.cue_in_hand, f.ball_on);
  if (o_.on_stroke) {
    StrokeRecord rec;
    rec.frame = frame;
    rec.stroke = f.shots;
    rec.striker = r.striker;
    rec.turn = turn;
    rec.kind = c.kind;
    rec.route = c.route;
    rec.stall = c.stall;
    rec.pot_probability = c.pot_probability;
    rec.plan_score = c.plan_score;
    rec.potted = static_cast<int>(s.potted.size());
    rec.foul = r.judgement.foul;
    rec.points = r.judgement.points;
    rec.penalty = r.judgement.penalty;
    rec.score = f.score;
    rec.plan_ms = c.plan_ms;
    rec.handover_outlook = handover;
    rec.plan_samples = c.samples;
    rec.plan_handovers = c.handovers;
    rec.ball_on = on_before;
    rec.table = c.seen;
    rec.plan_seed = c.plan_seed;
    if (c.stall) rec.stall_reason = c.stall_reason;
    o_.on_stroke(rec);
  }
  PlayerStats& p = report_.players[static_cast<size_t>(r.striker)];
  ++p.shots;
  p.plan_ms.push_back(c.plan_ms);
  plan_ms_.push_back(c.plan_ms);
  plan_ms_by_turn_[static_cast<size_t>(turn)].push_back(c.plan_ms);
  if (c.cut_short) ++report_.plans_cut_short;
  if (c.stall) {
    ++p.stalls;
    ++summary.stalls;
  } else {
    ++p.kinds[static_cast<size_t>(c.kind)];
    if (c.kind == ShotKind::kPot) ++p.routes[static_cast<size_t>(c.route)];
  }
  if (r.judgement.foul != Foul::kNone) {
    ++p.fouls;
    ++summary.fouls;
    report_.players[static_cast<size_t>(1 - r.striker)].penalty_points += r.judgement.penalty;
  }
  if (r.visit_over && r.break_points > 0) p.breaks.push_back(r.break_points);
  if (turn == TurnType::kBreakOff && std::isfinite(handover)) p.break_off_outlook.push_back(handover);
  if (c.kind == ShotKind::kSafety && !c.stall) {
    ++p.safeties;
    if (std::isfinite(handover)) p.safety_outlook.push_back(handover);
  }
}

FrameSummary MatchRunner::PlayFrame(int frame) {
  const auto index = static_cast<std::uint64_t>(frame);
  Rng rng(DeriveSeed(o_.seed, index));
  FrameSummary summary;
  summary.breaker = frame % 2;
  FrameState f = StartFrame(DeriveSeed(o_.seed, index, kTieCoinStream), summary.breaker, model_);
  f.max_shots = o_.max_shots_per_frame;
  // Each stroke counts towards the frame's own cap; this bound only backs it up.
  for (int k = 0; k <= kFrameShotCap && !f.over; ++k) Play(frame, f, Choose(f, frame, rng), rng, summary);
  summary.score = f.score;
  summary.winner = f.winner;
  summary.end = f.end;
  summary.shots = f.shots;
  summary.black_respotted = f.black_respotted;
  for (size_t p = 0; p < 2; ++p) report_.players[p].points += f.score[p];
  if (f.winner >= 0) ++report_.players[static_cast<size_t>(f.winner)].frames_won;
  if (f.end == FrameEnd::kShotCap) {
    ++report_.frames_capped;
    if (f.winner < 0) ++report_.frames_undecided;
  }
  if (f.black_respotted) ++report_.black_respots;
  report_.shots += f.shots;
  report_.stalls += summary.stalls;
  report_.records.push_back(summary);
  ++report_.frames;
  return summary;
}

MatchReport MatchRunner::Finish() {
  for (size_t i = 0; i < 2; ++i) {
    PlayerStats& p = report_.players[i];
    p.kind = o_.players[i];
    const int total = std::accumulate(p.breaks.begin(), p.breaks.end(), 0);
    p.mean_break = p.breaks.empty() ? 0 : static_cast<double>(total) / static_cast<double>(p.breaks.size());
    for (const int b : p.breaks) {
      p.highest_break = std::max(p.highest_break, b);
      if (b >= kCentury) ++p.centuries;
    }
    p.plan_ms_p50 = Percentile(p.plan_ms, 0.5);
    p.plan_ms_p99 = Percentile(p.plan_ms, 0.99);
    p.median_safety_outlook = p.safety_outlook.empty() ? std::numeric_limits<double>::quiet_NaN()
                                                       : Percentile(p.safety_outlook, 0.5);
    p.median_break_off_outlook = p.break_off_outlook.empty() ? std::numeric_limits<double>::quiet_NaN()
                                                             : Percentile(p.break_off_outlook, 0.5);
    p.mean_break_off_outlook =
        p.break_off_outlook.empty()
            ? std::numeric_limits<double>::quiet_NaN()
            : std::accumulate(p.break_off_outlook.begin(), p.break_off_outlook.end(), 0.0) /
                  static_cast<double>(p.break_off_outlook.size());
    p.mean_safety_outlook =
        p.safety_outlook.empty()
            ? std::numeric_limits<double>::quiet_NaN()
            : std::accumulate(p.safety_outlook.begin(), p.safety_outlook.end(), 0.0) /
                  static_cast<double>(p.safety_outlook.size());
    report_.highest_break = std::max(report_.highest_break, p.highest_break);
    report_.centuries += p.centuries;
  }
  report_.plan_ms_p50 = Percentile(plan_ms_, 0.5);
  report_.plan_ms_p99 = Percentile(plan_ms_, 0.99);
  for (size_t t = 0; t < plan_ms_by_turn_.size(); ++t) {
    const bool none = plan_ms_by_turn_[t].empty();  // NaN: no such turn was played
    report_.plan_ms_p50_by_turn[t] = none ? std::numeric_limits<double>::quiet_NaN() : Percentile(plan_ms_by_turn_[t], 0.5);
    report_.plan_ms_p99_by_turn[t] = none ? std::numeric_limits<double>::quiet_NaN() : Percentile(plan_ms_by_turn_[t], 0.99);
  }
  return report_;
}

}  // namespace

const char* ToString(PlayerKind kind) {
  switch (kind) {
    case PlayerKind::kDefault: return "default";
    case PlayerKind::kDirectPots: return "direct-pots";
    case PlayerKind::kOnePly: return "one-ply";
  }
  return "unknown";
}

std::optional<PlayerKind> ParsePlayerKind(std::string_view name) {
  for (int k = 0; k < kPlayerKindCount; ++k) {
    const auto kind = static_cast<PlayerKind>(k);
    if (name == ToString(kind)) return kind;
  }
  return std::nullopt;
}

void ConfigureRequest(PlayerKind kind, PlanRequest* request, double break_value, double position_spread) {
  request->kinds = ShotKinds{};
  request->routes = PotRoutes{};
  request->lookahead = true;
  request->break_value = break_value;
  request->position_spread = position_spread > 0 ? std::optional<double>(position_spread) : std::nullopt;
  switch (kind) {
    case PlayerKind::kDefault: break;
    case PlayerKind::kDirectPots:
      request->kinds = ShotKinds::Of(ShotKind::kPot);
      request->routes = PotRoutes::Of(PotRoute::kDirect);
      request->lookahead = false;
      request->break_value = std::nullopt;
      request->position_spread = std::nullopt;
      break;
    case PlayerKind::kOnePly: request->lookahead = false; break;
  }
}

PlanRequest ReplayRequest(const MatchOptions& o, const StrokeRecord& s) {
  PlanRequest req;
  req.table = s.table;
  FillTurnRequest(o, o.players[static_cast<size_t>(s.striker)], s.turn != TurnType::kOnTable, s.ball_on, s.plan_seed,
                  &req);
  return req;
}

std::string MatchOptionsError(const MatchOptions& o) {
  std::string errors;
  auto add = [&](const std::string& e) { errors += (errors.empty() ? "" : "; ") + e; };
  if (o.frames < 1 || o.frames > 100'000) add("frames = " + std::to_string(o.frames) + " (must be in [1, 100000])");
  if (o.max_shots_per_frame < 1 || o.max_shots_per_frame > kFrameShotCap) {
    add("max_shots_per_frame = " + std::to_string(o.max_shots_per_frame) + " (must be in [1, " +
        std::to_string(kFrameShotCap) + "])");
  }
  for (size_t i = 0; i < 2; ++i) {
    if (static_cast<int>(o.players[i]) >= kPlayerKindCount) {
      add("players[" + std::to_string(i) + "] = " + std::to_string(static_cast<int>(o.players[i])) +
          " (not a player)");
    }
  }
  PlanRequest settings;
  settings.limits = o.limits;
  settings.noise = o.noise;
  settings.time_budget = o.time_budget;
  settings.threads = o.threads;
  settings.max_simulations = o.max_simulations;
  settings.monte_carlo_samples = o.monte_carlo_samples;
  settings.break_value = o.break_value;
  settings.position_spread = o.position_spread;
  if (const std::vector<FieldError> e = ValidateSettings(settings); !e.empty()) add(Describe(e));
  if (o.world) {
    if (const std::string e = physics::ValidateModel(*o.world); !e.empty()) add("world: " + e);
  }
  return errors;
}

FallbackShot NearestBallOnShot(const TableState& table, bool cue_in_hand, BallOn on, const RobotLimits& limits,
                               const physics::TableModel& model) {
  std::vector<Vec2> placements;
  if (cue_in_hand) {
    placements = DPlacements(table, model);
    // A D with no free point cannot occur with 22 balls; place at its centre regardless.
    if (placements.empty()) placements.push_back(Vec2(model.spec().width / 2, model.spec().baulk_line));
  }
  FallbackShot out;
  Aim best;
  TableState best_table = table;
  std::vector<int> best_touching;
  for (size_t k = 0; k < std::max<size_t>(placements.size(), 1); ++k) {
    TableState t = table;
    if (cue_in_hand) t.balls.push_back({BallKind::kCue, placements[k]});
    const int cue = t.cue_index();
    if (cue < 0) throw std::invalid_argument("NearestBallOnShot: the table holds no cue ball and it is not in hand");
    std::vector<int> touching = TouchingCueBall(t, model);
    const Aim a = NearestOn(t, cue, on, touching, model.ball_radius());
    if (k == 0 || a.Better(best)) {
      best = a;
      best_table = std::move(t);
      best_touching = std::move(touching);
      if (cue_in_hand) out.cue_start = placements[k];
    }
  }
  const Vec2 cue = best_table.balls[static_cast<size_t>(best_table.cue_index())].position;
  out.target = best.target;
  out.first_ball = best.first;
  out.clear = best.clear;
  out.shot.speed = std::clamp(kFallbackSpeed, limits.min_speed, limits.max_speed);
  if (best.target >= 0) {
    out.shot.heading = Direction(best_table.balls[static_cast<size_t>(best.target)].position - cue);
  } else if (!best_touching.empty()) {
    out.shot.heading = Direction(cue - best_table.balls[static_cast<size_t>(best_touching.front())].position);
  } else {
    out.shot.heading = physics::kPi / 2;  // no ball on at all: up the table
  }
  return out;
}

const char* ToString(TurnType t) {
  switch (t) {
    case TurnType::kOnTable: return "on table";
    case TurnType::kInHand: return "in hand";
    case TurnType::kBreakOff: return "break-off";
  }
  return "unknown";
}

MatchReport RunMatch(const Planner& planner, const MatchOptions& options,
                     const std::function<void(int, const FrameSummary&)>& on_frame) {
  if (std::string e = MatchOptionsError(options); !e.empty()) throw std::invalid_argument(e);
  MatchRunner runner(planner, options);
  for (int f = 0; f < options.frames; ++f) {
    const FrameSummary summary = runner.PlayFrame(f);
    if (on_frame) on_frame(f, summary);
  }
  return runner.Finish();
}

}  // namespace snooker::planner
