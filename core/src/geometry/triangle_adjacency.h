// SPDX-License-Identifier: MIT
// Edge adjacency of a closed, consistently oriented triangle mesh: for each
// triangle edge, the triangle on the other side.
#pragma once

#include <array>
#include <vector>

#include "smartcollision/mesh.h"

namespace sc::detail {

/// Edge k of triangle t runs from corner k to corner (k + 1) % 3.
class TriangleAdjacency {
 public:
  /// InvalidGeometry unless every directed edge has exactly one opposite edge
  /// (each edge shared by two triangles with opposite winding).
  static Result<TriangleAdjacency> build(const MeshData& mesh);

  /// The triangle across edge k of t.
  int neighbour(int t, int k) const { return neighbours_[t][k]; }
  /// The edge index of that neighbour's copy of the edge (it runs the other way).
  int neighbourEdge(int t, int k) const { return neighbour_edges_[t][k]; }
  int triangleCount() const { return static_cast<int>(neighbours_.size()); }

 private:
  std::vector<std::array<int, 3>> neighbours_;
  std::vector<std::array<signed char, 3>> neighbour_edges_;
};

}  // namespace sc::detail
