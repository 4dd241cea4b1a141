// SPDX-License-Identifier: MIT
// What a preprocessed piece holds. Private to the library; reached through
// Piece::internals().
#pragma once

#include <vector>

#include "geometry/convex_polytope.h"
#include "preprocess/hull_bvh.h"
#include "smartcollision/model.h"

namespace sc::detail {

struct PieceData {
  ModelKind kind = ModelKind::ClosedPolyhedron;
  MeshData mesh;  ///< as stored (closed pieces oriented outward)
  PieceStats stats;
  Aabb bounds;
  /// Closed polyhedron: the convex patches (one for a convex piece), each a convex
  /// polytope inside the solid whose union of real faces is the piece's surface.
  /// Triangle soup: one two-sided leaf per input triangle, in input order.
  std::vector<ConvexPolytope> patches;
  /// Hull hierarchy over `patches` (one node for a convex piece).
  HullBvh hierarchy;
};

}  // namespace sc::detail
