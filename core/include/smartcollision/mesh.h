// SPDX-License-Identifier: MIT
// Geometry input: an indexed triangle set and the extents a piece may have. The
// lowest layer's input type, shared by validation, preprocessing and the façade.
#pragma once

#include <vector>

#include "smartcollision/types.h"

namespace sc {

/// An indexed triangle set. Indices count from 0.
struct MeshData {
  std::vector<Vec3> vertices;
  std::vector<Tri> triangles;
};

/// Extents a piece may have: the largest side of the box of the vertices its
/// triangles use lies in [kMinPieceExtent, kMaxPieceExtent] (or is 0: a soup that
/// is one point). Within it every internal threshold is relative to the models'
/// size, so results have the same relative accuracy at every scale (docs/api.md,
/// "Scale"); beyond it products of coordinates under- or overflow.
inline constexpr double kMinPieceExtent = 1e-9;
inline constexpr double kMaxPieceExtent = 1e9;

}  // namespace sc
