// SPDX-License-Identifier: MIT
// Quickhull in 3-D. Outline:
//  1. a first tetrahedron from the extreme points; every other point goes to the
//     outside set of the first face it lies above by more than the tolerance;
//  2. while a face has an outside set: its farthest point is the eye; the faces it
//     sees or lies in the plane of (within the tolerance; depth-first from that
//     face) are removed and the horizon they leave, a simple loop,
//     walked in order, is joined to the eye by new faces; the removed faces'
//     points go to the new faces they lie above, or are inside and dropped;
//  3. the checks that let the result stand in for qhull's: no sliver face, every
//     edge convex within the tolerance, every vertex a strict corner (the sum of its
//     faces' normals separates it from its neighbours), so that hill climbing on
//     the polytope finds the maximum. A vertex that is no corner lies on an edge
//     or face of the others' hull (one added before a collinear or coplanar point
//     farther out): it is dropped, the hull built again without it, and it must
//     then lie inside within the tolerance. Any doubt returns false.
// A point within the tolerance of the hull is dropped as inside, as qhull merges
// it; the tolerance is a few hundred rounding errors of the coordinates.
#include "preprocess/quick_hull.h"

#include <algorithm>
#include <cmath>

#include "geometry/math_util.h"

namespace sc::detail {
namespace {

/// Distance tolerance relative to the points' extent plus their largest coordinate.
constexpr double kRelativeTolerance = 1e-13;
/// A face with twice its area below this times its longest edge squared is a sliver.
constexpr double kSliver = 1e-12;
/// A vertex is a corner when its neighbours lie this much (relative) below it along
/// the sum of its faces' normals.
constexpr double kCorner = 1e-10;
/// Builds, each after dropping the vertices that were no corners.
constexpr int kAttempts = 3;

class QuickHull {
 public:
  QuickHull(const std::vector<Vec3>& points, QuickHullWorkspace& work)
      : p_(points), w_(work), faces_(work.faces) {}

  bool run(const std::vector<int>& original, ConvexPolytope& out, PolytopeKeep keep) {
    if (p_.size() < 4) return false;
    w_.excluded.assign(p_.size(), 0);
    w_.dropped.clear();
    for (int attempt = 0; attempt < kAttempts; ++attempt) {
      if (!build() || !collect(original)) return false;
      const std::size_t before = w_.dropped.size();
      dropNonCorners();
      if (w_.dropped.size() != before) continue;
      if (!droppedInside()) return false;
      releaseUnpacked(keep);
      out = ConvexPolytope::pack(parts_, lists_, keep);
      return true;
    }
    return false;
  }

 private:
  double distance(int face, int point) const {
    return faces_[face].normal.dot(p_[point]) - faces_[face].offset;
  }

  /// New face a -> b -> c; false for a sliver.
  bool makeFace(int a, int b, int c, int& index) {
    QuickHullWorkspace::Face face{};
    face.v[0] = a;
    face.v[1] = b;
    face.v[2] = c;
    face.adj[0] = face.adj[1] = face.adj[2] = -1;
    const Vec3 e1 = p_[b] - p_[a], e2 = p_[c] - p_[a];
    const Vec3 twice = e1.cross(e2);
    const double longest2 = std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
    const double length = twice.norm();
    if (!(length > kSliver * longest2)) return false;
    face.normal = twice / length;
    face.offset = face.normal.dot(p_[a]);
    face.outside = -1;
    face.visit = -1;
    face.serial = serial_++;
    face.alive = true;
    if (w_.free_faces.empty()) {
      index = static_cast<int>(faces_.size());
      faces_.push_back(face);
    } else {
      index = w_.free_faces.back();
      w_.free_faces.pop_back();
      faces_[index] = face;
    }
    return true;
  }

  /// Queues face `f` for an eye, with its serial to tell it from a later face in
  /// its slot.
  void queue(int f) {
    w_.stack.push_back(f);
    w_.stack.push_back(faces_[f].serial);
  }

  /// Puts `point` into the outside set of the first face of `candidates` it lies
  /// above by more than the tolerance; false when it is above none (inside).
  bool assign(int point, const int* candidates, int count) {
    for (int i = 0; i < count; ++i) {
      const int f = candidates[i];
      if (distance(f, point) > tol_) {
        w_.next_point[point] = faces_[f].outside;
        faces_[f].outside = point;
        return true;
      }
    }
    return false;
  }

  bool build();
  bool initialSimplex();
  bool addEye(int face);
  bool findHorizon(int face, int eye);
  bool collect(const std::vector<int>& original);
  /// Frees the working lists `keep` does not pack before the block is made: at the
  /// top of a hierarchy they are about as large as the polytope.
  void releaseUnpacked(PolytopeKeep keep) {
    std::vector<int>().swap(lists_.fill);
    std::vector<int>().swap(lists_.mark);
    std::vector<int>().swap(lists_.entries);
    if (keep == PolytopeKeep::Everything) return;
    std::vector<int>().swap(lists_.vertex_face_start);
    std::vector<int>().swap(lists_.vertex_faces);
  }
  void dropNonCorners();
  bool droppedInside() const;

  const std::vector<Vec3>& p_;
  QuickHullWorkspace& w_;
  std::vector<QuickHullWorkspace::Face>& faces_;
  /// The hull's arrays and derived lists before packing; freed with the call, as a
  /// hull's arrays are as large as the polytope itself.
  PolytopeParts parts_;
  FinalizeScratch lists_;
  int serial_ = 0;
  double tol_ = 0.0;
};

bool QuickHull::build() {
  if (!initialSimplex()) return false;
  while (!w_.stack.empty()) {
    const int serial = w_.stack.back();
    w_.stack.pop_back();
    const int f = w_.stack.back();
    w_.stack.pop_back();
    if (faces_[f].serial != serial || !faces_[f].alive || faces_[f].outside < 0) continue;
    if (!addEye(f)) return false;
  }
  return true;
}

bool QuickHull::initialSimplex() {
  const int n = static_cast<int>(p_.size());
  faces_.clear();
  w_.free_faces.clear();
  serial_ = 0;
  w_.stack.clear();
  w_.next_point.assign(p_.size(), -1);
  w_.point_mark.assign(p_.size(), -1);
  w_.visit = 0;  // faces and marks are fresh: the stamps start again
  const std::vector<char>& excluded = w_.excluded;
  int first = 0;
  while (first < n && excluded[first]) ++first;
  if (n - first < 4) return false;
  Aabb box;
  int lo[3] = {first, first, first}, hi[3] = {first, first, first};
  for (int i = first; i < n; ++i) {
    if (excluded[i]) continue;
    box.extend(p_[i]);
    for (int k = 0; k < 3; ++k) {
      if (p_[i][k] < p_[lo[k]][k]) lo[k] = i;
      if (p_[i][k] > p_[hi[k]][k]) hi[k] = i;
    }
  }
  const double extent = (box.max - box.min).norm();
  const double reach = std::max(box.max.cwiseAbs().maxCoeff(), box.min.cwiseAbs().maxCoeff());
  tol_ = kRelativeTolerance * (extent + reach);
  // The two farthest apart of the axis extremes, the point farthest from their
  // line, the point farthest from the plane of the three.
  int a = lo[0], b = hi[0];
  for (int k = 1; k < 3; ++k) {
    if ((p_[hi[k]] - p_[lo[k]]).squaredNorm() > (p_[b] - p_[a]).squaredNorm()) {
      a = lo[k];
      b = hi[k];
    }
  }
  const Vec3 axis = p_[b] - p_[a];
  if (!(axis.norm() > tol_)) return false;
  int c = -1, d = -1;
  double best = 0.0;
  for (int i = 0; i < n; ++i) {
    if (excluded[i]) continue;
    const double off = axis.cross(p_[i] - p_[a]).norm() / axis.norm();
    if (off > best) {
      best = off;
      c = i;
    }
  }
  if (c < 0 || !(best > tol_)) return false;
  const Vec3 normal = axis.cross(p_[c] - p_[a]).normalized();
  best = 0.0;
  for (int i = 0; i < n; ++i) {
    if (excluded[i]) continue;
    const double off = std::abs(normal.dot(p_[i] - p_[a]));
    if (off > best) {
      best = off;
      d = i;
    }
  }
  if (d < 0 || !(best > tol_)) return false;
  if (normal.dot(p_[d] - p_[a]) > 0.0) std::swap(b, c);  // d below face a, b, c
  int f[4];
  if (!makeFace(a, b, c, f[0]) || !makeFace(a, d, b, f[1]) || !makeFace(b, d, c, f[2]) ||
      !makeFace(c, d, a, f[3])) {
    return false;
  }
  // Each directed edge's twin among the four faces.
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k) {
      const int u = faces_[f[i]].v[k], v = faces_[f[i]].v[(k + 1) % 3];
      for (int j = 0; j < 4; ++j) {
        for (int m = 0; m < 3; ++m) {
          if (faces_[f[j]].v[m] == v && faces_[f[j]].v[(m + 1) % 3] == u)
            faces_[f[i]].adj[k] = f[j];
        }
      }
      if (faces_[f[i]].adj[k] < 0) return false;
    }
  }
  for (int i = n - 1; i >= 0; --i) {
    if (excluded[i] || i == a || i == b || i == c || i == d) continue;
    assign(i, f, 4);
  }
  for (int i = 0; i < 4; ++i) {
    if (faces_[f[i]].outside >= 0) queue(f[i]);
  }
  return true;
}

// Depth-first over the faces the eye sees, each entered across the edge it shares
// with the face it was reached from and left over its other edges in order: the
// edges to faces it does not see come out as the horizon loop, in order.
bool QuickHull::findHorizon(int face, int eye) {
  ++w_.visit;
  w_.visible.clear();
  w_.horizon.clear();
  std::vector<QuickHullWorkspace::Frame>& frames = w_.frames;
  frames.clear();
  faces_[face].visit = w_.visit;
  w_.visible.push_back(face);
  frames.push_back({face, 0, 0});
  while (!frames.empty()) {
    QuickHullWorkspace::Frame& top = frames.back();
    const int steps = top.face == face ? 3 : 2;
    if (top.step == steps) {
      frames.pop_back();
      continue;
    }
    const int f = top.face;
    const int k = (top.first + top.step++) % 3;
    const int g = faces_[f].adj[k];
    if (faces_[g].visit == w_.visit) continue;
    // A face the eye lies in the plane of goes too: the faces that replace it lie
    // in that plane, and a vertex inside a flat region is not left behind.
    if (distance(g, eye) >= -tol_) {
      faces_[g].visit = w_.visit;
      w_.visible.push_back(g);
      int back = 0;
      while (back < 3 && faces_[g].adj[back] != f) ++back;
      if (back == 3) return false;
      frames.push_back({g, (back + 1) % 3, 0});
    } else {
      w_.horizon.push_back(f);
      w_.horizon.push_back(k);
    }
  }
  return w_.horizon.size() >= 6;
}

bool QuickHull::addEye(int face) {
  int eye = faces_[face].outside;
  double far = distance(face, eye);
  for (int i = w_.next_point[eye]; i >= 0; i = w_.next_point[i]) {
    const double d = distance(face, i);
    if (d > far) {
      far = d;
      eye = i;
    }
  }
  if (!findHorizon(face, eye)) return false;
  const int edges = static_cast<int>(w_.horizon.size() / 2);
  auto start = [&](int e) { return faces_[w_.horizon[2 * e]].v[w_.horizon[2 * e + 1]]; };
  auto end = [&](int e) { return faces_[w_.horizon[2 * e]].v[(w_.horizon[2 * e + 1] + 1) % 3]; };
  // The horizon must be one simple loop: each edge starts where the one before
  // ends, and no vertex comes twice.
  ++w_.visit;
  for (int e = 0; e < edges; ++e) {
    if (end(e) != start((e + 1) % edges) || w_.point_mark[start(e)] == w_.visit) return false;
    w_.point_mark[start(e)] = w_.visit;
  }
  w_.orphans.clear();
  for (int f : w_.visible) {
    faces_[f].alive = false;
    for (int i = faces_[f].outside; i >= 0; i = w_.next_point[i]) {
      if (i != eye) w_.orphans.push_back(i);
    }
  }
  w_.created.clear();
  for (int e = 0; e < edges; ++e) {
    const int f = w_.horizon[2 * e], k = w_.horizon[2 * e + 1];
    const int beyond = faces_[f].adj[k];
    int index = -1;
    if (!makeFace(start(e), end(e), eye, index)) return false;
    faces_[index].adj[0] = beyond;
    for (int& back : faces_[beyond].adj) {
      if (back == f) back = index;
    }
    w_.created.push_back(index);
  }
  for (int e = 0; e < edges; ++e) {
    QuickHullWorkspace::Face& made = faces_[w_.created[e]];
    made.adj[1] = w_.created[(e + 1) % edges];
    made.adj[2] = w_.created[(e + edges - 1) % edges];
  }
  for (int i : w_.orphans) assign(i, w_.created.data(), edges);
  for (int f : w_.created) {
    if (faces_[f].outside >= 0) queue(f);
  }
  // The removed faces' slots serve later steps (this one read them until now).
  w_.free_faces.insert(w_.free_faces.end(), w_.visible.begin(), w_.visible.end());
  return true;
}

bool QuickHull::collect(const std::vector<int>& original) {
  w_.vertex_slot.assign(p_.size(), -1);
  w_.slot_point.clear();
  PolytopeParts& parts = parts_;
  parts.vertices.clear();
  parts.original.clear();
  parts.faces.clear();
  // The live faces in the order they were made, whatever slots they took.
  std::vector<int>& alive = w_.alive;
  alive.clear();
  for (int f = 0; f < static_cast<int>(faces_.size()); ++f)
    if (faces_[f].alive) alive.push_back(f);
  std::sort(alive.begin(), alive.end(),
            [&](int a, int b) { return faces_[a].serial < faces_[b].serial; });
  for (const int f : alive) {
    const QuickHullWorkspace::Face& face = faces_[f];
    // Convex within the tolerance: each neighbour's far corner is below this face.
    for (int k = 0; k < 3; ++k) {
      const QuickHullWorkspace::Face& g = faces_[face.adj[k]];
      for (int corner : g.v) {
        if (face.normal.dot(p_[corner]) - face.offset > tol_) return false;
      }
    }
    Tri tri;
    for (int k = 0; k < 3; ++k) {
      int& slot = w_.vertex_slot[face.v[k]];
      if (slot < 0) {
        slot = static_cast<int>(parts.vertices.size());
        w_.slot_point.push_back(face.v[k]);
        parts.vertices.push_back(p_[face.v[k]]);
        parts.original.push_back(original.empty() ? face.v[k] : original[face.v[k]]);
      }
      tri[k] = slot;
    }
    parts.faces.push_back(tri);
  }
  parts.face_source.assign(parts.faces.size(), -1);
  ConvexPolytope::derive(parts, lists_);
  return parts.faces.size() >= 4;
}

// A vertex no direction separates from its neighbours is on an edge or inside a
// face: hill climbing could stop there. Such vertices are dropped.
void QuickHull::dropNonCorners() {
  const std::vector<Vec3>& vertices = parts_.vertices;
  const std::vector<Tri>& faces = parts_.faces;
  const FinalizeScratch& out = lists_;
  const int n = static_cast<int>(vertices.size());
  for (int v = 0; v < n; ++v) {
    Vec3 direction = Vec3::Zero();
    for (int k = out.vertex_face_start[v]; k < out.vertex_face_start[v + 1]; ++k) {
      const Tri& f = faces[out.vertex_faces[k]];
      const Vec3& a = vertices[f[0]];
      direction += (vertices[f[1]] - a).cross(vertices[f[2]] - a).normalized();
    }
    const double length = direction.norm();
    bool corner = length > 0.0;
    for (int k = out.adjacency_start[v]; corner && k < out.adjacency_start[v + 1]; ++k) {
      const Vec3 edge = vertices[out.adjacency[k]] - vertices[v];
      corner = direction.dot(edge) < -kCorner * length * edge.norm();
    }
    if (corner) continue;
    w_.excluded[w_.slot_point[v]] = 1;
    w_.dropped.push_back(w_.slot_point[v]);
  }
}

bool QuickHull::droppedInside() const {
  for (const int point : w_.dropped) {
    for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {
      if (faces_[f].alive && distance(f, point) > tol_) return false;
    }
  }
  return true;
}

}  // namespace

bool quickHull(const std::vector<Vec3>& points, const std::vector<int>& original,
               QuickHullWorkspace& work, ConvexPolytope& out, PolytopeKeep keep) {
  if (!original.empty() && original.size() != points.size()) return false;
  for (const Vec3& p : points) {
    if (!allFinite(p)) return false;
  }
  return QuickHull(points, work).run(original, out, keep);
}

}  // namespace sc::detail
