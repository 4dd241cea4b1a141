// SPDX-License-Identifier: MIT
// Global penetration depth of two intersecting convex polytopes: the distance from
// the origin to the boundary of their Minkowski difference, by an expanding
// polytope of support points (EPA; G. van den Bergen, "Proximity Queries and
// Penetration Depth Computation on 3D Game Objects", GDC 2001).
#pragma once

#include <cstdint>

#include "geometry/convex_polytope.h"

namespace sc::detail {

enum class EpaStatus : std::uint8_t {
  Converged,     ///< depth and direction exact to the relative tolerance
  Touching,      ///< depth 0 (the origin is on the boundary, or the difference is flat)
  NotConverged,  ///< iteration cap: the best lower bound found, still a valid exit
};

struct EpaResult {
  EpaStatus status = EpaStatus::Touching;
  double depth = 0.0;           ///< >= 0
  Vec3 normal = Vec3::UnitZ();  ///< unit: translating A by depth * normal separates them
  Vec3 point_a = Vec3::Zero();  ///< deepest point of A, common frame
  Vec3 point_b = Vec3::Zero();  ///< matching point of B, common frame
  int iterations = 0;
  /// Vertex indices on A and B (into ConvexPolytope::vertices) of the face the depth
  /// was read from, when known (convexDepth); `face_count` 0 otherwise.
  int face_count = 0;
  int face_a[3] = {-1, -1, -1};
  int face_b[3] = {-1, -1, -1};
};

/// Outline, and where it departs from the textbook algorithm:
///   1. Start from support points of A - B in 14 directions (axes and diagonals), so
///      no GJK simplex of 1, 2 or 3 vertices ever has to be blown up by hand.
///   2. Hull the points (qhull, exact predicates); take the facet nearest the origin
///      (signed: while the origin is outside the hull the most negative facet).
///   3. Support in that facet's normal; if it does not move the facet out by more
///      than a relative 1e-12, stop; else add the point and repeat.
/// Never returns NaN; a flat difference (coplanar triangles) gives Touching with
/// the plane's normal. Allocates (it is meant for a pair's first contact, not per
/// frame). `a_from_b` and frames as in gjkDistance.
EpaResult penetrationDepth(const ConvexPolytope& a, const Rigid& frame_from_a,
                           const ConvexPolytope& b, const Rigid& frame_from_b,
                           int max_iterations = 64);

}  // namespace sc::detail
