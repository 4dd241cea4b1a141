// SPDX-License-Identifier: MIT
#include "geometry/triangle_adjacency.h"

#include <algorithm>
#include <cstdint>
#include <string>

namespace sc::detail {
namespace {

struct DirectedEdge {
  std::uint64_t key;  ///< (from, to) packed
  int tri;
  int k;
};

std::uint64_t edgeKey(int from, int to) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(from)) << 32) |
         static_cast<std::uint32_t>(to);
}

}  // namespace

Result<TriangleAdjacency> TriangleAdjacency::build(const MeshData& mesh) {
  const int n = static_cast<int>(mesh.triangles.size());
  std::vector<DirectedEdge> edges;
  edges.reserve(3 * static_cast<std::size_t>(n));
  for (int t = 0; t < n; ++t) {
    const Tri& f = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) edges.push_back({edgeKey(f[k], f[(k + 1) % 3]), t, k});
  }
  std::sort(edges.begin(), edges.end(),
            [](const DirectedEdge& a, const DirectedEdge& b) { return a.key < b.key; });
  for (std::size_t i = 1; i < edges.size(); ++i) {
    if (edges[i].key == edges[i - 1].key) {
      return Status(ErrorCode::InvalidGeometry, "triangles " + std::to_string(edges[i - 1].tri) +
                                                    " and " + std::to_string(edges[i].tri) +
                                                    " share an edge with the same winding");
    }
  }
  TriangleAdjacency adjacency;
  adjacency.neighbours_.assign(n, {-1, -1, -1});
  adjacency.neighbour_edges_.assign(n, {-1, -1, -1});
  for (const DirectedEdge& e : edges) {
    const Tri& f = mesh.triangles[e.tri];
    const std::uint64_t twin = edgeKey(f[(e.k + 1) % 3], f[e.k]);
    const auto it =
        std::lower_bound(edges.begin(), edges.end(), twin,
                         [](const DirectedEdge& a, std::uint64_t key) { return a.key < key; });
    if (it == edges.end() || it->key != twin) {
      return Status(ErrorCode::InvalidGeometry,
                    "edge " + std::to_string(e.k) + " of triangle " + std::to_string(e.tri) +
                        " has no opposite edge: the surface is not closed");
    }
    adjacency.neighbours_[e.tri][e.k] = it->tri;
    adjacency.neighbour_edges_[e.tri][e.k] = static_cast<signed char>(it->k);
  }
  return adjacency;
}

}  // namespace sc::detail
