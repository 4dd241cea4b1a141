// SPDX-License-Identifier: MIT
// Condition (2) of the decomposition: does a triangle outside a patch reach into a
// convex region (the patch's hull, a probe prism, a tetrahedron of new hull)
// shrunk by the tolerance? Walks the region's tree (region_tree.h), pruned by the
// convex region's planes or by a few planes that contain it.
#pragma once

#include <cstddef>
#include <vector>

#include "geometry/convex_polytope.h"
#include "geometry/halfspace_polytope.h"
#include "preprocess/decomposition_mesh.h"
#include "preprocess/patch_polytope.h"
#include "preprocess/region_tree.h"

namespace sc::detail {

/// Hulls with at most this many planes prune the tree with their own.
inline constexpr std::size_t kOwnPlanesUpTo = 64;

/// A few planes that contain the hull of `poly`'s vertices: both ways along each
/// outer direction and along the normals of its largest faces, each through the
/// vertices' support. Pruning the tree with them costs O(1) planes per node where
/// the hull's own planes cost O(hull size), which made each condition (2) check
/// quadratic in the patch. They contain the hull, so the hull shrunk by the
/// tolerance lies in them shrunk by it: no triangle reaching it is pruned.
std::vector<Plane> outerPlanes(const ConvexPolytope& poly);

/// The patch a test ignores, and whether it is the whole patch that `tree` counts
/// (then the walk skips the subtrees it fills).
struct PatchInTree {
  const PatchRef& patch;
  bool counted;
};

/// True when a triangle of `shared.mesh` outside the patch (and other than
/// `also_skip`) reaches the polytope given by `planes`, shrunk by the tolerance;
/// `bounds` encloses it and lies in the region `tree` covers. Non-empty `outer`
/// planes contain it and prune the tree in its place.
bool reachesInside(const SharedMesh& shared, const RegionTree& tree, PatchInTree patch,
                   std::vector<Plane> planes, const Aabb& bounds, int also_skip = -1,
                   std::vector<Plane> outer = {});

/// reachesInside for several polytopes (the first bounds.size() of `polytopes`, each
/// in its bounds) in one walk of the tree:
/// true when some triangle reaches one of them. A triangle is tested against a
/// polytope only where its own box may reach it, so the answer is the same as
/// one reachesInside per polytope.
bool reachesAnyInside(const SharedMesh& shared, const RegionTree& tree, PatchInTree patch,
                      std::vector<HalfspacePolytope>& polytopes, const std::vector<Aabb>& bounds,
                      int also_skip);

}  // namespace sc::detail
