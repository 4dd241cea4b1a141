// SPDX-License-Identifier: MIT
// Found by fuzz_scene_api: a soup group placed at x = -1e300 was accepted (only
// non-finite placements were refused); moving it back near the origin then made
// the dynamic query's motion overflow, and UpdateStatus reported a distance of
// -inf. Fixed: placement centres are held to the vertex limit, 1e100, at every
// entry (SetTransformation of objects and groups, Scene::addObject and
// setGroupPlacement), so a placed model's coordinates never exceed 2e100.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "sc.h"
#include "support/sc_results.h"
#include "smartcollision/scene.h"

namespace {

const double kSquare[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const SCint kSquareTris[] = {0, 1, 2, 0, 2, 3};

void expectFiniteResults(SCSceneManager& scene) {
  sc::test::forEachOkDirection(scene, [&](SCint i, bool reverse) {
    double distance = 0.0;
    double tpdv[3] = {};
    ASSERT_EQ(scene.GetStatus(SC_DISTANCE, &distance, i, reverse), SC_NO_ERROR);
    ASSERT_EQ(scene.GetStatus(SC_TPD_VECTOR, tpdv, i, reverse), SC_NO_ERROR);
    EXPECT_TRUE(std::isfinite(distance)) << distance;
    EXPECT_GE(distance, 0.0);
    for (double c : tpdv) EXPECT_TRUE(std::isfinite(c));
  });
}

TEST(HugeGroupPosition, PositionsBeyondTheCoordinateLimitAreRefusedAndChangeNothing) {
  SCObject square(SC_OBJECT_TYPE_TRIANGLE_SOUP);
  ASSERT_EQ(square.AddTriangles(kSquare, 4, kSquareTris, 2), SC_NO_ERROR);
  SCSceneManager scene(SC_SCENE_MANAGER_TRIANGLE_SOUP);
  ASSERT_EQ(scene.AddObject(1, &square), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObjectToGroup(0, 1), SC_NO_ERROR);

  for (SCenum type : {SC_POSITION_ORIGIN, SC_POSITION_WORLD_CENTER, SC_POSITION_LOCAL_CENTER,
                      SC_POSITION_NEW_WORLD_CENTER, SC_POSITION_NEW_LOCAL_CENTER}) {
    const double far[3] = {-1e300, 0.0, 0.0};
    EXPECT_EQ(scene.SetTransformation(0, type, far), SC_ERROR_INVALID_ARGUMENT) << type;
    const double beyond[3] = {0.0, 2e100, 0.0};
    EXPECT_EQ(scene.SetTransformation(0, type, beyond), SC_ERROR_INVALID_ARGUMENT) << type;
  }
  double matrix[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1e300, 0, 0, 1};
  EXPECT_EQ(scene.SetTransformation(0, SC_TRANSFORMATION_MATRIX, matrix),
            SC_ERROR_INVALID_ARGUMENT);
  double center[3] = {1, 1, 1};
  ASSERT_EQ(scene.GetTransformation(0, SC_POSITION_WORLD_CENTER, center), SC_NO_ERROR);
  EXPECT_EQ(center[0], 0.0);  // unchanged by the refused calls
  EXPECT_EQ(center[1], 0.0);

  // The object's own placement has the same limit.
  SCObject other(SC_OBJECT_TYPE_TRIANGLE_SOUP);
  ASSERT_EQ(other.AddTriangles(kSquare, 4, kSquareTris, 2), SC_NO_ERROR);
  const double far[3] = {1e101, 0.0, 0.0};
  EXPECT_EQ(other.SetTransformation(SC_POSITION_WORLD_CENTER, far), SC_ERROR_INVALID_ARGUMENT);
}

TEST(HugeGroupPosition, FarthestAcceptedPositionThenBackGivesFiniteResults) {
  // The fuzz input's sequence, at the limit instead of beyond it.
  SCObject square(SC_OBJECT_TYPE_TRIANGLE_SOUP);
  SCObject other(SC_OBJECT_TYPE_TRIANGLE_SOUP);
  ASSERT_EQ(square.AddTriangles(kSquare, 4, kSquareTris, 2), SC_NO_ERROR);
  ASSERT_EQ(other.AddTriangles(kSquare, 4, kSquareTris, 2), SC_NO_ERROR);
  SCSceneManager scene(SC_SCENE_MANAGER_TRIANGLE_SOUP);
  ASSERT_EQ(scene.AddObject(1, &square), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObject(2, &other), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObjectToGroup(0, 1), SC_NO_ERROR);
  ASSERT_EQ(scene.SetAttributeDouble(SC_SCENE_MANAGER_MAX_DISTANCE, 1e300), SC_NO_ERROR);
  const double far[3] = {-1e100, -0.014, 0.015};
  ASSERT_EQ(scene.SetTransformation(0, SC_POSITION_WORLD_CENTER, far), SC_NO_ERROR);
  ASSERT_EQ(scene.UpdateStatus(), SC_NO_ERROR);
  expectFiniteResults(scene);
  const double back[3] = {0.625, 0.0, 0.0};
  ASSERT_EQ(scene.SetTransformation(0, SC_POSITION_WORLD_CENTER, back), SC_NO_ERROR);
  ASSERT_EQ(scene.UpdateStatus(), SC_NO_ERROR);
  expectFiniteResults(scene);
}

TEST(HugeGroupPosition, ModernApiRefusesPlacementsBeyondTheLimit) {
  sc::MeshData mesh;
  for (int i = 0; i < 4; ++i) mesh.vertices.emplace_back(kSquare[3 * i], kSquare[3 * i + 1], 0.0);
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  auto piece = sc::buildPiece(sc::ModelKind::TriangleSoup, mesh);
  ASSERT_TRUE(piece.ok());
  const auto model = std::make_shared<const sc::Model>(sc::ModelKind::TriangleSoup,
                                                       std::vector<sc::PiecePtr>{piece.value()});
  sc::Scene scene(sc::ModelKind::TriangleSoup);
  sc::Placement far;
  far.world_center = sc::Vec3(0.0, 0.0, 1e101);
  EXPECT_EQ(scene.addObject(1, model, far).code(), sc::ErrorCode::InvalidArgument);
  EXPECT_FALSE(scene.hasObject(1));
  ASSERT_TRUE(scene.addObject(1, model, sc::Placement{}).ok());
  ASSERT_TRUE(scene.addObjectToGroup(0, 1).ok());
  EXPECT_EQ(scene.setGroupPlacement(0, far).code(), sc::ErrorCode::InvalidArgument);
  EXPECT_EQ(scene.groupPlacement(0).value().world_center, sc::Vec3::Zero());
}

}  // namespace
