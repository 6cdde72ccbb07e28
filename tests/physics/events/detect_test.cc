#include "physics/events/detect.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace snooker::physics {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Analytic event times against detector output: root refinement is to full double
// precision, so times of ~1 s agree to ~1e-15 s; 1e-12 s leaves margin. s.
constexpr double kTimeTol = 1e-12;
// The contract: at a returned time the distance equals the contact distance to
// within this. m.
constexpr double kDistTol = kContactTolerance;
// Brute-force scan step: 1e-4 s at speeds up to ~6 m/s is 0.6 mm per step. s.
constexpr double kScanStep = 1e-4;

const double kR = BallParams().radius;

PositionPoly Path(Vec2 c, Vec2 b = Vec2::Zero(), Vec2 a = Vec2::Zero()) {
  PositionPoly p;
  p.c = c;
  p.b = b;
  p.a = a;
  return p;
}

double Dist(const PositionPoly& p, const PositionPoly& q, double t) {
  return (p.At(t) - q.At(t)).norm();
}

TEST(DetectTest, HeadOnAtConstantVelocity) {
  const double t = DetectBallBall(Path({0, 0}, {0, 1}), Path({0, 1}), kR, 10.0);
  EXPECT_NEAR(t, 1 - 2 * kR, kTimeTol);
  // Both moving towards each other.
  const double t2 = DetectBallBall(Path({0, 0}, {0, 1}), Path({0, 1}, {0, -3}), kR, 10.0);
  EXPECT_NEAR(t2, (1 - 2 * kR) / 4, kTimeTol);
  // Beyond t_max: none.
  EXPECT_EQ(DetectBallBall(Path({0, 0}, {0, 1}), Path({0, 1}), kR, 0.5), kInf);
}

TEST(DetectTest, HeadOnWhileDecelerating) {
  // y(t) = v t - d t^2 / 2 reaches s = 1 - 2R at t = (v - sqrt(v^2 - 2 d s)) / d.
  const double v = 2.0, d = ClothParams().mu_s * ClothParams().g, s = 1 - 2 * kR;
  const double t = DetectBallBall(Path({0, 0}, {0, v}, {0, -d / 2}), Path({0, 1}), kR, 10.0);
  EXPECT_NEAR(t, (v - std::sqrt(v * v - 2 * d * s)) / d, kTimeTol);
  // Too slow to get there: the ball stops first (the path is valid until v / d).
  EXPECT_EQ(DetectBallBall(Path({0, 0}, {0, 0.5}, {0, -d / 2}), Path({0, 1}), kR, 0.5 / d),
            kInf);
}

TEST(DetectTest, ObliqueContact) {
  for (double h : {0.0, 0.01, 0.03, 0.05}) {
    const double x0 = 0.7, v = 1.3;
    const double t = DetectBallBall(Path({0, 0}, {v, 0}), Path({x0, h}), kR, 10.0);
    EXPECT_NEAR(t, (x0 - std::sqrt(4 * kR * kR - h * h)) / v, kTimeTol) << h;
  }
}

TEST(DetectTest, GrazingPaths) {
  const double x0 = 0.7, v = 1.3;
  // Missing by 1e-7 m: no event. Overlapping by 1e-7 m: an event near the tangency.
  EXPECT_EQ(DetectBallBall(Path({0, 0}, {v, 0}), Path({x0, 2 * kR + 1e-7}), kR, 10.0), kInf);
  const double t = DetectBallBall(Path({0, 0}, {v, 0}), Path({x0, 2 * kR - 1e-7}), kR, 10.0);
  ASSERT_LT(t, kInf);
  const PositionPoly a = Path({0, 0}, {v, 0}), b = Path({x0, 2 * kR - 1e-7});
  EXPECT_NEAR(Dist(a, b, t), 2 * kR, kDistTol);
  EXPECT_NEAR(t, x0 / v, 1e-3);
  // Exactly tangent: either no event or the tangency itself; never an overlap.
  const double g = DetectBallBall(Path({0, 0}, {v, 0}), Path({x0, 2 * kR}), kR, 10.0);
  if (g < kInf) {
    EXPECT_NEAR(g, x0 / v, 1e-6);
  }
}

TEST(DetectTest, AlreadyTouching) {
  const PositionPoly still = Path({0, 2 * kR});
  // Approaching: event now; separating: none; resting together: none.
  EXPECT_EQ(DetectBallBall(Path({0, 0}, {0, 1}), still, kR, 1.0), 0.0);
  EXPECT_EQ(DetectBallBall(Path({0, 0}, {0, -1}), still, kR, 1.0), kInf);
  EXPECT_EQ(DetectBallBall(Path({0, 0}), still, kR, 1.0), kInf);
  // Sliding past each other tangentially: none.
  EXPECT_EQ(DetectBallBall(Path({0, 0}, {1, 0}), still, kR, 1.0), kInf);
  // Tangential but accelerating into each other faster than the relative path curves
  // away (g''(0) = 2 (0.1^2 - 4R * 1) < 0): it would overlap at once.
  EXPECT_EQ(DetectBallBall(Path({0, 0}, {0.1, 0}, {0, 1}), still, kR, 1.0), 0.0);
  // Tangential at 1 m/s, the same pull: the path curves away, no overlap.
  EXPECT_EQ(DetectBallBall(Path({0, 0}, {1, 0}, {0, 1}), still, kR, 1.0), kInf);
  // Separating, then pulled back by the acceleration: y(t) = -t + t^2 returns to 0 at
  // t = 1, moving towards the other ball.
  EXPECT_NEAR(DetectBallBall(Path({0, 0}, {0, -1}, {0, 1}), still, kR, 2.0), 1.0, kTimeTol);
  // Within the touching tolerance counts as touching.
  EXPECT_EQ(DetectBallBall(Path({0, -0.5 * kContactTolerance}, {0, 1}), still, kR, 1.0), 0.0);
}

TEST(DetectTest, ZeroAndBadTimeLimits) {
  const PositionPoly still = Path({0, 2 * kR});
  EXPECT_EQ(DetectBallBall(Path({0, 0}, {0, 1}), still, kR, 0.0), 0.0);
  EXPECT_EQ(DetectBallBall(Path({0, -1}, {0, 1}), still, kR, 0.0), kInf);
  EXPECT_EQ(DetectBallBall(Path({0, 0}, {0, 1}), still, kR, -1.0), kInf);
  EXPECT_EQ(DetectBallBall(Path({0, 0}, {0, 1}), still, kR, NAN), kInf);
  // No time limit: the polynomial's root bound stands in.
  EXPECT_NEAR(DetectBallBall(Path({0, -1}, {0, 1}), still, kR, kInf), 1.0, kTimeTol);
}

// Random pairs on curved (decelerating, sliding) paths against a fine time scan:
// never later than the first scanned overlap, the distance right at the returned
// time, and no overlap before it.
TEST(DetectTest, BallBallAgreesWithBruteForceScan) {
  std::mt19937_64 rng(1234);
  std::uniform_real_distribution<double> u(-1.0, 1.0), tm(0.2, 2.0);
  const double half_decel = 0.5 * ClothParams().mu_s * ClothParams().g;
  int events = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const PositionPoly a = Path({0.5 * u(rng), 0.5 * u(rng)}, {3 * u(rng), 3 * u(rng)},
                                {half_decel * u(rng), half_decel * u(rng)});
    // Aim b roughly at where a will be at t = 0.5 s, so that many trials collide.
    const Vec2 bc(0.5 * u(rng), 0.5 * u(rng));
    const PositionPoly b = Path(bc, 2.0 * (a.At(0.5) - bc) + 0.3 * Vec2(u(rng), u(rng)),
                                {half_decel * u(rng), half_decel * u(rng)});
    if (Dist(a, b, 0) <= 2 * kR) continue;  // starts overlapping: not a valid input
    const double t_max = tm(rng);
    const double t = DetectBallBall(a, b, kR, t_max);
    double scan = kInf;
    for (double s = kScanStep; s <= t_max; s += kScanStep) {
      if (Dist(a, b, s) < 2 * kR) {
        scan = s;
        break;
      }
    }
    if (scan < kInf) {
      ++events;
      ASSERT_LE(t, scan) << "trial " << trial;
    }
    if (t == kInf) continue;
    ASSERT_LE(t, t_max);
    EXPECT_NEAR(Dist(a, b, t), 2 * kR, kDistTol) << "trial " << trial;
    for (double s = 0; s < t; s += kScanStep) {
      ASSERT_GE(Dist(a, b, s), 2 * kR - kDistTol) << "trial " << trial << " at " << s;
    }
  }
  EXPECT_GT(events, 400);
}

TEST(DetectTest, CushionHeadOnAndDecelerating) {
  const TableModel table;
  const CushionSegment& baulk = table.segments()[0];
  ASSERT_STREQ(baulk.name, "baulk");
  EXPECT_NEAR(DetectBallCushion(Path({0.9, 0.5}, {0, -2}), baulk, kR, 10.0), (0.5 - kR) / 2,
              kTimeTol);
  // Decelerating: 0.5 - R = v t - d t^2 / 2.
  const double v = 1.5, d = 2.0, s = 0.5 - kR;
  EXPECT_NEAR(DetectBallCushion(Path({0.9, 0.5}, {0, -v}, {0, d / 2}), baulk, kR, 10.0),
              (v - std::sqrt(v * v - 2 * d * s)) / d, kTimeTol);
  // A smaller contact distance (raised nose) gives a later contact.
  const double c = 0.024;
  EXPECT_NEAR(DetectBallCushion(Path({0.9, 0.5}, {0, -2}), baulk, c, 10.0), (0.5 - c) / 2,
              kTimeTol);
  // Moving parallel to it or away from it: none.
  EXPECT_EQ(DetectBallCushion(Path({0.9, 0.5}, {1, 0}), baulk, kR, 10.0), kInf);
  EXPECT_EQ(DetectBallCushion(Path({0.9, 0.5}, {0, 1}), baulk, kR, 10.0), kInf);
}

TEST(DetectTest, CushionContactMustLieOnTheSegment) {
  const TableModel table;
  const CushionSegment& baulk = table.segments()[0];
  // Heading into the baulk-left pocket mouth, beyond the nose's end: not this nose.
  const Vec2 mouth = table.pocket(PocketId::kBaulkLeft).mouth_centre;
  const Vec2 start(mouth.x(), 0.4);
  EXPECT_EQ(DetectBallCushion(Path(start, {0, -1}), baulk, kR, 10.0), kInf);
  // From behind the line (inside the pocket) towards it: not a contact.
  EXPECT_EQ(DetectBallCushion(Path({0.9, -0.1}, {0, 1}), baulk, kR, 0.05), kInf);
  // Touching and approaching: now; touching and leaving: none.
  EXPECT_EQ(DetectBallCushion(Path({0.9, kR}, {0.3, -1}), baulk, kR, 1.0), 0.0);
  EXPECT_EQ(DetectBallCushion(Path({0.9, kR}, {0.3, 1}), baulk, kR, 1.0), kInf);
  EXPECT_EQ(DetectBallCushion(Path({0.9, kR}, {0.3, 0}), baulk, kR, 1.0), kInf);
}

TEST(DetectTest, JawHeadOnAndPocketEntry) {
  const TableModel table;
  const JawCircle& jaw = table.jaws()[0];
  const Vec2 start = jaw.centre + Vec2(0.3, 0.4);  // 0.5 m away
  const Vec2 dir = (jaw.centre - start).normalized();
  EXPECT_NEAR(DetectBallJaw(Path(start, 2 * dir), jaw, kR, 10.0), (0.5 - kR - jaw.radius) / 2,
              kTimeTol);
  EXPECT_EQ(DetectBallJaw(Path(start, -2 * dir), jaw, kR, 10.0), kInf);

  const Pocket& p = table.pocket(PocketId::kMiddleRight);
  const Vec2 far = p.capture_centre - 0.6 * p.axis;
  EXPECT_NEAR(DetectBallPocket(Path(far, 1.5 * p.axis), p, 10.0),
              (0.6 - p.capture_radius) / 1.5, kTimeTol);
  EXPECT_EQ(DetectBallPocket(Path(far, -1.5 * p.axis), p, 10.0), kInf);
  EXPECT_EQ(DetectBallPocket(Path(p.capture_centre), p, 10.0), 0.0);  // already in
  EXPECT_EQ(DetectBallPocket(Path(far), p, 10.0), kInf);              // at rest
}

// Random straight and curved paths against every cushion, knuckle and pocket of the
// table, compared with a fine scan of the gap (contact distance and segment extent).
TEST(DetectTest, BoundaryDetectorsAgreeWithBruteForceScan) {
  const TableModel table;
  std::mt19937_64 rng(8080);
  std::uniform_real_distribution<double> u(-1.0, 1.0), ux(kR, 1.778 - kR), uy(kR, 3.569 - kR);
  const double half_decel = 0.5 * ClothParams().mu_s * ClothParams().g;
  const double t_max = 1.0;
  int events = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const PositionPoly p = Path({ux(rng), uy(rng)}, {4 * u(rng), 4 * u(rng)},
                                {half_decel * u(rng), half_decel * u(rng)});
    for (const JawCircle& j : table.jaws()) {
      const double contact = kR + j.radius;
      const double t = DetectBallJaw(p, j, kR, t_max);
      double scan = kInf;
      for (double s = kScanStep; s <= t_max && scan == kInf; s += kScanStep) {
        if ((p.At(s) - j.centre).norm() < contact) scan = s;
      }
      if (scan < kInf) ++events;
      ASSERT_LE(t, scan);
      if (t < kInf) {
        EXPECT_NEAR((p.At(t) - j.centre).norm(), contact, kDistTol);
      }
    }
    for (const CushionSegment& c : table.segments()) {
      if (c.kind != SegmentKind::kCushion) continue;
      const Vec2 along = (c.p1 - c.p0).normalized();
      const double len = (c.p1 - c.p0).norm();
      const double t = DetectBallCushion(p, c, kR, t_max);
      // A contact is the gap turning negative between samples, from the playing
      // side, with the centre's projection on the segment.
      double scan = kInf;
      bool was_apart = (p.c - c.p0).dot(c.normal) >= kR;
      for (double s = kScanStep; s <= t_max && scan == kInf; s += kScanStep) {
        const Vec2 q = p.At(s) - c.p0;
        const double x = q.dot(along);
        const bool apart = q.dot(c.normal) >= kR;
        if (was_apart && !apart && x >= 0 && x <= len) scan = s;
        was_apart = apart;
      }
      if (scan < kInf) ++events;
      ASSERT_LE(t, scan) << c.name << " trial " << trial;
      if (t < kInf) {
        EXPECT_NEAR((p.At(t) - c.p0).dot(c.normal), kR, kDistTol);
      }
    }
  }
  EXPECT_GT(events, 50);
}

TEST(DetectTest, TransitionWithinTheLimitOnly) {
  const BallParams ball;
  const ClothParams cloth;
  BallState s;
  s.v = Vec3(1, 0, 0);
  s.s = MotionState::kSliding;
  const double t = TransitionTime(s, ball, cloth);
  EXPECT_EQ(DetectTransition(s, ball, cloth, 10.0), t);
  EXPECT_EQ(DetectTransition(s, ball, cloth, t), t);
  EXPECT_EQ(DetectTransition(s, ball, cloth, 0.5 * t), kInf);
  EXPECT_EQ(DetectTransition(BallState{}, ball, cloth, 10.0), kInf);  // stationary
  EXPECT_EQ(DetectTransition(s, ball, cloth, NAN), kInf);
}

}  // namespace
}  // namespace snooker::physics

namespace snooker::physics {
namespace {

// How a touching contact starts: the four classes of ClassifyContact.
TEST(ContactTest, ClassifiesTouchingContacts) {
  const PositionPoly still = Path({0, 2 * kR});
  // Apart: more than the contact tolerance away, whatever the motion.
  EXPECT_EQ(ClassifyContact(BallBallGap(Path({0, -1e-6}, {0, 1}), still, kR).g, 4 * kR),
            ContactStart::kApart);
  // Approaching faster than the tolerance.
  EXPECT_EQ(ClassifyContact(BallBallGap(Path({0, 0}, {0, 1e-6}), still, kR).g, 4 * kR),
            ContactStart::kApproaching);
  // No normal speed, decelerating into the other: pressing.
  EXPECT_EQ(ClassifyContact(BallBallGap(Path({0, 0}, {0, 0}, {0, 0.5}), still, kR).g, 4 * kR),
            ContactStart::kPressing);
  // Below the acceleration tolerance, or moving along the tangent: touching.
  EXPECT_EQ(ClassifyContact(BallBallGap(Path({0, 0}, {0, 0}, {0, 1e-12}), still, kR).g, 4 * kR),
            ContactStart::kTouching);
  EXPECT_EQ(ClassifyContact(BallBallGap(Path({0, 0}, {1, 0}), still, kR).g, 4 * kR),
            ContactStart::kTouching);
  // Separating.
  EXPECT_EQ(ClassifyContact(BallBallGap(Path({0, 0}, {0, -1e-3}), still, kR).g, 4 * kR),
            ContactStart::kTouching);
}

// A ball rolling along a cushion it touches, its gap zero to rounding, makes no
// event however long it rolls; one frozen to the cushion and rolling away makes
// none either.
TEST(ContactTest, RollingAlongACushionIsNoEvent) {
  const CushionSegment seg{{0, 0}, {0, 3}, {1, 0}, SegmentKind::kCushion, PocketId::kBaulkLeft, "left"};
  const double c = 0.02437211521390788;
  // Heading 90 deg from rounded trigonometry: a normal speed of 6e-17 m/s.
  const Vec2 dir(std::cos(kPi / 2), std::sin(kPi / 2));
  const double decel = 0.5 * 0.0128 * 9.81;
  EXPECT_EQ(DetectBallCushion(Path({c, 0.5}, dir, -decel * dir), seg, c, 8.0), kInf);
  EXPECT_EQ(DetectBallCushion(Path({c, 0.5}, -dir, decel * dir), seg, c, 8.0), kInf);
  EXPECT_EQ(DetectBallCushion(Path({c, 0.5}, {0.3, 0.5}), seg, c, 8.0), kInf);
}

// A pair that parts slowly and is brought back by its decelerations makes contact
// again (a search that missed it would let the two overlap).
TEST(ContactTest, SlowPartingThatTurnsRoundIsFound) {
  const PositionPoly still = Path({0, 2 * kR});
  const CushionSegment seg{{0, -1}, {0, 1}, {1, 0}, SegmentKind::kCushion, PocketId::kBaulkLeft, "left"};
  // Parting at 1e-6 m/s against a pull of 0.1 m/s^2: y(t) = -1e-6 t + 0.05 t^2 never
  // opens beyond the contact band (5e-12 m), so the contact begins where the two
  // start to approach faster than twice the speed tolerance.
  const PositionPoly back = Path({0, 0}, {0, -1e-6}, {0, 0.05});
  ASSERT_EQ(ClassifyContact(BallBallGap(back, still, kR).g, 4 * kR), ContactStart::kTouching);
  const double turn = (1e-6 + 2 * kApproachSpeedTolerance) / 0.1;
  EXPECT_NEAR(DetectBallBall(back, still, kR, 1.0), turn, kTimeTol);
  EXPECT_NEAR(DetectBallCushion(Path({kR, 0}, {1e-6, 0}, {-0.05, 0}), seg, kR, 1.0), turn, kTimeTol);
  // Parting at 1e-3 m/s: the gap opens to 5e-6 m and closes again at t = 0.02 s.
  const PositionPoly far = Path({0, 0}, {0, -1e-3}, {0, 0.05});
  const double t = DetectBallBall(far, still, kR, 1.0);
  EXPECT_NEAR(t, 0.02, 1e-9);
  EXPECT_LE(std::abs(2 * kR - Dist(far, still, t)), kDistTol);
  EXPECT_NEAR(DetectBallCushion(Path({kR, 0}, {1e-3, 0}, {-0.05, 0}), seg, kR, 1.0), 0.02, 1e-9);
}

}  // namespace
}  // namespace snooker::physics
