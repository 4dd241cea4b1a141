// SPDX-License-Identifier: MIT
// The closest feature of a polytope at a point: vertex, edge or face, named by the
// piece's original vertex indices.
#pragma once

#include "geometry/convex_polytope.h"
#include "smartcollision/types.h"

namespace sc::detail {

/// Feature tolerance of a polytope, as results report features: relative to its size
/// and position, with no absolute floor, so it holds at every scale.
inline double featureTolerance(const ConvexPolytope& poly) {
  return 1e-9 * (poly.radius + poly.center.norm());
}

/// The smallest feature of `poly` containing `point` (polytope-local frame), seeded
/// by the simplex vertices `ids[0..count)` GJK ended with. Vertex if within
/// `tolerance` of a vertex, else an edge of a face containing the point, else a face.
/// A face that is not an input triangle, or an edge of no input triangle, is virtual.
/// Vertex indices are original (ConvexPolytope::original).
Feature closestFeature(const ConvexPolytope& poly, const Vec3& point, const int* ids, int count,
                       double tolerance);

}  // namespace sc::detail
