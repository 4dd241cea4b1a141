// SPDX-License-Identifier: MIT
// A pair first seen touching, or overlapping by at most the tolerance (a body placed at
// rest on another), starts tracking and reports Touching; it reported
// InvalidInitialTransformation from an overlap or a gap below ~1e-11 of its size, so
// such a body could not be started. A deeper first overlap keeps that error.
// Ground truth: unit cubes (scaled) face on face, edge on face and vertex on face,
// whose touching heights are analytic.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sc.h"
#include "smartcollision/collision.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

/// A cube of side `scale` (the target) over another at the origin, in one contact.
struct Contact {
  const char* name;
  Quat orientation;
  Vec3 offset;          ///< sideways, in cube sides
  double touch_height;  ///< centre height at touching, in cube sides
};

std::vector<Contact> contacts() {
  const Vec3 diagonal = Vec3(1, 1, 1).normalized();
  return {
      {"face", Quat::Identity(), Vec3(0.25, 0.25, 0), 1.0},
      {"edge", Quat(Eigen::AngleAxisd(0.25 * kPi, Vec3::UnitX())), Vec3(0.1, 0, 0),
       0.5 + std::sqrt(0.5)},
      {"vertex", Quat::FromTwoVectors(diagonal, -Vec3::UnitZ()), Vec3(0.1, 0.2, 0),
       0.5 + 0.5 * std::sqrt(3.0)},
  };
}

struct Cubes {
  explicit Cubes(double s) : scale(s), cube(boxModel(Vec3::Constant(0.5 * s))) {
    settings.tolerance = 1e-3 * s;
  }
  /// The target with its centre `height` sides up (in `c`'s contact).
  Placement at(const Contact& c, double height) const {
    Placement p;
    p.world_center = scale * (c.offset + Vec3(0, 0, height));
    p.orientation = c.orientation;
    return p;
  }
  void update(const Placement& p) {
    tracker.update({&a, 1, p}, {&b, 1, Placement()}, {true, true}, settings, out);
  }

  double scale;
  ModelPtr cube;
  Part a{cube.get(), Rigid(), 1}, b{cube.get(), Rigid(), 2};
  SceneSettings settings;
  PairTracker tracker;
  DirectedResult out[2];
};

/// First-sight gaps (in tolerances; negative: overlaps) that start as Touching.
constexpr double kTouchingGaps[] = {1e-9, 0.0, -1e-9, -0.5, -0.99, 0.5};

TEST(FirstSeenTouching, WithinTheToleranceStartsTouching) {
  for (const double s : {1e-3, 1.0, 1e3}) {
    for (const Contact& c : contacts()) {
      for (const double gap : kTouchingGaps) {
        SCOPED_TRACE(::testing::Message()
                     << "scale " << s << ", " << c.name << ", gap " << gap << " tolerances");
        Cubes cubes(s);
        const double tol = cubes.settings.tolerance;
        const double height = c.touch_height + gap * 1e-3;
        cubes.update(cubes.at(c, height));
        for (int dir = 0; dir < 2; ++dir) {
          const DirectedResult& r = cubes.out[dir];
          ASSERT_EQ(r.code, ErrorCode::Ok) << "direction " << dir;
          EXPECT_EQ(r.status, DirectionStatus::Touching) << "direction " << dir;
          EXPECT_NEAR(r.distance, std::max(gap, 0.0) * tol, 1e-9 * s) << "direction " << dir;
          EXPECT_TRUE(r.tpdv.isZero(0.0));
          EXPECT_NEAR(std::abs(r.normal.z()), 1.0, 1e-6) << "the top face's normal";
          EXPECT_TRUE(cubes.tracker.tracking(dir));
        }
        // The proxy follows the path from there: the same pose again gives the overlap
        // as a tracked pair does, a deeper one its depth, a higher one the distance.
        cubes.update(cubes.at(c, height));
        ASSERT_EQ(cubes.out[0].code, ErrorCode::Ok);
        EXPECT_NEAR(cubes.out[0].distance, gap * tol, 1e-9 * s);
        cubes.update(cubes.at(c, c.touch_height - 0.1));
        ASSERT_EQ(cubes.out[0].code, ErrorCode::Ok);
        EXPECT_EQ(cubes.out[0].status, DirectionStatus::Penetrating);
        EXPECT_NEAR(cubes.out[0].distance, -0.1 * s, 1e-9 * s);
        EXPECT_NEAR(cubes.out[0].tpdv.z(), -0.1 * s, 1e-9 * s);
        cubes.update(cubes.at(c, c.touch_height + 0.5));
        ASSERT_EQ(cubes.out[0].code, ErrorCode::Ok);
        EXPECT_EQ(cubes.out[0].status, DirectionStatus::Separated);
        EXPECT_NEAR(cubes.out[0].distance, 0.5 * s, 1e-9 * s);
      }
    }
  }
}

TEST(FirstSeenTouching, DeeperThanTheToleranceKeepsTheManualsError) {
  for (const double s : {1e-3, 1.0, 1e3}) {
    for (const Contact& c : contacts()) {
      for (const double gap : {-1.5, -3.0, -100.0}) {
        SCOPED_TRACE(::testing::Message()
                     << "scale " << s << ", " << c.name << ", gap " << gap << " tolerances");
        Cubes cubes(s);
        cubes.update(cubes.at(c, c.touch_height + gap * 1e-3));
        for (int dir = 0; dir < 2; ++dir) {
          EXPECT_EQ(cubes.out[dir].code, ErrorCode::InvalidInitialTransformation);
          EXPECT_EQ(cubes.out[dir].status, DirectionStatus::FirstSeenIntersecting);
          EXPECT_FALSE(cubes.tracker.tracking(dir));
        }
      }
    }
  }
}

TEST(FirstSeenTouching, EveryRotationModeStartsTouching) {
  for (const RotationMode mode :
       {RotationMode::None, RotationMode::Input, RotationMode::Free, RotationMode::Mix}) {
    for (const Contact& c : contacts()) {
      SCOPED_TRACE(::testing::Message() << "mode " << static_cast<int>(mode) << ", " << c.name);
      Cubes cubes(1.0);
      cubes.settings.rotation_mode = mode;
      cubes.update(cubes.at(c, c.touch_height - 1e-12));
      ASSERT_EQ(cubes.out[0].code, ErrorCode::Ok);
      EXPECT_EQ(cubes.out[0].status, DirectionStatus::Touching);
      cubes.update(cubes.at(c, c.touch_height + 0.5));
      ASSERT_EQ(cubes.out[0].code, ErrorCode::Ok);
      EXPECT_NEAR(cubes.out[0].distance, 0.5, 1e-9);
    }
  }
}

TEST(FirstSeenTouching, AGroupOfTwoCubesRestingOnAnother) {
  // Two parts: not a convex pair, so the general path decides the first sight.
  Cubes cubes(1.0);
  Part parts[2] = {cubes.a, cubes.a};
  parts[1].group_from_model.translation = Vec3(1.0, 0, 0);
  parts[1].id = 3;
  for (const double gap : {0.0, -1e-12, -0.5e-3}) {
    PairTracker tracker;
    Placement p;
    p.world_center = Vec3(-0.2, 0.3, 1.0 + gap);
    tracker.update({parts, 2, p}, {&cubes.b, 1, Placement()}, {true, true}, cubes.settings,
                   cubes.out);
    for (int dir = 0; dir < 2; ++dir) {
      ASSERT_EQ(cubes.out[dir].code, ErrorCode::Ok) << gap;
      EXPECT_EQ(cubes.out[dir].status, DirectionStatus::Touching) << gap;
    }
    p.world_center.z() = 0.9;
    tracker.update({parts, 2, p}, {&cubes.b, 1, Placement()}, {true, true}, cubes.settings,
                   cubes.out);
    ASSERT_EQ(cubes.out[0].code, ErrorCode::Ok);
    EXPECT_NEAR(cubes.out[0].distance, -0.1, 1e-9) << gap;
  }
  PairTracker tracker;
  Placement deep;
  deep.world_center = Vec3(-0.2, 0.3, 0.99);
  tracker.update({parts, 2, deep}, {&cubes.b, 1, Placement()}, {true, true}, cubes.settings,
                 cubes.out);
  EXPECT_EQ(cubes.out[0].code, ErrorCode::InvalidInitialTransformation);
}

TEST(FirstSeenTouching, AReportedContactPoseFedBackAfterATeleportStarts) {
  // sc.h, as docs/api.md's teleport: INACTIVE, set the pose, ACTIVE.
  const double v[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  const int t[] = {0, 3, 2, 0, 2, 1, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                   3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
  SCSceneManager s(SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
  SCObject a(SC_OBJECT_TYPE_CLOSED_POLYHEDRON), b(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  ASSERT_EQ(a.AddTriangles(v, 8, t, 12), SC_NO_ERROR);
  ASSERT_EQ(b.AddTriangles(v, 8, t, 12), SC_NO_ERROR);
  ASSERT_EQ(s.AddObject(1, &a), SC_NO_ERROR);
  ASSERT_EQ(s.AddObject(2, &b), SC_NO_ERROR);
  ASSERT_EQ(s.AddObjectToGroup(0, 1), SC_NO_ERROR);
  for (const double z : {1.5, 0.8}) {
    const double origin[3] = {0.25, 0.25, z};
    ASSERT_EQ(s.SetTransformation(0, SC_POSITION_ORIGIN, origin), SC_NO_ERROR);
    ASSERT_EQ(s.UpdateStatus(), SC_NO_ERROR);
  }
  double position[3], orientation[4], distance = 0;
  ASSERT_EQ(s.GetStatus(SC_DISTANCE, &distance, 0, false), SC_NO_ERROR);
  ASSERT_NEAR(distance, -0.2, 1e-9);
  ASSERT_EQ(s.GetStatus(SC_CONTACT_POSITION, position, 0, false), SC_NO_ERROR);
  ASSERT_EQ(s.GetStatus(SC_CONTACT_ORIENTATION, orientation, 0, false), SC_NO_ERROR);
  ASSERT_EQ(s.SetActivityGroup(0, SC_ACTIVITY_INACTIVE), SC_NO_ERROR);
  ASSERT_EQ(s.SetTransformation(0, SC_ORIENTATION_QUATERNION, orientation), SC_NO_ERROR);
  ASSERT_EQ(s.SetTransformation(0, SC_POSITION_WORLD_CENTER, position), SC_NO_ERROR);
  ASSERT_EQ(s.SetActivityGroup(0, SC_ACTIVITY_ACTIVE), SC_NO_ERROR);
  ASSERT_EQ(s.UpdateStatus(), SC_NO_ERROR);
  SCint result = -1;
  ASSERT_EQ(s.GetStatus(SC_STATUS_RESULT, &result, 0, false), SC_NO_ERROR);
  EXPECT_EQ(result, SC_NO_ERROR) << SCGetErrorString(result);
  ASSERT_EQ(s.GetStatus(SC_DISTANCE, &distance, 0, false), SC_NO_ERROR);
  EXPECT_NEAR(distance, 0.0, 1e-9);
}

}  // namespace
}  // namespace sc::test
