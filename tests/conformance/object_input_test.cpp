// SPDX-License-Identifier: MIT
// SCObject::AddTriangles through sc.h, in double and float: one test per class of bad
// input (docs/sc-api.md, SCObject), each showing through a scene that the object is
// unchanged; inside-out pieces, triangle soup, and piece ids in call order.
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cube.h"
#include "sc.h"

namespace {

using sc_conformance::cubeVertices;
using sc_conformance::kCubeTriangles;

// List 10-1: the unit-corner tetrahedron, outward winding.
const std::vector<double> kTetraVertices = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
const std::vector<int> kTetraTriangles = {0, 2, 1, 1, 3, 0, 0, 3, 2, 1, 2, 3};

template <class Real>
std::vector<Real> as(const std::vector<double>& v) {
  return std::vector<Real>(v.begin(), v.end());
}

template <class Real>
SCint add(SCObject& o, const std::vector<double>& vertices, const std::vector<int>& triangles) {
  const std::vector<Real> v = as<Real>(vertices);
  return o.AddTriangles(v.data(), static_cast<SCint>(v.size() / 3), triangles.data(),
                        static_cast<SCint>(triangles.size() / 3));
}

/// What two probe cubes (groups 0 and 1, both at gap 1) see of `o` as static object
/// 1: near its tetrahedron piece at the origin (probe at x in [-2,-1]) and near a cube
/// piece at x in [10,11] (probe at x in [12,13]). Per probe: piece ids and distance.
std::vector<double> probe(SCObject& o) {
  SCSceneManager scene(SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
  SCObject near_tetra(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  SCObject near_cube(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  const std::vector<double> a = cubeVertices(-2.0, 0.0, 0.0);
  const std::vector<double> b = cubeVertices(12.0, 0.0, 0.0);
  EXPECT_EQ(near_tetra.AddTriangles(a.data(), 8, kCubeTriangles, 12), SC_NO_ERROR);
  EXPECT_EQ(near_cube.AddTriangles(b.data(), 8, kCubeTriangles, 12), SC_NO_ERROR);
  EXPECT_EQ(scene.AddObject(1, &o), SC_NO_ERROR);
  EXPECT_EQ(scene.AddObject(2, &near_tetra), SC_NO_ERROR);
  EXPECT_EQ(scene.AddObject(3, &near_cube), SC_NO_ERROR);
  EXPECT_EQ(scene.AddObjectToGroup(0, 2), SC_NO_ERROR);
  EXPECT_EQ(scene.AddObjectToGroup(1, 3), SC_NO_ERROR);
  EXPECT_EQ(scene.UpdateStatus(), SC_NO_ERROR);
  std::vector<double> seen;
  SCint count = -1;
  EXPECT_EQ(scene.GetStatus(SC_STATUS_COUNT, &count), SC_NO_ERROR);
  for (int i = 0; i < count; ++i) {
    SCint g[2], p[2], r = -1;
    EXPECT_EQ(scene.GetStatus(SC_GROUP_ID, g, i, false), SC_NO_ERROR);
    if (g[1] != SC_GROUP_STATIC) continue;  // the probes among themselves
    EXPECT_EQ(scene.GetStatus(SC_STATUS_RESULT, &r, i, false), SC_NO_ERROR);
    if (r != SC_NO_ERROR) continue;
    double d = -1.0;
    EXPECT_EQ(scene.GetStatus(SC_PIECE_ID, p, i, false), SC_NO_ERROR);
    EXPECT_EQ(scene.GetStatus(SC_DISTANCE, &d, i, false), SC_NO_ERROR);
    seen.insert(seen.end(), {double(g[0]), double(p[0]), double(p[1]), d});
  }
  EXPECT_EQ(scene.DeleteObject(1), SC_NO_ERROR);  // `o` outlives this scene
  return seen;
}

/// Probe 0 sees piece 0 (the tetrahedron) and probe 1 sees piece 1, both at gap 1.
const std::vector<double> kExpectedProbe = {0, 0, 0, 1.0, 1, 0, 1, 1.0};

/// Adds the tetrahedron, lets `bad` try to add a piece, then adds the far cube. The
/// bad call must return `code`, and the object must look exactly like one that never
/// saw it: the far cube is still piece 1 and both pieces are where they were.
template <class Real, class Bad>
void expectRejected(SCint code, Bad bad) {
  SCObject reference(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  SCObject tested(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  for (SCObject* o : {&reference, &tested})
    ASSERT_EQ(add<Real>(*o, kTetraVertices, kTetraTriangles), SC_NO_ERROR);
  EXPECT_EQ(bad(tested), code);
  const std::vector<double> far = cubeVertices(10.0, 0.0, 0.0);
  const std::vector<int> cube(kCubeTriangles, kCubeTriangles + 36);
  for (SCObject* o : {&reference, &tested}) ASSERT_EQ(add<Real>(*o, far, cube), SC_NO_ERROR);
  const std::vector<double> seen = probe(tested);
  EXPECT_EQ(seen, probe(reference));
  ASSERT_EQ(seen.size(), kExpectedProbe.size());
  for (size_t i = 0; i < seen.size(); ++i) EXPECT_NEAR(seen[i], kExpectedProbe[i], 1e-9) << i;
}

/// `bad` adds these arrays as they are.
template <class Real>
void expectArraysRejected(SCint code, const std::vector<double>& vertices,
                          const std::vector<int>& triangles) {
  expectRejected<Real>(code, [&](SCObject& o) { return add<Real>(o, vertices, triangles); });
}

struct RealNames {
  template <class T>
  static std::string GetName(int) {
    return std::is_same_v<T, double> ? "Double" : "Float";
  }
};

template <class Real>
class AddTrianglesInput : public testing::Test {};
using Reals = testing::Types<double, float>;
TYPED_TEST_SUITE(AddTrianglesInput, Reals, RealNames);

TYPED_TEST(AddTrianglesInput, NaNCoordinateIsInvalidArgument) {
  for (int i = 0; i < 12; i += 5) {
    std::vector<double> v = kTetraVertices;
    v[i] = std::numeric_limits<double>::quiet_NaN();
    expectArraysRejected<TypeParam>(SC_ERROR_INVALID_ARGUMENT, v, kTetraTriangles);
  }
}

TYPED_TEST(AddTrianglesInput, InfiniteCoordinateIsInvalidArgument) {
  for (double inf : {std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity()}) {
    std::vector<double> v = kTetraVertices;
    v[7] = inf;
    expectArraysRejected<TypeParam>(SC_ERROR_INVALID_ARGUMENT, v, kTetraTriangles);
  }
}

TYPED_TEST(AddTrianglesInput, NegativeCountIsInvalidArgument) {
  const std::vector<TypeParam> v = as<TypeParam>(kTetraVertices);
  const int* t = kTetraTriangles.data();
  expectRejected<TypeParam>(SC_ERROR_INVALID_ARGUMENT,
                            [&](SCObject& o) { return o.AddTriangles(v.data(), -4, t, 4); });
  expectRejected<TypeParam>(SC_ERROR_INVALID_ARGUMENT,
                            [&](SCObject& o) { return o.AddTriangles(v.data(), 4, t, -1); });
  expectRejected<TypeParam>(SC_ERROR_INVALID_ARGUMENT,
                            [&](SCObject& o) { return o.AddTriangles(v.data(), -1, t, -1); });
}

TYPED_TEST(AddTrianglesInput, NullPointerWithNonZeroCountIsInvalidArgument) {
  const std::vector<TypeParam> v = as<TypeParam>(kTetraVertices);
  const TypeParam* no_vertices = nullptr;
  const int* t = kTetraTriangles.data();
  expectRejected<TypeParam>(SC_ERROR_INVALID_ARGUMENT,
                            [&](SCObject& o) { return o.AddTriangles(no_vertices, 4, t, 4); });
  expectRejected<TypeParam>(SC_ERROR_INVALID_ARGUMENT,
                            [&](SCObject& o) { return o.AddTriangles(v.data(), 4, nullptr, 4); });
}

TYPED_TEST(AddTrianglesInput, IndexOutOfRangeIsInvalidArgument) {
  for (int bad : {4, 5, 1 << 30}) {
    std::vector<int> t = kTetraTriangles;
    t[10] = bad;
    expectArraysRejected<TypeParam>(SC_ERROR_INVALID_ARGUMENT, kTetraVertices, t);
  }
  // In range of the array but beyond vertexCount.
  const std::vector<TypeParam> v = as<TypeParam>(kTetraVertices);
  expectRejected<TypeParam>(SC_ERROR_INVALID_ARGUMENT, [&](SCObject& o) {
    return o.AddTriangles(v.data(), 3, kTetraTriangles.data(), 4);
  });
}

TYPED_TEST(AddTrianglesInput, NegativeIndexIsInvalidArgument) {
  for (int bad : {-1, std::numeric_limits<int>::min()}) {
    std::vector<int> t = kTetraTriangles;
    t[4] = bad;
    expectArraysRejected<TypeParam>(SC_ERROR_INVALID_ARGUMENT, kTetraVertices, t);
  }
}

TYPED_TEST(AddTrianglesInput, OpenMeshIsInvalidGeometry) {
  const std::vector<int> three_faces(kTetraTriangles.begin(), kTetraTriangles.begin() + 9);
  expectArraysRejected<TypeParam>(SC_ERROR_INVALID_GEOMETRY, kTetraVertices, three_faces);
}

TYPED_TEST(AddTrianglesInput, EdgeSharedByThreeTrianglesIsInvalidGeometry) {
  // A fin on edge 0-1 of the tetrahedron.
  std::vector<double> v = kTetraVertices;
  v.insert(v.end(), {0.5, -1.0, -1.0});
  std::vector<int> t = kTetraTriangles;
  t.insert(t.end(), {0, 1, 4});
  expectArraysRejected<TypeParam>(SC_ERROR_INVALID_GEOMETRY, v, t);
}

TYPED_TEST(AddTrianglesInput, SameWindingOnASharedEdgeIsInvalidGeometry) {
  std::vector<int> t = kTetraTriangles;
  std::swap(t[1], t[2]);  // face 0 turned over, the other three kept
  expectArraysRejected<TypeParam>(SC_ERROR_INVALID_GEOMETRY, kTetraVertices, t);
}

TYPED_TEST(AddTrianglesInput, DegenerateTriangleIsInvalidGeometry) {
  // Face 1-2-3 split at the midpoint 4 of edge 1-2; the zero-area triangle 1-2-4
  // closes the surface, so only the degeneracy is wrong.
  std::vector<double> v = kTetraVertices;
  v.insert(v.end(), {0.5, 0.5, 0.0});
  const std::vector<int> t = {0, 2, 1, 1, 3, 0, 0, 3, 2, 1, 4, 3, 4, 2, 3, 1, 2, 4};
  expectArraysRejected<TypeParam>(SC_ERROR_INVALID_GEOMETRY, v, t);
  // A triangle naming one vertex twice.
  std::vector<int> repeated = kTetraTriangles;
  repeated[2] = repeated[0];
  expectArraysRejected<TypeParam>(SC_ERROR_INVALID_GEOMETRY, kTetraVertices, repeated);
}

TYPED_TEST(AddTrianglesInput, TwoShellsAreInvalidGeometry) {
  std::vector<double> v = kTetraVertices;
  for (int i = 0; i < 12; ++i) v.push_back(kTetraVertices[i] + (i % 3 == 0 ? 5.0 : 0.0));
  std::vector<int> t = kTetraTriangles;
  for (int i : kTetraTriangles) t.push_back(i + 4);
  expectArraysRejected<TypeParam>(SC_ERROR_INVALID_GEOMETRY, v, t);
}

TYPED_TEST(AddTrianglesInput, PinchedVertexIsInvalidGeometry) {
  // A second tetrahedron standing on vertex 3 = {0,0,1}: the two touch in that vertex only.
  std::vector<double> v = kTetraVertices;
  v.insert(v.end(), {1, 0, 1, 0, 1, 1, 0, 0, 2});
  const int map[4] = {3, 4, 5, 6};
  std::vector<int> t = kTetraTriangles;
  for (int i : kTetraTriangles) t.push_back(map[i]);
  expectArraysRejected<TypeParam>(SC_ERROR_INVALID_GEOMETRY, v, t);
}

TYPED_TEST(AddTrianglesInput, InsideOutTetrahedronIsFlippedAndWorks) {
  std::vector<int> reversed = kTetraTriangles;
  for (size_t i = 0; i < reversed.size(); i += 3) std::swap(reversed[i + 1], reversed[i + 2]);
  SCObject object(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  ASSERT_EQ(add<TypeParam>(object, kTetraVertices, reversed), SC_NO_ERROR);
  const std::vector<double> far = cubeVertices(10.0, 0.0, 0.0);
  ASSERT_EQ(add<TypeParam>(object, far, std::vector<int>(kCubeTriangles, kCubeTriangles + 36)),
            SC_NO_ERROR);
  const std::vector<double> seen = probe(object);
  ASSERT_EQ(seen.size(), kExpectedProbe.size());
  for (size_t i = 0; i < seen.size(); ++i) EXPECT_NEAR(seen[i], kExpectedProbe[i], 1e-9) << i;

  // And it is solid: the List 10-1 motion gives sqrt(4/3), then depth sqrt(1/12).
  SCObject inside_out(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  SCObject mover(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  ASSERT_EQ(add<TypeParam>(inside_out, kTetraVertices, reversed), SC_NO_ERROR);
  ASSERT_EQ(add<TypeParam>(mover, kTetraVertices, kTetraTriangles), SC_NO_ERROR);
  SCSceneManager scene(SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
  ASSERT_EQ(scene.AddObject(1, &mover), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObject(2, &inside_out), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObjectToGroup(0, 1), SC_NO_ERROR);
  const double p1[3] = {1.0, 1.0, 1.0}, p2[3] = {0.0, 0.0, 0.5};
  double d = 0.0;
  ASSERT_EQ(scene.SetTransformation(0, SC_POSITION_ORIGIN, p1), SC_NO_ERROR);
  ASSERT_EQ(scene.UpdateStatus(), SC_NO_ERROR);
  ASSERT_EQ(scene.GetStatus(SC_DISTANCE, &d, 0, false), SC_NO_ERROR);
  EXPECT_NEAR(d, std::sqrt(4.0 / 3.0), 1e-6);
  ASSERT_EQ(scene.SetTransformation(0, SC_POSITION_ORIGIN, p2), SC_NO_ERROR);
  ASSERT_EQ(scene.UpdateStatus(), SC_NO_ERROR);
  ASSERT_EQ(scene.GetStatus(SC_DISTANCE, &d, 0, false), SC_NO_ERROR);
  EXPECT_NEAR(d, -std::sqrt(1.0 / 12.0), 1e-6);
}

TYPED_TEST(AddTrianglesInput, TriangleSoupAcceptsDegenerateAndOpenTriangles) {
  // A collinear triangle, a triangle naming one vertex twice, and one proper triangle
  // in the plane z = 0; nothing closed.
  const std::vector<double> v = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0};
  const std::vector<int> t = {0, 1, 3, 0, 0, 2, 0, 1, 2};
  SCObject soup(SC_OBJECT_TYPE_TRIANGLE_SOUP);
  ASSERT_EQ(add<TypeParam>(soup, v, t), SC_NO_ERROR);
  // The same bad arguments as for closed polyhedra are still rejected.
  std::vector<double> nan = v;
  nan[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(add<TypeParam>(soup, nan, t), SC_ERROR_INVALID_ARGUMENT);
  std::vector<int> out_of_range = t;
  out_of_range[8] = 4;
  EXPECT_EQ(add<TypeParam>(soup, v, out_of_range), SC_ERROR_INVALID_ARGUMENT);
}

// Pending: soup pieces get no collision leaves yet (piece_builder.cpp: "the triangle
// BVH is built by a later stage"), so every soup pair reports SC_ERROR_NO_RESULT.
// Enable once triangle-soup queries land.
TYPED_TEST(AddTrianglesInput, TriangleSoupWithDegenerateTrianglesIsSeenByTheScene) {
  const std::vector<double> v = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0};
  const std::vector<int> t = {0, 1, 3, 0, 0, 2, 0, 1, 2};
  SCObject soup(SC_OBJECT_TYPE_TRIANGLE_SOUP);
  ASSERT_EQ(add<TypeParam>(soup, v, t), SC_NO_ERROR);
  // A soup cube one above the proper triangle sees it at distance 1.
  SCSceneManager scene(SC_SCENE_MANAGER_TRIANGLE_SOUP);
  SCObject probe_cube(SC_OBJECT_TYPE_TRIANGLE_SOUP);
  const std::vector<double> c = cubeVertices(0.0, 0.0, 1.0);
  ASSERT_EQ(probe_cube.AddTriangles(c.data(), 8, kCubeTriangles, 12), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObject(1, &soup), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObject(2, &probe_cube), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObjectToGroup(0, 2), SC_NO_ERROR);
  ASSERT_EQ(scene.UpdateStatus(), SC_NO_ERROR);
  SCint count = -1, pids[2] = {-1, -1};
  ASSERT_EQ(scene.GetStatus(SC_STATUS_COUNT, &count), SC_NO_ERROR);
  ASSERT_EQ(count, 1);
  double d = 0.0;
  ASSERT_EQ(scene.GetStatus(SC_DISTANCE, &d, 0, false), SC_NO_ERROR);
  EXPECT_NEAR(d, 1.0, 1e-9);
  ASSERT_EQ(scene.GetStatus(SC_PIECE_ID, pids, 0, false), SC_NO_ERROR);
  EXPECT_EQ(pids[1], 0);
}

TYPED_TEST(AddTrianglesInput, PieceIdsCountFromZeroInCallOrder) {
  SCObject object(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  const std::vector<int> cube(kCubeTriangles, kCubeTriangles + 36);
  ASSERT_EQ(add<TypeParam>(object, cubeVertices(30.0, 0.0, 0.0), cube), SC_NO_ERROR);
  ASSERT_EQ(add<TypeParam>(object, cubeVertices(0.0, 0.0, 0.0), cube), SC_NO_ERROR);
  SCObject mover(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  ASSERT_EQ(add<TypeParam>(mover, cubeVertices(0.0, 0.0, 0.0), cube), SC_NO_ERROR);
  // Next to the first piece (x = 30), then next to the second (x = 0), gap 2 each. A
  // fresh scene each time: moving straight from one to the other would pass through
  // the pieces, and the dynamic penetration depth would follow that path.
  for (const auto& [x, piece] : {std::pair<double, int>{33.0, 0}, {-3.0, 1}}) {
    SCSceneManager scene(SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
    ASSERT_EQ(scene.AddObject(7, &object), SC_NO_ERROR);
    ASSERT_EQ(scene.AddObject(8, &mover), SC_NO_ERROR);
    ASSERT_EQ(scene.AddObjectToGroup(0, 8), SC_NO_ERROR);
    const double origin[3] = {x, 0.0, 0.0};
    ASSERT_EQ(scene.SetTransformation(0, SC_POSITION_ORIGIN, origin), SC_NO_ERROR);
    ASSERT_EQ(scene.UpdateStatus(), SC_NO_ERROR);
    SCint pids[2] = {-1, -1}, oids[2] = {-1, -1};
    double d = 0.0;
    ASSERT_EQ(scene.GetStatus(SC_PIECE_ID, pids, 0, false), SC_NO_ERROR);
    ASSERT_EQ(scene.GetStatus(SC_OBJECT_ID, oids, 0, false), SC_NO_ERROR);
    ASSERT_EQ(scene.GetStatus(SC_DISTANCE, &d, 0, false), SC_NO_ERROR);
    EXPECT_EQ(pids[0], 0);
    EXPECT_EQ(pids[1], piece) << "mover at x = " << x;
    EXPECT_EQ(oids[0], 8);
    EXPECT_EQ(oids[1], 7);
    EXPECT_NEAR(d, 2.0, 1e-9);
  }
}

}  // namespace
