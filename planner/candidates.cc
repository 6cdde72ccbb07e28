#include "planner/candidates.h"

#include <algorithm>
#include <cmath>

namespace snooker::planner {

using physics::Vec2;

const char* ToString(PruneReason r) {
  switch (r) {
    case PruneReason::kNone: return "kept";
    case PruneReason::kCutTooThin: return "cut too thin or past 90 deg";
    case PruneReason::kPocketAngle: return "pocket closed at that angle";
    case PruneReason::kCueBallPath: return "cue ball's path blocked";
    case PruneReason::kObjectBallPath: return "object ball's path blocked";
    case PruneReason::kCueRoom: return "no room for the cue";
  }
  return "unknown";
}

std::optional<Candidate> AssessPot(const TableState& table, int cue, int object,
                                   physics::PocketId pocket, const PotContext& ctx,
                                   PruneReason* why) {
  PruneReason dummy;
  PruneReason& reason = why ? *why : dummy;
  reason = PruneReason::kNone;
  const Vec2 c = table.balls[static_cast<size_t>(cue)].position;
  const Vec2 o = table.balls[static_cast<size_t>(object)].position;
  const auto est = EstimatePot(c, o, pocket, ctx.sigma_of(cue), ctx.sigma_of(object), ctx.noise,
                               *ctx.pockets, *ctx.throws);
  if (!est) {
    // Either no cut under 90 deg reaches the line, or the pocket is closed to it.
    const auto direct = AimAlong(c, o, Direction(ctx.table->pocket(pocket).mouth_centre - o),
                                 ctx.table->ball_radius());
    reason = !direct || std::abs(direct->cut) > ctx.max_cut ? PruneReason::kCutTooThin
                                                           : PruneReason::kPocketAngle;
    return std::nullopt;
  }
  if (std::abs(est->aim.cut) > ctx.max_cut) {
    reason = PruneReason::kCutTooThin;
    return std::nullopt;
  }
  const double two_r = 2 * ctx.table->ball_radius();
  if (TravelMargin(c, est->aim.ghost, two_r + ctx.path_clearance, table, cue, object) < 0) {
    reason = PruneReason::kCueBallPath;
    return std::nullopt;
  }
  const physics::Pocket& p = ctx.table->pocket(pocket);
  const Vec2 u(std::cos(est->object_direction), std::sin(est->object_direction));
  const Vec2 mouth = p.mouth_centre + est->window.centre() * Left(u);
  if (TravelMargin(o, mouth, two_r + ctx.path_clearance, table, cue, object) < 0) {
    reason = PruneReason::kObjectBallPath;
    return std::nullopt;
  }
  Candidate cand;
  cand.object = object;
  cand.pocket = pocket;
  cand.estimate = *est;
  cand.cue_margin = CueMargin(table, cue, est->aim.heading, ctx.cue, *ctx.table);
  if (cand.cue_margin < 0) {
    reason = PruneReason::kCueRoom;
    return std::nullopt;
  }
  return cand;
}

CandidateSet EnumerateCandidates(const TableState& table, BallOn on, const PotContext& ctx) {
  CandidateSet set;
  const int cue = table.cue_index();
  if (cue < 0) return set;
  for (size_t i = 0; i < table.balls.size(); ++i) {
    if (!IsLegalTarget(on, table.balls[i].kind)) continue;
    for (int k = 0; k < physics::kPocketCount; ++k) {
      ++set.pairs;
      PruneReason why;
      auto c = AssessPot(table, cue, static_cast<int>(i), static_cast<physics::PocketId>(k), ctx, &why);
      if (c) {
        set.candidates.push_back(*c);
      } else {
        ++set.pruned[static_cast<size_t>(why)];
      }
    }
  }
  // Most likely first; ties (symmetric tables) by ball then pocket, for determinism.
  std::stable_sort(set.candidates.begin(), set.candidates.end(),
                   [](const Candidate& a, const Candidate& b) {
                     return a.estimate.probability > b.estimate.probability;
                   });
  return set;
}

}  // namespace snooker::planner
