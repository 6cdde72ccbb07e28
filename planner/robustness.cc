#include "planner/robustness.h"

#include <algorithm>
#include <cmath>

namespace snooker::planner {

using physics::Vec2;

namespace {
// Sweeps that push a sampled table's overlapping balls apart: the 22 balls of the
// opening rack, drawn with 0.2 mm of noise, took 3 to 31 in 57 draws (8 sweeps,
// the cap before, left most of them overlapping, and the simulator refused them).
constexpr int kMaxSettleSweeps = 200;
}  // namespace

void SampleTruePositions(const TableState& seen, const PotContext& ctx, Rng& rng,
                         std::vector<Vec2>* out) {
  const size_t n = seen.balls.size();
  out->resize(n);
  for (size_t i = 0; i < n; ++i) {
    const double s = ctx.sigma_of(static_cast<int>(i));
    (*out)[i] = seen.balls[i].position + s * Vec2(rng.Gaussian(), rng.Gaussian());
  }
  // Vision saw touching balls as touching or nearly so; the draw may overlap them.
  // Push overlapping pairs apart symmetrically, and every ball back onto the bed,
  // sweep after sweep until nothing overlaps.
  const physics::TableModel& table = *ctx.table;
  const double two_r = 2 * table.ball_radius() + 1e-8;
  const double c = table.cushion_contact_distance() + 1e-9;
  const double w = table.spec().width, l = table.spec().length;
  bool settled = false;
  for (int sweep = 0; sweep < kMaxSettleSweeps && !settled; ++sweep) {
    bool moved = false;
    for (size_t i = 0; i < n; ++i) {
      for (size_t j = i + 1; j < n; ++j) {
        Vec2 d = (*out)[j] - (*out)[i];
        const double dist = d.norm();
        if (dist >= two_r - 1e-9) continue;  // pushed pairs end at two_r
        d = dist > 0 ? Vec2(d / dist) : Vec2(1, 0);
        const double push = 0.5 * (two_r - dist);
        (*out)[i] -= push * d;
        (*out)[j] += push * d;
        moved = true;
      }
    }
    for (Vec2& p : *out) {
      const Vec2 q(std::clamp(p.x(), c, w - c), std::clamp(p.y(), c, l - c));
      if (q != p) moved = true;
      p = q;
    }
    settled = !moved;
  }
  // A cluster the sweeps could not settle: the positions seen, which are valid.
  if (!settled) {
    for (size_t i = 0; i < n; ++i) (*out)[i] = seen.balls[i].position;
  }
}

physics::Shot SampleExecution(const physics::Shot& shot, const NoiseModel& noise, Rng& rng) {
  physics::Shot s = shot;
  s.speed = std::max(0.0, shot.speed * (1 + noise.speed_fraction * rng.Gaussian()));
  s.heading = shot.heading + noise.heading * rng.Gaussian();
  s.topspin = shot.topspin + noise.topspin * rng.Gaussian();
  s.sidespin = shot.sidespin + noise.sidespin * rng.Gaussian();
  return s;
}

PlayedStroke SampleStroke(const physics::CueStrike& cue, const physics::CueParams& cue_params,
                          const physics::BallParams& ball, double gravity, const NoiseModel& noise,
                          bool model_uncertainty, Rng& rng) {
  physics::CueStrike k = cue;
  k.speed = std::max(0.0, cue.speed * (1 + noise.cue_speed_fraction * rng.Gaussian()));
  k.heading = cue.heading + noise.aim * rng.Gaussian();
  k.side = cue.side + noise.tip_offset / ball.radius * rng.Gaussian();
  k.height = cue.height + noise.tip_offset / ball.radius * rng.Gaussian();
  k.elevation = std::clamp(cue.elevation + noise.elevation * rng.Gaussian(), 0.0, 0.45 * physics::kPi);
  const double squirt_error = rng.Gaussian(), throw_error = rng.Gaussian();
  const physics::StrikeResult res = physics::Strike(k, cue_params, ball, gravity);
  PlayedStroke out;
  out.status = res.status;
  out.shot = res.shot;
  if (model_uncertainty) {
    out.shot.heading += noise.squirt_fraction * squirt_error * res.squirt;
    out.throw_scale = std::max(0.0, 1 + noise.throw_fraction * throw_error);
  }
  out.shot = SampleExecution(out.shot, noise, rng);
  return out;
}

physics::CueStrike LevelStrikeFor(const physics::Shot& shot, const physics::CueParams& cue,
                                  const physics::BallParams& ball, double gravity) {
  if (const auto k = physics::StrikeFor(shot, 0.0, cue, ball, gravity)) return *k;
  physics::Shot plain = shot;
  plain.topspin = plain.sidespin = plain.swerve_spin = 0;
  if (const auto k = physics::StrikeFor(plain, 0.0, cue, ball, gravity)) return *k;
  return physics::CueStrike{0.0, shot.heading, 0.0, 0.0, 0.0};
}

void MonteCarloTally::Add(const MonteCarloTally& o) {
  samples += o.samples;
  successes += o.successes;
  pocket_successes += o.pocket_successes;
  fouls += o.fouls;
  score_sum += o.score_sum;
  success_score_sum += o.success_score_sum;
  handovers += o.handovers;
  handovers_snookered += o.handovers_snookered;
  opponent_pot_sum += o.opponent_pot_sum;
  opponent_points_sum += o.opponent_points_sum;
  line_samples += o.line_samples;
  line_inside += o.line_inside;
  z_sum += o.z_sum;
  z2_sum += o.z2_sum;
  interrupted = interrupted || o.interrupted;
}

double MonteCarloTally::fitted_line_rate() const {
  const double n = line_samples;
  const double mu = z_sum / n;
  const double sigma = std::sqrt(std::max(0.0, (z2_sum - n * mu * mu) / (n - 1)));
  return sigma > 1e-9 ? NormalCdf((1 - mu) / sigma) - NormalCdf((-1 - mu) / sigma) : (std::abs(mu) < 1 ? 1.0 : 0.0);
}

double MonteCarloTally::tail_corrected_score(int min_line_samples) const {
  if (line_samples < std::max(min_line_samples, 2) || successes == 0) return mean_score();
  const double n = line_samples;
  const double counted = line_inside / n;
  const double success = success_score_sum / successes;
  // With no miss among the samples, a miss is taken to hand the opponent what the
  // pot would have left the striker.
  const int misses = samples - successes;
  const double miss = misses > 0 ? (score_sum - success_score_sum) / misses : -std::max(success, 0.0);
  return mean_score() + (fitted_line_rate() - counted) * (n / samples) * (success - miss);
}

namespace {
SampleWorth HandedOver(double score, const Outlook& o) {
  return SampleWorth{score, true, o.pot_probability, o.expected_points, o.snooker.snookered};
}
}  // namespace

SampleWorth MonteCarloScore(const ShotSetup& setup, const ShotOutcome& out, std::span<const Vec2> finals,
                            const PotContext& after_ctx, const SearchSettings& settings, LeaveScratch* scratch) {
  if (scratch == nullptr) {  // buffers of its own, cleared only here: 25 kB, most of it the line cache
    LeaveScratch own;
    return MonteCarloScore(setup, out, finals, after_ctx, settings, &own);
  }
  const TableState& table = *setup.table;
  if (out.success && setup.kind == ShotKind::kPot) {
    return SampleWorth{ScoreLeave(table, setup.on, setup.object, finals, out.potted, 1.0, after_ctx, settings, scratch).score};
  }
  if (out.foul == Foul::kNone) {
    const Leave leave = ScoreSafety(table, setup.on, out.first_hit, finals, out.potted, after_ctx, settings, scratch);
    return leave.opponent ? HandedOver(leave.score, *leave.opponent) : SampleWorth{leave.score};
  }
  const int named = setup.object >= 0 ? setup.object : out.first_hit;
  const std::optional<BallKind> nominated =
      named >= 0 ? std::optional<BallKind>(table.balls[static_cast<size_t>(named)].kind) : std::nullopt;
  const int penalty = FoulPenalty(table, setup.on, nominated, out.first_hit, out.potted);
  // The opponent plays the table left, from the D when the cue ball went down.
  LeaveScratch& buf = *scratch;
  ApplyShotInto(table, setup.on, finals, out.potted, true, *after_ctx.table, &buf.after, nullptr);
  const TableState& after = buf.after;
  if (const auto opponent_on = OpeningBallOn(after)) {
    const Outlook o = OpponentOutlook(after, *opponent_on, after_ctx, settings, &buf.placed, &buf.lines);
    return HandedOver(-(penalty + (o.expected_points - o.expected_penalty)), o);
  }
  return SampleWorth{-static_cast<double>(penalty)};
}

namespace {
constexpr double kFarOutside = 5;  // |z| of a line with no window, in half-widths
}  // namespace

MonteCarloTally RunSamples(const ShotSetup& setup, const physics::CueStrike& cue, const PotContext& ctx,
                           const SearchSettings& settings, ShotSimulator& sim, const StopControl& stop,
                           std::uint64_t seed, int count, bool measure_line, SampleScratch* scratch) {
  MonteCarloTally tally;
  Rng rng(seed);
  const physics::Interrupt interrupt = stop.AsInterrupt();
  SampleScratch own;
  SampleScratch& buf = scratch != nullptr ? *scratch : own;
  // The next shot is seen afresh by vision: every ball with the default sigma (the
  // balls' indices change once some drop). Assigning into a kept context reuses
  // its capacity.
  buf.after_ctx = ctx;
  buf.after_ctx.position_sigma.clear();
  const PotContext& after_ctx = buf.after_ctx;
  std::vector<Vec2>& truth = buf.truth;
  std::vector<Vec2>& finals = buf.finals;
  for (int k = 0; k < count; ++k) {
    if (stop.Due()) {
      tally.interrupted = true;
      break;
    }
    SampleTruePositions(*setup.table, ctx, rng, &truth);
    const PlayedStroke played = SampleStroke(cue, ctx.cue_params(), sim.params().ball, sim.params().cloth.g,
                                             ctx.execution, true, rng);
    sim.set_throw_scale(played.throw_scale);
    // To rest, never stopped early: a miss is scored by the table it leaves.
    const ShotOutcome& out = sim.Run(setup, played.shot, truth, ShotSimulator::Mode::kToRest, interrupt);
    sim.set_throw_scale(1.0);
    if (out.status == physics::SimStatus::kInterrupted) {
      tally.interrupted = true;
      break;
    }
    ++tally.samples;
    finals.clear();
    for (const physics::BallState& b : sim.final_balls()) finals.push_back(b.r);
    const SampleWorth worth = MonteCarloScore(setup, out, finals, after_ctx, settings, &buf.leave);
    tally.score_sum += worth.score;
    if (out.success) tally.success_score_sum += worth.score;
    if (worth.handed_over) {
      ++tally.handovers;
      if (worth.snookered) ++tally.handovers_snookered;
      tally.opponent_pot_sum += worth.opponent_pot;
      tally.opponent_points_sum += worth.opponent_points;
    }
    if (measure_line && ctx.pockets != nullptr && out.first_line.valid && out.first_hit == setup.object) {
      const PocketWindow w = ctx.pockets->Window(setup.pocket, out.first_line.direction, out.first_line.arrival_speed);
      // An empty window (a line no pocket takes) counts as far outside.
      const double z = w.empty || !(w.width() > 0) ? kFarOutside
                               : std::clamp((out.first_line.offset - w.centre()) / (0.5 * w.width()), -kFarOutside, kFarOutside);
      ++tally.line_samples;
      if (std::abs(z) < 1) ++tally.line_inside;
      tally.z_sum += z;
      tally.z2_sum += z * z;
    }
    if (out.foul != Foul::kNone) ++tally.fouls;
    if (!out.success) continue;
    ++tally.successes;
    if (setup.kind == ShotKind::kPot && out.object_pocket == static_cast<int>(setup.pocket)) ++tally.pocket_successes;
  }
  return tally;
}

}  // namespace snooker::planner
