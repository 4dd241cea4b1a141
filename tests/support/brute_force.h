// SPDX-License-Identifier: MIT
// Brute-force references: exact surface distance of two placed triangle meshes
// (minimum over all triangle pairs), point-surface and point-feature distances,
// and point-in-convex-polytope.
#pragma once

#include <vector>

#include "geometry/convex_polytope.h"
#include "smartcollision/model.h"

namespace sc::test {

struct SurfaceDistance {
  double distance = 0.0;
  Vec3 point_a = Vec3::Zero();  ///< common frame
  Vec3 point_b = Vec3::Zero();  ///< common frame
};

/// Minimum distance between the surfaces of `a` and `b` placed by rigid
/// transforms: every triangle pair, skipping pairs whose bounding spheres are
/// already farther apart than the best so far (exact, just faster).
SurfaceDistance meshSurfaceDistance(const MeshData& a, const Rigid& frame_from_a, const MeshData& b,
                                    const Rigid& frame_from_b);

/// Distance from p (mesh frame) to the nearest triangle of the mesh.
double pointSurfaceDistance(const MeshData& mesh, const Vec3& p);

/// Largest d . x over the polytope's vertices, each one tried.
double supportValue(const detail::ConvexPolytope& poly, const Vec3& d);

/// True when every directed edge of `faces` is used once and its reverse once: a
/// closed surface, wound consistently.
bool eachEdgeOnceEachWay(const std::vector<Tri>& faces);

/// True when p (polytope frame) is inside every face plane, within `tolerance`.
bool pointInConvexPolytope(const detail::ConvexPolytope& poly, const Vec3& p, double tolerance);

/// Distance from p to the vertex, segment or triangle `feature` whose vertex
/// indices refer to `points`.
double pointFeatureDistance(const std::vector<Vec3>& points, const Feature& feature, const Vec3& p);

/// Exact global penetration depth of two placed convex polytopes.
struct ExactDepth {
  double depth = kInfinity;      ///< distance from the origin to the hull boundary
  Vec3 normal = Vec3::Zero();    ///< outward normal of the nearest facet
  double runner_up = kInfinity;  ///< depth of the next facet with another normal
};
/// The origin's distance to the boundary of the hull of {wa a - wb b} over every
/// vertex pair (qhull): translating A by depth * normal makes them touch.
ExactDepth exactPenetrationDepth(const detail::ConvexPolytope& a, const Rigid& wa,
                                 const detail::ConvexPolytope& b, const Rigid& wb);

}  // namespace sc::test
