// The snooker table: geometry, markings and pockets, kept apart from the balls'
// state (MuJoCo's mjModel / mjData split). Built once from a TableSpec, immutable.
//
// Frame (types.h): x across the table from 0 (the left cushion nose) to `width`, y
// along it from 0 (the baulk cushion nose) to `length` (the top cushion nose), z up.
// A viewer at the baulk end facing +y has +x on their right: "left" means x = 0.
//
// The boundary, in the plane of the ball centres' contacts:
//  * six straight cushion noses (the playing area is the rectangle they bound); each
//    ends where its pocket's jaw begins;
//  * at each jaw a circle, the knuckle, tangent to the nose line at the nose's end;
//  * behind each knuckle a straight jaw wall, tangent to the knuckle, running into
//    the pocket at the jaw angle (measured through the cushion between nose and
//    wall), so a ball can rattle between the jaws.
// The boundary is tangent-continuous (nose -> knuckle -> wall). A ball is pocketed
// when its centre enters the pocket's capture circle, which lies on the pocket axis
// behind the mouth and covers the channel between the walls before they end.
//
// Why these shapes: the governing body (WPBSA) does not publish pocket templates,
// so every pocket dimension is an estimate and a parameter; circles and segments
// keep every detector a polynomial root problem (physics/events/detect.h).
// docs/table-model.md lists each value and its source or reasoning.
//
// Contact distances: a ball touches a cushion nose at cushion_height above the
// cloth, so its centre is then cushion_contact_distance() (< R) from the nose line.
// ValidatePlacement and the simulator (physics/sim/simulate.h) both use that distance,
// and the simulator gives the cushion model this same contact height.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "physics/core/limits.h"
#include "physics/core/params.h"
#include "physics/core/types.h"

namespace snooker::physics {

enum class PocketId : std::uint8_t {
  kBaulkLeft,    ///< corner at (0, 0)
  kBaulkRight,   ///< corner at (width, 0)
  kMiddleLeft,   ///< middle of the x = 0 cushion
  kMiddleRight,  ///< middle of the x = width cushion
  kTopLeft,      ///< corner at (0, length)
  kTopRight,     ///< corner at (width, length)
};
inline constexpr int kPocketCount = 6;

/// "baulk-left", "baulk-right", "middle-left", "middle-right", "top-left", "top-right".
const char* ToString(PocketId id);

/// The colours, each with its own spot.
enum class Colour : std::uint8_t { kYellow, kGreen, kBrown, kBlue, kPink, kBlack };
inline constexpr int kColourCount = 6;

/// "yellow", "green", "brown", "blue", "pink", "black".
const char* ToString(Colour c);

inline constexpr int kRedCount = 15;

/// The shape of one kind of pocket (all four corners share one, both middles another).
struct PocketShape {
  /// Distance between the two points where the straight cushion noses end and the
  /// knuckles begin, across the pocket axis. m.
  double mouth_width = 0;
  /// Radius of each knuckle (the rounded jaw end). m.
  double knuckle_radius = 0;
  /// Angle between the cushion nose and the jaw wall, measured through the cushion
  /// (the "cut angle"). Walls converge towards the pocket when it exceeds
  /// 90 deg + the angle between nose and mouth line (45 deg for corners). rad.
  double jaw_angle = 0;
  /// Length of each straight jaw wall, from its tangent point on the knuckle. m.
  double wall_length = 0;
  /// Depth behind the mouth line, on the pocket axis, at which a ball centre is
  /// captured (the front of the capture circle). m.
  double fall_depth = 0;
  /// Radius of the capture circle; its centre is on the axis, fall_depth +
  /// capture_radius behind the mouth line. m.
  double capture_radius = 0;
};

/// Corner pocket estimates (docs/table-model.md).
inline constexpr PocketShape kCornerPocketShape{
    .mouth_width = 0.086,
    .knuckle_radius = 0.010,
    .jaw_angle = DegToRad(142.0),
    .wall_length = 0.050,
    .fall_depth = 0.015,
    .capture_radius = 0.045,
};

/// Middle pocket estimates (docs/table-model.md).
inline constexpr PocketShape kMiddlePocketShape{
    .mouth_width = 0.087,
    .knuckle_radius = 0.008,
    .jaw_angle = DegToRad(100.0),
    .wall_length = 0.040,
    .fall_depth = 0.008,
    .capture_radius = 0.040,
};

/// Parameters of a full-size table (WPBSA dimensions; pockets estimated).
struct TableSpec {
  /// Playing area across the table, between cushion noses (5 ft 10 in). m.
  double width = 1.778;
  /// Playing area along the table, between cushion noses (11 ft 8.5 in). m.
  double length = 3.569;
  /// Distance of the baulk line from the baulk cushion nose (29 in). m.
  double baulk_line = 0.737;
  /// Radius of the D, centred on the middle of the baulk line (11.5 in). m.
  double d_radius = 0.292;
  /// Distance of the black spot from the top cushion nose (12.75 in). m.
  double black_spot = 0.324;
  /// Gap between a ball on the pink spot and the apex red of the triangle. m.
  double apex_gap = 0.001;
  /// Height above the cloth at which a ball touches the cushion nose. m. Measured
  /// 36 mm for snooker (Mathavan et al. 2010); their cushion model uses 7R/5
  /// (SevenFifthsCushionHeight, 36.75 mm for R = 26.25 mm).
  double cushion_height = 0.036;
  PocketShape corner = kCornerPocketShape;
  PocketShape middle = kMiddlePocketShape;
};

/// 7R/5, the cushion contact height of Mathavan et al.'s cushion model. m.
double SevenFifthsCushionHeight(const BallParams& ball);

/// Empty when a TableModel can be built from `spec` and `ball`; otherwise a message
/// naming each bad value.
std::string ValidateTableSpec(const TableSpec& spec, const BallParams& ball);

enum class SegmentKind : std::uint8_t {
  kCushion,  ///< a straight cushion nose
  kJawWall,  ///< a straight jaw wall behind a knuckle, inside a pocket
};

/// A straight piece of the boundary.
struct CushionSegment {
  /// End points, table frame. m.
  Vec2 p0 = Vec2::Zero();
  Vec2 p1 = Vec2::Zero();
  /// Unit normal pointing to the side the balls are on: into the playing area for a
  /// cushion nose, into the pocket channel for a jaw wall.
  Vec2 normal = Vec2::Zero();
  SegmentKind kind = SegmentKind::kCushion;
  /// The pocket a jaw wall belongs to; for a cushion nose, the pocket at p0.
  PocketId pocket = PocketId::kBaulkLeft;
  /// "baulk", "top", "left-baulk", ... or "<pocket> wall 0/1". Static storage.
  const char* name = "";
};

/// A knuckle: the rounded end of a jaw.
struct JawCircle {
  /// Centre, table frame. m.
  Vec2 centre = Vec2::Zero();
  /// m.
  double radius = 0;
  PocketId pocket = PocketId::kBaulkLeft;
};

struct Pocket {
  PocketId id = PocketId::kBaulkLeft;
  /// Midpoint between the two nose ends (the middle of the mouth line). m.
  Vec2 mouth_centre = Vec2::Zero();
  /// Unit vector along the pocket axis, pointing out of the playing area.
  Vec2 axis = Vec2::Zero();
  /// Capture circle: a ball whose centre enters it drops. Centre (m), radius (m).
  Vec2 capture_centre = Vec2::Zero();
  double capture_radius = 0;
};

/// A named ball position for ValidatePlacement.
struct BallPlacement {
  /// Name used in messages ("cue", "red-3", ...); empty gives "ball <index>".
  std::string_view name;
  /// Centre, table frame. m.
  Vec2 r = Vec2::Zero();
};

class TableModel {
 public:
  static constexpr int kCushionCount = 6;
  static constexpr int kJawWallCount = 2 * kPocketCount;
  static constexpr int kSegmentCount = kCushionCount + kJawWallCount;
  static constexpr int kJawCount = 2 * kPocketCount;
  /// Tolerance of ValidatePlacement, m: balls placed touching (the red triangle)
  /// may overlap by rounding error, ~1e-17 m; 1e-9 m is far below anything visible.
  static constexpr double kPlacementTolerance = 1e-9;

  /// Builds the table. Throws std::invalid_argument with ValidateTableSpec's
  /// message if the spec is invalid (construction is not on a hot path).
  explicit TableModel(const TableSpec& spec = TableSpec(), const BallParams& ball = BallParams());

  const TableSpec& spec() const { return spec_; }
  /// Ball radius used for the markings and placement checks. m.
  double ball_radius() const { return radius_; }
  /// Horizontal distance from a ball's centre to a cushion nose line when the ball
  /// touches the nose at cushion_height h: sqrt(R^2 - (h - R)^2). A ball frozen to a
  /// cushion has its centre this far inside the playing area. m.
  double cushion_contact_distance() const;

  /// Cushion noses first (baulk, top, left-baulk, left-top, right-baulk, right-top),
  /// then the jaw walls, two per pocket in PocketId order.
  std::span<const CushionSegment> segments() const { return segments_; }
  /// Knuckles, two per pocket in PocketId order.
  std::span<const JawCircle> jaws() const { return jaws_; }
  /// Pockets in PocketId order.
  std::span<const Pocket> pockets() const { return pockets_; }
  const Pocket& pocket(PocketId id) const { return pockets_[static_cast<int>(id)]; }

  /// Spot of a colour, table frame. m.
  Vec2 spot(Colour c) const { return spots_[static_cast<int>(c)]; }
  /// The 15 reds of the opening triangle, apex first, then row by row (rows of
  /// 1..5 balls, each row from -x to +x), table frame. m.
  std::span<const Vec2> reds() const { return reds_; }

  /// Problems ValidatePlacement lists by default; the rest are counted.
  static constexpr std::size_t kMaxPlacementProblems = 5;

  /// Whether a ball centred at `r` rests in a pocket's mouth, past the line of the
  /// cushion noses: between the knuckles or the jaw walls and clear of them by
  /// cushion_contact_distance(), short of the capture circle. The simulator leaves
  /// balls there (a ball that stops on the lip), so such a place is a placement.
  bool InPocketMouth(const Vec2& r) const { return PocketMouthAt(r).has_value(); }
  /// The pocket in whose mouth a ball centred at `r` rests (InPocketMouth), if any.
  std::optional<PocketId> PocketMouthAt(const Vec2& r) const;

  /// Empty when every ball lies inside the playing area by at least
  /// cushion_contact_distance() or in a pocket's mouth (InPocketMouth), and no two
  /// overlap (both within kPlacementTolerance); otherwise a message naming the first
  /// `max_problems` offending balls and values, then "and N more" (its length is bounded by
  /// max_problems and the names' lengths, whatever the number of balls). More than
  /// limits::kMaxBalls balls are refused at once, before the quadratic overlap check.
  std::string ValidatePlacement(std::span<const BallPlacement> balls,
                                std::size_t max_problems = kMaxPlacementProblems) const;

 private:
  TableSpec spec_;
  double radius_ = 0;
  std::array<CushionSegment, kSegmentCount> segments_{};
  std::array<JawCircle, kJawCount> jaws_{};
  std::array<Pocket, kPocketCount> pockets_{};
  std::array<Vec2, kColourCount> spots_{};
  std::array<Vec2, kRedCount> reds_{};
};

/// The built-in full-size table (TableSpec and BallParams defaults), built once,
/// shared and immutable.
const TableModel& DefaultTable();

}  // namespace snooker::physics
