// SPDX-License-Identifier: MIT
// Hierarchy of convex hulls over a piece's leaves (patches of a closed piece, or
// the triangles of a soup): each inner node bounds the hull of its children, by
// that hull or, where storing it costs more than it saves, by its sphere alone.
#pragma once

#include <vector>

#include "geometry/convex_polytope.h"
#include "smartcollision/model.h"

namespace sc::detail {

struct HullBvhNode {
  Vec3 center = Vec3::Zero();  ///< bounding sphere of the node's polytope (piece frame)
  double radius = 0.0;
  int left = -1;   ///< inner: first child; leaf: -1
  int right = -1;  ///< inner: second child; leaf: -1
  /// Leaf: index into the leaves; inner: into HullBvh::hulls, or -1 when the node
  /// keeps no hull (its sphere bounds it; queries descend to its children).
  int polytope = -1;

  bool leaf() const { return left < 0; }
  /// A leaf, or an inner node with a hull: GJK can measure it.
  bool hasPolytope() const { return polytope >= 0; }
};

/// Binary tree over the leaves, root at nodes[0] (empty without leaves). One leaf
/// is a tree of one node and no hull. Inner node polytopes are convex hulls of their
/// descendants' vertices (small ones kept as the bare point set, which has the same
/// hull), so every inner polytope contains its descendants. With
/// HullLevels::Alternate some inner nodes keep none: their bounding spheres, of the
/// same points, bound them.
struct HullBvh {
  std::vector<HullBvhNode> nodes;
  std::vector<ConvexPolytope> hulls;  ///< the polytopes of the inner nodes that keep one
  std::vector<int> leaf_node;         ///< per leaf: its node
  int depth = 0;                      ///< edges on the longest root-leaf path

  /// The polytope of `node` (hasPolytope()): a leaf's from `leaves`, an inner
  /// node's from `hulls`.
  const ConvexPolytope& polytope(const std::vector<ConvexPolytope>& leaves, int node) const {
    const HullBvhNode& n = nodes[node];
    return n.leaf() ? leaves[n.polytope] : hulls[n.polytope];
  }
};

/// Which inner nodes keep a polytope (up to 24 distinct points as a bare point
/// set). Every: all of them, as a closed piece's queries lean on them and its patch
/// leaves dwarf them. Alternate: a soup's nodes of even depth only. On a soup's
/// curved surface about half of all the vertices lie on the hulls of every depth,
/// so each depth costs about that again (1M-triangle torus: 20 to 35 bytes per
/// triangle per depth). Its small point sets stay: without them the queries on a
/// soup ran 1.7x slower (the sphere of a few triangles bounds them far worse).
enum class HullLevels { Every, Alternate };

/// Builds the hierarchy top-down by median splits along the principal axis of the
/// leaves' centres, then the inner polytopes bottom-up (quickHull, else qhull). `progress` (may be
/// empty) gets fractions in [0, 1], throttled, on the calling thread. Each depth's
/// hulls are built on up to `threads` threads; the result is the same for any count.
HullBvh buildHullBvh(const std::vector<ConvexPolytope>& leaves, const ProgressCallback& progress,
                     int threads = 1, HullLevels levels = HullLevels::Every);

/// Fills `leaf_node`, `depth` and every node's bounding sphere from `nodes`, `hulls`
/// and `leaves` (a node without hull: the sphere of its descendants' points, as its
/// hull would give), after checking the structure: a binary tree rooted at 0 in
/// which every node is reached once, every leaf index appears once, every hull once.
/// False (bvh unchanged otherwise) when the structure is invalid. Inner hulls keep
/// what queries read of them (vertices, original indices, faces, adjacency), not
/// face sources (all virtual) or vertex-face lists.
bool finishHullBvh(const std::vector<ConvexPolytope>& leaves, HullBvh& bvh);

}  // namespace sc::detail
