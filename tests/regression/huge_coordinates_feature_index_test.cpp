// SPDX-License-Identifier: MIT
// Found by fuzz_add_triangles: a soup whose one (degenerate) triangle lies about
// 4.5e279 from the origin is accepted, squared distances overflow to inf, and
// closestFeature
// (core/src/query/features.cpp) then indexes poly.original[-1] during UpdateStatus.
// Fixed: coordinates beyond 1e100 in magnitude are refused (mesh_validation).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "sc.h"
#include "support/sc_results.h"
#include "support/test_support.h"

namespace {

double fromBits(unsigned long long bits) {
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

TEST(HugeCoordinates, SoupNearDoubleMaxReportsFiniteOrRefuses) {
  sc::test::FpTrapsOff traps;  // the point of the test is what overflow leads to
  // The crash input's vertices (raw bits) and its single triangle (0, 0, 0).
  const double soup[] = {fromBits(0x01ff01ffff010105ull), fromBits(0xf9ff0100ffff01ffull),
                         fromBits(0x0020000000ffffffull), fromBits(0x080808fff8210028ull),
                         fromBits(0x0000000000005a1eull), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  ASSERT_LT(soup[1], -1e279);  // finite, so AddTriangles accepts it
  const SCint soup_tris[] = {0, 0, 0};
  const double tetra[] = {1, 1, 1, -1, -1, 1, -1, 1, -1, 1, -1, -1};
  const SCint tetra_tris[] = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};

  SCObject object(SC_OBJECT_TYPE_TRIANGLE_SOUP);
  if (object.AddTriangles(soup, 4, soup_tris, 1) != SC_NO_ERROR) {
    GTEST_SUCCEED() << "refusing such coordinates is a fix too";
    return;
  }
  SCObject other(SC_OBJECT_TYPE_TRIANGLE_SOUP);
  ASSERT_EQ(other.AddTriangles(tetra, 4, tetra_tris, 4), SC_NO_ERROR);

  SCSceneManager scene(SC_SCENE_MANAGER_TRIANGLE_SOUP);
  ASSERT_EQ(scene.AddObject(1, &object), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObject(2, &other), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObjectToGroup(1, 1), SC_NO_ERROR);
  ASSERT_EQ(scene.UpdateStatus(), SC_NO_ERROR);
  sc::test::forEachOkDirection(scene, [&](SCint i, bool reverse) {
    double distance = 0.0;
    SCint features[3] = {};
    ASSERT_EQ(scene.GetStatus(SC_DISTANCE, &distance, i, reverse), SC_NO_ERROR);
    ASSERT_EQ(scene.GetStatus(SC_FEATURE_ON_TARGET, features, i, reverse), SC_NO_ERROR);
    EXPECT_TRUE(std::isfinite(distance));
    EXPECT_GE(features[0], 0);
  });
}

}  // namespace
