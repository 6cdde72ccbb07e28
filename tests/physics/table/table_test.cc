#include "physics/table/table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/events/detect.h"
#include "physics/motion/motion.h"

namespace snooker::physics {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Geometry is built from a few products and sums of O(1) m values: rounding ~1e-16 m.
constexpr double kGeomTol = 1e-12;

class TableTest : public ::testing::Test {
 protected:
  TableModel table_;
  double R() const { return table_.ball_radius(); }
  double W() const { return table_.spec().width; }
  double L() const { return table_.spec().length; }
};

TEST_F(TableTest, DimensionsAndSpotsAsSpecified) {
  EXPECT_EQ(W(), 1.778);
  EXPECT_EQ(L(), 3.569);
  const double cx = 0.889;
  EXPECT_NEAR((table_.spot(Colour::kBrown) - Vec2(cx, 0.737)).norm(), 0, kGeomTol);
  EXPECT_NEAR((table_.spot(Colour::kYellow) - Vec2(cx + 0.292, 0.737)).norm(), 0, kGeomTol);
  EXPECT_NEAR((table_.spot(Colour::kGreen) - Vec2(cx - 0.292, 0.737)).norm(), 0, kGeomTol);
  EXPECT_NEAR((table_.spot(Colour::kBlue) - Vec2(cx, 1.7845)).norm(), 0, kGeomTol);
  EXPECT_NEAR((table_.spot(Colour::kPink) - Vec2(cx, 0.75 * 3.569)).norm(), 0, kGeomTol);
  EXPECT_NEAR((table_.spot(Colour::kBlack) - Vec2(cx, 3.569 - 0.324)).norm(), 0, kGeomTol);
  // Seen from the baulk end facing +y, +x is on the right: yellow right of brown.
  EXPECT_GT(table_.spot(Colour::kYellow).x(), table_.spot(Colour::kBrown).x());
  EXPECT_EQ(table_.spec().cushion_height, 0.036);
  EXPECT_NEAR(SevenFifthsCushionHeight(BallParams()), 0.03675, kGeomTol);
  EXPECT_STREQ(ToString(PocketId::kMiddleLeft), "middle-left");
  EXPECT_STREQ(ToString(Colour::kPink), "pink");
  for (const Pocket& p : table_.pockets()) {
    const bool middle = p.id == PocketId::kMiddleLeft || p.id == PocketId::kMiddleRight;
    if (middle) {
      EXPECT_NEAR(p.mouth_centre.y(), 1.7845, kGeomTol);
    }
    const bool left = std::string(ToString(p.id)).find("left") != std::string::npos;
    EXPECT_EQ(p.mouth_centre.x() < W() / 2, left) << ToString(p.id);
  }
}

TEST_F(TableTest, RedsTouchInATriangleBehindThePink) {
  const auto reds = table_.reds();
  ASSERT_EQ(reds.size(), static_cast<std::size_t>(kRedCount));
  const Vec2 pink = table_.spot(Colour::kPink);
  // Apex on the long axis, behind the pink (towards the top cushion), not touching it.
  EXPECT_NEAR(reds[0].x(), W() / 2, kGeomTol);
  EXPECT_GT(reds[0].y(), pink.y());
  EXPECT_NEAR((reds[0] - pink).norm(), 2 * R() + table_.spec().apex_gap, kGeomTol);
  EXPECT_GT((reds[0] - pink).norm(), 2 * R());
  int touching_pairs = 0;
  for (std::size_t i = 0; i < reds.size(); ++i) {
    EXPECT_GT(reds[i].y(), pink.y() + 2 * R());
    EXPECT_LT(reds[i].y(), table_.spot(Colour::kBlack).y() - 2 * R());
    for (std::size_t j = i + 1; j < reds.size(); ++j) {
      const double d = (reds[i] - reds[j]).norm();
      EXPECT_GE(d, 2 * R() - kGeomTol) << i << " " << j;
      if (d < 2 * R() + kGeomTol) ++touching_pairs;
    }
  }
  // A triangle of side 5: 3 * (1 + 2 + 3 + 4) = 30 touching neighbour pairs.
  EXPECT_EQ(touching_pairs, 30);
}

TEST_F(TableTest, FullRackIsALegalPlacement) {
  std::vector<BallPlacement> balls;
  const char* const names[] = {"yellow", "green", "brown", "blue", "pink", "black"};
  for (int c = 0; c < kColourCount; ++c) {
    balls.push_back({names[c], table_.spot(static_cast<Colour>(c))});
  }
  std::vector<std::string> red_names;
  for (int i = 0; i < kRedCount; ++i) red_names.push_back("red-" + std::to_string(i));
  for (int i = 0; i < kRedCount; ++i) balls.push_back({red_names[i], table_.reds()[i]});
  balls.push_back({"cue", Vec2(0.8, 0.6)});
  EXPECT_EQ(table_.ValidatePlacement(balls), "");
}

TEST_F(TableTest, PlacementMessagesNameTheBallAndValue) {
  const std::vector<BallPlacement> off = {{"cue", Vec2(0.01, 1.0)}};
  const std::string m = table_.ValidatePlacement(off);
  EXPECT_NE(m.find("cue"), std::string::npos) << m;
  EXPECT_NE(m.find("x = 0.01"), std::string::npos) << m;
  EXPECT_NE(m.find("left cushion"), std::string::npos) << m;

  const std::vector<BallPlacement> top = {{"black", Vec2(0.9, L() - 0.5 * R())}};
  EXPECT_NE(table_.ValidatePlacement(top).find("top cushion"), std::string::npos);

  const std::vector<BallPlacement> overlap = {{"red-1", Vec2(1.0, 1.0)},
                                              {"red-2", Vec2(1.0, 1.0 + 2 * R() - 1e-4)}};
  const std::string o = table_.ValidatePlacement(overlap);
  EXPECT_NE(o.find("red-1"), std::string::npos) << o;
  EXPECT_NE(o.find("red-2"), std::string::npos) << o;
  EXPECT_NE(o.find("overlaps"), std::string::npos) << o;

  const std::vector<BallPlacement> unnamed = {{"", Vec2(1.0, 1.0)}, {"", Vec2(NAN, 1.0)}};
  EXPECT_NE(table_.ValidatePlacement(unnamed).find("ball 1"), std::string::npos);

  // Touching a cushion or another ball exactly is legal.
  const std::vector<BallPlacement> touching = {{"a", Vec2(R(), 1.0)},
                                               {"b", Vec2(3 * R(), 1.0)}};
  EXPECT_EQ(table_.ValidatePlacement(touching), "");
}

// A pocket's mouth past the line of the noses holds a ball on the lip: along the axis
// from the nose line to the capture circle. Inside the capture circle, against a
// knuckle, or behind a cushion beside the mouth is no place for a ball.
TEST_F(TableTest, APocketsMouthHoldsABallOnTheLipAndNowhereBehindTheCushions) {
  const double c = table_.cushion_contact_distance();
  for (const Pocket& p : table_.pockets()) {
    const Vec2 across(-p.axis.y(), p.axis.x());
    // Where the axis crosses the noses' line (c inside it), and where the capture circle begins.
    const double inside = (p.capture_centre - p.mouth_centre).dot(p.axis) - p.capture_radius;
    for (double depth = -0.004; depth < inside - 1e-4; depth += 0.001) {
      const Vec2 r = p.mouth_centre + depth * p.axis;
      const bool past = r.x() < c || r.y() < c || r.x() > W() - c || r.y() > L() - c;
      EXPECT_EQ(table_.InPocketMouth(r), past) << ToString(p.id) << " depth " << depth;
      if (past) {  // this pocket's mouth, not another's
        EXPECT_EQ(table_.PocketMouthAt(r), p.id) << ToString(p.id) << " depth " << depth;
      }
      EXPECT_EQ(table_.ValidatePlacement(std::vector<BallPlacement>{{"ball", r}}), "") << ToString(p.id) << depth;
    }
    EXPECT_FALSE(table_.InPocketMouth(p.capture_centre)) << ToString(p.id);
    const Vec2 deep = p.mouth_centre + (inside + 1e-4) * p.axis;
    EXPECT_NE(table_.ValidatePlacement(std::vector<BallPlacement>{{"ball", deep}}), "") << ToString(p.id);
    for (const JawCircle& jaw : table_.jaws()) {
      if (jaw.pocket != p.id) continue;
      // Against the knuckle from the mouth's middle: 1 mm short of the contact distance.
      const Vec2 to = (p.mouth_centre - jaw.centre).normalized();
      const Vec2 against = jaw.centre + (jaw.radius + c - 0.001) * to;
      EXPECT_FALSE(table_.InPocketMouth(against)) << ToString(p.id);
    }
    // Beside the mouth, behind the cushion: past the noses' line by 5 mm, a mouth's
    // width along it.
    for (const double side : {-1.0, 1.0}) {
      const Vec2 behind = p.mouth_centre + 0.005 * p.axis + side * 0.09 * across;
      EXPECT_FALSE(table_.InPocketMouth(behind)) << ToString(p.id);
      EXPECT_NE(table_.ValidatePlacement(std::vector<BallPlacement>{{"ball", behind}}), "") << ToString(p.id);
    }
  }
}

TEST_F(TableTest, NormalsAreUnitAndPointToTheBalls) {
  const Vec2 centre(W() / 2, L() / 2);
  for (const CushionSegment& s : table_.segments()) {
    EXPECT_NEAR(s.normal.norm(), 1.0, kGeomTol) << s.name;
    EXPECT_NEAR(s.normal.dot(s.p1 - s.p0), 0.0, kGeomTol) << s.name;
    if (s.kind == SegmentKind::kCushion) {
      EXPECT_GT(s.normal.dot(centre - s.p0), 0.5) << s.name;
    } else {
      // Into the pocket channel: towards the pocket axis.
      const Pocket& p = table_.pocket(s.pocket);
      const Vec2 off = s.p0 - p.mouth_centre;
      const Vec2 lateral = off - off.dot(p.axis) * p.axis;
      EXPECT_LT(s.normal.dot(lateral), 0.0) << s.name;
    }
  }
}

// The boundary is tangent-continuous: every nose ends on a knuckle, tangent to it,
// and every jaw wall starts on its knuckle, tangent to it.
TEST_F(TableTest, NosesKnucklesAndWallsJoinWithoutGaps) {
  const auto segs = table_.segments();
  const auto jaws = table_.jaws();
  ASSERT_EQ(segs.size(), static_cast<std::size_t>(TableModel::kSegmentCount));
  ASSERT_EQ(jaws.size(), static_cast<std::size_t>(TableModel::kJawCount));
  std::vector<int> nose_ends_on_jaw(jaws.size(), 0);
  for (int i = 0; i < TableModel::kCushionCount; ++i) {
    ASSERT_EQ(segs[i].kind, SegmentKind::kCushion);
    for (const Vec2& end : {segs[i].p0, segs[i].p1}) {
      int matches = 0;
      for (std::size_t j = 0; j < jaws.size(); ++j) {
        const Vec2 to_centre = jaws[j].centre - end;
        if (std::abs(to_centre.norm() - jaws[j].radius) > kGeomTol) continue;
        // Tangent there: the centre lies straight behind the nose.
        if ((to_centre + jaws[j].radius * segs[i].normal).norm() > kGeomTol) continue;
        ++matches;
        ++nose_ends_on_jaw[j];
      }
      EXPECT_EQ(matches, 1) << segs[i].name;
    }
  }
  for (int n : nose_ends_on_jaw) EXPECT_EQ(n, 1);  // each knuckle ends exactly one nose
  for (int i = TableModel::kCushionCount; i < TableModel::kSegmentCount; ++i) {
    const CushionSegment& w = segs[i];
    ASSERT_EQ(w.kind, SegmentKind::kJawWall);
    const JawCircle& jaw = jaws[i - TableModel::kCushionCount];
    EXPECT_EQ(jaw.pocket, w.pocket);
    EXPECT_NEAR((w.p0 - jaw.centre).norm(), jaw.radius, kGeomTol) << w.name;
    EXPECT_NEAR(((w.p0 - jaw.centre) / jaw.radius - w.normal).norm(), 0.0, kGeomTol) << w.name;
  }
}

bool Contains(std::span<const CushionSegment> segs, const Vec2& a, const Vec2& b, const Vec2& n) {
  return std::any_of(segs.begin(), segs.end(), [&](const CushionSegment& s) {
    const bool same = (s.p0 - a).norm() < kGeomTol && (s.p1 - b).norm() < kGeomTol;
    const bool swapped = (s.p0 - b).norm() < kGeomTol && (s.p1 - a).norm() < kGeomTol;
    return (same || swapped) && (s.normal - n).norm() < kGeomTol;
  });
}

TEST_F(TableTest, SymmetricAboutTheLongAxisAndTheMiddle) {
  const auto mirror_x = [&](const Vec2& p) { return Vec2(W() - p.x(), p.y()); };
  const auto flip_x = [](const Vec2& n) { return Vec2(-n.x(), n.y()); };
  const auto mirror_y = [&](const Vec2& p) { return Vec2(p.x(), L() - p.y()); };
  const auto flip_y = [](const Vec2& n) { return Vec2(n.x(), -n.y()); };
  const auto segs = table_.segments();
  for (const CushionSegment& s : segs) {
    EXPECT_TRUE(Contains(segs, mirror_x(s.p0), mirror_x(s.p1), flip_x(s.normal))) << s.name;
    EXPECT_TRUE(Contains(segs, mirror_y(s.p0), mirror_y(s.p1), flip_y(s.normal))) << s.name;
  }
  for (const JawCircle& j : table_.jaws()) {
    const auto has = [&](const Vec2& c) {
      return std::any_of(table_.jaws().begin(), table_.jaws().end(), [&](const JawCircle& k) {
        return (k.centre - c).norm() < kGeomTol && k.radius == j.radius;
      });
    };
    EXPECT_TRUE(has(mirror_x(j.centre)));
    EXPECT_TRUE(has(mirror_y(j.centre)));
  }
  for (const Pocket& p : table_.pockets()) {
    const auto has = [&](const Vec2& c) {
      return std::any_of(table_.pockets().begin(), table_.pockets().end(), [&](const Pocket& q) {
        return (q.capture_centre - c).norm() < kGeomTol && q.capture_radius == p.capture_radius;
      });
    };
    EXPECT_TRUE(has(mirror_x(p.capture_centre))) << ToString(p.id);
    EXPECT_TRUE(has(mirror_y(p.capture_centre))) << ToString(p.id);
  }
  EXPECT_NEAR((mirror_x(table_.spot(Colour::kYellow)) - table_.spot(Colour::kGreen)).norm(), 0,
              kGeomTol);
  for (const Vec2& r : table_.reds()) {
    const bool has = std::any_of(table_.reds().begin(), table_.reds().end(),
                                 [&](const Vec2& q) { return (q - mirror_x(r)).norm() < kGeomTol; });
    EXPECT_TRUE(has);
  }
}

// The distance from the legal area (centres at least R inside the noses) to a
// capture circle: a ball at rest on the table is never in a pocket.
TEST_F(TableTest, CaptureCirclesStayOutsideTheLegalArea) {
  for (const Pocket& p : table_.pockets()) {
    const Vec2 nearest(std::clamp(p.capture_centre.x(), R(), W() - R()),
                       std::clamp(p.capture_centre.y(), R(), L() - R()));
    EXPECT_GT((nearest - p.capture_centre).norm(), p.capture_radius) << ToString(p.id);
  }
}

// No way out behind the jaws: a ball centre sliding along a jaw wall (R from it) is
// inside the capture circle by the time it reaches the wall's far end, and so is
// the end itself. By convexity of the circle, every centre path from the channel
// past the walls' ends then crosses the capture circle first.
TEST_F(TableTest, JawWallsEndInsideTheCaptureCircle) {
  for (const CushionSegment& w : table_.segments()) {
    if (w.kind != SegmentKind::kJawWall) continue;
    const Pocket& p = table_.pocket(w.pocket);
    EXPECT_LT((w.p1 - p.capture_centre).norm(), p.capture_radius) << w.name;
    EXPECT_LT((w.p1 + R() * w.normal - p.capture_centre).norm(), p.capture_radius) << w.name;
    // And the wall starts outside it: a ball can touch the wall before it drops.
    EXPECT_GT((w.p0 + R() * w.normal - p.capture_centre).norm(), p.capture_radius) << w.name;
  }
}

// First event for a ball at p moving at constant velocity v against the whole
// boundary. kind: 0 none, 1 segment, 2 jaw, 3 pocket.
struct Hit {
  double t = kInf;
  int kind = 0;
  Vec2 normal = Vec2::Zero();
};

Hit FirstHit(const TableModel& table, const Vec2& p, const Vec2& v, double t_max) {
  PositionPoly path;
  path.c = p;
  path.b = v;
  const double r = table.ball_radius();
  Hit hit;
  for (const CushionSegment& s : table.segments()) {
    const double t = DetectBallCushion(path, s, r, t_max);
    if (t < hit.t) hit = {t, 1, s.normal};
  }
  for (const JawCircle& j : table.jaws()) {
    const double t = DetectBallJaw(path, j, r, t_max);
    if (t < hit.t) hit = {t, 2, (path.At(t) - j.centre).normalized()};
  }
  for (const Pocket& q : table.pockets()) {
    const double t = DetectBallPocket(path, q, t_max);
    if (t <= hit.t) hit = {t, 3, Vec2::Zero()};
  }
  return hit;
}

// Shoots balls in straight lines, reflecting them at every cushion, knuckle and
// wall: if the boundary had a gap, some ball would leave the table without
// entering a capture circle.
TEST_F(TableTest, BoundaryIsClosedExceptThroughThePockets) {
  constexpr int kShots = 600;
  constexpr int kMaxBounces = 40;
  constexpr double kMargin = 0.2;  // m: anything this far outside the noses escaped
  std::mt19937_64 rng(2718);
  std::uniform_real_distribution<double> ux(R(), W() - R()), uy(R(), L() - R()), u(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, kPocketCount - 1);
  int captured = 0, jaw_hits = 0, wall_hits = 0;
  for (int shot = 0; shot < kShots; ++shot) {
    Vec2 p(ux(rng), uy(rng));
    // Half the shots aim near a pocket mouth to exercise the jaws.
    const Pocket& target = table_.pockets()[pick(rng)];
    Vec2 v = shot % 2 ? Vec2(u(rng), u(rng))
                      : Vec2(target.mouth_centre + 0.06 * Vec2(u(rng), u(rng)) - p);
    if (v.norm() < 1e-3) continue;
    v.normalize();
    for (int bounce = 0; bounce < kMaxBounces; ++bounce) {
      const Hit h = FirstHit(table_, p, v, 10.0);
      ASSERT_LT(h.t, kInf) << "shot " << shot << " escaped from (" << p.x() << ", " << p.y()
                           << ") along (" << v.x() << ", " << v.y() << ")";
      p += h.t * v;
      ASSERT_GT(p.x(), -kMargin);
      ASSERT_LT(p.x(), W() + kMargin);
      ASSERT_GT(p.y(), -kMargin);
      ASSERT_LT(p.y(), L() + kMargin);
      if (h.kind == 3) {
        ++captured;
        break;
      }
      jaw_hits += h.kind == 2;
      if (h.kind == 1 && (std::abs(p.x() - R()) > 1e-6 && std::abs(p.x() - W() + R()) > 1e-6 &&
                          std::abs(p.y() - R()) > 1e-6 && std::abs(p.y() - L() + R()) > 1e-6)) {
        ++wall_hits;
      }
      v -= 2 * v.dot(h.normal) * h.normal;
    }
  }
  std::printf("closure: %d captured, %d knuckle and %d wall contacts\n", captured, jaw_hits,
              wall_hits);
  EXPECT_GT(captured, kShots / 4);
  EXPECT_GT(jaw_hits, 10);
  EXPECT_GT(wall_hits, 10);
}

// A ball sent straight down a pocket's axis, or a little off it, drops without
// touching a jaw; one hugging the baulk cushion drops in the corner.
TEST_F(TableTest, StraightInShotsDrop) {
  constexpr double kOffAxis = 0.005;  // m, inside the estimated clearance (docs)
  for (const Pocket& p : table_.pockets()) {
    const Vec2 lateral(-p.axis.y(), p.axis.x());
    for (double off : {-kOffAxis, 0.0, kOffAxis}) {
      const Vec2 start = p.mouth_centre - 0.3 * p.axis + off * lateral;
      const Hit h = FirstHit(table_, start, p.axis, 10.0);
      EXPECT_EQ(h.kind, 3) << ToString(p.id) << " offset " << off;
    }
  }
  // Running just off the baulk cushion into the corner. (Exactly along it, at y = R,
  // the ball first grazes the baulk knuckle where the nose ends, with zero normal
  // speed: a tangency, which the detectors report.)
  const Hit along = FirstHit(table_, Vec2(0.5, R() + 1e-4), Vec2(-1, 0), 10.0);
  EXPECT_EQ(along.kind, 3);
  const Hit graze = FirstHit(table_, Vec2(0.5, R()), Vec2(-1, 0), 10.0);
  EXPECT_EQ(graze.kind, 2);
  EXPECT_NEAR(graze.t, 0.5 - table_.segments()[0].p0.x(), 1e-6);
}

TEST_F(TableTest, InvalidSpecsAreRejectedWithTheirValue) {
  EXPECT_EQ(ValidateTableSpec(TableSpec(), BallParams()), "");
  TableSpec bad;
  bad.corner.mouth_width = 0.04;
  const std::string m = ValidateTableSpec(bad, BallParams());
  EXPECT_NE(m.find("corner.mouth_width = 0.04"), std::string::npos) << m;
  EXPECT_THROW(TableModel(bad, BallParams()), std::invalid_argument);
  TableSpec nan;
  nan.width = NAN;
  EXPECT_NE(ValidateTableSpec(nan, BallParams()).find("width"), std::string::npos);
  TableSpec crowded;
  crowded.apex_gap = 0.3;
  EXPECT_NE(ValidateTableSpec(crowded, BallParams()).find("apex_gap"), std::string::npos);
}

}  // namespace
}  // namespace snooker::physics
