// Candidates for the pots that are not direct, and for escapes from snookers, in
// the shape of a direct pot's Candidate (candidates.h): the balls, the pocket, a
// nominal aim with the bracket the planner's search refines it in, and a fast
// estimate from the geometry alone (no simulation; microseconds each).
//
// Routes (shot_kind.h names the pot routes):
//  * PLANT: the cue ball hits ball A, A hits ball B into the pocket; both must be on
//    (two reds while a red is on: a colour on is one ball). B's line into the pocket
//    is the direct pot's (the window's centre); A must reach B's ghost-ball position
//    for it, and the cue ball cuts A along that direction. A SET is a plant of two
//    touching balls: B leaves along the line of centres, turned at most set_throw by
//    the throw between them, so the set is on only when that line finds the pocket.
//  * DOUBLE: the object ball off one cushion into the pocket (cushion_paths.h from
//    the object ball to the pocket's aim point), the cue ball cutting it along the
//    path's first leg.
//  * KICK: the cue ball off one or two cushions onto the object ball's ghost-ball
//    position for its direct line into the pocket.
//  * ESCAPE (out of a snooker, no pot intended): the cue ball off one or two cushions
//    to hit a ball on, anywhere on it, the other balls clear of its path.
//
// Estimates, in pot_estimate.h's currency (a probability under the noise model):
// the object ball's line at the mouth is Gaussian, P = WindowProbability. Every
// error is carried to the mouth through the ghost-ball lever k = L / (2R cos c):
//  * plant: A's lateral error at B, sA (LateralSigma of the pot of A along its
//    path), is B's impact-parameter error, so
//      sigma_B^2 = kB^2 sA^2 + sigma_B,vision^2 (kB^2 + 1 + 2 kB cos cB) + LB^2 t_B^2,
//    the cue ball's error amplified twice (kA kB): a plant's chance falls much faster
//    with distance and cut than a direct pot's (t_B: the throw of A on B per speed
//    noise);
//  * set: the line of centres, error sqrt(sigma_A^2 + sigma_B^2) / 2R in angle;
//  * double and kick: the mirror path is a straight line when unfolded, so the
//    direct pot's terms hold over the unfolded length; each cushion adds an
//    independent error of the outgoing direction, the speed noise through
//    ReboundSpeedSensitivity (cushion_paths.h), carried over the path after it
//    (and, for a kick, through the lever k);
//  * escape: the cue ball's lateral error at the ball, (heading x L, vision, each
//    cushion's rebound error over the rest of the path), against the offsets where
//    it hits the ball first: P = the Gaussian's mass over the widest clear run of
//    offsets in (-2R, 2R), aimed at its centre; miss_probability = 1 - P.
//
// Aim. AimBy::kCut (plants, doubles: the cue ball goes straight to its first ball):
// the search varies the cut on the first ball (cut + cut_bracket), or, through
// search.h PredictCut, the first ball's direction (first_direction +
// direction_bracket); heading_bracket is the heading range that cut range spans.
// AimBy::kHeading (kicks, escapes: the cue ball goes off cushions first): the search
// varies the heading (heading + heading_bracket). Brackets cover the mirror's
// measured rebound error (cushion_paths.h), the throw between balls
// (ThrowAllowance) and, for an escape, the whole clear run of offsets.
//
// Pruning, as for direct pots: cuts past the context's max_cut, pockets closed to
// the line, any path (cue ball, first ball, potted ball, each leg) within 2R plus
// path_clearance of another ball, no room for the cue (CueMargin), cushion contacts
// in a jaw or a mouth or too glancing; pots whose estimate is under min_probability.
//
// Cost (Release, 15 reds and the colours, red on, 50 random frames, the best of 7
// runs per frame, on the 2-core development machine shared with other builds):
// plants 134 us per call (1260 ball-ball-pocket triples, 0.11 us each), doubles
// 102 us (360 ball-pocket-cushion triples), kicks 158 us (1440 ball-pocket-cushion
// sequences), escapes 209 us (240 ball-cushion sequences, 0.87 us each); the direct
// pots' EnumerateCandidates takes 29 us on the same frames.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "planner/candidates.h"
#include "planner/cushion_paths.h"
#include "planner/shot_kind.h"

namespace snooker::planner {

enum class Route : std::uint8_t { kPlant, kDouble, kKick, kEscape };
/// "plant", "double", "kick", "escape".
const char* ToString(Route route);
/// kPot for the three pots, kEscape for an escape.
ShotKind KindOf(Route route);
/// The pot route (PotRoute::kPlant for a plant or a set); nullopt for an escape.
std::optional<PotRoute> PotRouteOf(Route route);

enum class AimBy : std::uint8_t {
  kCut,      ///< straight to the first ball: the search varies the cut on it
  kHeading,  ///< off cushions first: the search varies the heading
};

struct RouteCandidate {
  Route route = Route::kPlant;
  /// A plant of two touching balls.
  bool set = false;
  /// The ball the cue ball hits first; the ball to pot (-1 for an escape).
  int first_ball = -1;
  int potted_ball = -1;
  std::optional<physics::PocketId> pocket;

  AimBy aim = AimBy::kCut;
  /// The nominal cue-ball heading and the range to search around it. rad.
  double heading = 0;
  AimBracket heading_bracket;
  /// The cut on the first ball at the nominal aim (geometry.h's sign: the ghost-
  /// ball cut for kCut, the cut the mirror path makes for kHeading) and, for kCut
  /// only, the range to search around it (direction_bracket through the ghost-ball
  /// lever, widened by ThrowAllowance on the side throw needs). rad.
  double cut = 0;
  AimBracket cut_bracket;
  /// The direction the first ball must leave along (a plant's A towards B's ghost
  /// position, a set's line of centres, a double's first leg, a kick's line into
  /// the pocket; an escape: the cue ball's last leg) and, for kCut only, the range
  /// of it to search (a double: its path's mirror bracket; a plant: what B's throw
  /// asks of A; a set: set_throw), throw not included: what PredictCut takes as
  /// object_direction. rad.
  double first_direction = 0;
  AimBracket direction_bracket;
  /// The potted ball's direction over its last stretch into the pocket (an
  /// escape: the first ball's direction after the contact at the nominal aim). rad.
  double object_direction = 0;
  /// The ghost-ball position the route is built on: where A must meet B (a
  /// plant; a set: A's own place), where the cue ball meets the first ball (double,
  /// kick, escape). m.
  physics::Vec2 ghost = physics::Vec2::Zero();
  /// The cushion path: the cue ball's (kick, escape) or the potted ball's (double).
  std::optional<CushionPath> path;
  /// The potted ball's travel to the mouth (a double's path length), or an escape's
  /// cue-ball travel to the ball. m.
  double distance = 0;
  PocketWindow window;
  /// Lateral standard deviation at the mouth (pots) or at the ball (escape). m.
  double sigma = 0;
  /// Pots: how far the potted ball's line moves at the mouth per radian of the cue
  /// ball's heading (pot_estimate.h HeadingGain through the route's levers; 0 for a
  /// set, whose line the heading hardly moves). m/rad.
  double heading_gain = 0;
  /// Pots: the chance the route pots the ball (pot_estimate.h's currency). Escape:
  /// the chance the cue ball hits the ball first.
  double probability = 0;
  /// 1 - probability (an escape's ranking key).
  double miss_probability = 1;
  /// CueMargin for the nominal heading. m.
  double cue_margin = 0;
};

enum class RouteRefusal : std::uint8_t {
  kNone,
  kNotOn,           ///< a ball is not on (a plant's two must both be on)
  kCutTooThin,      ///< a cut past max_cut (the cue ball's, or A's on B)
  kPocketAngle,     ///< the pocket is closed to the line (or a set's line misses it)
  kNoCushionPath,   ///< the mirror path is refused (cushion_paths.h PathRefusal)
  kCueBallPath,     ///< the cue ball's path passes too near a ball (an escape: no clear offset)
  kFirstBallPath,   ///< a plant's A passes too near a ball on its way to B
  kObjectBallPath,  ///< the potted ball's path passes too near a ball
  kCueRoom,         ///< no room for the cue
  kUnlikely,        ///< the pot's estimate is under min_probability
  kTooLong,         ///< a kick's cue-ball path is longer than max_kick_length
};
inline constexpr int kRouteRefusalCount = 11;
const char* ToString(RouteRefusal r);

struct RouteOptions {
  CushionPathOptions paths;
  /// Cushions a kick and an escape may take (1 or 2). A double takes one.
  int kick_cushions = 2;
  int escape_cushions = 2;
  /// A kick's cue-ball path longer than this is refused: the cue ball meets the
  /// object ball slowly, after rebounds that have taken it far from the mirror's
  /// line (a 9 m kick up and down the table, aimed over its whole bracket in the
  /// simulator, never sends the object ball within 0.3 m of its line). m.
  double max_kick_length = 5.0;
  /// Each cushion's error that the search cannot correct is the speed noise's
  /// effect on the rebound (cushion_paths.h ReboundSpeedSensitivity times the noise
  /// model's speed_fraction), so the estimate stays in the noise model's currency.
  /// A real cushion varies more than the simulator's; this standard deviation of
  /// the outgoing direction (rad) is added per cushion for it (0: none).
  double rebound_extra_sigma = 0;
  /// Two balls whose centres are within 2R + set_gap touch: a set. m.
  double set_gap = 0.5e-3;
  /// How far the throw between the balls of a set can turn B off their line of
  /// centres. rad.
  double set_throw = 1.5 * physics::kPi / 180;
  /// Half-width of a set's cut bracket: the cue ball can push A over a wide range
  /// of angles. rad.
  double set_cut_range = 15.0 * physics::kPi / 180;
  /// An escape's contact must be at least this far inside the ball's edge (a
  /// hairline contact is not a safe hit). m.
  double escape_edge = 3e-3;
  /// Offsets sampled across (-2R, 2R) for an escape's clear run (odd: 0 included).
  int escape_offsets = 17;
  /// Pots whose estimate is under this are dropped.
  double min_probability = 1e-3;
  /// Each enumerator keeps at most this many, best first.
  int max_candidates = 24;
};

/// The throw a bracket allows for on a cut `cut` (rad): the object ball leaves up
/// to this much nearer the cue ball's heading than the line of centres (search.h:
/// 0.5 deg at 10 deg, 2.8 deg at 80 deg for a rolling ball). rad.
double ThrowAllowance(double cut);

/// One plant (or set): the cue ball (index `cue`) onto `first`, `first` onto
/// `potted` into `pocket`; nullopt with the reason in *why.
std::optional<RouteCandidate> AssessPlant(const TableState& table, int cue, BallOn on, int first,
                                          int potted, physics::PocketId pocket, const PotContext& ctx,
                                          const RouteOptions& options = {},
                                          RouteRefusal* why = nullptr);
/// One double: `object` off `line` into `pocket`.
std::optional<RouteCandidate> AssessDouble(const TableState& table, int cue, BallOn on, int object,
                                           physics::PocketId pocket, CushionLine line,
                                           const PotContext& ctx, const RouteOptions& options = {},
                                           RouteRefusal* why = nullptr);
/// One kick: the cue ball off `lines` (one or two, in order) onto `object`'s ghost
/// position for its direct line into `pocket`.
std::optional<RouteCandidate> AssessKick(const TableState& table, int cue, BallOn on, int object,
                                         physics::PocketId pocket, std::span<const CushionLine> lines,
                                         const PotContext& ctx, const RouteOptions& options = {},
                                         RouteRefusal* why = nullptr);
/// One escape: the cue ball off `lines` (one or two, in order) onto `object`.
std::optional<RouteCandidate> AssessEscape(const TableState& table, int cue, BallOn on, int object,
                                           std::span<const CushionLine> lines, const PotContext& ctx,
                                           const RouteOptions& options = {},
                                           RouteRefusal* why = nullptr);

/// What an enumerator considered and why it dropped the rest.
struct RouteStats {
  int considered = 0;
  std::array<int, kRouteRefusalCount> refused{};
};

/// Every candidate of a route for the cue ball `cue` and the ball on `on`: plants
/// over ordered pairs of balls on and pockets; doubles over balls on, pockets and
/// the four cushions; kicks over balls on, pockets and the cushion sequences (one,
/// then two cushions); escapes over balls on and the cushion sequences. Pots by
/// probability, most likely first; escapes by miss_probability in steps of 0.001,
/// least first (chances closer than that are equal), then fewer cushions, then the
/// shorter path; at most max_candidates. Empty without a cue ball.
std::vector<RouteCandidate> EnumeratePlants(const TableState& table, int cue, BallOn on,
                                            const PotContext& ctx, const RouteOptions& options = {},
                                            RouteStats* stats = nullptr);
std::vector<RouteCandidate> EnumerateDoubles(const TableState& table, int cue, BallOn on,
                                             const PotContext& ctx, const RouteOptions& options = {},
                                             RouteStats* stats = nullptr);
std::vector<RouteCandidate> EnumerateKicks(const TableState& table, int cue, BallOn on,
                                           const PotContext& ctx, const RouteOptions& options = {},
                                           RouteStats* stats = nullptr);
std::vector<RouteCandidate> EnumerateEscapes(const TableState& table, int cue, BallOn on,
                                             const PotContext& ctx, const RouteOptions& options = {},
                                             RouteStats* stats = nullptr);

}  // namespace snooker::planner
