#include "planner/position.h"

#include <algorithm>
#include <cmath>

namespace snooker::planner {
namespace {

using physics::Vec2;

struct Option {
  int ball;
  physics::PocketId pocket;
  double probability;  // estimate, before the cue-ball discounts
  double score;        // probability * (value + continuation)
};

// Distance from the cue-ball centre to the nearest cushion contact line, m (0 when
// frozen to it).
double CushionGap(const Vec2& c, const physics::TableModel& table) {
  const double d = table.cushion_contact_distance();
  const double w = table.spec().width, l = table.spec().length;
  return std::max(0.0, std::min({c.x() - d, w - d - c.x(), c.y() - d, l - d - c.y()}));
}

}  // namespace

PositionValue EvaluatePosition(const TableState& table, BallOn next_on, const PotContext& ctx,
                               const PositionOptions& options, PocketLineCache* lines) {
  PositionValue out;
  const int cue = table.cue_index();
  if (cue < 0) return out;
  const Vec2 c = table.balls[static_cast<size_t>(cue)].position;
  const double r = ctx.table->ball_radius();
  const double cushion = options.cushion_factor +
                         (1 - options.cushion_factor) * std::min(1.0, CushionGap(c, *ctx.table) / r);
  // Every option's estimate (cheap), best score first.
  Option options_buf[physics::Simulator::kMaxBalls * physics::kPocketCount];
  int count = 0;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    const BallKind kind = table.balls[i].kind;
    if (!IsLegalTarget(next_on, kind)) continue;
    const Vec2 o = table.balls[i].position;
    for (int k = 0; k < physics::kPocketCount; ++k) {
      const auto id = static_cast<physics::PocketId>(k);
      // Cheapest test first: the pocket's angular reach from the ball (a dot
      // product against the cosine of the largest approach angle, no atan2).
      const physics::Pocket& p = ctx.table->pocket(id);
      const Vec2 to_mouth = p.mouth_centre - o;
      if (to_mouth.dot(p.axis) < ctx.pockets->ReachCosine(id) * to_mouth.norm()) continue;
      // The line depends on the object ball alone: the cache's when there is one.
      const auto line = lines != nullptr ? lines->Line(*ctx.pockets, o, id) : LineIntoPocket(*ctx.pockets, o, id);
      if (!line) continue;
      const auto est = EstimatePotAlong(*line, c, o, id, ctx.sigma_of(cue), ctx.sigma_of(static_cast<int>(i)),
                                        ctx.noise, *ctx.pockets, *ctx.throws);
      if (!est || std::abs(est->aim.cut) > ctx.max_cut || est->probability <= 0) continue;
      options_buf[count++] = {static_cast<int>(i), id, est->probability,
                              est->probability * (Value(kind) + options.continuation)};
    }
  }
  std::sort(options_buf, options_buf + count, [](const Option& a, const Option& b) {
    if (a.score != b.score) return a.score > b.score;
    return a.ball != b.ball ? a.ball < b.ball : a.pocket < b.pocket;
  });
  // Check paths and cue room best first, one option per ball, until three balls
  // are found; then weight them by their discounted scores.
  Option taken[3];
  int n_taken = 0;
  for (int k = 0; k < count && n_taken < 3; ++k) {
    const Option& opt = options_buf[k];
    if (std::any_of(taken, taken + n_taken, [&](const Option& t) { return t.ball == opt.ball; })) {
      continue;
    }
    const auto cand = AssessPot(table, cue, opt.ball, opt.pocket, ctx);
    if (!cand) continue;
    const double room = std::min(1.0, cand->cue_margin / options.cramped_room);
    const double p = opt.probability * cushion *
                     (options.room_factor + (1 - options.room_factor) * room);
    const double value = Value(table.balls[static_cast<size_t>(opt.ball)].kind) + options.continuation;
    taken[n_taken++] = {opt.ball, opt.pocket, p, p * value};
  }
  std::sort(taken, taken + n_taken, [](const Option& a, const Option& b) { return a.score > b.score; });
  for (int k = 0; k < n_taken; ++k) {
    const double w = options.weights[static_cast<size_t>(k)];
    out.value += w * taken[k].probability;
    out.expected_points += w * taken[k].score;
  }
  if (n_taken > 0) {
    out.next_ball = taken[0].ball;
    out.next_pocket = taken[0].pocket;
    out.next_probability = taken[0].probability;
  }
  return out;
}

}  // namespace snooker::planner
