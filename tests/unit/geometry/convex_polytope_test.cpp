// SPDX-License-Identifier: MIT
// Support mapping by hill climbing against a linear scan, on hulls large enough
// (> 32 vertices) that hill climbing is used.
#include "geometry/convex_polytope.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

#include "support/brute_force.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

using test::supportValue;

TEST(ConvexPolytope, HillClimbingSupportEqualsBruteForceOnLargeHulls) {
  const std::uint64_t seed = 1234;
  SCOPED_TRACE(::testing::Message() << "seed " << seed);
  test::Rng rng(seed);
  int hulls = 0, queries = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const double size = test::logUniform(rng, 1e-2, 1e2);
    // Points on a squashed sphere: almost all are hull vertices.
    std::vector<Vec3> points;
    const Vec3 axes(1.0, test::uniform(rng, 0.2, 1.0), test::uniform(rng, 0.05, 1.0));
    const int n = 40 + 20 * trial;
    for (int i = 0; i < n; ++i)
      points.push_back(size * test::randomDirection(rng).cwiseProduct(axes));
    const ConvexPolytope poly = test::hullOf(points);
    ASSERT_GT(poly.vertices.size(), 32u);
    ++hulls;
    const int nv = static_cast<int>(poly.vertices.size());
    int hint = 0;
    for (int q = 0; q < 200; ++q) {
      const Vec3 d = test::randomDirection(rng) * test::logUniform(rng, 1e-3, 1e3);
      if (q % 3 == 0) hint = std::uniform_int_distribution<int>(0, nv - 1)(rng);  // cold hint
      const int got = poly.support(d, hint);
      ASSERT_GE(got, 0);
      ASSERT_LT(got, nv);
      EXPECT_EQ(hint, got);
      // Ties are allowed; the value must be the maximum.
      EXPECT_GE(poly.vertices[got].dot(d), supportValue(poly, d) - 1e-15 * size * d.norm());
      ++queries;
    }
  }
  EXPECT_EQ(hulls, 40);
  EXPECT_EQ(queries, 8000);
}

TEST(ConvexPolytope, OutOfRangeHintsAreTolerated) {
  test::Rng rng(5);
  std::vector<Vec3> points;
  for (int i = 0; i < 100; ++i) points.push_back(test::randomDirection(rng));
  const ConvexPolytope poly = test::hullOf(points);
  for (int hint : {-5, 100000}) {
    int h = hint;
    const Vec3 d(0.3, -0.2, 0.9);
    const int got = poly.support(d, h);
    EXPECT_GE(poly.vertices[got].dot(d), supportValue(poly, d) - 1e-15);
  }
}

TEST(ConvexPolytope, FinalizeBuildsSymmetricAdjacencyAndBounds) {
  const ConvexPolytope box = test::polytopeFromMesh(test::boxMesh(Vec3(1, 2, 3)));
  ASSERT_EQ(box.adjacency_start.size(), 9u);
  for (int v = 0; v < 8; ++v) {
    for (int k = box.adjacency_start[v]; k < box.adjacency_start[v + 1]; ++k) {
      const int w = box.adjacency[k];
      const auto first = box.adjacency.begin() + box.adjacency_start[w];
      const auto last = box.adjacency.begin() + box.adjacency_start[w + 1];
      EXPECT_NE(std::find(first, last, v), last);
    }
  }
  EXPECT_VEC_NEAR(box.bounds().min, Vec3(-1, -2, -3), 0.0);
  EXPECT_VEC_NEAR(box.bounds().max, Vec3(1, 2, 3), 0.0);
  EXPECT_NEAR(box.radius, std::sqrt(14.0), 1e-12);
}

// Each vertex's neighbours are exactly the vertices it shares a face edge with,
// sorted and once each; each vertex's faces are exactly the faces holding it.
TEST(ConvexPolytope, FinalizeAdjacencyEqualsTheFaceEdges) {
  test::Rng rng(77);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec3> points;
    for (int i = 0; i < 10 + 15 * trial; ++i) points.push_back(test::randomDirection(rng));
    const ConvexPolytope poly = test::hullOf(points);
    const int n = static_cast<int>(poly.vertices.size());
    std::vector<std::set<int>> neighbours(n), faces_of(n);
    for (int f = 0; f < static_cast<int>(poly.faces.size()); ++f) {
      for (int k = 0; k < 3; ++k) {
        neighbours[poly.faces[f][k]].insert(
            {poly.faces[f][(k + 1) % 3], poly.faces[f][(k + 2) % 3]});
        faces_of[poly.faces[f][k]].insert(f);
      }
    }
    ASSERT_EQ(poly.adjacency_start.size(), static_cast<std::size_t>(n + 1));
    for (int v = 0; v < n; ++v) {
      const std::vector<int> got(poly.adjacency.begin() + poly.adjacency_start[v],
                                 poly.adjacency.begin() + poly.adjacency_start[v + 1]);
      EXPECT_EQ(got, std::vector<int>(neighbours[v].begin(), neighbours[v].end()));
      const std::set<int> around(poly.vertex_faces.begin() + poly.vertex_face_start[v],
                                 poly.vertex_faces.begin() + poly.vertex_face_start[v + 1]);
      EXPECT_EQ(around, faces_of[v]);
    }
    EXPECT_EQ(poly.adjacency.size(), static_cast<std::size_t>(poly.adjacency_start[n]));
  }
}

// Faces that are not a closed, consistently wound surface (one triangle, a hull with
// a face turned over, random triangles) take the slower path; the lists are still
// exactly the vertices each vertex shares a face with, sorted and once each.
TEST(ConvexPolytope, FinalizeAdjacencyOfOpenOrMiswoundFacesEqualsTheFaceEdges) {
  test::Rng rng(79);
  std::vector<PolytopeParts> cases;
  PolytopeParts one;
  one.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(5, 5, 5)};
  one.faces = {Tri(0, 1, 2)};
  cases.push_back(one);
  std::vector<Vec3> points;
  for (int i = 0; i < 40; ++i) points.push_back(test::randomDirection(rng));
  PolytopeParts turned = test::hullOf(points).parts();
  std::swap(turned.faces[3][1], turned.faces[3][2]);
  cases.push_back(turned);
  std::uniform_int_distribution<int> pick(0, 11);
  for (int trial = 0; trial < 20; ++trial) {
    PolytopeParts random;
    random.vertices.assign(12, Vec3::Zero());
    for (int f = 0; f < 3 + trial; ++f) random.faces.emplace_back(pick(rng), pick(rng), pick(rng));
    cases.push_back(random);
  }
  for (const PolytopeParts& parts : cases) {
    const ConvexPolytope poly = ConvexPolytope::build(parts);
    const int n = static_cast<int>(poly.vertices.size());
    std::vector<std::set<int>> neighbours(n);
    for (const Tri& f : poly.faces) {
      for (int k = 0; k < 3; ++k) {
        for (int j = 0; j < 3; ++j)
          if (f[j] != f[k]) neighbours[f[k]].insert(f[j]);
      }
    }
    ASSERT_EQ(poly.adjacency_start.size(), static_cast<std::size_t>(n + 1));
    for (int v = 0; v < n; ++v) {
      const std::vector<int> got(poly.adjacency.begin() + poly.adjacency_start[v],
                                 poly.adjacency.begin() + poly.adjacency_start[v + 1]);
      EXPECT_EQ(got, std::vector<int>(neighbours[v].begin(), neighbours[v].end())) << v;
    }
  }
}

// A bare point set (no faces, as the hierarchy keeps small inner nodes) keeps no
// adjacency arrays; its support is still the brute-force maximum, past the size at
// which faced polytopes hill-climb.
TEST(ConvexPolytope, PointSetHasNoAdjacencyAndScansForItsSupport) {
  test::Rng rng(78);
  PolytopeParts parts;
  for (int i = 0; i < 40; ++i) parts.vertices.push_back(test::randomDirection(rng));
  const ConvexPolytope points = ConvexPolytope::build(parts);
  EXPECT_TRUE(points.adjacency_start.empty() && points.adjacency.empty());
  EXPECT_TRUE(points.vertex_face_start.empty() && points.vertex_faces.empty());
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 d = test::randomDirection(rng);
    int hint = trial % 40;
    const int got = points.support(d, hint);
    EXPECT_EQ(points.vertices[got].dot(d), supportValue(points, d));
  }
}

/// The adjacency and vertex-face lists recomputed from the faces alone.
void expectListsFromFaces(const ConvexPolytope& poly) {
  const int n = static_cast<int>(poly.vertices.size());
  std::vector<std::set<int>> neighbours(n);
  std::vector<std::vector<int>> around(n);
  for (int f = 0; f < static_cast<int>(poly.faces.size()); ++f) {
    const Tri& t = poly.faces[f];
    for (int k = 0; k < 3; ++k) {
      around[t[k]].push_back(f);
      for (int j = 0; j < 3; ++j)
        if (t[j] != t[k]) neighbours[t[k]].insert(t[j]);
    }
  }
  ASSERT_EQ(poly.adjacency_start.size(), static_cast<std::size_t>(n + 1));
  ASSERT_EQ(poly.vertex_face_start.size(), static_cast<std::size_t>(n + 1));
  for (int v = 0; v < n; ++v) {
    const std::vector<int> adjacent(poly.adjacency.begin() + poly.adjacency_start[v],
                                    poly.adjacency.begin() + poly.adjacency_start[v + 1]);
    EXPECT_EQ(adjacent, std::vector<int>(neighbours[v].begin(), neighbours[v].end())) << v;
    const std::vector<int> faces(poly.vertex_faces.begin() + poly.vertex_face_start[v],
                                 poly.vertex_faces.begin() + poly.vertex_face_start[v + 1]);
    EXPECT_EQ(faces, around[v]) << v;
  }
}

// A two-sided triangle (a soup's leaf) takes its faces, adjacency and vertex-face
// lists from shared constants: they must be what the faces give, for every kind of
// polytope that keeps them, and the owned arrays its own.
TEST(ConvexPolytope, TwoSidedTriangleSharesListsEqualToTheFaceEdges) {
  PolytopeParts parts;
  parts.vertices = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 1)};
  parts.original = {7, 4, 9};
  parts.faces = {Tri(0, 1, 2), Tri(0, 2, 1)};
  parts.face_source = {5, 5};
  const ConvexPolytope a = ConvexPolytope::build(parts);
  const ConvexPolytope b = ConvexPolytope::build(parts);
  expectListsFromFaces(a);
  EXPECT_EQ(a.faces.data(), b.faces.data());  // shared
  EXPECT_EQ(a.adjacency.data(), b.adjacency.data());
  EXPECT_NE(a.vertices.data(), b.vertices.data());  // owned
  EXPECT_NE(a.face_source.data(), b.face_source.data());
  EXPECT_EQ(std::vector<int>(a.original.begin(), a.original.end()), parts.original);
  EXPECT_EQ(std::vector<int>(a.face_source.begin(), a.face_source.end()), parts.face_source);
  const ConvexPolytope soup = ConvexPolytope::build(parts, PolytopeKeep::NoFaceLists);
  EXPECT_TRUE(soup.vertex_face_start.empty() && soup.vertex_faces.empty());
  EXPECT_EQ(soup.adjacency, a.adjacency);
  EXPECT_EQ(soup.face_source, a.face_source);
}

// Copies own their arrays (equal contents, another block) and keep shared ones;
// a moved-from polytope is empty; reduced() drops exactly what it says.
TEST(ConvexPolytope, CopyMoveAndReduceKeepEveryArray) {
  std::vector<Vec3> points;
  test::Rng rng(80);
  for (int i = 0; i < 60; ++i) points.push_back(test::randomDirection(rng));
  const ConvexPolytope hull = test::hullOf(points);
  ConvexPolytope copy = hull;
  EXPECT_EQ(copy.vertices, hull.vertices);
  EXPECT_EQ(copy.original, hull.original);
  EXPECT_EQ(copy.faces, hull.faces);
  EXPECT_EQ(copy.face_source, hull.face_source);
  EXPECT_EQ(copy.adjacency_start, hull.adjacency_start);
  EXPECT_EQ(copy.adjacency, hull.adjacency);
  EXPECT_EQ(copy.vertex_face_start, hull.vertex_face_start);
  EXPECT_EQ(copy.vertex_faces, hull.vertex_faces);
  EXPECT_EQ(copy.center, hull.center);
  EXPECT_EQ(copy.radius, hull.radius);
  EXPECT_NE(copy.vertices.data(), hull.vertices.data());
  expectListsFromFaces(copy);
  const ConvexPolytope support = copy.reduced(PolytopeKeep::Support);
  EXPECT_TRUE(support.face_source.empty() && support.vertex_face_start.empty() &&
              support.vertex_faces.empty());
  EXPECT_EQ(support.vertices, hull.vertices);
  EXPECT_EQ(support.faces, hull.faces);
  EXPECT_EQ(support.adjacency, hull.adjacency);
  const ConvexPolytope moved = std::move(copy);
  EXPECT_EQ(moved.vertices, hull.vertices);
  EXPECT_TRUE(copy.vertices.empty() && copy.faces.empty() && copy.adjacency.empty());  // NOLINT
}

}  // namespace
}  // namespace sc::detail
