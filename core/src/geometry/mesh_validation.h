// SPDX-License-Identifier: MIT
// Input checks of manual 6.2 and docs/api.md: finiteness and indices for every
// piece; closedness, winding, non-degeneracy and one shell for closed polyhedra.
#pragma once

#include "geometry/math_util.h"
#include "smartcollision/mesh.h"

namespace sc::detail {

/// Finite coordinates, indices in range, counts consistent, an extent within
/// [kMinPieceExtent, kMaxPieceExtent] (or 0). InvalidArgument otherwise.
Status validateArrays(const MeshData& mesh);

/// For a closed polyhedron piece: every edge shared by exactly two triangles with
/// opposite winding, no degenerate (zero-area) triangle, one connected shell.
/// InvalidGeometry otherwise. If the piece is inside out (negative signed volume)
/// its triangles are flipped in place and `flipped` is set.
Status validateClosed(MeshData& mesh, bool& flipped);

/// True when every edge of the closed, consistently oriented mesh is convex or flat
/// (within a relative angular tolerance), i.e. the piece is a convex polyhedron.
bool isConvex(const MeshData& mesh);

}  // namespace sc::detail
