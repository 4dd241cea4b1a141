// SPDX-License-Identifier: MIT
// Closest feature of a polytope at a point, searched around GJK's final simplex:
// its vertices and their neighbours first, then the faces around them, and only
// if those miss (rounding far beyond tolerance) every face.
#include "query/features.h"

#include <algorithm>
#include <limits>

#include "geometry/triangle_distance.h"

namespace sc::detail {
namespace {

struct Seeds {
  int ids[4] = {0, 0, 0, 0};
  int count = 0;

  bool has(int v) const {
    for (int k = 0; k < count; ++k) {
      if (ids[k] == v) return true;
    }
    return false;
  }
};

/// Distinct valid simplex vertices; the nearest vertex when none is valid.
Seeds collectSeeds(const ConvexPolytope& poly, const Vec3& point, const int* ids, int count) {
  Seeds seeds;
  const int n = static_cast<int>(poly.vertices.size());
  for (int k = 0; k < count && k < 4; ++k) {
    if (ids[k] >= 0 && ids[k] < n && !seeds.has(ids[k])) seeds.ids[seeds.count++] = ids[k];
  }
  if (seeds.count == 0) {
    double best = std::numeric_limits<double>::infinity();
    for (int v = 0; v < n; ++v) {
      const double d = (poly.vertices[v] - point).squaredNorm();
      if (d < best) {
        best = d;
        seeds.ids[0] = v;
      }
    }
    seeds.count = 1;
  }
  return seeds;
}

int originalIndex(const ConvexPolytope& poly, int v) {
  return poly.original.empty() ? v : poly.original[v];
}

/// Calls f(v) for every seed and every neighbour of a seed.
template <class F>
void forSeedsAndNeighbours(const ConvexPolytope& poly, const Seeds& seeds, F&& f) {
  for (int k = 0; k < seeds.count; ++k) {
    const int s = seeds.ids[k];
    f(s, -1);
    if (poly.adjacency_start.empty()) continue;
    for (int j = poly.adjacency_start[s]; j < poly.adjacency_start[s + 1]; ++j) {
      f(poly.adjacency[j], s);
    }
  }
}

bool faceIsVirtual(const ConvexPolytope& poly, std::size_t f) {
  return f >= poly.face_source.size() || poly.face_source[f] == -1;
}

/// Calls f(face) for every face around vertex v (found by a scan if the polytope has
/// no vertex-face lists).
template <class F>
void forFacesAround(const ConvexPolytope& poly, int v, F&& f) {
  if (poly.vertex_face_start.empty()) {
    for (std::size_t g = 0; g < poly.faces.size(); ++g) {
      const Tri& t = poly.faces[g];
      if (t[0] == v || t[1] == v || t[2] == v) f(static_cast<int>(g));
    }
    return;
  }
  for (int k = poly.vertex_face_start[v]; k < poly.vertex_face_start[v + 1]; ++k)
    f(poly.vertex_faces[static_cast<std::size_t>(k)]);
}

/// A real edge lies on at least one input triangle.
bool edgeIsVirtual(const ConvexPolytope& poly, int u, int v) {
  bool real = false;
  forFacesAround(poly, u, [&](int f) {
    const Tri& t = poly.faces[f];
    const bool has_u = t[0] == u || t[1] == u || t[2] == u;
    const bool has_v = t[0] == v || t[1] == v || t[2] == v;
    real = real || (has_u && has_v && !faceIsVirtual(poly, static_cast<std::size_t>(f)));
  });
  return !real;
}

/// The preferred face by (contains the point, is real, distance), ties to the lower
/// index, whatever order the faces are offered in.
struct FaceChoice {
  double tolerance;
  int best = -1;
  bool best_inside = false, best_real = false;
  double best_d = std::numeric_limits<double>::infinity();

  void offer(const ConvexPolytope& poly, const Vec3& point, int f) {
    const Tri& t = poly.faces[f];
    const Vec3 corners[3] = {poly.vertices[t[0]], poly.vertices[t[1]], poly.vertices[t[2]]};
    const double d = pointTriangleDistance(point, corners);
    const bool inside = d <= tolerance;
    const bool real = !faceIsVirtual(poly, static_cast<std::size_t>(f));
    const bool better = best < 0 || (inside != best_inside         ? inside
                                     : inside && real != best_real ? real
                                     : d != best_d                 ? d < best_d
                                                                   : f < best);
    if (better) {
      best = f;
      best_inside = inside;
      best_real = real;
      best_d = d;
    }
  }
};

/// Best face by (contains the point, is real, distance); only faces touching a
/// seed unless `all`. Returns -1 when no face qualifies.
int bestFace(const ConvexPolytope& poly, const Vec3& point, const Seeds& seeds, bool all,
             double tolerance) {
  FaceChoice choice{tolerance};
  if (all) {
    for (std::size_t f = 0; f < poly.faces.size(); ++f)
      choice.offer(poly, point, static_cast<int>(f));
    return choice.best;
  }
  // The faces around the seeds, through the vertex-face lists (a face shared by two
  // seeds is offered twice: harmless).
  for (int k = 0; k < seeds.count; ++k)
    forFacesAround(poly, seeds.ids[k], [&](int f) { choice.offer(poly, point, f); });
  return choice.best_inside ? choice.best : -1;
}

}  // namespace

Feature closestFeature(const ConvexPolytope& poly, const Vec3& point, const int* ids, int count,
                       double tolerance) {
  Feature feature;
  if (poly.vertices.empty()) return feature;
  const Seeds seeds = collectSeeds(poly, point, ids, count);

  int vertex = -1;
  double vertex_d = std::numeric_limits<double>::infinity();
  forSeedsAndNeighbours(poly, seeds, [&](int v, int) {
    const double d = (poly.vertices[v] - point).norm();
    if (d < vertex_d) {
      vertex_d = d;
      vertex = v;
    }
  });
  if (vertex_d <= tolerance) {
    feature.vertices[0] = originalIndex(poly, vertex);
    return feature;
  }

  int edge_u = -1, edge_v = -1;
  double edge_d = std::numeric_limits<double>::infinity();
  forSeedsAndNeighbours(poly, seeds, [&](int v, int seed) {
    if (seed < 0) return;
    const double d = pointSegmentDistance(point, poly.vertices[seed], poly.vertices[v]);
    if (d < edge_d) {
      edge_d = d;
      edge_u = std::min(seed, v);
      edge_v = std::max(seed, v);
    }
  });
  if (edge_d <= tolerance) {
    feature.type = FeatureType::Edge;
    feature.vertices[0] = originalIndex(poly, edge_u);
    feature.vertices[1] = originalIndex(poly, edge_v);
    feature.is_virtual = edgeIsVirtual(poly, edge_u, edge_v);
    return feature;
  }

  int face = bestFace(poly, point, seeds, false, tolerance);
  if (face < 0) face = bestFace(poly, point, seeds, true, tolerance);
  if (face < 0) {  // a polytope without faces: the nearest vertex
    feature.vertices[0] = originalIndex(poly, vertex);
    return feature;
  }
  const Tri& t = poly.faces[face];
  feature.type = FeatureType::Face;
  for (int k = 0; k < 3; ++k) feature.vertices[k] = originalIndex(poly, t[k]);
  feature.is_virtual = faceIsVirtual(poly, static_cast<std::size_t>(face));
  return feature;
}

}  // namespace sc::detail
