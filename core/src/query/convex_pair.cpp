// SPDX-License-Identifier: MIT
#include "query/convex_pair.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "geometry/math_util.h"

namespace sc::detail {
namespace {

using Vertex = EpaScratch::Vertex;
using Face = EpaScratch::Face;

// Converged when the support point moves the nearest face out by at most this,
// relative to the pair's size: some 50 roundings of a coordinate.
constexpr double kConverged = 1e-14;
// A face whose sine between two edges is below this has no reliable normal.
constexpr double kSliver = 1e-9;
// The expansion adds one vertex per iteration; a polytope pair needs far fewer.
constexpr int kMaxIterations = 512;

using Cso = MinkowskiSupport;

/// The expanding polytope over the scratch arrays: faces with their neighbours and
/// a min-heap of (distance, face) from which removed faces are dropped lazily.
class Polytope {
 public:
  Polytope(EpaScratch& s, double tolerance) : s_(s), tolerance_(tolerance) {
    // First use: room for a typical expansion (256-vertex hulls: 13 iterations, some
    // 80 faces) at once, some 13 KB; a longer one grows the arrays, and they stay.
    if (s_.faces.capacity() == 0) {
      s_.vertices.reserve(32);
      s_.faces.reserve(128);
      s_.heap.reserve(128);
      s_.stack.reserve(32);
      s_.rim.reserve(32);
    }
    s_.vertices.clear();
    s_.faces.clear();
    s_.heap.clear();
  }

  int addVertex(const Vertex& v) {
    s_.vertices.push_back(v);
    return static_cast<int>(s_.vertices.size()) - 1;
  }
  const Vertex& vertex(int v) const { return s_.vertices[v]; }
  Face& face(int f) { return s_.faces[f]; }

  /// Outward face (i, j, k), or -1 when it is a sliver or the origin is beyond it.
  int addFace(int i, int j, int k) {
    const Vec3& p0 = s_.vertices[i].w;
    const Vec3 e1 = s_.vertices[j].w - p0, e2 = s_.vertices[k].w - p0;
    const Vec3 n = e1.cross(e2);
    const double nn = n.squaredNorm();
    const double q1 = e1.squaredNorm(), q2 = e2.squaredNorm(), q3 = (e2 - e1).squaredNorm();
    // Every corner's sine, squared: |n|^2 / (product of its two edges' squares).
    if (!(nn > kSliver * kSliver * std::max({q1 * q2, q1 * q3, q2 * q3}))) return -1;
    Face f;
    f.v[0] = i;
    f.v[1] = j;
    f.v[2] = k;
    f.n = n / std::sqrt(nn);
    f.d = f.n.dot(p0 + (e1 + e2) / 3.0);  // at the centroid: no corner favoured
    if (f.d < -tolerance_) return -1;     // the polytope no longer holds the origin
    s_.faces.push_back(f);
    const int id = static_cast<int>(s_.faces.size()) - 1;
    s_.heap.emplace_back(f.d, id);
    std::push_heap(s_.heap.begin(), s_.heap.end(), std::greater<>());
    return id;
  }

  /// Nearest live face, or -1.
  int nearest() {
    while (!s_.heap.empty() && !s_.faces[s_.heap.front().second].live) {
      std::pop_heap(s_.heap.begin(), s_.heap.end(), std::greater<>());
      s_.heap.pop_back();
    }
    return s_.heap.empty() ? -1 : s_.heap.front().second;
  }

  /// Neighbour links of the first tetrahedron's faces, from their shared edges.
  void linkAll() {
    const int n = static_cast<int>(s_.faces.size());
    for (int f = 0; f < n; ++f)
      for (int k = 0; k < 3; ++k) {
        const int a = s_.faces[f].v[k], b = s_.faces[f].v[(k + 1) % 3];
        for (int g = 0; g < n; ++g)
          if (edgeIndex(g, b, a) >= 0) s_.faces[f].adj[k] = g;
      }
  }

  /// Replaces the faces vertex `w` sees, flooded from face `start` (which sees it),
  /// by the cone from their rim to w. False when the rim is not one simple loop or
  /// a new face is unusable (the caller falls back).
  bool expand(int start, int w) {
    if (!collectRim(start, s_.vertices[w].w)) return false;
    const int first_new = static_cast<int>(s_.faces.size());
    for (const auto& r : s_.rim) {
      const int f = addFace(r[0], r[1], w);
      if (f < 0) return false;
      Face& outside = s_.faces[r[2]];
      const int e = edgeIndex(r[2], r[1], r[0]);
      if (e < 0) return false;
      outside.adj[e] = f;
      s_.faces[f].adj[0] = r[2];
    }
    // Cone faces meet along (b, w) and (w, a): link each to the one sharing it.
    const int count = static_cast<int>(s_.rim.size());
    for (int i = 0; i < count; ++i) {
      int next = -1, prev = -1;
      for (int j = 0; j < count; ++j) {
        if (s_.rim[j][0] == s_.rim[i][1]) next = (next < 0) ? j : -2;
        if (s_.rim[j][1] == s_.rim[i][0]) prev = (prev < 0) ? j : -2;
      }
      if (next < 0 || prev < 0) return false;  // a rim vertex met twice, or none
      s_.faces[first_new + i].adj[1] = first_new + next;
      s_.faces[first_new + i].adj[2] = first_new + prev;
    }
    return true;
  }

 private:
  int edgeIndex(int f, int a, int b) const {
    const Face& face = s_.faces[f];
    for (int k = 0; k < 3; ++k)
      if (face.v[k] == a && face.v[(k + 1) % 3] == b) return k;
    return -1;
  }
  bool sees(int f, const Vec3& w) const {
    const Face& face = s_.faces[f];
    return face.n.dot(w - s_.vertices[face.v[0]].w) > 0.0;
  }
  /// Floods the faces that see w (marking them dead) and lists the rim's edges.
  bool collectRim(int start, const Vec3& w) {
    s_.rim.clear();
    s_.stack.clear();
    s_.faces[start].live = false;
    s_.stack.push_back(start);
    while (!s_.stack.empty()) {
      const int f = s_.stack.back();
      s_.stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int g = s_.faces[f].adj[k];
        if (g < 0) return false;
        if (!s_.faces[g].live) continue;  // seen already (or removed earlier: none)
        if (sees(g, w)) {
          s_.faces[g].live = false;
          s_.stack.push_back(g);
        } else {
          s_.rim.push_back({s_.faces[f].v[k], s_.faces[f].v[(k + 1) % 3], g});
        }
      }
    }
    return s_.rim.size() >= 3;
  }

  EpaScratch& s_;
  double tolerance_;
};

/// The first polytope: GJK's tetrahedron, oriented outward. False when it is flat.
bool startTetrahedron(const SimplexCache& simplex, const Cso& cso, Polytope& p) {
  Vertex v[4];
  for (int m = 0; m < 4; ++m) v[m] = cso.pair(simplex.a[m], simplex.b[m]);
  const Vec3 e1 = v[1].w - v[0].w, e2 = v[2].w - v[0].w, e3 = v[3].w - v[0].w;
  const double det = e1.dot(e2.cross(e3));
  if (!(std::abs(det) > kSliver * e1.norm() * e2.norm() * e3.norm())) return false;
  if (det < 0.0) std::swap(v[0], v[1]);  // now det > 0: faces below are outward
  for (const Vertex& x : v) p.addVertex(x);
  static constexpr int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& f : kFaces)
    if (p.addFace(f[0], f[1], f[2]) < 0) return false;
  p.linkAll();
  return true;
}

/// The result from the converged face f of the polytope, in the common frame.
void report(Polytope& p, int f, const Rigid& frame_from_a, EpaResult& out) {
  const Face& face = p.face(f);
  out.depth = std::max(0.0, face.d);
  out.status = out.depth > 0.0 ? EpaStatus::Converged : EpaStatus::Touching;
  // A - B moved by -depth * n puts the origin on this face: A moves by -depth * n.
  out.normal = frame_from_a.rotation * (-face.n);
  const Vertex &v0 = p.vertex(face.v[0]), &v1 = p.vertex(face.v[1]), &v2 = p.vertex(face.v[2]);
  const Vec3 l = triangleWeights(v0.w, v1.w, v2.w, face.d * face.n);
  out.point_a = frame_from_a * Vec3(l[0] * v0.pa + l[1] * v1.pa + l[2] * v2.pa);
  out.point_b = frame_from_a * Vec3(l[0] * v0.pb + l[1] * v1.pb + l[2] * v2.pb);
  out.face_count = 3;
  for (int k = 0; k < 3; ++k) {
    out.face_a[k] = p.vertex(face.v[k]).ia;
    out.face_b[k] = p.vertex(face.v[k]).ib;
  }
}

/// EPA from GJK's tetrahedron; false when the polytope degenerates on the way.
bool expandFrom(const SimplexCache& simplex, Cso& cso, double scale, const Rigid& frame_from_a,
                EpaScratch& scratch, EpaResult& out) {
  const double tolerance = kConverged * scale;
  Polytope p(scratch, tolerance);
  if (!startTetrahedron(simplex, cso, p)) return false;
  for (int it = 0; it < kMaxIterations; ++it) {
    const int f = p.nearest();
    if (f < 0) return false;
    const Face& face = p.face(f);
    // Climb from the face's corner furthest along its normal: a support point of a
    // nearby direction, so the climb is short.
    int corner = face.v[0];
    for (int k : face.v)
      if (face.n.dot(p.vertex(k).w) > face.n.dot(p.vertex(corner).w)) corner = k;
    cso.hint_a = p.vertex(corner).ia;
    cso.hint_b = p.vertex(corner).ib;
    const Vertex w = cso.support(face.n);
    bool known = false;
    for (int k : face.v) known = known || (p.vertex(k).ia == w.ia && p.vertex(k).ib == w.ib);
    if (known || face.n.dot(w.w) - face.d <= tolerance) {
      out.iterations = it + 1;
      report(p, f, frame_from_a, out);
      return true;
    }
    if (!p.expand(f, p.addVertex(w))) return false;
  }
  return false;
}

/// GJK for the pair, its simplex left in cache.gjk.
GjkResult runGjk(const ConvexPolytope& a, const Rigid& fa, const ConvexPolytope& b, const Rigid& fb,
                 ConvexPairCache& cache) {
  return gjkDistance(a, fa, b, fb, GjkSettings(), cache.gjk);
}

}  // namespace

ConvexDepthStatus convexDepth(const ConvexPolytope& a, const Rigid& frame_from_a,
                              const ConvexPolytope& b, const Rigid& frame_from_b,
                              ConvexPairCache& cache, EpaResult& result) {
  result = EpaResult();
  // Non-finite frames or an empty polytope have no depth to find here.
  if (a.vertices.empty() || b.vertices.empty() || !allFinite(frame_from_a.rotation) ||
      !allFinite(frame_from_a.translation) || !allFinite(frame_from_b.rotation) ||
      !allFinite(frame_from_b.translation))
    return ConvexDepthStatus::Separated;
  const GjkResult g = runGjk(a, frame_from_a, b, frame_from_b, cache);
  if (g.status == GjkStatus::Separated) return ConvexDepthStatus::Separated;
  bool done = false;
  if (g.status == GjkStatus::Intersecting && g.count == 4) {
    const Rigid a_from_b = frame_from_a.inverse() * frame_from_b;
    Cso cso{a, b, a_from_b, a_from_b.rotation.transpose(), cache.gjk.hint_a, cache.gjk.hint_b};
    const double scale = a.radius + b.radius + (a_from_b * b.center - a.center).norm();
    done = expandFrom(cache.gjk, cso, scale, frame_from_a, cache.epa, result);
    cache.gjk.hint_a = cso.hint_a;
    cache.gjk.hint_b = cso.hint_b;
  }
  // A flat or touching simplex, a degenerate expansion, GJK out of iterations: the
  // hull-based EPA, slower and robust to all of them.
  if (!done) result = penetrationDepth(a, frame_from_a, b, frame_from_b);
  return result.status == EpaStatus::Touching ? ConvexDepthStatus::Touching
                                              : ConvexDepthStatus::Penetrating;
}

}  // namespace sc::detail
