// SPDX-License-Identifier: MIT
#include "geometry/triangle_adjacency.h"

#include <algorithm>
#include <numeric>
#include <string>

namespace sc::detail {
namespace {

/// Edge k of triangle `tri`, filed under its first vertex.
struct OutEdge {
  int to;
  int tri;
  int k;
};

bool byTarget(const OutEdge& a, const OutEdge& b) {
  return a.to != b.to ? a.to < b.to : a.tri < b.tri;
}

}  // namespace

Result<TriangleAdjacency> TriangleAdjacency::build(const MeshData& mesh) {
  const int n = static_cast<int>(mesh.triangles.size());
  // Directed edges grouped by their first vertex (a counting sort, linear in the mesh),
  // each group sorted by the last vertex: a lookup is a search in one vertex's few
  // edges, and a vertex of many triangles costs a sort, not a quadratic scan.
  std::vector<int> start(mesh.vertices.size() + 1, 0);
  for (const Tri& f : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++start[static_cast<std::size_t>(f[k]) + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<OutEdge> out(3 * static_cast<std::size_t>(n));
  std::vector<int> next(start.begin(), start.end() - 1);
  for (int t = 0; t < n; ++t) {
    const Tri& f = mesh.triangles[t];
    for (int k = 0; k < 3; ++k)
      out[static_cast<std::size_t>(next[f[k]]++)] = {f[(k + 1) % 3], t, k};
  }
  const auto group = [&](int v) {
    return std::make_pair(out.begin() + start[v], out.begin() + start[v + 1]);
  };
  for (int v = 0; v + 1 < static_cast<int>(start.size()); ++v) {
    const auto [first, last] = group(v);
    std::sort(first, last, byTarget);
    for (auto it = first; it != last && it + 1 != last; ++it) {
      if (it->to == (it + 1)->to) {
        return Status(ErrorCode::InvalidGeometry, "triangles " + std::to_string(it->tri) + " and " +
                                                      std::to_string((it + 1)->tri) +
                                                      " share an edge with the same winding");
      }
    }
  }
  TriangleAdjacency adjacency;
  adjacency.neighbours_.assign(n, {-1, -1, -1});
  adjacency.neighbour_edges_.assign(n, {-1, -1, -1});
  for (int v = 0; v + 1 < static_cast<int>(start.size()); ++v) {
    for (auto [e, end] = group(v); e != end; ++e) {
      const auto [first, last] = group(e->to);
      const auto twin =
          std::lower_bound(first, last, v, [](const OutEdge& a, int to) { return a.to < to; });
      if (twin == last || twin->to != v) {
        return Status(ErrorCode::InvalidGeometry,
                      "edge " + std::to_string(e->k) + " of triangle " + std::to_string(e->tri) +
                          " has no opposite edge: the surface is not closed");
      }
      adjacency.neighbours_[e->tri][e->k] = twin->tri;
      adjacency.neighbour_edges_[e->tri][e->k] = static_cast<signed char>(twin->k);
    }
  }
  return adjacency;
}

}  // namespace sc::detail
