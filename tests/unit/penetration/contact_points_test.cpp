// SPDX-License-Identifier: MIT
// PairTracker::contactPoints: one point per leaf pair within the margin at the
// contact configuration, carried to the current pose; the main one agrees with the
// result.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "sc_support/off_mesh.h"
#include "smartcollision/collision.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

Placement at(const Vec3& c) {
  Placement p;
  p.world_center = c;
  return p;
}

TEST(ContactPoints, LPrismOnASlabTouchesWithBothPatches) {
  auto prism = support::readOff(std::string(SC_TEST_DATA_DIR) + "/l_prism.off");
  ASSERT_TRUE(prism.ok());
  const ModelPtr l = closedModel(prism.value());
  ASSERT_EQ(l->pieces()[0]->stats().patches, 2);
  const ModelPtr slab = closedModel(boxMesh(Vec3(10, 10, 1)));
  const Part a{l.get(), Rigid(), 7}, b{slab.get(), Rigid(), 9};
  // Lowest point of the prism, so it can be set just above the slab's top (z = 1).
  const double bottom = l->bounds().min.z();
  SceneSettings settings;
  PairTracker tracker;
  DirectedResult out[2];
  tracker.update({&a, 1, at(Vec3(0, 0, 1.0 + 1e-4 - bottom))}, {&b, 1, at(Vec3::Zero())},
                 {true, false}, settings, out);
  ASSERT_EQ(out[0].code, ErrorCode::Ok);
  const Placement pressed = at(Vec3(0, 0, 1.0 - 0.01 - bottom));
  tracker.update({&a, 1, pressed}, {&b, 1, at(Vec3::Zero())}, {true, false}, settings, out);
  ASSERT_EQ(out[0].code, ErrorCode::Ok);
  ASSERT_NEAR(out[0].distance, -0.01, settings.tolerance);

  std::vector<ContactPoint> points;
  tracker.contactPoints(0, settings.tolerance, points);
  // The prism's flat bottom spans both convex patches: one point each.
  ASSERT_EQ(points.size(), 2u);
  for (const ContactPoint& p : points) {
    EXPECT_EQ(p.target_object, 7);
    EXPECT_EQ(p.opponent_object, 9);
    EXPECT_VEC_NEAR(p.normal, Vec3::UnitZ(), 1e-9);
    EXPECT_NEAR(p.separation, -0.01, settings.tolerance);
    EXPECT_NEAR(p.point_on_opponent.z(), 1.0, settings.tolerance);
    EXPECT_NEAR(p.point_on_target.z(), 1.0 - 0.01, settings.tolerance);
  }
  // Direction 1 was not computed: no points.
  tracker.contactPoints(1, settings.tolerance, points);
  EXPECT_TRUE(points.empty());
}

TEST(ContactPoints, ApartGivesTheClosestPairAndANegativeMarginNothing) {
  const ModelPtr box = closedModel(boxMesh(Vec3(1, 1, 1)));
  const Part a{box.get(), Rigid(), 1}, b{box.get(), Rigid(), 2};
  PairTracker tracker;
  DirectedResult out[2];
  tracker.update({&a, 1, at(Vec3(3, 0, 0))}, {&b, 1, at(Vec3::Zero())}, {true, true}, {}, out);
  std::vector<ContactPoint> points;
  tracker.contactPoints(1, 0.0, points);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_NEAR(points[0].separation, 1.0, 1e-12);
  EXPECT_VEC_NEAR(points[0].normal, -Vec3::UnitX(), 1e-12);
  tracker.contactPoints(1, -1.0, points);
  EXPECT_TRUE(points.empty());
}

/// Unit cubes: group a (the target of direction 0) at `top` over group b, a cube at
/// `bottom`. With `general`, a's group holds a second cube far to the side, so the
/// general path decides instead of the convex pair's.
struct TouchingCubes {
  explicit TouchingCubes(bool general) : count(general ? 2 : 1) {
    parts[1].group_from_model.translation = Vec3(3, 0, 0);
  }
  void update(const Placement& top, const Placement& bottom = Placement()) {
    tracker.update({parts, count, top}, {&floor, 1, bottom}, {true, true}, settings, out);
  }
  /// The points of direction `dir`, each checked against the touching contact: on
  /// the plane z = `plane`, target and opponent points together, the normal from the
  /// opponent to the target, `separation` the signed gap.
  std::vector<ContactPoint> touching(int dir, double plane, double separation) {
    std::vector<ContactPoint> points;
    tracker.contactPoints(dir, settings.tolerance, points);
    const Vec3 up = Vec3(0, 0, dir == 0 ? 1.0 : -1.0);
    for (const ContactPoint& p : points) {
      EXPECT_EQ(p.target_object, dir == 0 ? 1 : 2);
      EXPECT_EQ(p.opponent_object, dir == 0 ? 2 : 1);
      EXPECT_VEC_NEAR(p.normal, up, 1e-9);
      EXPECT_NEAR(p.separation, separation, 1e-9);
      EXPECT_NEAR(p.point_on_opponent.z(), plane, 1e-9);
      EXPECT_VEC_NEAR(p.point_on_target, p.point_on_opponent - separation * up, 1e-9);
    }
    return points;
  }

  ModelPtr cube = boxModel(Vec3::Constant(0.5));
  Part parts[2] = {{cube.get(), Rigid(), 1}, {cube.get(), Rigid(), 3}};
  Part floor{cube.get(), Rigid(), 2};
  int count;
  SceneSettings settings;
  PairTracker tracker;
  DirectedResult out[2];
};

Placement posed(const Vec3& c, const Quat& q) {
  Placement p = at(c);
  p.orientation = q;
  return p;
}

/// Gaps of a first sight that reports Touching: exact, and a rounding either side.
constexpr double kTouchingGaps[] = {0.0, 1e-12, -1e-12};

TEST(ContactPoints, FaceToFaceCubesTouchingGiveTheirPoint) {
  for (const bool general : {false, true}) {
    for (const double gap : kTouchingGaps) {
      SCOPED_TRACE(::testing::Message() << (general ? "general" : "convex") << ", gap " << gap);
      TouchingCubes cubes(general);
      cubes.update(at(Vec3(0.25, 0.25, 1.0 + gap)));
      for (int dir = 0; dir < 2; ++dir) {
        ASSERT_EQ(cubes.out[dir].status, DirectionStatus::Touching) << "direction " << dir;
        const std::vector<ContactPoint> points = cubes.touching(dir, 0.5, gap);
        ASSERT_EQ(points.size(), 1u) << "direction " << dir;
        // On the faces' overlap, the square [-0.25, 0.5]^2.
        const Vec3& p = points[0].point_on_opponent;
        EXPECT_TRUE(p.x() >= -0.25 - 1e-9 && p.x() <= 0.5 + 1e-9) << p.transpose();
        EXPECT_TRUE(p.y() >= -0.25 - 1e-9 && p.y() <= 0.5 + 1e-9) << p.transpose();
      }
    }
  }
}

TEST(ContactPoints, CubesTrackedIntoTouchingGiveTheirPoint) {
  for (const bool general : {false, true}) {
    for (const double gap : kTouchingGaps) {
      SCOPED_TRACE(::testing::Message() << (general ? "general" : "convex") << ", gap " << gap);
      TouchingCubes cubes(general);
      cubes.update(at(Vec3(0.25, 0.25, 1.5)));
      cubes.update(at(Vec3(0.25, 0.25, 1.0 + gap)));
      ASSERT_EQ(cubes.out[0].code, ErrorCode::Ok);
      EXPECT_EQ(cubes.touching(0, 0.5, gap).size(), 1u);
    }
  }
}

TEST(ContactPoints, EdgeOnEdgeTouchingGivesTheCrossing) {
  // The bottom cube's top edge runs along y, the top cube's bottom edge along x: they
  // cross at (0, 0, sqrt(1/2)).
  const double h = std::sqrt(0.5);
  const Quat along_y(Eigen::AngleAxisd(0.25 * kPi, Vec3::UnitY()));
  const Quat along_x(Eigen::AngleAxisd(0.25 * kPi, Vec3::UnitX()));
  for (const bool general : {false, true}) {
    for (const double gap : kTouchingGaps) {
      SCOPED_TRACE(::testing::Message() << (general ? "general" : "convex") << ", gap " << gap);
      TouchingCubes cubes(general);
      cubes.update(posed(Vec3(0, 0, 2 * h + gap), along_x), posed(Vec3::Zero(), along_y));
      for (int dir = 0; dir < 2; ++dir) {
        ASSERT_EQ(cubes.out[dir].status, DirectionStatus::Touching) << "direction " << dir;
        const std::vector<ContactPoint> points = cubes.touching(dir, h, gap);
        ASSERT_EQ(points.size(), 1u) << "direction " << dir;
        EXPECT_VEC_NEAR(points[0].point_on_opponent, Vec3(0, 0, h), 1e-9);
      }
    }
  }
}

TEST(ContactPoints, BoxOnABoxTurnedAQuarterRightAngleTouchesInTheOctagon) {
  // The faces meet in the regular octagon |x|, |y| <= 1/2, |x| + |y| <= sqrt(1/2). Two
  // convex pieces are one leaf pair: one point (documented), inside that polygon.
  const Quat turned(Eigen::AngleAxisd(0.25 * kPi, Vec3::UnitZ()));
  for (const bool general : {false, true}) {
    for (const double gap : kTouchingGaps) {
      SCOPED_TRACE(::testing::Message() << (general ? "general" : "convex") << ", gap " << gap);
      TouchingCubes cubes(general);
      cubes.update(posed(Vec3(0, 0, 1.0 + gap), turned));
      for (int dir = 0; dir < 2; ++dir) {
        ASSERT_EQ(cubes.out[dir].status, DirectionStatus::Touching) << "direction " << dir;
        const std::vector<ContactPoint> points = cubes.touching(dir, 0.5, gap);
        ASSERT_EQ(points.size(), 1u) << "direction " << dir;
        const Vec3& p = points[0].point_on_opponent;
        EXPECT_LE(std::max(std::abs(p.x()), std::abs(p.y())), 0.5 + 1e-9) << p.transpose();
        EXPECT_LE(std::abs(p.x()) + std::abs(p.y()), std::sqrt(0.5) + 1e-9) << p.transpose();
      }
    }
  }
}

TEST(ContactPoints, ABodyStartedAtItsReportedContactPoseTouches) {
  for (const bool general : {false, true}) {
    SCOPED_TRACE(general ? "general" : "convex");
    TouchingCubes pressed(general);
    pressed.update(at(Vec3(0.25, 0.25, 1.5)));
    pressed.update(at(Vec3(0.25, 0.25, 0.9)));
    ASSERT_EQ(pressed.out[0].status, DirectionStatus::Penetrating);
    const Placement contact =
        posed(pressed.out[0].contact_position, pressed.out[0].contact_orientation);
    TouchingCubes restarted(general);
    restarted.update(contact);
    ASSERT_EQ(restarted.out[0].code, ErrorCode::Ok);
    EXPECT_NE(restarted.out[0].status, DirectionStatus::FirstSeenIntersecting);
    std::vector<ContactPoint> points;
    restarted.tracker.contactPoints(0, restarted.settings.tolerance, points);
    ASSERT_EQ(points.size(), 1u);
    EXPECT_VEC_NEAR(points[0].normal, Vec3::UnitZ(), 1e-9);
    EXPECT_LE(std::abs(points[0].separation), restarted.settings.tolerance);
    EXPECT_NEAR(points[0].point_on_opponent.z(), 0.5, restarted.settings.tolerance);
  }
}

TEST(ContactPoints, ApartCubesKeepTheirClosestPairAndDeepOverlapsNone) {
  for (const bool general : {false, true}) {
    SCOPED_TRACE(general ? "general" : "convex");
    TouchingCubes apart(general);
    apart.update(at(Vec3(0.25, 0.25, 1.25)));
    ASSERT_EQ(apart.out[0].status, DirectionStatus::Separated);
    std::vector<ContactPoint> points;
    apart.tracker.contactPoints(0, apart.settings.tolerance, points);
    ASSERT_EQ(points.size(), 1u);
    EXPECT_EQ(points[0].separation, apart.out[0].distance);
    EXPECT_EQ(points[0].point_on_target, apart.out[0].point_on_target);
    EXPECT_EQ(points[0].point_on_opponent, apart.out[0].point_on_opponent);
    // First seen overlapping by 3/4 of the tolerance: Touching, but deeper than the
    // half-tolerance lift, so that leaf pair is left out (pair_tracker.h).
    TouchingCubes deep(general);
    deep.update(at(Vec3(0.25, 0.25, 1.0 - 0.75 * deep.settings.tolerance)));
    ASSERT_EQ(deep.out[0].status, DirectionStatus::Touching);
    deep.tracker.contactPoints(0, deep.settings.tolerance, points);
    EXPECT_TRUE(points.empty());
  }
}

}  // namespace
}  // namespace sc::test
