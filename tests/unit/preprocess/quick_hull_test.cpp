// SPDX-License-Identifier: MIT
// Our Quickhull against qhull: where it answers, the same extreme points, every
// input point inside, closed and outward, and hill climbing finds the brute-force
// support; flat input gets no answer (the hierarchy then asks qhull).
#include "preprocess/quick_hull.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "preprocess/convex_hull.h"
#include "support/brute_force.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

std::set<int> originals(const ConvexPolytope& hull) {
  return std::set<int>(hull.original.begin(), hull.original.end());
}

/// Every directed edge once with its reverse; every point inside; hill climbing
/// from any start gives the brute-force support value.
void expectValidHull(const ConvexPolytope& hull, const std::vector<Vec3>& points, test::Rng& rng) {
  EXPECT_TRUE(test::eachEdgeOnceEachWay({hull.faces.begin(), hull.faces.end()}));
  const double size = (hull.bounds().max - hull.bounds().min).norm();
  for (const Vec3& p : points) EXPECT_TRUE(test::pointInConvexPolytope(hull, p, 1e-12 * size));
  for (std::size_t i = 0; i < hull.vertices.size(); ++i)
    EXPECT_EQ(hull.vertices[i], points[hull.original[i]]);
  for (int k = 0; k < 50; ++k) {
    const Vec3 d = test::randomDirection(rng);
    int hint = static_cast<int>(rng() % hull.vertices.size());
    const int best = hull.support(d, hint);
    double brute = -kInfinity;
    for (const Vec3& p : points) brute = std::max(brute, d.dot(p));
    EXPECT_NEAR(d.dot(hull.vertices[best]), brute, 1e-12 * size);
  }
}

/// quickHull and qhull on the same points: where ours answers, the same vertices.
/// Returns whether ours answered.
bool compareWithQhull(const std::vector<Vec3>& points, test::Rng& rng) {
  QuickHullWorkspace work;
  ConvexPolytope ours;
  if (!quickHull(points, {}, work, ours)) return false;
  expectValidHull(ours, points, rng);
  const Result<ConvexPolytope> reference = convexHull(points);
  EXPECT_TRUE(reference.ok());
  if (reference.ok()) {
    EXPECT_EQ(originals(ours), originals(reference.value()));
  }
  return true;
}

TEST(QuickHull, RandomPointsGiveQhullsVertices) {
  test::Rng rng(0x5A1);
  QuickHullWorkspace reused;  // the workspace carries nothing from one hull to the next
  for (int trial = 0; trial < 60; ++trial) {
    SCOPED_TRACE(trial);
    const double size = test::logUniform(rng, 1e-3, 1e3);
    std::vector<Vec3> points = test::randomPoints(rng, 4 + trial * 17, size);
    const Vec3 offset = size * 10.0 * test::randomDirection(rng);
    for (Vec3& p : points) p += offset;
    EXPECT_TRUE(compareWithQhull(points, rng));
    ConvexPolytope again;
    ASSERT_TRUE(quickHull(points, {}, reused, again));
    EXPECT_EQ(originals(again), originals(convexHull(points).value()));
  }
}

/// n random points on the unit sphere (every one a hull vertex) and their hull.
std::vector<Vec3> sphereHull(test::Rng& rng, int n, QuickHullWorkspace& work,
                             ConvexPolytope& hull) {
  std::vector<Vec3> points;
  for (int i = 0; i < n; ++i) points.push_back(test::randomDirection(rng));
  EXPECT_TRUE(quickHull(points, {}, work, hull));
  return points;
}

TEST(QuickHull, SpherePointsAreAllVertices) {
  test::Rng rng(3);
  QuickHullWorkspace work;
  ConvexPolytope hull;
  const std::vector<Vec3> points = sphereHull(rng, 2000, work, hull);
  EXPECT_EQ(hull.vertices.size(), points.size());
  EXPECT_EQ(hull.faces.size(), 2 * points.size() - 4);
  expectValidHull(hull, points, rng);
}

// The removed faces' slots are reused: the workspace holds about the live faces,
// not every face made (a hierarchy's root on a 1M soup made millions).
TEST(QuickHull, WorkspaceHoldsAboutTheLiveFaces) {
  test::Rng rng(11);
  QuickHullWorkspace work;
  ConvexPolytope hull;
  const std::vector<Vec3> points = sphereHull(rng, 4000, work, hull);
  int made = 0;  // serials count every face made
  for (const QuickHullWorkspace::Face& f : work.faces) made = std::max(made, f.serial + 1);
  const std::size_t live = hull.faces.size();
  EXPECT_GT(static_cast<std::size_t>(made), 2 * live);  // the build did replace faces
  EXPECT_LE(work.faces.size(), live + live / 4);
  expectValidHull(hull, points, rng);
}

TEST(QuickHull, BoxWithPointsOnItsFacesKeepsOnlyTheCorners) {
  test::Rng rng(5);
  std::vector<Vec3> points;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      for (int k = 0; k < 4; ++k) points.emplace_back(i, j, 0.5 * k);
    }
  }
  QuickHullWorkspace work;
  ConvexPolytope hull;
  // Coplanar points: it may decline, but an answer must be the eight corners.
  if (quickHull(points, {}, work, hull)) {
    EXPECT_EQ(hull.vertices.size(), 8u);
    expectValidHull(hull, points, rng);
  }
  const std::vector<Vec3> corners = test::boxMesh(Vec3(1, 2, 3)).vertices;
  std::vector<Vec3> inner = corners;
  inner.push_back(Vec3(0.1, 0.2, 0.3));
  ASSERT_TRUE(quickHull(inner, {}, work, hull));
  EXPECT_EQ(hull.vertices.size(), 8u);
  expectValidHull(hull, inner, rng);
}

// The hierarchy's inputs: vertices of neighbouring soup triangles of a torus, many
// of them coplanar in fours (its quads).
TEST(QuickHull, TorusPatchesAgreeWithQhullWhereItAnswers) {
  test::Rng rng(9);
  const MeshData torus = test::torusMesh(1.0, 0.3, 60, 30);
  int answered = 0, asked = 0;
  for (int first = 0; first + 400 <= static_cast<int>(torus.vertices.size()); first += 97) {
    for (const int count : {30, 120, 400}) {
      const std::vector<Vec3> points(torus.vertices.begin() + first,
                                     torus.vertices.begin() + first + count);
      ++asked;
      if (compareWithQhull(points, rng)) ++answered;
    }
  }
  // Declining is allowed, but it must not be the rule on such input.
  EXPECT_GT(answered, asked / 2) << answered << " of " << asked;
}

TEST(QuickHull, FlatOrTooFewPointsGetNoAnswer) {
  QuickHullWorkspace work;
  ConvexPolytope hull;
  EXPECT_FALSE(quickHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {}, work, hull));
  std::vector<Vec3> flat;
  for (int i = 0; i < 50; ++i) flat.emplace_back(i % 7, i / 7, 0.0);
  EXPECT_FALSE(quickHull(flat, {}, work, hull));
  std::vector<Vec3> line;
  for (int i = 0; i < 10; ++i) line.emplace_back(i, 2 * i, 3 * i);
  EXPECT_FALSE(quickHull(line, {}, work, hull));
  const std::vector<Vec3> bad = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
                                 Vec3(0, 0, std::numeric_limits<double>::quiet_NaN())};
  EXPECT_FALSE(quickHull(bad, {}, work, hull));
  EXPECT_FALSE(quickHull(test::boxMesh(Vec3(1, 1, 1)).vertices, {1, 2}, work, hull));
}

}  // namespace
}  // namespace sc::detail
