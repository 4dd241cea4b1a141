// SPDX-License-Identifier: MIT
// The convex polytope of one surface patch: the hull of the patch's vertices whose
// faces are the patch's own triangles plus virtual triangles that close the hull.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "geometry/convex_polytope.h"
#include "geometry/halfspace_polytope.h"
#include "geometry/triangle_adjacency.h"
#include "smartcollision/model.h"

namespace sc::detail {

/// Every geometric test of the decomposition allows this much, relative to the
/// diagonal of the mesh's bounding box: points within it of a plane are on it,
/// and hulls may reach out of the solid by about this much.
inline constexpr double kDecompositionRelativeTolerance = 1e-6;
/// Patches whose vertices lie within this many tolerances of a plane are flat: their
/// hull is a double-sided polygon without interior.
inline constexpr double kFlatFactor = 2.0;
/// Depth, in tolerances, of the probe prisms under virtual faces of thin hulls; a
/// hull thinner than twice this is thin.
inline constexpr double kProbeDepth = 20.0;

/// kDecompositionRelativeTolerance times the bounding-box diagonal of the vertices
/// the triangles use (model units).
double decompositionTolerance(const MeshData& mesh);

/// A patch: the first `count` triangles of `faces`. `rank[t]` is triangle t's
/// position in `faces` or -1, so membership is one lookup.
struct PatchRef {
  const std::vector<int>& faces;
  const std::vector<int>& rank;
  int count = 0;

  bool contains(int t) const { return rank[t] >= 0 && rank[t] < count; }
};

struct PatchPolytope {
  /// Vertices: the patch's vertices (`original` = input index). Faces: the patch's
  /// triangles (face_source = input index), then the virtual faces (-1).
  ConvexPolytope polytope;
  int virtual_faces = 0;
  bool flat = false;        ///< within kFlatFactor tolerances of a plane
  bool used_qhull = false;  ///< supporting planes and coverage checked on the full hull
  /// Not flat: the hull's outward face planes (qhull's, or those of `polytope`).
  /// The hull shrunk by the tolerance must meet no triangle outside the patch.
  std::vector<Plane> planes;
  /// Flat or thin hulls have (almost) no interior to test. Instead, under each
  /// virtual face that looks the patch's way (a pocket in the patch's outline) the
  /// solid must go on: these prisms, to kProbeDepth tolerances under the face and
  /// from kFlatFactor tolerances under it (thin hulls) or above it (flat patches,
  /// so that a triangle of the patch's plane left in a pocket is refused too), must
  /// meet no triangle outside the patch.
  std::vector<std::array<Plane, 5>> probes;
};

/// How buildPatchPolytope finds the hull's supporting planes and checks that the
/// faces cover the hull exactly once.
enum class HullCheck : std::uint8_t {
  /// The vertices' hull (quickHull, or convexHull where it declines): support by
  /// hill climbing, coverage by area.
  Qhull,
  /// Patches of at most kScanVertices vertices skip qhull: support by scanning
  /// the vertices, coverage by the winding number about the vertices' centroid.
  /// Larger patches use qhull. For the many checks while a patch grows.
  Quick,
};
inline constexpr int kScanVertices = 48;

/// Builds the polytope of `patch` (triangles of a closed, outward-oriented mesh
/// with the given adjacency). InvalidGeometry when the patch is not on the
/// boundary of its hull within `tolerance`, or its virtual faces cannot be found
/// (no ear, or the faces do not cover the hull once), or a flat patch's pocket
/// borders a convex edge (so it reaches out of the solid). Does not test other
/// triangles against the hull: the caller does, with `planes` and `probes`.
Result<PatchPolytope> buildPatchPolytope(const MeshData& mesh, const TriangleAdjacency& adjacency,
                                         const PatchRef& patch, double tolerance,
                                         HullCheck check = HullCheck::Qhull);

}  // namespace sc::detail
