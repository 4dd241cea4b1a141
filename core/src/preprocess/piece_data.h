// SPDX-License-Identifier: MIT
// What a preprocessed piece holds. Private to the library; reached through
// Piece::internals().
#pragma once

#include <vector>

#include "geometry/convex_polytope.h"
#include "smartcollision/model.h"

namespace sc::detail {

struct PieceData {
  ModelKind kind = ModelKind::ClosedPolyhedron;
  MeshData mesh;  ///< as stored (closed pieces oriented outward)
  PieceStats stats;
  Aabb bounds;
  /// Closed polyhedron: the convex patches (one for a convex piece), each a convex
  /// polytope inside the solid whose union of real faces is the piece's surface.
  std::vector<ConvexPolytope> patches;
};

}  // namespace sc::detail
