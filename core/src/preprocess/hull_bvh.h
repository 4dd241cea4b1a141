// SPDX-License-Identifier: MIT
// Hierarchy of convex hulls over a piece's leaves (patches of a closed piece, or
// the triangles of a soup): each inner node bounds the hull of its children.
#pragma once

#include <vector>

#include "geometry/convex_polytope.h"
#include "smartcollision/model.h"

namespace sc::detail {

struct HullBvhNode {
  Vec3 center = Vec3::Zero();  ///< bounding sphere of the node's polytope (piece frame)
  double radius = 0.0;
  int left = -1;      ///< inner: first child; leaf: -1
  int right = -1;     ///< inner: second child; leaf: -1
  int polytope = -1;  ///< leaf: index into the leaves; inner: into HullBvh::hulls

  bool leaf() const { return left < 0; }
};

/// Binary tree over the leaves, root at nodes[0] (empty without leaves). One leaf
/// is a tree of one node and no hull. Inner node polytopes are convex hulls of their
/// children's vertices (small ones are kept as the bare point set, which has the same
/// hull, without faces), so every inner polytope contains its descendants.
struct HullBvh {
  std::vector<HullBvhNode> nodes;
  std::vector<ConvexPolytope> hulls;  ///< inner nodes' polytopes
  std::vector<int> leaf_node;         ///< per leaf: its node
  int depth = 0;                      ///< edges on the longest root-leaf path

  /// The polytope of `node`: a leaf's from `leaves`, an inner node's from `hulls`.
  const ConvexPolytope& polytope(const std::vector<ConvexPolytope>& leaves, int node) const {
    const HullBvhNode& n = nodes[node];
    return n.leaf() ? leaves[n.polytope] : hulls[n.polytope];
  }
};

/// Builds the hierarchy top-down by median splits along the principal axis of the
/// leaves' centres, then the inner polytopes bottom-up (quickHull, else qhull). `progress` (may be
/// empty) gets fractions in [0, 1], throttled, on the calling thread. Each depth's
/// hulls are built on up to `threads` threads; the result is the same for any count.
HullBvh buildHullBvh(const std::vector<ConvexPolytope>& leaves, const ProgressCallback& progress,
                     int threads = 1);

/// Fills `leaf_node`, `depth` and every node's bounding sphere from `nodes`, `hulls`
/// and `leaves`, after checking the structure: a binary tree rooted at 0 in which
/// every node is reached once, every leaf index appears once, every hull once.
/// False (bvh unchanged otherwise) when the structure is invalid. Inner hulls keep
/// what queries read of them (vertices, original indices, faces, adjacency), not
/// face sources (all virtual) or vertex-face lists.
bool finishHullBvh(const std::vector<ConvexPolytope>& leaves, HullBvh& bvh);

}  // namespace sc::detail
