// Straight-line paths of a ball off one or two cushions, by mirror images: the
// geometry of doubles (the object ball), kicks and escapes (the cue ball).
//
// The model. A ball touches a cushion nose when its centre is
// TableModel::cushion_contact_distance() c from the nose line (the nose is at
// cushion_height, above the centre), so the centre rebounds off the contact line: the
// nose line moved c into the playing area. Four contact lines bound the rectangle the
// centres move in (CushionLine). A rebound is taken as a mirror: the path from start
// S to target T off line A is the straight line from S to T's mirror image across A,
// and off A then B the line from S to the image across A of T's image across B. Each
// contact must lie on a straight cushion nose, at least jaw_margin from its ends (a
// contact nearer a pocket meets the knuckle or drops: the knuckle reaches
// R + knuckle radius from its centre, beyond the contact line within about 12 mm of
// the nose's end), and the legs, straight segments between the points, lie inside the
// rectangle (its convexity: every leg joins two of its points), but for a last leg
// into a pocket's mouth.
//
// The model's limits. A real rebound is not a mirror: the cushion returns about 0.8
// to 0.9 of the normal speed, friction at the nose (7R/5 above the cloth) and at the
// cloth turns the tangential speed and the spin, and the spin left after the impact
// curves the path until the ball rolls again. The mirror heading is a starting point;
// the planner's search corrects the aim by simulation, inside the aim bracket each
// path carries: the heading range that the mirror's typical error, measured with the
// simulator, needs (MirrorReboundError, BracketFor). Spin (side, screw) changes the
// rebound far more than the bracket covers; that is the search's to find.
//
// Measured error of the mirror (tests/planner/cushion_paths_test.cc,
// MirrorErrorTable; full-fidelity simulator, one ball struck rolling along the
// mirror heading from S, 0.6 m before its contact point on the left cushion, to T
// 0.6 m after it). dh: the heading correction (deg) that puts the ball's path
// through T; eps = dh / ReboundHeadingGain: the same as an error of the outgoing
// direction at the cushion (deg, positive: the real rebound leaves wider of the
// cushion's normal than the mirror's):
//
//   incidence   1.0 m/s         2.0 m/s         3.0 m/s         4.0 m/s
//   (deg)       dh     eps      dh     eps      dh     eps      dh     eps
//      5       -0.03  -0.07    -0.35  -0.70    -0.52  -1.05    -0.52  -1.04
//     15       -0.11  -0.22    -1.04  -2.09    -1.59  -3.17    -1.51  -3.02
//     25       -0.16  -0.32    -1.56  -3.12    -2.39  -4.78    -1.94  -3.87
//     35       +0.47  +0.93    -1.08  -2.16    -2.13  -4.26    -1.68  -3.36
//     45       +1.83  +3.65    +0.26  +0.51    -1.36  -2.72    -1.30  -2.60
//     55       +3.35  +6.70    +1.62  +3.24    -0.46  -0.93    -0.81  -1.63
//     65       +4.85  +9.69    +2.61  +5.21    +0.86  +1.71    -0.25  -0.51
//     75       +5.66 +11.33    +2.86  +5.71    +1.79  +3.59    +0.73  +1.47
//
// Fast and shallow, the ball leaves narrower (the nose's friction takes tangential
// speed); slow and steep, wider (the topspin it brought in pulls it back towards
// the cushion as it curves). The error is systematic, several degrees, and changes
// sign with speed, so the bracket is wide: MirrorReboundError is the envelope of
// eps over speeds of 1, 1.5, 2, 3 and 4 m/s and legs of 0.3, 0.6 and 1 m before
// and after the cushion (45 cases per incidence), widened by a tenth: from
// [-1.6, +0.1] deg at 5 deg of incidence through [-6.9, +0.1] at 25, [-5.3, +4.5] at
// 45 to [-0.2, +14.1] at 75. A stun ball (no topspin) errs more, eps from -10 to
// +15 deg over the same cases: CushionPathOptions::sliding widens the bracket to
// cover it (doubles: an object ball leaves a contact without topspin). Neither
// covers the spin the search adds, nor speeds under 1 m/s. The rebound's noise is small in the simulator: 2 rad/s of
// sidespin noise decays (22 rad/s^2) before the cushion, and 1 % of speed moves
// eps by 0.01 to 0.08 deg (root mean square; ReboundSpeedSensitivity).
//
// Cost: a path is a few reflections and intersections (tens of ns); the clearance
// check is one segment distance per leg and ball.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "physics/core/types.h"
#include "physics/table/table.h"
#include "planner/rules.h"

namespace snooker::planner {

/// The four contact lines, each a cushion nose line moved c into the playing area.
enum class CushionLine : std::uint8_t {
  kBaulk,  ///< y = c (the baulk cushion)
  kTop,    ///< y = length - c
  kLeft,   ///< x = c (both left cushions, split by the middle pocket)
  kRight,  ///< x = width - c
};
inline constexpr int kCushionLineCount = 4;
/// "baulk", "top", "left", "right".
const char* ToString(CushionLine line);

/// A contact line: the points p with normal . p = offset; normal is the unit vector
/// into the playing area.
struct ContactLine {
  physics::Vec2 normal = physics::Vec2::Zero();
  double offset = 0;  ///< m
  /// Signed distance of p from the line, positive inside the playing area. m.
  double Inside(const physics::Vec2& p) const { return normal.dot(p) - offset; }
  /// p's mirror image across the line.
  physics::Vec2 Mirror(const physics::Vec2& p) const { return p - 2 * Inside(p) * normal; }
};
ContactLine ContactLineOf(const physics::TableModel& table, CushionLine line);

/// Where a path meets a cushion.
struct CushionContact {
  CushionLine line = CushionLine::kBaulk;
  ContactLine contact_line;
  /// Index in TableModel::segments() of the straight nose touched (0 to 5).
  int segment = -1;
  /// The ball's centre at the contact. m.
  physics::Vec2 point = physics::Vec2::Zero();
  /// Angle between the incoming leg and the cushion's normal: 0 square on, towards
  /// pi/2 along the cushion. rad.
  double incidence = 0;
  /// Distance along the nose from the contact to the nearer end of the nose. m.
  double nose_margin = 0;
};

/// A heading range around a nominal heading, as offsets: the range is
/// [nominal + lo, nominal + hi], lo <= 0 <= hi. rad.
struct AimBracket {
  double lo = 0;
  double hi = 0;
  double width() const { return hi - lo; }
  bool Contains(double offset) const { return offset >= lo && offset <= hi; }
};

/// A path off one or two cushions from `start` to `target` (ball centres).
struct CushionPath {
  int cushions = 0;  ///< 1 or 2
  std::array<CushionContact, 2> contacts{};
  /// start, the contact point(s), target: the first cushions + 2 are used.
  std::array<physics::Vec2, 4> points{};
  /// The mirror heading at the start and the direction of the last leg. rad.
  double heading = 0;
  double final_direction = 0;
  /// Length of each leg (cushions + 1 used) and in all. m.
  std::array<double, 3> legs{};
  double length = 0;
  /// The headings to search (see above), for a ball that arrives rolling, or
  /// (sliding) one that may arrive sliding.
  AimBracket bracket;
  bool sliding = false;

  int leg_count() const { return cushions + 1; }
  const physics::Vec2& start() const { return points[0]; }
  const physics::Vec2& target() const { return points[static_cast<size_t>(cushions + 1)]; }
  /// Path length from contact i (0-based) to the target. m.
  double LengthAfter(int contact) const;
  /// A point near leg `leg` mapped into the unfolded frame, where the whole path is
  /// the straight segment from start() along `heading` over `length` (the mirror
  /// images across the contacts before that leg).
  physics::Vec2 Unfold(int leg, const physics::Vec2& p) const;
  /// The inverse of Unfold for the same leg.
  physics::Vec2 Fold(int leg, const physics::Vec2& p) const;
};

/// Why MirrorPath refused a path.
enum class PathRefusal : std::uint8_t {
  kNone,
  kOutside,     ///< the start off the table, or it or the target not inside a line used by min_inside
  kOffCushion,  ///< a contact in a pocket mouth, within jaw_margin of a jaw, or off the table
  kGlancing,    ///< an incidence past max_incidence
  kBlocked,     ///< a leg passes another ball closer than 2R plus the clearance
};
const char* ToString(PathRefusal r);

struct CushionPathOptions {
  /// Least distance along a nose from a contact to the nose's end. m.
  double jaw_margin = 0.035;
  /// Largest angle of incidence (a glance along the cushion is unpredictable). rad.
  double max_incidence = 75.0 * physics::kPi / 180;
  /// Least distance of the start and the target inside each contact line (a ball
  /// frozen to a cushion cannot be played off it). m.
  double min_inside = 1e-3;
  /// Added to each side of every bracket, for what the measured rebound error leaves
  /// out (a path's other approximations). rad.
  double bracket_floor = 0.1 * physics::kPi / 180;
  /// The ball may reach a cushion sliding (an object ball just hit, which leaves
  /// without topspin): brackets and sensitivities cover stun arrivals too.
  bool sliding = false;
};

/// The path from `start` to `target` off the contact lines `lines` in order (one or
/// two, the two different), or nullopt with the reason. The start must be on the
/// table (inside all four lines), the target only inside the lines used: a pocket's
/// aim point lies beyond its own cushions' lines. Geometry only: other balls are
/// LegsMargin's.
std::optional<CushionPath> MirrorPath(const physics::TableModel& table, const physics::Vec2& start,
                                      const physics::Vec2& target, std::span<const CushionLine> lines,
                                      const CushionPathOptions& options = {},
                                      PathRefusal* why = nullptr);

/// Smallest distance from the segment [a, b] to the centre of any ball of `table`
/// but the indices in `skip`, minus `clearance` (geometry.h PathMargin with any
/// number of exceptions). +infinity when no ball counts. m.
double SegmentMargin(const physics::Vec2& a, const physics::Vec2& b, double clearance,
                     const TableState& table, std::span<const int> skip);

/// The smallest SegmentMargin over the path's legs: every leg skips `mover` (the
/// ball travelling) and `other` (-1: none), the last leg also `target_ball` (the ball
/// whose ghost-ball position the path ends at; -1: none). >= 0: the path is clear
/// with `clearance` (2R plus a margin for a ball's path) to spare. m.
double LegsMargin(const CushionPath& path, double clearance, const TableState& table, int mover,
                  int other = -1, int target_ball = -1);

/// The range of the mirror's error on the outgoing direction at a cushion (rad,
/// positive wider of the normal than the mirror), covering the measured errors
/// (table above) of a ball struck rolling at 1 to 4 m/s, or (sliding) struck
/// rolling or stun, meeting the cushion at `incidence` (rad).
struct ReboundError {
  double lo = 0;
  double hi = 0;
};
ReboundError MirrorReboundError(double incidence, bool sliding = false);

/// How much the rebound turns with the speed, |d(eps)/d(ln speed)| (rad per unit
/// relative speed change, the root mean square over the same cases): what the
/// speed noise does to a path the search has aimed. At 1 % of speed, 0.01 to 0.08
/// deg rolling, up to 0.13 deg sliding.
double ReboundSpeedSensitivity(double incidence, bool sliding = false);

/// d(heading)/d(eps_i): the turn of the start heading that keeps the path through
/// the target when the outgoing direction at contact i turns by eps_i (positive
/// wider of the normal). Dimensionless.
double ReboundHeadingGain(const CushionPath& path, int contact);

/// The aim bracket of a path: each contact's MirrorReboundError through its gain,
/// summed as intervals, widened by `floor` on each side. Offsets, rad.
AimBracket BracketFor(const CushionPath& path, double floor);

/// Every path off one cushion (the four lines in order), then, when max_cushions is
/// 2, off two (every ordered pair of different lines), from `start` to `target` that
/// MirrorPath accepts and whose legs pass every other ball (LegsMargin >= 0 with
/// `clearance`), appended to `out`. Returns how many were appended.
int AppendCushionPaths(const physics::TableModel& model, const TableState& table,
                       const physics::Vec2& start, const physics::Vec2& target, int max_cushions,
                       double clearance, int mover, int other, int target_ball,
                       const CushionPathOptions& options, std::vector<CushionPath>& out);

}  // namespace snooker::planner
