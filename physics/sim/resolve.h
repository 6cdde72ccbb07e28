// Event resolvers in the table frame.
//
// Impacts: each rotates the balls into the frame of its impact model, calls the
// model (or looks the answer up in an impact table), rotates back and reclassifies
// the motion.
//  * ball-ball: Mathavan, Jackson & Parkin (2014), physics/impact/ball_ball.h, in the
//    collision frame Y = line of centres from the first ball to the second, Z up.
//  * ball-cushion (a straight nose or a jaw wall, and a knuckle, whose local normal
//    is the line from its centre to the ball's): Mathavan, Jackson & Parkin (2010),
//    physics/impact/ball_cushion.h, in the cushion frame Y = into the cushion, Z up.
// Frames and signs: docs/physics-notes.md sections 1 and 8.
//
// Contacts: a ball-ball or ball-boundary contact as the detector found it standing
// (physics/events/detect.h, ClassifyContact) - an impact when approaching, a resting
// contact when pressing (physics/sim/contacts.h), nothing when only touching.
//
// The small vertical velocity an impact leaves (a "jump", paper section 2.2; a few
// cm/s, ~1 mm of flight) is dropped: the ball is taken to stay on the cloth, losing
// that little kinetic energy (docs/physics-notes.md section 6). physics/motion/
// motion.h's Settle does it and reclassifies.
//
// Pure functions; no allocation, no exception.
#pragma once

#include "physics/impact/ball_ball.h"
#include "physics/impact/ball_cushion.h"
#include "physics/impact/impact_table.h"
#include "physics/core/ball_state.h"
#include "physics/core/params.h"
#include "physics/events/detect.h"
#include "physics/sim/sim_params.h"

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

/// A contact between two touching balls, resolved.
struct PairContactResolution {
  /// kOk, or the impact solver's failure (kInvalidInput, kStepLimit): the run stops.
  ImpactStatus status = ImpactStatus::kOk;
  /// How the contact stood when it was resolved: as given, except that an approach
  /// the impact model does not see (rounding at the detector's threshold) is
  /// kTouching.
  ContactStart contact = ContactStart::kApart;
  /// True when an impact was resolved.
  bool impact = false;
  BallState a, b;  ///< the two balls afterwards, settled on the cloth
  ImpulseWork work;
};

/// Resolves the contact of the touching balls `a` and `b` (centres 2R apart) that
/// ClassifyContact found standing as `contact`:
///  * kApproaching: the impact (ResolveBallBallOnTable), rest_speed applied to each
///    ball (AfterImpact) and the pair held together if the cloth would bring it back
///    at once (HoldIfReturning); an approach the model does not see is removed
///    (RemoveApproach);
///  * kPressing: a resting contact (HoldTogether); `level_a` and `level_b` are the
///    pressing contacts each ball had resolved earlier at the same instant (read
///    only here);
///  * kTouching, kApart: nothing.
PairContactResolution ResolveBallBallContact(const BallState& a, const BallState& b,
                                             ContactStart contact, int level_a, int level_b,
                                             const SimParams& p, const BallBallTable* table);

/// A contact between a ball and a fixed boundary (cushion nose, jaw wall, knuckle),
/// resolved.
struct BoundaryContactResolution {
  /// kOk, or the impact solver's failure (kInvalidInput, kStepLimit): the run stops.
  ImpactStatus status = ImpactStatus::kOk;
  /// As PairContactResolution::contact.
  ContactStart contact = ContactStart::kApart;
  BallState ball;  ///< the ball afterwards, settled on the cloth
  ImpulseWork work;
};

/// Resolves the contact of ball `s` with a boundary whose unit normal at the contact,
/// horizontal and from the boundary towards the ball, is `normal`, found standing as
/// `contact`:
///  * kApproaching: the impact (ResolveBallCushionOnTable), rest_speed applied
///    (AfterImpact) and the ball held against the boundary if its friction would
///    bring it back at once (HoldIfReturning); an approach the model does not see
///    loses its normal velocity;
///  * kPressing: the ball held against the boundary (HoldAgainst), or stopped if
///    `level` (the pressing contacts it had resolved earlier at the same instant, read
///    only here) is not 0: pressed a second time at one instant, it is wedged;
///  * kTouching, kApart: nothing.
BoundaryContactResolution ResolveBoundaryContact(const BallState& s, const Vec2& normal,
                                                 ContactStart contact, int level,
                                                 const SimParams& p, const CushionTable* table);

}  // namespace snooker::physics
