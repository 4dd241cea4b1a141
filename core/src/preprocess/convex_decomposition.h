// SPDX-License-Identifier: MIT
// Convex surface decomposition of a closed piece (manual 6.3; SWIFT++, Ehmann &
// Lin, Eurographics 2001): patches grown across convex edges, each lying on the
// boundary of its own convex hull, each hull inside the solid.
#pragma once

#include <vector>

#include "geometry/convex_polytope.h"
#include "smartcollision/model.h"

namespace sc::detail {

struct Decomposition {
  /// One convex polytope per patch: the hull of the patch's vertices. Faces equal to
  /// an input triangle carry its index in face_source; the others are virtual (-1).
  std::vector<ConvexPolytope> patches;
  std::vector<int> triangle_patch;  ///< per input triangle, its patch
  int virtual_faces = 0;
};

/// Decomposes a validated, outward-oriented closed piece. A convex piece gives one
/// patch. `progress` and `cancel` may be empty; `cancel` is asked after each patch
/// and stops the work with InvalidOperation. Patches grow within spatial regions
/// of the mesh, on `threads` threads (at least one); the result is the same for
/// every thread count. Both callbacks run on the calling thread only.
Result<Decomposition> decomposeConvexSurface(const MeshData& mesh, const ProgressCallback& progress,
                                             const CancelCallback& cancel = {}, int threads = 1);

}  // namespace sc::detail
