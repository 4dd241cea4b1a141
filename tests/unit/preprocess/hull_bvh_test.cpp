// SPDX-License-Identifier: MIT
// Hull hierarchy: its leaves are exactly the piece's leaves (patches or soup
// triangles), every inner polytope contains its children's vertices and holds
// nothing else, the tree is balanced, and broken structures are rejected.
#include "preprocess/hull_bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <set>
#include <vector>

#include "preprocess/cache_file.h"
#include "preprocess/convex_hull.h"
#include "preprocess/piece_data.h"
#include "support/brute_force.h"
#include "support/meshes.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

using test::supportValue;

/// `point` lies in `hull`: inside every face plane for a faceted hull; for a bare
/// point set (or a flat polygon) no direction separates it from the vertices.
bool contains(const ConvexPolytope& hull, const Vec3& point, double tolerance,
              const std::vector<Vec3>& directions) {
  if (!hull.faces.empty()) return test::pointInConvexPolytope(hull, point, tolerance);
  for (const Vec3& v : hull.vertices) {
    if (v == point) return true;
  }
  for (const Vec3& d : directions) {
    if (d.dot(point) > supportValue(hull, d) + tolerance) return false;
  }
  return true;
}

/// Checks the hierarchy against its definition; returns the leaves seen.
void expectValidHierarchy(const std::vector<ConvexPolytope>& leaves, const HullBvh& bvh) {
  const int n = static_cast<int>(leaves.size());
  ASSERT_EQ(static_cast<int>(bvh.nodes.size()), 2 * n - 1);
  ASSERT_LE(static_cast<int>(bvh.hulls.size()), std::max(0, n - 1));
  ASSERT_EQ(static_cast<int>(bvh.leaf_node.size()), n);
  test::Rng rng(7);
  std::vector<Vec3> directions;
  for (int k = 0; k < 200; ++k) directions.push_back(test::randomDirection(rng));

  // Leaves = the given leaves, each once; leaf_node points back.
  std::vector<int> seen(leaves.size(), 0);
  for (int i = 0; i < static_cast<int>(bvh.nodes.size()); ++i) {
    const HullBvhNode& node = bvh.nodes[i];
    if (!node.leaf()) continue;
    ASSERT_GE(node.polytope, 0);
    ASSERT_LT(node.polytope, n);
    ++seen[node.polytope];
    EXPECT_EQ(bvh.leaf_node[node.polytope], i);
  }
  for (int s : seen) EXPECT_EQ(s, 1);

  // Per node: the points of the leaves below (by recursion from the root).
  std::function<std::vector<Vec3>(int, int)> below = [&](int index, int level) {
    const HullBvhNode& node = bvh.nodes[index];
    EXPECT_LE(level, bvh.depth);
    if (node.leaf()) {
      const ConvexPolytope& leaf = bvh.polytope(leaves, index);
      const double size = 1e-12 * (1.0 + leaf.radius + leaf.center.norm());
      for (const Vec3& v : leaf.vertices) EXPECT_LE((v - node.center).norm(), node.radius + size);
      return std::vector<Vec3>(leaf.vertices.begin(), leaf.vertices.end());
    }
    std::vector<Vec3> points = below(node.left, level + 1);
    const std::vector<Vec3> right = below(node.right, level + 1);
    points.insert(points.end(), right.begin(), right.end());
    // Its sphere holds every point below, hull or not...
    const double size = 1e-12 * (1.0 + node.radius + node.center.norm());
    for (const Vec3& v : points) EXPECT_LE((v - node.center).norm(), node.radius + size);
    if (!node.hasPolytope()) return points;
    const ConvexPolytope& poly = bvh.polytope(leaves, index);
    EXPECT_EQ(node.center, poly.center);
    EXPECT_EQ(node.radius, poly.radius);
    // ...its hull contains them too...
    for (const Vec3& v : points)
      EXPECT_TRUE(contains(poly, v, 1e-9 * (1.0 + poly.radius), directions))
          << "node " << index << " misses a point below it";
    // ...and no more: each of its vertices is a vertex of a leaf below.
    for (const Vec3& v : poly.vertices)
      EXPECT_NE(std::find(points.begin(), points.end(), v), points.end()) << "node " << index;
    return points;
  };
  below(0, 0);
  EXPECT_EQ(bvh.depth, n <= 1 ? 0 : static_cast<int>(std::ceil(std::log2(n))));
}

/// Hulls of random points, with vertex indices of their own.
std::vector<ConvexPolytope> randomLeaves(test::Rng& rng, int count) {
  std::vector<ConvexPolytope> leaves;
  int next_original = 0;
  while (static_cast<int>(leaves.size()) < count) {
    std::vector<Vec3> points = test::randomPoints(rng, 4 + static_cast<int>(rng() % 20), 1.0);
    const Vec3 offset = 20.0 * Vec3(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1),
                                    test::uniform(rng, -1, 1));
    for (Vec3& p : points) p += offset;
    Result<ConvexPolytope> hull = convexHull(points);
    if (!hull.ok()) continue;
    for (int& o : hull.value().original) o += next_original;
    next_original += static_cast<int>(points.size());
    leaves.push_back(std::move(hull.value()));
  }
  return leaves;
}

TEST(HullBvh, RandomLeavesGiveABalancedTreeOfContainingHulls) {
  test::Rng rng(0x4B7);
  for (const int count : {2, 3, 5, 17, 200}) {
    SCOPED_TRACE(count);
    const std::vector<ConvexPolytope> leaves = randomLeaves(rng, count);
    const HullBvh bvh = buildHullBvh(leaves, {});
    expectValidHierarchy(leaves, bvh);
    // The root is the hull of everything: as far out as the farthest leaf.
    for (int k = 0; k < 20; ++k) {
      const Vec3 d = test::randomDirection(rng);
      double leaf_max = -kInfinity;
      for (const ConvexPolytope& l : leaves) leaf_max = std::max(leaf_max, supportValue(l, d));
      if (!bvh.nodes[0].hasPolytope()) break;  // few points: the sphere was checked
      EXPECT_NEAR(supportValue(bvh.hulls[bvh.nodes[0].polytope], d), leaf_max, 1e-12 * 40);
    }
  }
}

TEST(HullBvh, OneLeafIsATreeOfOneNodeWithoutHull) {
  test::Rng rng(3);
  const std::vector<ConvexPolytope> leaves = randomLeaves(rng, 1);
  const HullBvh bvh = buildHullBvh(leaves, {});
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_TRUE(bvh.nodes[0].leaf());
  EXPECT_TRUE(bvh.hulls.empty());
  EXPECT_EQ(bvh.depth, 0);
  EXPECT_TRUE(buildHullBvh({}, {}).nodes.empty());
}

TEST(HullBvh, IsDeterministic) {
  test::Rng rng(11);
  const std::vector<ConvexPolytope> leaves = randomLeaves(rng, 64);
  const HullBvh a = buildHullBvh(leaves, {});
  const HullBvh b = buildHullBvh(leaves, {});
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].left, b.nodes[i].left);
    EXPECT_EQ(a.nodes[i].polytope, b.nodes[i].polytope);
  }
  for (std::size_t i = 0; i < a.hulls.size(); ++i)
    EXPECT_EQ(a.hulls[i].vertices, b.hulls[i].vertices);
}

TEST(HullBvh, PlanarSoupGetsFlatHullsThatContainTheTriangles) {
  // A 12 x 12 grid of squares in z = 0, two triangles each: every hull is flat,
  // so qhull refuses them and the in-plane hull takes over.
  MeshData grid;
  const int n = 12;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) grid.vertices.emplace_back(x, y, 0.0);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x;
      grid.triangles.emplace_back(a, a + 1, a + n + 2);
      grid.triangles.emplace_back(a, a + n + 2, a + n + 1);
    }
  }
  const Result<PiecePtr> piece = buildPiece(ModelKind::TriangleSoup, grid);
  ASSERT_TRUE(piece.ok());
  const PieceData& data = piece.value()->internals();
  expectValidHierarchy(data.patches, data.hierarchy);
  // Flat hulls keep only their polygon's corners: no node gathers the grid's points.
  std::size_t most = 0;
  for (const ConvexPolytope& hull : data.hierarchy.hulls)
    most = std::max(most, hull.vertices.size());
  EXPECT_LE(most, 24u);
  EXPECT_EQ(piece.value()->stats().tree_depth, data.hierarchy.depth);
}

TEST(HullBvh, LeavesOfADecomposedPieceArePatches) {
  MeshData mesh;
  ASSERT_NO_FATAL_FAILURE(mesh = test::loadTestMesh("elephant"));
  const Result<PiecePtr> piece = buildPiece(ModelKind::ClosedPolyhedron, mesh);
  ASSERT_TRUE(piece.ok()) << piece.status().message();
  const PieceData& data = piece.value()->internals();
  ASSERT_GT(data.patches.size(), 100u);
  expectValidHierarchy(data.patches, data.hierarchy);
  EXPECT_EQ(piece.value()->stats().tree_depth, data.hierarchy.depth);
  // Inner hull vertices are input vertices.
  for (const ConvexPolytope& hull : data.hierarchy.hulls) {
    for (std::size_t i = 0; i < hull.vertices.size(); ++i)
      ASSERT_EQ(hull.vertices[i], data.mesh.vertices[hull.original[i]]);
  }
}

// Inner hulls keep what the traversal reads of them (vertices, faces, adjacency),
// not face sources (all virtual) or vertex-face lists, built or loaded: those were
// a tenth of a soup's memory.
TEST(HullBvh, InnerHullsKeepOnlyWhatTheTraversalReads) {
  MeshData mesh;
  ASSERT_NO_FATAL_FAILURE(mesh = test::loadTestMesh("elephant"));
  const Result<PiecePtr> piece = buildPiece(ModelKind::ClosedPolyhedron, mesh);
  ASSERT_TRUE(piece.ok()) << piece.status().message();
  const PieceData& built = piece.value()->internals();
  PieceData loaded;
  loaded.kind = built.kind;
  loaded.mesh = built.mesh;
  const std::uint64_t key = 7;
  ASSERT_TRUE(decodePieceCache(encodePieceCache(key, built), key, loaded));
  for (const PieceData* data : {&built, static_cast<const PieceData*>(&loaded)}) {
    int faceted = 0;
    for (const ConvexPolytope& hull : data->hierarchy.hulls) {
      EXPECT_TRUE(hull.face_source.empty());
      EXPECT_TRUE(hull.vertex_face_start.empty());
      EXPECT_TRUE(hull.vertex_faces.empty());
      if (hull.faces.empty()) continue;
      ++faceted;
      EXPECT_EQ(hull.adjacency_start.size(), hull.vertices.size() + 1);
    }
    EXPECT_GT(faceted, 0);
  }
}

TEST(HullBvh, RandomSoupLeavesAreItsTriangles) {
  test::Rng rng(5);
  MeshData soup;
  for (int t = 0; t < 300; ++t) {
    const Vec3 c(test::uniform(rng, -5, 5), test::uniform(rng, -5, 5), test::uniform(rng, -5, 5));
    for (int k = 0; k < 3; ++k) soup.vertices.push_back(c + 0.5 * test::randomDirection(rng));
    soup.triangles.emplace_back(3 * t, 3 * t + 1, 3 * t + 2);
  }
  soup.triangles.emplace_back(0, 0, 1);  // degenerate: a segment
  const Result<PiecePtr> piece = buildPiece(ModelKind::TriangleSoup, soup);
  ASSERT_TRUE(piece.ok());
  const PieceData& data = piece.value()->internals();
  ASSERT_EQ(data.patches.size(), soup.triangles.size());
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(data.patches[t].vertices[k], soup.vertices[soup.triangles[t][k]]);
  }
  expectValidHierarchy(data.patches, data.hierarchy);
}

/// Per node: the input vertices (original indices) below it; checks which inner
/// nodes keep a polytope: all of them, or when `alternate` those at even depths
/// (over few points or many). Returns the hull-less inner nodes above 24
/// points; `small_without` the others.
int expectHullPolicy(const std::vector<ConvexPolytope>& leaves, const HullBvh& bvh, bool alternate,
                     int& small_without) {
  int large_without = 0;
  small_without = 0;
  std::function<std::set<int>(int, int)> below = [&](int index, int depth) {
    const HullBvhNode& node = bvh.nodes[index];
    if (node.leaf()) {
      const ConvexPolytope& leaf = leaves[node.polytope];
      return std::set<int>(leaf.original.begin(), leaf.original.end());
    }
    std::set<int> ids = below(node.left, depth + 1);
    const std::set<int> right = below(node.right, depth + 1);
    ids.insert(right.begin(), right.end());
    const bool large = ids.size() > 24u;
    EXPECT_EQ(node.hasPolytope(), !alternate || depth % 2 == 0)
        << "node " << index << " at depth " << depth << " over " << ids.size() << " points";
    if (!node.hasPolytope()) ++(large ? large_without : small_without);
    return ids;
  };
  below(0, 0);
  return large_without;
}

TEST(HullBvh, SoupsKeepHullsOnEveryOtherDepthClosedPiecesEverywhere) {
  const Result<PiecePtr> soup =
      buildPiece(ModelKind::TriangleSoup, test::torusMesh(1.0, 0.3, 32, 16));
  ASSERT_TRUE(soup.ok());
  const PieceData& s = soup.value()->internals();
  expectValidHierarchy(s.patches, s.hierarchy);
  int small = 0;
  EXPECT_GT(expectHullPolicy(s.patches, s.hierarchy, true, small), 0);
  EXPECT_GT(small, 0);
  MeshData elephant;
  ASSERT_NO_FATAL_FAILURE(elephant = test::loadTestMesh("elephant"));
  const Result<PiecePtr> closed = buildPiece(ModelKind::ClosedPolyhedron, elephant);
  ASSERT_TRUE(closed.ok());
  const PieceData& c = closed.value()->internals();
  EXPECT_EQ(expectHullPolicy(c.patches, c.hierarchy, false, small), 0);
  EXPECT_EQ(small, 0);
}

TEST(HullBvh, ConvexPieceNeedsNoTree) {
  const Result<PiecePtr> piece =
      buildPiece(ModelKind::ClosedPolyhedron, test::boxMesh(Vec3(1.0, 2.0, 3.0)));
  ASSERT_TRUE(piece.ok());
  const PieceData& data = piece.value()->internals();
  EXPECT_EQ(data.hierarchy.nodes.size(), 1u);
  EXPECT_TRUE(data.hierarchy.hulls.empty());
  EXPECT_EQ(piece.value()->stats().tree_depth, 0);
}

TEST(HullBvh, ProgressRisesToOne) {
  test::Rng rng(13);
  const std::vector<ConvexPolytope> leaves = randomLeaves(rng, 500);
  std::vector<double> fractions;
  buildHullBvh(leaves, [&](double f, const char*) { fractions.push_back(f); });
  ASSERT_GE(fractions.size(), 10u);
  EXPECT_LE(fractions.size(), 120u) << "not throttled";
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_GE(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
}

TEST(HullBvh, FinishRejectsBrokenStructures) {
  test::Rng rng(17);
  const std::vector<ConvexPolytope> leaves = randomLeaves(rng, 8);
  const HullBvh good = buildHullBvh(leaves, {});
  HullBvh copy = good;
  ASSERT_TRUE(finishHullBvh(leaves, copy));
  EXPECT_EQ(copy.depth, good.depth);

  const auto broken = [&](const std::function<void(HullBvh&)>& edit) {
    HullBvh b = good;
    edit(b);
    return !finishHullBvh(leaves, b);
  };
  EXPECT_TRUE(broken([](HullBvh& b) { b.nodes.pop_back(); }));
  EXPECT_TRUE(broken([](HullBvh& b) { b.hulls.pop_back(); }));
  EXPECT_TRUE(broken([](HullBvh& b) { b.nodes[0].left = 0; }));  // a cycle
  EXPECT_TRUE(broken([](HullBvh& b) { b.nodes[0].right = b.nodes[0].left; }));
  EXPECT_TRUE(broken([](HullBvh& b) { b.nodes[0].left = 1000; }));
  EXPECT_TRUE(broken([](HullBvh& b) { b.nodes[0].polytope = -1; }));  // a hull unused
  EXPECT_TRUE(broken([](HullBvh& b) { b.nodes[0].polytope = -2; }));
  EXPECT_TRUE(broken([](HullBvh& b) {  // a hull named twice
    for (HullBvhNode& n : b.nodes) {
      if (&n != &b.nodes[0] && n.hasPolytope() && !n.leaf()) n.polytope = b.nodes[0].polytope;
    }
  }));
  // A node without hull, its hull gone: valid, bounded by its sphere.
  HullBvh fewer = good;
  ASSERT_TRUE(fewer.nodes[0].hasPolytope());
  fewer.hulls.erase(fewer.hulls.begin() + fewer.nodes[0].polytope);
  for (HullBvhNode& n : fewer.nodes)
    if (!n.leaf() && n.polytope > good.nodes[0].polytope) --n.polytope;
  fewer.nodes[0].polytope = -1;
  ASSERT_TRUE(finishHullBvh(leaves, fewer));
  EXPECT_EQ(fewer.nodes[0].center, copy.nodes[0].center);
  EXPECT_NEAR(fewer.nodes[0].radius, copy.nodes[0].radius, 1e-15 * copy.nodes[0].radius);
  expectValidHierarchy(leaves, fewer);
  EXPECT_TRUE(broken([](HullBvh& b) {
    // Two leaves naming the same patch.
    int first = -1;
    for (HullBvhNode& n : b.nodes) {
      if (!n.leaf()) continue;
      if (first < 0) {
        first = n.polytope;
      } else {
        n.polytope = first;
        break;
      }
    }
  }));
  EXPECT_TRUE(broken([](HullBvh& b) {
    for (HullBvhNode& n : b.nodes) {
      if (n.leaf()) {
        n.right = 0;
        break;
      }
    }
  }));
}

}  // namespace
}  // namespace sc::detail
