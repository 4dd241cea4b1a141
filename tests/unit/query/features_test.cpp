// SPDX-License-Identifier: MIT
// Closest features on a box with known faces, virtual faces and edges, the
// real-face preference, and random surface points on random hulls.
#include "query/features.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "support/brute_force.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

constexpr double kTol = 1e-9;

/// The box of half extent 1 with original index = 10 + local index.
ConvexPolytope box() {
  ConvexPolytope poly = test::polytopeFromMesh(test::boxMesh(Vec3(1, 1, 1)));
  for (int& o : poly.original) o += 10;
  return poly;
}

std::vector<int> sorted(const Feature& f) {
  std::vector<int> v(f.vertices, f.vertices + f.count());
  std::sort(v.begin(), v.end());
  return v;
}

int faceIndex(const ConvexPolytope& poly, int a, int b, int c) {
  for (std::size_t f = 0; f < poly.faces.size(); ++f) {
    std::vector<int> t = {poly.faces[f][0], poly.faces[f][1], poly.faces[f][2]};
    std::vector<int> want = {a, b, c};
    std::sort(t.begin(), t.end());
    std::sort(want.begin(), want.end());
    if (t == want) return static_cast<int>(f);
  }
  return -1;
}

TEST(ClosestFeature, PointAtAVertexGivesTheVertex) {
  const ConvexPolytope poly = box();
  const int ids[3] = {7, 5, 6};
  const Feature f = closestFeature(poly, Vec3(1, 1, 1) + Vec3(1e-12, 0, 0), ids, 3, kTol);
  EXPECT_EQ(f.type, FeatureType::Vertex);
  EXPECT_EQ(f.vertices[0], 17);
  EXPECT_FALSE(f.is_virtual);
}

TEST(ClosestFeature, PointOnAnEdgeGivesTheEdgeEvenFromOneSeed) {
  const ConvexPolytope poly = box();
  const int both[2] = {0, 1};
  const Feature f = closestFeature(poly, Vec3(0.25, -1, -1), both, 2, kTol);
  EXPECT_EQ(f.type, FeatureType::Edge);
  EXPECT_EQ(sorted(f), (std::vector<int>{10, 11}));
  EXPECT_FALSE(f.is_virtual);
  const int one[1] = {1};
  EXPECT_EQ(sorted(closestFeature(poly, Vec3(0.25, -1, -1), one, 1, kTol)),
            (std::vector<int>{10, 11}));
}

TEST(ClosestFeature, PointInsideAFaceGivesTheTriangle) {
  const ConvexPolytope poly = box();
  const int ids[3] = {4, 5, 7};
  const Feature f = closestFeature(poly, Vec3(0.3, 0.2, 1), ids, 3, kTol);
  EXPECT_EQ(f.type, FeatureType::Face);
  EXPECT_EQ(sorted(f), (std::vector<int>{14, 15, 17}));
  EXPECT_FALSE(f.is_virtual);
  const int one[1] = {4};  // found among the faces around a single seed
  EXPECT_EQ(sorted(closestFeature(poly, Vec3(0.3, 0.2, 1), one, 1, kTol)),
            (std::vector<int>{14, 15, 17}));
}

TEST(ClosestFeature, PointOnAFaceDiagonalGivesTheDiagonalEdge) {
  const ConvexPolytope poly = box();
  const int ids[3] = {4, 5, 7};
  const Feature f = closestFeature(poly, Vec3(0.1, 0.1, 1), ids, 3, kTol);
  EXPECT_EQ(f.type, FeatureType::Edge);
  EXPECT_EQ(sorted(f), (std::vector<int>{14, 17}));
  EXPECT_FALSE(f.is_virtual);
}

TEST(ClosestFeature, VirtualFacesAndEdgesAreMarked) {
  ConvexPolytope poly = box();
  // Edge 4-5 lies on faces (4,5,7) and (0,5,4); make both virtual.
  const int f457 = faceIndex(poly, 4, 5, 7), f054 = faceIndex(poly, 0, 5, 4);
  ASSERT_GE(f457, 0);
  ASSERT_GE(f054, 0);
  poly.face_source[f457] = -1;
  const int ids[3] = {4, 5, 7};
  const Feature face = closestFeature(poly, Vec3(0.3, 0.2, 1), ids, 3, kTol);
  EXPECT_EQ(face.type, FeatureType::Face);
  EXPECT_TRUE(face.is_virtual);
  const Feature edge_half = closestFeature(poly, Vec3(0, -1, 1), ids, 3, kTol);
  EXPECT_EQ(edge_half.type, FeatureType::Edge);
  EXPECT_FALSE(edge_half.is_virtual);  // still on the real face (0,5,4)
  poly.face_source[f054] = -1;
  const Feature edge = closestFeature(poly, Vec3(0, -1, 1), ids, 3, kTol);
  EXPECT_EQ(edge.type, FeatureType::Edge);
  EXPECT_TRUE(edge.is_virtual);
}

TEST(ClosestFeature, PrefersARealFaceWhenSeveralContainThePoint) {
  // A slab thinner than the tolerance: a point on its bottom lies within
  // tolerance of the top too. The bottom is virtual, the top real.
  const double h = 1e-12;
  MeshData prism;
  prism.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
                    Vec3(0, 0, h), Vec3(1, 0, h), Vec3(0, 1, h)};
  prism.triangles = {Tri(0, 2, 1), Tri(3, 4, 5),  // bottom, top
                     Tri(0, 1, 4), Tri(0, 4, 3), Tri(1, 2, 5),
                     Tri(1, 5, 4), Tri(2, 0, 3), Tri(2, 3, 5)};
  ConvexPolytope poly = test::polytopeFromMesh(prism);
  poly.face_source[0] = -1;
  const int ids[2] = {0, 4};
  const Feature f = closestFeature(poly, Vec3(0.25, 0.25, 0), ids, 2, kTol);
  EXPECT_EQ(f.type, FeatureType::Face);
  EXPECT_EQ(sorted(f), (std::vector<int>{3, 4, 5}));
  EXPECT_FALSE(f.is_virtual);
}

TEST(ClosestFeature, NoValidSeedsFallsBackToTheNearestVertex) {
  const ConvexPolytope poly = box();
  const int ids[2] = {-1, 99};
  const Feature f = closestFeature(poly, Vec3(0.3, 0.2, 1), ids, 2, kTol);
  EXPECT_EQ(f.type, FeatureType::Face);
  EXPECT_EQ(sorted(f), (std::vector<int>{14, 15, 17}));
}

TEST(ClosestFeature, RandomSurfacePointsLieOnTheirFeature) {
  const std::uint64_t seed = 42;
  SCOPED_TRACE(::testing::Message() << "seed " << seed);
  test::Rng rng(seed);
  int counts[3] = {0, 0, 0};
  for (int trial = 0; trial < 30; ++trial) {
    const double size = test::logUniform(rng, 1e-2, 1e2);
    const std::vector<Vec3> points = test::randomPoints(rng, 50, size);
    const ConvexPolytope poly = test::hullOf(points);
    for (int q = 0; q < 60; ++q) {
      const Tri& t =
          poly.faces[std::uniform_int_distribution<int>(0, int(poly.faces.size()) - 1)(rng)];
      // A vertex, an edge point or a face point of this triangle.
      double u = test::uniform(rng, 0.05, 0.6), v = test::uniform(rng, 0.05, 0.9 - u);
      if (q % 3 == 0) u = v = 0.0;
      if (q % 3 == 1) v = 0.0;
      const Vec3 p = poly.vertices[t[0]] + u * (poly.vertices[t[1]] - poly.vertices[t[0]]) +
                     v * (poly.vertices[t[2]] - poly.vertices[t[0]]);
      const int ids[3] = {t[0], t[1], t[2]};
      const Feature f = closestFeature(poly, p, ids, 3, 1e-9 * size);
      EXPECT_LE(test::pointFeatureDistance(points, f, p), 1e-9 * size);
      EXPECT_EQ(static_cast<int>(f.type), q % 3);
      ++counts[static_cast<int>(f.type)];
    }
  }
  EXPECT_EQ(counts[0], 600);
}

}  // namespace
}  // namespace sc::detail
