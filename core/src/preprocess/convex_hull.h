// SPDX-License-Identifier: MIT
// Convex hulls through qhull (reentrant libqhull_r, double precision).
#pragma once

#include <vector>

#include "geometry/convex_polytope.h"

namespace sc::detail {

/// The convex hull of `points`, triangulated, outward counter-clockwise; each hull
/// vertex keeps `original[i]` of the point it came from (or i if `original` is
/// empty). Faces get face_source -1 (the caller marks real faces).
/// InvalidGeometry when the points span less than a 3-D volume.
Result<ConvexPolytope> convexHull(const std::vector<Vec3>& points,
                                  const std::vector<int>& original = {});

}  // namespace sc::detail
