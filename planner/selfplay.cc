#include "planner/selfplay.h"

#include <algorithm>
#include <cmath>

#include "planner/robustness.h"
#include "planner/shot_sim.h"

namespace snooker::planner {

using physics::Vec2;

namespace {

// Scattered balls keep this much air to every other ball and spot, m: "where they
// do not touch".
constexpr double kScatterGap = 1e-3;

bool FreeSpot(const Vec2& p, const TableState& t, const physics::TableModel& table, bool avoid_spots) {
  const double need = 2 * table.ball_radius() + kScatterGap;
  for (const Ball& b : t.balls) {
    if ((b.position - p).norm() < need) return false;
  }
  if (avoid_spots) {
    for (int c = 0; c < physics::kColourCount; ++c) {
      if ((table.spot(static_cast<physics::Colour>(c)) - p).norm() < need) return false;
    }
  }
  return true;
}

Vec2 RandomFree(Rng& rng, const TableState& t, const physics::TableModel& table, bool avoid_spots) {
  const double c = table.cushion_contact_distance() + kScatterGap;
  const double w = table.spec().width, l = table.spec().length;
  Vec2 p;
  for (int tries = 0; tries < 10000; ++tries) {  // a 22-ball table is mostly empty
    p = Vec2(rng.Uniform(c, w - c), rng.Uniform(c, l - c));
    if (FreeSpot(p, t, table, avoid_spots)) return p;
  }
  return p;
}

}  // namespace

double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const double rank = std::ceil(std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size()));
  const size_t i = static_cast<size_t>(std::max(1.0, rank)) - 1;
  return values[std::min(i, values.size() - 1)];
}

TableState RandomFrame(Rng& rng, int reds, const physics::TableModel& table) {
  TableState t;
  for (int c = 0; c < physics::kColourCount; ++c) {
    t.balls.push_back({KindOf(static_cast<physics::Colour>(c)), table.spot(static_cast<physics::Colour>(c))});
  }
  for (int i = 0; i < reds; ++i) t.balls.push_back({BallKind::kRed, RandomFree(rng, t, table, true)});
  t.balls.insert(t.balls.begin(), Ball{BallKind::kCue, RandomFree(rng, t, table, false)});
  return t;
}

SelfPlayReport RunSelfPlay(const Planner& planner, const SelfPlayOptions& o,
                           void (*on_frame)(int, const FrameRecord&, void*), void* context) {
  SelfPlayReport report;
  const physics::TableModel& model = *planner.config().table;
  // The world: the planner's own model unless another is given.
  const physics::Model world = o.world.value_or(planner.config().model());
  ShotSimulator truth_sim(model, world.Apply(planner.config().full));
  PotContext vision_ctx;
  vision_ctx.table = &model;
  vision_ctx.noise = o.noise;
  const physics::Interrupt no_interrupt;
  for (int f = 0; f < o.frames; ++f) {
    Rng rng(DeriveSeed(o.seed, static_cast<std::uint64_t>(f)));
    const int reds = o.min_reds + static_cast<int>(rng.Uniform() * (o.max_reds - o.min_reds + 1));
    TableState truth = RandomFrame(rng, std::min(reds, o.max_reds), model);
    FrameRecord rec;
    rec.reds = truth.reds();
    std::optional<BallOn> on = BallOn::kRed;
    std::vector<Vec2> seen_positions, finals;
    for (int k = 0;; ++k) {
      if (k >= o.max_shots_per_frame) {
        rec.end = "shot cap";
        break;
      }
      // What vision reports.
      SampleTruePositions(truth, vision_ctx, rng, &seen_positions);
      PlanRequest req;
      req.table = truth;
      for (size_t i = 0; i < truth.balls.size(); ++i) req.table.balls[i].position = seen_positions[i];
      req.ball_on = on;
      req.limits = o.limits;
      req.noise = o.noise;
      req.time_budget = o.time_budget;
      req.max_shots = 1;
      req.seed = DeriveSeed(o.seed, static_cast<std::uint64_t>(f), static_cast<std::uint64_t>(k) + 1);
      req.position_play = o.position_play;
      req.lookahead = o.lookahead;
      // Alone at the table there is no one to play safe against: pots only (by any
      // route), the fallback's legal stroke when there is none.
      req.kinds = ShotKinds::Of(ShotKind::kPot);
      req.threads = o.threads;
      req.max_simulations = o.max_simulations;
      req.monte_carlo_samples = o.monte_carlo_samples;
      req.break_value = o.break_value;
      req.position_spread = o.position_spread;
      const PlanAnswer answer = planner.Plan(req);
      report.plan_ms.push_back(answer.elapsed * 1e3);
      if (answer.cut_short) ++report.plans_cut_short;
      if (answer.shots.empty()) {
        rec.end = "no pot";
        break;
      }
      const PlannedShot& plan = answer.shots.front();
      if (plan.kind != ShotKind::kPot) {
        // A break alone has no opponent to play safe against: the visit ends there.
        rec.end = ToString(plan.kind);
        break;
      }
      // The robot's cue, with its execution noise, striking in the world.
      const PlayedStroke stroke =
          SampleStroke(plan.cue, world.cue, world.ball, world.cloth.g, o.noise, o.uncertain_world, rng);
      const physics::Shot& played = stroke.shot;
      truth_sim.set_throw_scale(stroke.throw_scale);
      const ShotSetup setup{&truth, truth.cue_index(), plan.object_ball, plan.pocket, *on, plan.kind,
                            plan.route == PotRoute::kPlant ? plan.first_ball : -1};
      const ShotOutcome& out = truth_sim.Run(setup, played, {}, ShotSimulator::Mode::kFull, no_interrupt);
      ++rec.attempts;
      if (out.status != physics::SimStatus::kAtRest) {
        rec.end = std::string("foul: ") + ToString(Foul::kSimulationFailed);
        break;
      }
      const BallKind object_kind = truth.balls[static_cast<size_t>(plan.object_ball)].kind;
      const ShotJudgement j = JudgeShot(truth, *on, object_kind, out.first_hit, out.potted);
      if (j.foul != Foul::kNone) {
        rec.end = std::string("foul: ") + ToString(j.foul);
        break;
      }
      if (out.object_pocket >= 0) ++rec.pots;
      if (j.legal_pots == 0) {
        rec.end = "miss";
        break;
      }
      rec.points += j.points;
      finals.clear();
      for (const physics::BallState& b : truth_sim.final_balls()) finals.push_back(b.r);
      const BallOn was_on = *on;
      truth = ApplyShot(truth, was_on, finals, out.potted, false, model);
      on = NextBallOn(was_on, *j.potted_kind, truth);
      if (!on) {
        rec.end = "cleared";
        break;
      }
    }
    report.shots += rec.attempts;
    report.pots += rec.pots;
    report.max_break = std::max(report.max_break, rec.points);
    report.mean_break += rec.points;
    report.records.push_back(rec);
    if (on_frame != nullptr) on_frame(f, rec, context);
  }
  report.frames = o.frames;
  if (o.frames > 0) report.mean_break /= o.frames;
  report.pot_rate = report.shots > 0 ? static_cast<double>(report.pots) / report.shots : 0;
  report.plan_ms_p50 = Percentile(report.plan_ms, 0.5);
  report.plan_ms_p99 = Percentile(report.plan_ms, 0.99);
  return report;
}

}  // namespace snooker::planner
