// Event resolvers in the table frame: each rotates the balls into the frame of its
// impact model, calls the model, rotates back and reclassifies the motion.
//  * ball-ball: Mathavan, Jackson & Parkin (2014), physics/impact/ball_ball.h, in the
//    collision frame Y = line of centres from the first ball to the second, Z up.
//  * ball-cushion (a straight nose or a jaw wall, and a knuckle, whose local normal
//    is the line from its centre to the ball's): Mathavan, Jackson & Parkin (2010),
//    physics/impact/ball_cushion.h, in the cushion frame Y = into the cushion, Z up.
//
// The small vertical velocity an impact leaves (a "jump", paper section 2.2; a few
// cm/s, ~1 mm of flight) is dropped: the ball is taken to stay on the cloth, losing
// that little kinetic energy. physics/motion/motion.h's Settle does it and reclassifies.
//
// Pure functions; no allocation, no exception.
#pragma once

#include "physics/impact/ball_ball.h"
#include "physics/impact/ball_cushion.h"
#include "physics/impact/impact_table.h"
#include "physics/core/ball_state.h"
#include "physics/core/params.h"

namespace snooker::physics {

/// Rotation from the table frame into the frame with Y along the horizontal unit
/// vector `y` and Z up (X = Y x Z). Rows are the new axes in table coordinates.
Eigen::Matrix3d FrameAlong(const Vec2& y);

struct BallBallResolution {
  ImpactStatus status = ImpactStatus::kOk;
  BallState a, b;  ///< the two balls after the impact, settled on the cloth
  ImpulseWork work;
};

/// Resolves the impact of two touching balls `a` and `b` (centres 2R apart). With a
/// `table` (built for these parameters: BallBallTable::Matches) the impact of a
/// rolling ball on one at rest is looked up where the table covers it
/// (work.table_lookups = 1); every other impact goes to the solver.
BallBallResolution ResolveBallBallOnTable(const BallState& a, const BallState& b,
                                          const BallParams& ball, const BallBallParams& contact,
                                          const ClothParams& cloth,
                                          const ImpulseSolverOptions& options,
                                          const BallBallTable* table = nullptr);

struct CushionResolution {
  ImpactStatus status = ImpactStatus::kOk;
  BallState ball;  ///< the ball after the impact, settled on the cloth
  ImpulseWork work;
};

/// Resolves the impact of a ball on a cushion whose unit normal at the contact,
/// horizontal and pointing from the cushion towards the ball, is `normal`. With a
/// `table` (built for these parameters: CushionTable::Matches) a rolling ball's impact
/// is looked up where the table covers it (work.table_lookups = 1); every other impact
/// goes to the solver.
CushionResolution ResolveBallCushionOnTable(const BallState& s, const Vec2& normal,
                                            const BallParams& ball, const CushionParams& cushion,
                                            const ImpulseSolverOptions& options,
                                            const CushionTable* table = nullptr);

}  // namespace snooker::physics
