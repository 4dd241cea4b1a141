// SPDX-License-Identifier: MIT
// Path semantics of the dynamic penetration depth, and how to leave them. A cube
// that jumps from x = 3 to x = -5 past another (unit cubes) went through
// it: the proxy stops at the first contact, so the pair reports a depth of 6 for as
// long as the cube stays there, though it ends 4 units clear. That is the manual's
// "nothing passes through"; a caller that means a teleport resets the proxies
// (Scene::teleportGroup, PairTracker::reset, or in sc.h the group set INACTIVE and
// back), and the pair then reports the distance at the new pose, +4. Or it states
// once how far a path goes (PairSettings::teleport_distance): a longer motion in one
// update is a teleport.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "sc.h"
#include "smartcollision/collision.h"
#include "smartcollision/scene.h"
#include "support/sc_results.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

Placement at(double x) {
  Placement p;
  p.world_center = Vec3(x, 0, 0);
  return p;
}

/// Two moving groups (0 jumps, 1 stays at the origin), both directions computed.
struct JumpScene {
  JumpScene() : scene(ModelKind::ClosedPolyhedron) {
    const ModelPtr box = boxModel(Vec3(0.5, 0.5, 0.5));
    EXPECT_TRUE(scene.addObject(1, box, at(3.0)).ok());
    EXPECT_TRUE(scene.addObject(2, box, at(0.0)).ok());
    EXPECT_TRUE(scene.addObjectToGroup(0, 1).ok());
    EXPECT_TRUE(scene.addObjectToGroup(1, 2).ok());
    EXPECT_TRUE(scene.update().ok());
    EXPECT_NEAR(distance(0), 2.0, 1e-12);
  }
  double distance(int direction) const {
    EXPECT_EQ(scene.pairs().size(), 1u);
    const DirectedResult& r = scene.pairs()[0].results[direction];
    EXPECT_EQ(r.code, ErrorCode::Ok);
    return r.distance;
  }
  Scene scene;
};

TEST(Teleport, AJumpThroughKeepsThePathDepth) {
  JumpScene s;
  ASSERT_TRUE(s.scene.setGroupPlacement(0, at(-5.0)).ok());
  for (int frame = 0; frame < 3; ++frame) {
    ASSERT_TRUE(s.scene.update().ok());
    EXPECT_NEAR(s.distance(0), -6.0, 1e-3) << "frame " << frame;
    EXPECT_NEAR(s.distance(1), -6.0, 1e-3) << "frame " << frame;
  }
}

TEST(Teleport, SceneTeleportGroupResetsTheProxies) {
  JumpScene s;
  ASSERT_TRUE(s.scene.teleportGroup(0, at(-5.0)).ok());
  ASSERT_TRUE(s.scene.update().ok());
  EXPECT_NEAR(s.distance(0), 4.0, 1e-12);
  EXPECT_NEAR(s.distance(1), 4.0, 1e-12);
  // Back the same way, by teleport too (a path back would pass through again).
  ASSERT_TRUE(s.scene.teleportGroup(0, at(3.0)).ok());
  ASSERT_TRUE(s.scene.update().ok());
  EXPECT_NEAR(s.distance(0), 2.0, 1e-12);
  // After a jump that went through, a teleport to where the group already is resets.
  ASSERT_TRUE(s.scene.setGroupPlacement(0, at(-5.0)).ok());
  ASSERT_TRUE(s.scene.update().ok());
  ASSERT_NEAR(s.distance(0), -6.0, 1e-3);
  ASSERT_TRUE(s.scene.teleportGroup(0, s.scene.groupPlacement(0).value()).ok());
  ASSERT_TRUE(s.scene.update().ok());
  EXPECT_NEAR(s.distance(0), 4.0, 1e-12);
  EXPECT_NEAR(s.distance(1), 4.0, 1e-12);
}

TEST(Teleport, TeleportGroupRefusesWhatSetGroupPlacementRefuses) {
  JumpScene s;
  EXPECT_EQ(s.scene.teleportGroup(kStaticGroup, at(0.0)).code(), ErrorCode::InvalidOperation);
  EXPECT_EQ(s.scene.teleportGroup(9, at(0.0)).code(), ErrorCode::InvalidId);
  Placement bad = at(0.0);
  bad.orientation = Quat(0, 0, 0, 0);
  EXPECT_EQ(s.scene.teleportGroup(0, bad).code(), ErrorCode::InvalidArgument);
  // Refused calls change nothing: the group is still at x = 3 and tracked.
  EXPECT_EQ(s.scene.groupPlacement(0).value().world_center, Vec3(3, 0, 0));
  ASSERT_TRUE(s.scene.setGroupPlacement(0, at(-5.0)).ok());
  ASSERT_TRUE(s.scene.update().ok());
  EXPECT_NEAR(s.distance(0), -6.0, 1e-3);
}

TEST(Teleport, TeleportIntoAnotherGroupStartsAsAFirstSight) {
  JumpScene s;
  ASSERT_TRUE(s.scene.teleportGroup(0, at(0.5)).ok());
  ASSERT_TRUE(s.scene.update().ok());
  EXPECT_EQ(s.scene.pairs()[0].results[0].code, ErrorCode::InvalidInitialTransformation);
}

TEST(Teleport, PairTrackerResetForgetsBothDirections) {
  const ModelPtr box = boxModel(Vec3(0.5, 0.5, 0.5));
  const Part a{box.get(), Rigid(), 1}, b{box.get(), Rigid(), 2};
  PairTracker tracker;
  DirectedResult out[2];
  tracker.update({&a, 1, at(3.0)}, {&b, 1, at(0.0)}, {true, true}, SceneSettings(), out);
  ASSERT_NEAR(out[0].distance, 2.0, 1e-12);
  tracker.update({&a, 1, at(-5.0)}, {&b, 1, at(0.0)}, {true, true}, SceneSettings(), out);
  ASSERT_NEAR(out[0].distance, -6.0, 1e-3);
  tracker.reset();
  EXPECT_FALSE(tracker.tracking(0));
  EXPECT_FALSE(tracker.tracking(1));
  tracker.update({&a, 1, at(-5.0)}, {&b, 1, at(0.0)}, {true, true}, SceneSettings(), out);
  EXPECT_NEAR(out[0].distance, 4.0, 1e-12);
  EXPECT_NEAR(out[1].distance, 4.0, 1e-12);
}

TEST(Teleport, AMotionBeyondTheTeleportDistanceStartsAsAFirstSight) {
  JumpScene s;
  SceneSettings settings;
  settings.teleport_distance = 7.9;  // the jump of 8 is a teleport; 7.9 is still a path
  ASSERT_TRUE(s.scene.setSettings(settings).ok());
  ASSERT_TRUE(s.scene.setGroupPlacement(0, at(-5.0)).ok());
  ASSERT_TRUE(s.scene.update().ok());
  EXPECT_NEAR(s.distance(0), 4.0, 1e-12);
  EXPECT_NEAR(s.distance(1), 4.0, 1e-12);
  // A path again: 7.9 back through the other cube stops at its first contact, x = -1.
  ASSERT_TRUE(s.scene.setGroupPlacement(0, at(2.9)).ok());
  ASSERT_TRUE(s.scene.update().ok());
  EXPECT_NEAR(s.distance(0), -3.9, 1e-3);
  ASSERT_TRUE(s.scene.setGroupPlacement(0, at(8.5)).ok());  // 5.6 on: still behind it
  ASSERT_TRUE(s.scene.update().ok());
  EXPECT_NEAR(s.distance(0), -9.5, 1e-3);
  // 8 into the other cube: first seen intersecting, as a fresh tracker says.
  ASSERT_TRUE(s.scene.setGroupPlacement(0, at(0.5)).ok());
  ASSERT_TRUE(s.scene.update().ok());
  EXPECT_EQ(s.scene.pairs()[0].results[0].code, ErrorCode::InvalidInitialTransformation);
  EXPECT_EQ(s.scene.pairs()[0].results[1].code, ErrorCode::InvalidInitialTransformation);
}

TEST(Teleport, TeleportDistanceOutOfRangeIsRefusedAndChangesNothing) {
  JumpScene s;
  for (const double bad : {0.0, -1.0, std::nan("")}) {
    SceneSettings settings;
    settings.teleport_distance = bad;
    EXPECT_EQ(validate(static_cast<const PairSettings&>(settings)).code(),
              ErrorCode::InvalidArgument);
    EXPECT_EQ(s.scene.setSettings(settings).code(), ErrorCode::InvalidArgument);
  }
  EXPECT_EQ(s.scene.settings().teleport_distance, kInfinity);
  ASSERT_TRUE(s.scene.setGroupPlacement(0, at(-5.0)).ok());
  ASSERT_TRUE(s.scene.update().ok());
  EXPECT_NEAR(s.distance(0), -6.0, 1e-3);
}

/// sc.h: the same jump through the manual's calls.
TEST(Teleport, ScApiInactiveThenActiveResetsEveryDirection) {
  const MeshData mesh = boxMesh(Vec3(0.5, 0.5, 0.5));
  std::vector<double> xyz;
  for (const Vec3& v : mesh.vertices) xyz.insert(xyz.end(), {v.x(), v.y(), v.z()});
  std::vector<int> ids;
  for (const Tri& t : mesh.triangles) ids.insert(ids.end(), {t[0], t[1], t[2]});
  SCObject jumper(SC_OBJECT_TYPE_CLOSED_POLYHEDRON), other(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  for (SCObject* o : {&jumper, &other}) {
    ASSERT_EQ(o->AddTriangles(xyz.data(), static_cast<int>(mesh.vertices.size()), ids.data(),
                              static_cast<int>(mesh.triangles.size())),
              SC_NO_ERROR);
  }
  SCSceneManager scene(SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
  ASSERT_EQ(scene.AddObject(1, &jumper), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObject(2, &other), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObjectToGroup(0, 1), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObjectToGroup(1, 2), SC_NO_ERROR);
  auto distances = [&scene](double expected, double tolerance) {
    ASSERT_EQ(scene.UpdateStatus(), SC_NO_ERROR);
    for (const bool reverse : {false, true}) {
      double d = 0.0;
      ASSERT_EQ(scene.GetStatus(SC_DISTANCE, &d, 0, reverse), SC_NO_ERROR);
      EXPECT_NEAR(d, expected, tolerance) << "reverse " << reverse;
    }
  };
  const double start[3] = {3, 0, 0}, end[3] = {-5, 0, 0};
  ASSERT_EQ(scene.SetTransformation(0, SC_POSITION_WORLD_CENTER, start), SC_NO_ERROR);
  ASSERT_NO_FATAL_FAILURE(distances(2.0, 1e-12));
  ASSERT_EQ(scene.SetTransformation(0, SC_POSITION_WORLD_CENTER, end), SC_NO_ERROR);
  ASSERT_NO_FATAL_FAILURE(distances(-6.0, 1e-3));
  // The teleport: the group leaves every pair for a moment, and so its proxies.
  ASSERT_EQ(scene.SetActivityGroup(0, SC_ACTIVITY_INACTIVE), SC_NO_ERROR);
  ASSERT_EQ(scene.SetActivityGroup(0, SC_ACTIVITY_ACTIVE), SC_NO_ERROR);
  ASSERT_NO_FATAL_FAILURE(distances(4.0, 1e-12));
  // Or the teleport distance: out of range refused, then the jump of 8 back is one.
  ASSERT_NO_FATAL_FAILURE(
      expectDoubleAttribute(scene, SC_SCENE_MANAGER_TELEPORT_DISTANCE, kInfinity, 0.0, 7.9));
  ASSERT_EQ(scene.SetTransformation(0, SC_POSITION_WORLD_CENTER, start), SC_NO_ERROR);
  ASSERT_NO_FATAL_FAILURE(distances(2.0, 1e-12));
}

}  // namespace
}  // namespace sc::test
