// SPDX-License-Identifier: MIT
// Global penetration depth of two convex polytopes without a hull library: GJK's
// final tetrahedron grown by an expanding polytope (EPA) kept as a triangle list,
// support points by hill climbing on each polytope's vertex adjacency.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "query/epa.h"
#include "query/gjk.h"
#include "query/minkowski.h"

namespace sc::detail {

/// Work arrays of convexDepth(), kept between calls: once grown, a call allocates
/// nothing.
struct EpaScratch {
  using Vertex = MinkowskiVertex;
  struct Face {
    int v[3] = {0, 0, 0};       ///< outward counter-clockwise
    int adj[3] = {-1, -1, -1};  ///< face across edge (v[k], v[k + 1])
    Vec3 n = Vec3::UnitZ();
    double d = 0.0;  ///< n . w: distance of its plane from the origin
    bool live = true;
  };
  std::vector<Vertex> vertices;
  std::vector<Face> faces;
  std::vector<std::pair<double, int>> heap;  ///< (distance, face), nearest first
  std::vector<int> stack;
  std::vector<std::array<int, 3>> rim;  ///< (from, to, outside face) of the seen region
};

/// Warm start of one convex pair: GJK's last simplex and support hints.
struct ConvexPairCache {
  SimplexCache gjk;
  EpaScratch epa;
};

enum class ConvexDepthStatus : std::uint8_t {
  Separated,    ///< GJK found the polytopes apart (or a frame is not finite): no depth
  Penetrating,  ///< `result` holds the depth, exact to the relative tolerance
  Touching,     ///< depth 0 (the origin on the boundary of A - B); `result` holds it
};

/// Outline:
///   1. GJK (warm-started from `cache`); apart -> Separated.
///   2. Its final simplex, a tetrahedron holding the origin (a triangle through the
///      origin gets the support points on both sides of its plane), is the first
///      polytope.
///   3. Take the face nearest the origin; the support point in its normal moves that
///      face out by at most a relative 1e-14 (or is a vertex already): done, the
///      face lies on a facet of A - B, and its distance is the depth. Else the faces
///      the point sees are replaced by the cone from their rim to the point.
/// Where the polytope degenerates (a flat simplex, a sliver face, a rim that is not
/// one loop) it falls back to penetrationDepth(), the hull-based EPA, so the answer
/// is the same. Result fields and frames as in penetrationDepth().
ConvexDepthStatus convexDepth(const ConvexPolytope& a, const Rigid& frame_from_a,
                              const ConvexPolytope& b, const Rigid& frame_from_b,
                              ConvexPairCache& cache, EpaResult& result);

}  // namespace sc::detail
