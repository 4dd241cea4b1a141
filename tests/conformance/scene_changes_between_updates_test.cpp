// SPDX-License-Identifier: MIT
// Changes between two updates (docs/api.md, "Scene, groups and activities" and
// "Results"): the last update's results stay as they were until the next update,
// a removed object's included, in sc.h and in the modern Scene alike; and
// AddObjectToGroup on an object already in another group moves it there.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "cube.h"
#include "sc.h"
#include "smartcollision/scene.h"

namespace {

using sc_conformance::cubeVertices;
using sc_conformance::kCubeTriangles;

std::unique_ptr<SCObject> makeCube(double x, double y, double z) {
  auto o = std::make_unique<SCObject>(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  const std::vector<double> v = cubeVertices(x, y, z);
  EXPECT_EQ(o->AddTriangles(v.data(), 8, kCubeTriangles, 12), SC_NO_ERROR);
  return o;
}

/// Object 1 (group 0) one unit beside static object 2, and static object 3 far off.
struct TwoCubes {
  SCSceneManager manager{SC_SCENE_MANAGER_CLOSED_POLYHEDRA};
  std::unique_ptr<SCObject> o1 = makeCube(0.0, 0.0, 0.0);
  std::unique_ptr<SCObject> o2 = makeCube(2.0, 0.0, 0.0);
  std::unique_ptr<SCObject> o3 = makeCube(0.0, 9.0, 0.0);

  TwoCubes() {
    EXPECT_EQ(manager.AddObject(1, o1.get()), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObject(2, o2.get()), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObject(3, o3.get()), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObjectToGroup(0, 1), SC_NO_ERROR);
  }
  SCint count() {
    SCint n = -1;
    EXPECT_EQ(manager.GetStatus(SC_STATUS_COUNT, &n), SC_NO_ERROR);
    return n;
  }
  /// Group 0's origin to (x, 0, z); the static cube 2 spans x in [2, 3].
  void moveTo(double x, double z) {
    const double p[3] = {x, 0.0, z};
    EXPECT_EQ(manager.SetTransformation(0, SC_POSITION_ORIGIN, p), SC_NO_ERROR);
  }
};

TEST(SceneChangesBetweenUpdates, ScResultsOfARemovedObjectStayUntilTheNextUpdate) {
  TwoCubes s;
  ASSERT_EQ(s.manager.UpdateStatus(), SC_NO_ERROR);
  ASSERT_EQ(s.count(), 1);
  ASSERT_EQ(s.manager.DeleteObject(1), SC_NO_ERROR);
  // Still the last update's pair: group 0 (gone now) against the static group.
  ASSERT_EQ(s.count(), 1);
  SCint groups[2], objects[2];
  double distance = -1.0;
  ASSERT_EQ(s.manager.GetStatus(SC_GROUP_ID, groups, 0, false), SC_NO_ERROR);
  ASSERT_EQ(s.manager.GetStatus(SC_OBJECT_ID, objects, 0, false), SC_NO_ERROR);
  ASSERT_EQ(s.manager.GetStatus(SC_DISTANCE, &distance, 0, false), SC_NO_ERROR);
  EXPECT_EQ(groups[0], 0);
  EXPECT_EQ(groups[1], SC_GROUP_STATIC);
  EXPECT_EQ(objects[0], 1);
  EXPECT_EQ(objects[1], 2);
  EXPECT_NEAR(distance, 1.0, 1e-9);
  double origin[3];
  EXPECT_EQ(s.manager.GetTransformation(0, SC_POSITION_ORIGIN, origin), SC_ERROR_INVALID_ID);
  ASSERT_EQ(s.manager.UpdateStatus(), SC_NO_ERROR);
  EXPECT_EQ(s.count(), 0);
}

TEST(SceneChangesBetweenUpdates, SceneResultsOfARemovedObjectStayUntilTheNextUpdate) {
  const sc::ModelPtr cube = [] {
    sc::MeshData mesh;
    const std::vector<double> v = cubeVertices(0.0, 0.0, 0.0);
    for (int i = 0; i < 8; ++i) mesh.vertices.emplace_back(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    for (int t = 0; t < 12; ++t)
      mesh.triangles.push_back(
          {kCubeTriangles[3 * t], kCubeTriangles[3 * t + 1], kCubeTriangles[3 * t + 2]});
    auto piece = sc::buildPiece(sc::ModelKind::ClosedPolyhedron, mesh);
    EXPECT_TRUE(piece.ok());
    return std::make_shared<sc::Model>(sc::ModelKind::ClosedPolyhedron,
                                       std::vector<sc::PiecePtr>{piece.value()});
  }();
  sc::Scene scene(sc::ModelKind::ClosedPolyhedron);
  sc::Placement beside;
  beside.world_center = sc::Vec3(2, 0, 0);
  ASSERT_TRUE(scene.addObject(1, cube, sc::Placement()).ok());
  ASSERT_TRUE(scene.addObject(2, cube, beside).ok());
  ASSERT_TRUE(scene.addObjectToGroup(0, 1).ok());
  ASSERT_TRUE(scene.update().ok());
  ASSERT_EQ(scene.pairs().size(), 1u);
  const sc::DirectedResult before = scene.pairs()[0].results[0];
  ASSERT_TRUE(scene.deleteObject(1).ok());
  EXPECT_FALSE(scene.hasGroup(0));
  ASSERT_EQ(scene.pairs().size(), 1u);
  EXPECT_EQ(scene.pairs()[0].groups[0], 0);
  EXPECT_EQ(scene.pairs()[0].results[0].code, sc::ErrorCode::Ok);
  EXPECT_EQ(scene.pairs()[0].results[0].distance, before.distance);
  EXPECT_EQ(scene.pairs()[0].results[0].target_object, 1);
  ASSERT_TRUE(scene.update().ok());
  EXPECT_TRUE(scene.pairs().empty());
}

TEST(SceneChangesBetweenUpdates, AddObjectToGroupMovesAnObjectFromAnotherGroup) {
  TwoCubes s;
  s.moveTo(0.0, 0.5);
  double before[16], after[16];
  ASSERT_EQ(s.o1->GetTransformation(SC_TRANSFORMATION_MATRIX, before), SC_NO_ERROR);
  ASSERT_EQ(s.manager.AddObjectToGroup(7, 1), SC_NO_ERROR);
  // It stays where it is, now in group 7 alone; group 0 lost its last object.
  ASSERT_EQ(s.o1->GetTransformation(SC_TRANSFORMATION_MATRIX, after), SC_NO_ERROR);
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(after[i], before[i], 1e-12) << i;
  double origin[3];
  EXPECT_EQ(s.manager.GetTransformation(0, SC_POSITION_ORIGIN, origin), SC_ERROR_INVALID_ID);
  EXPECT_EQ(s.manager.DeleteObjectFromGroup(0, 1), SC_ERROR_INVALID_ID);
  // Group 7 moves it now.
  const double up[3] = {0.0, 0.0, 2.0};
  ASSERT_EQ(s.manager.SetTransformation(7, SC_POSITION_ORIGIN, up), SC_NO_ERROR);
  ASSERT_EQ(s.o1->GetTransformation(SC_TRANSFORMATION_MATRIX, after), SC_NO_ERROR);
  EXPECT_NEAR(after[14], 2.0, 1e-12);
  ASSERT_EQ(s.manager.UpdateStatus(), SC_NO_ERROR);
  ASSERT_EQ(s.count(), 1);
  SCint groups[2];
  ASSERT_EQ(s.manager.GetStatus(SC_GROUP_ID, groups, 0, false), SC_NO_ERROR);
  EXPECT_EQ(groups[0], 7);
  EXPECT_EQ(s.manager.DeleteObjectFromGroup(7, 1), SC_NO_ERROR);
}

TEST(SceneChangesBetweenUpdates, AddObjectToGroupKeepsOrDropsTheTrackingState) {
  // Group 0 slides from apart into the static cube by 0.1: a depth, followed.
  for (const bool move : {false, true}) {
    SCOPED_TRACE(move ? "moved to group 7" : "added to its own group again");
    TwoCubes s;
    s.moveTo(0.5, 0.0);
    ASSERT_EQ(s.manager.UpdateStatus(), SC_NO_ERROR);
    s.moveTo(1.1, 0.0);
    ASSERT_EQ(s.manager.UpdateStatus(), SC_NO_ERROR);
    SCint result = -1;
    ASSERT_EQ(s.manager.GetStatus(SC_STATUS_RESULT, &result, 0, false), SC_NO_ERROR);
    ASSERT_EQ(result, SC_NO_ERROR);
    // Again into its own group: nothing changes. Into another: the object leaves its
    // pairs, and the new group's pair is first seen intersecting.
    ASSERT_EQ(s.manager.AddObjectToGroup(move ? 7 : 0, 1), SC_NO_ERROR);
    ASSERT_EQ(s.manager.UpdateStatus(), SC_NO_ERROR);
    ASSERT_EQ(s.manager.GetStatus(SC_STATUS_RESULT, &result, 0, false), SC_NO_ERROR);
    EXPECT_EQ(result, move ? SC_ERROR_INVALID_INITIAL_TRANSFORMATION : SC_NO_ERROR);
    double distance = 0.0;
    if (!move) {
      ASSERT_EQ(s.manager.GetStatus(SC_DISTANCE, &distance, 0, false), SC_NO_ERROR);
      EXPECT_NEAR(distance, -0.1, 1e-6);
    }
  }
}

}  // namespace
