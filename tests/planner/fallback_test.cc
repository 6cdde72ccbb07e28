// The fallback's scan (planner/fallback.h): a legal stroke for a cue ball that only a
// raised cue can play, within the request's spin limits.
#include "planner/fallback.h"

#include <gtest/gtest.h>

#include <cmath>

#include "physics/table/table.h"
#include "planner/planner.h"

namespace snooker::planner {
namespace {

using physics::Vec2;

// The cue ball frozen to the left cushion, a red across the table straight out from
// it and another along the cushion behind a colour: every stroke at the red needs a
// raised cue, and the tip's height is capped by the topspin limit.
TEST(FallbackScanTest, RaisesTheCueWithinTheSpinLimits) {
  const physics::TableModel& model = physics::DefaultTable();
  const double c = model.cushion_contact_distance();
  TableState t;
  t.balls = {{BallKind::kCue, Vec2(c, 1.8)}, {BallKind::kRed, Vec2(1.2, 1.8)}};
  // With topspin up to 1.2 of the rolling spin a raised stroke exists; at 0.9 the tip
  // cannot be high enough, and any stroke found keeps the limit.
  for (const double limit : {1.25, 1.2, 0.9}) {
    const Planner& planner = Planner::Default();
    PlanRequest r;
    r.table = t;
    r.limits.max_topspin_fraction = limit;
    PotContext ctx = planner.ContextFor(r);
    SearchSettings settings = planner.config().search_settings;
    settings.limits = r.limits;
    ShotSimulator sim(model, planner.config().full);
    const auto found = FindLegalStroke(t, 0, BallOn::kRed, ctx, settings, sim, physics::Interrupt{}, FallbackOptions{});
    if (limit >= 1.2) {
      ASSERT_TRUE(found.has_value()) << "limit " << limit;
    } else if (!found) {
      continue;
    }
    EXPECT_GT(found->cue.elevation, 0) << "limit " << limit;
    EXPECT_LE(std::abs(found->shot.topspin), limit * found->shot.speed / model.ball_radius() * (1 + 1e-12));
    // The shot is what the cue gives, exactly.
    const physics::StrikeResult res =
        physics::Strike(found->cue, ctx.cue_params(), planner.config().full.ball, planner.config().full.cloth.g);
    EXPECT_EQ(res.status, physics::StrikeStatus::kOk);
    EXPECT_EQ(res.shot.speed, found->shot.speed);
    EXPECT_EQ(res.shot.topspin, found->shot.topspin);
  }
}

}  // namespace
}  // namespace snooker::planner
