// SPDX-License-Identifier: MIT
// Convex hulls through qhull: closed, outward, extreme vertices only, original
// indices kept, silent errors for flat or bad input.
#include "preprocess/convex_hull.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include "support/brute_force.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

/// Every directed edge once, its reverse once; Euler characteristic 2.
void expectClosedOutward(const ConvexPolytope& hull) {
  EXPECT_TRUE(test::eachEdgeOnceEachWay({hull.faces.begin(), hull.faces.end()}));
  const int v = static_cast<int>(hull.vertices.size());
  const int e = 3 * static_cast<int>(hull.faces.size()) / 2;
  const int f = static_cast<int>(hull.faces.size());
  EXPECT_EQ(v - e + f, 2);
  // Outward and non-degenerate: every vertex is on the inner side of every face,
  // and each face has area.
  const double size = (hull.bounds().max - hull.bounds().min).norm();
  for (const Tri& t : hull.faces) {
    const Vec3 n = (hull.vertices[t[1]] - hull.vertices[t[0]])
                       .cross(hull.vertices[t[2]] - hull.vertices[t[0]]);
    EXPECT_GT(n.norm(), 1e-9 * size * size);
    for (const Vec3& p : hull.vertices) {
      EXPECT_LE(n.normalized().dot(p - hull.vertices[t[0]]), 1e-12 * size);
    }
  }
  EXPECT_EQ(hull.face_source.size(), hull.faces.size());
  EXPECT_EQ(hull.original.size(), hull.vertices.size());
  EXPECT_EQ(hull.adjacency_start.size(), hull.vertices.size() + 1);
}

TEST(ConvexHull, CubeWithInteriorPointsKeepsTheEightCorners) {
  const MeshData box = test::boxMesh(Vec3(1, 2, 3));
  std::vector<Vec3> points = box.vertices;
  points.insert(points.begin() + 3, Vec3(0.1, 0.2, 0.3));
  points.push_back(Vec3(-0.5, 1.0, 2.0));
  const Result<ConvexPolytope> hull = convexHull(points);
  ASSERT_TRUE(hull.ok()) << hull.status().message();
  const ConvexPolytope& h = hull.value();
  EXPECT_EQ(h.vertices.size(), 8u);
  EXPECT_EQ(h.faces.size(), 12u);
  expectClosedOutward(h);
  for (std::size_t i = 0; i < h.vertices.size(); ++i) {
    EXPECT_EQ(h.vertices[i], points[h.original[i]]);
    EXPECT_NE(h.original[i], 3);
    EXPECT_NE(h.original[i], 9);
  }
  for (int s : h.face_source) EXPECT_EQ(s, -1);
}

TEST(ConvexHull, OriginalIndicesAreMappedThroughTheGivenTable) {
  const MeshData box = test::boxMesh(Vec3(1, 1, 1));
  std::vector<int> original;
  for (int i = 0; i < 8; ++i) original.push_back(100 + 7 * i);
  const Result<ConvexPolytope> hull = convexHull(box.vertices, original);
  ASSERT_TRUE(hull.ok());
  std::set<int> seen(hull.value().original.begin(), hull.value().original.end());
  EXPECT_EQ(seen, std::set<int>(original.begin(), original.end()));
}

TEST(ConvexHull, GridPointsOnEdgesAndFacesAreNotVertices) {
  // A 4x4x4 grid: points on box edges and faces are coplanar or collinear.
  std::vector<Vec3> points;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      for (int k = 0; k < 4; ++k) points.emplace_back(i, j, 0.5 * k);
    }
  }
  const Result<ConvexPolytope> hull = convexHull(points);
  ASSERT_TRUE(hull.ok()) << hull.status().message();
  EXPECT_EQ(hull.value().vertices.size(), 8u);
  EXPECT_EQ(hull.value().faces.size(), 12u);
  expectClosedOutward(hull.value());
}

TEST(ConvexHull, RandomPointsAreAllInsideAndVerticesAreExtreme) {
  const std::uint64_t seed = 7;
  SCOPED_TRACE(::testing::Message() << "seed " << seed);
  test::Rng rng(seed);
  for (int trial = 0; trial < 50; ++trial) {
    const double size = test::logUniform(rng, 1e-3, 1e3);
    std::vector<Vec3> points = test::randomPoints(rng, 4 + trial * 5, size);
    const Vec3 offset = size * 10.0 * test::randomDirection(rng);
    for (Vec3& p : points) p += offset;
    const Result<ConvexPolytope> hull = convexHull(points);
    ASSERT_TRUE(hull.ok()) << hull.status().message();
    const ConvexPolytope& h = hull.value();
    expectClosedOutward(h);
    for (const Vec3& p : points) EXPECT_TRUE(test::pointInConvexPolytope(h, p, 1e-12 * size));
    // Extreme: the sum of a vertex's face normals lies inside its normal cone, so
    // the vertex is the unique maximiser of that direction over all points.
    std::vector<Vec3> cone(h.vertices.size(), Vec3::Zero());
    for (const Tri& t : h.faces) {
      const Vec3 n = (h.vertices[t[1]] - h.vertices[t[0]])
                         .cross(h.vertices[t[2]] - h.vertices[t[0]])
                         .normalized();
      for (int k = 0; k < 3; ++k) cone[t[k]] += n;
    }
    for (std::size_t i = 0; i < h.vertices.size(); ++i) {
      EXPECT_EQ(h.vertices[i], points[h.original[i]]);
      const Vec3 d = cone[i].normalized();
      for (std::size_t j = 0; j < points.size(); ++j) {
        if (static_cast<int>(j) == h.original[i]) continue;
        EXPECT_LT(d.dot(points[j]), d.dot(h.vertices[i]));
      }
    }
  }
}

TEST(ConvexHull, SpherePointsAreAllVertices) {
  test::Rng rng(11);
  std::vector<Vec3> points;
  for (int i = 0; i < 200; ++i) points.push_back(test::randomDirection(rng));
  const Result<ConvexPolytope> hull = convexHull(points);
  ASSERT_TRUE(hull.ok());
  EXPECT_EQ(hull.value().vertices.size(), 200u);
  EXPECT_EQ(hull.value().faces.size(), 2u * 200 - 4);
  expectClosedOutward(hull.value());
}

TEST(ConvexHull, FlatOrTooFewPointsAreInvalidGeometry) {
  const std::vector<Vec3> square = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                                    Vec3(0.5, 0.5, 0)};
  EXPECT_EQ(convexHull(square).status().code(), ErrorCode::InvalidGeometry);
  const std::vector<Vec3> line = {Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2), Vec3(3, 3, 3)};
  EXPECT_EQ(convexHull(line).status().code(), ErrorCode::InvalidGeometry);
  const std::vector<Vec3> same(6, Vec3(1, 2, 3));
  EXPECT_EQ(convexHull(same).status().code(), ErrorCode::InvalidGeometry);
  const std::vector<Vec3> three = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_EQ(convexHull(three).status().code(), ErrorCode::InvalidGeometry);
  EXPECT_EQ(convexHull({}).status().code(), ErrorCode::InvalidGeometry);
}

TEST(ConvexHull, BadArgumentsAreInvalidArgument) {
  const MeshData box = test::boxMesh(Vec3(1, 1, 1));
  EXPECT_EQ(convexHull(box.vertices, {1, 2, 3}).status().code(), ErrorCode::InvalidArgument);
  std::vector<Vec3> points = box.vertices;
  points[2].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(convexHull(points).status().code(), ErrorCode::InvalidArgument);
}

TEST(ConvexHull, ErrorsPrintNothing) {
  const std::vector<Vec3> square = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  const Result<ConvexPolytope> hull = convexHull(square);
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_FALSE(hull.ok());
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
}

TEST(ConvexHull, NearlyFlatInputStaysFiniteUnderTraps) {
  // Thickness at rounding level: either a valid hull or InvalidGeometry, no trap.
  std::vector<Vec3> points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 1e-17),
                              Vec3(0.3, 0.2, -1e-17)};
  const Result<ConvexPolytope> hull = convexHull(points);
  if (hull.ok()) expectClosedOutward(hull.value());
  SUCCEED();
}

}  // namespace
}  // namespace sc::detail
