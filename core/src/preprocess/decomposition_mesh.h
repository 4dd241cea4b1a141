// SPDX-License-Identifier: MIT
// What the patch growth of every region reads of a closed mesh: adjacency, face
// planes, convex edges, an AABB tree of the triangles and the regions. Built once,
// then read-only, so workers on different regions share it.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "geometry/aabb_tree.h"
#include "geometry/triangle_adjacency.h"
#include "smartcollision/model.h"

namespace sc::detail {

/// Patches grow within regions of at most this many triangles (their hulls are still
/// tested against every triangle they can meet, of any region). It bounds a patch's size, and with
/// it the cost of its checks, so the work grows linearly with the mesh; and regions are
/// independent, so they run in parallel.
inline constexpr int kRegionTriangles = 8192;

/// Per-triangle data every region's worker reads; built once, then read-only.
struct SharedMesh {
  explicit SharedMesh(const MeshData& m) : mesh(m) {}
  Status prepare();
  void splitRegions(std::vector<int>& ids, int begin, int end, const std::vector<Vec3>& centres);
  int regionCount() const { return static_cast<int>(region_start.size()) - 1; }

  const MeshData& mesh;
  double tol = 0.0;
  TriangleAdjacency adjacency;
  std::vector<Vec3> normals;
  std::vector<double> offsets;
  std::vector<std::array<char, 3>> convex_edge;
  /// Directed edges (from << 32 | to) and their triangles, sorted, for triangleOf.
  std::vector<std::pair<std::uint64_t, int>> edge_triangle;
  AabbTree tree;
  /// Regions: triangles region_start[r] .. region_start[r + 1] of region_order.
  std::vector<int> region_of;
  std::vector<int> region_order;
  std::vector<int> region_start;
};

}  // namespace sc::detail
