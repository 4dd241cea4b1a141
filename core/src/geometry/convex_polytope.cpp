// SPDX-License-Identifier: MIT
#include "geometry/convex_polytope.h"

#include <algorithm>
#include <cmath>

namespace sc::detail {

namespace {

/// Sorts a vertex's few neighbours (insertion sort: a hull vertex has about six).
void sortSmall(int* first, int* last) {
  for (int* i = first + 1; i < last; ++i) {
    const int value = *i;
    int* j = i;
    for (; j > first && *(j - 1) > value; --j) *j = *(j - 1);
    *j = value;
  }
}

}  // namespace

void ConvexPolytope::finalize() {
  FinalizeScratch scratch;
  finalize(scratch);
}

void ConvexPolytope::finalize(FinalizeScratch& scratch) {
  // A bare point set (an inner node of a hierarchy) has no faces to walk: its
  // arrays stay empty, which every reader takes as "scan the vertices".
  if (faces.empty()) {
    adjacency_start.clear();
    adjacency.clear();
    vertex_face_start.clear();
    vertex_faces.clear();
  } else {
    buildAdjacency(scratch);
  }
  const int n = static_cast<int>(vertices.size());
  bounds = Aabb();
  for (const Vec3& p : vertices) bounds.extend(p);
  center = n > 0 ? Vec3(0.5 * (bounds.min + bounds.max)) : Vec3::Zero();
  radius = 0.0;
  for (const Vec3& p : vertices) radius = std::max(radius, (p - center).squaredNorm());
  radius = std::sqrt(radius);
}

void ConvexPolytope::buildAdjacency(FinalizeScratch& scratch) {
  // One pass over the faces files each corner under its vertex: the face (CSR) and
  // the corner's two other vertices, its candidate neighbours. Each vertex's
  // candidates then lose their repeats (a mark per vertex; on a closed surface each
  // neighbour comes twice) and are sorted in place. Walking each vertex's faces
  // instead visits every face three times; a cache load finalizes tens of
  // thousands of polytopes with the same scratch. Raw pointers: every array here
  // holds ints, so through the vectors each store would reload every bound.
  const int n = static_cast<int>(vertices.size());
  const int face_count = static_cast<int>(faces.size());
  vertex_face_start.assign(static_cast<std::size_t>(n) + 1, 0);
  int* const start = vertex_face_start.data();
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) ++start[f[k] + 1];
  for (int v = 0; v < n; ++v) start[v + 1] += start[v];
  const int corners = start[n];
  scratch.fill.assign(start, start + n);
  scratch.entries.resize(2 * static_cast<std::size_t>(corners));
  vertex_faces.resize(static_cast<std::size_t>(corners));
  int* const fill = scratch.fill.data();
  int* const entries = scratch.entries.data();
  int* const around = vertex_faces.data();
  for (int f = 0; f < face_count; ++f) {
    const int a = faces[f][0], b = faces[f][1], c = faces[f][2];
    const int sa = fill[a]++, sb = fill[b]++, sc = fill[c]++;
    around[sa] = around[sb] = around[sc] = f;
    entries[2 * sa] = b, entries[2 * sa + 1] = c;
    entries[2 * sb] = c, entries[2 * sb + 1] = a;
    entries[2 * sc] = a, entries[2 * sc + 1] = b;
  }
  scratch.mark.assign(static_cast<std::size_t>(n), -1);
  int* const mark = scratch.mark.data();
  adjacency_start.resize(static_cast<std::size_t>(n) + 1);
  adjacency_start[0] = 0;
  int kept = 0;  // candidates kept so far, compacted to the front of `entries`
  for (int v = 0; v < n; ++v) {
    const int first = kept;
    const int end = 2 * start[v + 1];
    mark[v] = v;  // v is no neighbour of its own
    for (int k = 2 * start[v]; k < end; ++k) {
      const int w = entries[k];
      if (mark[w] == v) continue;
      mark[w] = v;
      entries[kept++] = w;
    }
    sortSmall(entries + first, entries + kept);
    adjacency_start[v + 1] = kept;
  }
  adjacency.assign(entries, entries + kept);
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
