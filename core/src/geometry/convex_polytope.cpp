// SPDX-License-Identifier: MIT
#include "geometry/convex_polytope.h"

#include <algorithm>

namespace sc::detail {

void ConvexPolytope::finalize() {
  const int n = static_cast<int>(vertices.size());
  // Vertex adjacency in CSR directly (two entries per face corner, then sorted and
  // made unique per vertex): a vector per vertex cost n allocations per polytope.
  std::vector<int> start(n + 1, 0);
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) start[f[k] + 1] += 2;
  for (int v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<int> entries(static_cast<std::size_t>(start[n]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const Tri& f : faces) {
    for (int k = 0; k < 3; ++k) {
      entries[static_cast<std::size_t>(fill[f[k]]++)] = f[(k + 1) % 3];
      entries[static_cast<std::size_t>(fill[f[k]]++)] = f[(k + 2) % 3];
    }
  }
  adjacency_start.assign(n + 1, 0);
  int kept = 0;
  for (int v = 0; v < n; ++v) {
    // Compacted in place: the write position never passes the read position.
    const auto first = entries.begin() + start[v];
    const auto end = entries.begin() + start[v + 1];
    std::sort(first, end);
    const auto last = std::unique(first, end);
    for (auto it = first; it != last; ++it) entries[static_cast<std::size_t>(kept++)] = *it;
    adjacency_start[v + 1] = kept;
  }
  adjacency.assign(entries.begin(), entries.begin() + kept);
  vertex_face_start.assign(n + 1, 0);
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) ++vertex_face_start[f[k] + 1];
  for (int v = 0; v < n; ++v) vertex_face_start[v + 1] += vertex_face_start[v];
  vertex_faces.assign(static_cast<std::size_t>(vertex_face_start[n]), -1);
  fill.assign(vertex_face_start.begin(), vertex_face_start.end() - 1);
  for (int f = 0; f < static_cast<int>(faces.size()); ++f)
    for (int k = 0; k < 3; ++k) vertex_faces[static_cast<std::size_t>(fill[faces[f][k]]++)] = f;
  bounds = Aabb();
  for (const Vec3& p : vertices) bounds.extend(p);
  center = n > 0 ? Vec3(0.5 * (bounds.min + bounds.max)) : Vec3::Zero();
  radius = 0.0;
  for (const Vec3& p : vertices) radius = std::max(radius, (p - center).norm());
}

int ConvexPolytope::support(const Vec3& direction, int& hint) const {
  const int n = static_cast<int>(vertices.size());
  // Small polytopes: a linear scan beats pointer chasing.
  if (n <= 32 || adjacency.empty()) {
    int best = 0;
    double best_dot = vertices[0].dot(direction);
    for (int i = 1; i < n; ++i) {
      const double d = vertices[i].dot(direction);
      if (d > best_dot) {
        best_dot = d;
        best = i;
      }
    }
    hint = best;
    return best;
  }
  // Hill climbing: on a convex surface a vertex no neighbour improves on is a
  // maximum (flat regions are triangulated, so ties lie on the maximal face).
  int v = (hint >= 0 && hint < n) ? hint : 0;
  double v_dot = vertices[v].dot(direction);
  for (bool improved = true; improved;) {
    improved = false;
    int best = v;
    for (int k = adjacency_start[v]; k < adjacency_start[v + 1]; ++k) {
      const int w = adjacency[k];
      const double d = vertices[w].dot(direction);
      if (d > v_dot) {
        best = w;
        v_dot = d;
        improved = true;
      }
    }
    v = best;
  }
  hint = v;
  return v;
}

}  // namespace sc::detail
