// SPDX-License-Identifier: MIT
// The polytope of one convex surface patch. Outline:
//  1. collect the patch's vertices; the patch is flat when they all lie within
//     kFlatFactor tolerances of the plane of its area-weighted normal;
//  2. not flat: every patch triangle's plane must support the vertices, checked
//     by hill climbing on the vertices' hull (our Quickhull, quick_hull.h, or
//     qhull's where ours declines; for small patches in HullCheck::Quick, by
//     scanning the vertices);
//  3. trace the patch's boundary loops over the mesh adjacency, each with the
//     uncovered part of the hull surface on its left (seen from outside);
//  4. ear-clip each loop: an ear is a non-degenerate triangle of consecutive loop
//     vertices on a supporting plane of the hull that holds no other patch vertex.
//     Because the ears close the loops, the patch's own triangles are the hull's
//     faces wherever the hull is flat, whatever triangulation qhull chose there.
//     A flat patch is a double-sided polygon: the pockets on its own side (hull
//     polygon minus patch) are clipped first, then the back side;
//  5. the faces must cover the hull exactly once: their area equals the hull's
//     (or, without qhull, they wind once around an interior point);
//  6. flat or thin hulls have (almost) no interior to test other triangles
//     against, so their wedge at each boundary edge must fit the solid's: where
//     the neighbouring triangle bends down (a convex edge), the virtual face on
//     that edge must not rise above the neighbour's plane (a flat patch's pocket
//     over a convex edge would stick out of the solid);
//  7. flat or thin hulls get probe prisms under the virtual faces that look the
//     patch's way (see PatchPolytope::probes).
#include "preprocess/patch_polytope.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "geometry/math_util.h"
#include "preprocess/convex_hull.h"
#include "preprocess/quick_hull.h"

namespace sc::detail {
namespace {

using Vec2 = Eigen::Vector2d;

/// An ear lower than this many tolerances is degenerate (its plane is noise).
constexpr double kSliver = 1e-3;
/// Relative error allowed between the faces' total area and the hull's.
constexpr double kAreaTolerance = 1e-6;
/// A point this many tolerances outside an ear's edge still counts as on it.
constexpr double kOnEdge = 1e-2;

double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

/// Area of the convex hull of 2-D points (Andrew's monotone chain).
double convexArea2d(std::vector<Vec2> pts) {
  std::sort(pts.begin(), pts.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  const int n = static_cast<int>(pts.size());
  if (n < 3) return 0.0;
  std::vector<Vec2> hull(2 * static_cast<std::size_t>(n));
  int k = 0;
  for (int i = 0; i < n; ++i) {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], pts[i]) <= 0.0) --k;
    hull[k++] = pts[i];
  }
  for (int i = n - 2, lower = k + 1; i >= 0; --i) {
    while (k >= lower && cross2(hull[k - 2], hull[k - 1], pts[i]) <= 0.0) --k;
    hull[k++] = pts[i];
  }
  double twice = 0.0;
  for (int i = 0; i + 1 < k; ++i)
    twice += hull[i].x() * hull[i + 1].y() - hull[i].y() * hull[i + 1].x();
  return 0.5 * twice;
}

double triangleArea(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

class Builder {
 public:
  Builder(const MeshData& mesh, const TriangleAdjacency& adjacency, const PatchRef& patch,
          double tolerance, HullCheck check)
      : mesh_(mesh), adjacency_(adjacency), patch_(patch), tol_(tolerance), check_(check) {}

  Result<PatchPolytope> run();

 private:
  int localOf(int vertex) const {
    return static_cast<int>(std::lower_bound(verts_.begin(), verts_.end(), vertex) -
                            verts_.begin());
  }
  static Status fail(const char* why) { return {ErrorCode::InvalidGeometry, why}; }

  void collectVertices();
  void classifyFlat();
  Status buildHull();
  bool trianglesSupport() const;
  /// max over the patch's vertices of n . p
  double support(const Vec3& n) const;
  bool windsOnce() const;
  void facePlanes();
  void traceLoops();
  bool clipLoop(const std::vector<int>& loop, const std::vector<std::array<int, 2>>& edges);
  bool wedgesFit() const;
  bool isEar3d(int a, int b, int c) const;
  bool isEar2d(int a, int b, int c, bool front, const std::vector<int>& ring, int ring_start,
               const std::vector<int>& next) const;
  bool areaMatches() const;
  void addProbes();

  const MeshData& mesh_;
  const TriangleAdjacency& adjacency_;
  const PatchRef& patch_;
  double tol_;
  HullCheck check_;
  bool use_qhull_ = false;

  std::vector<int> verts_;               ///< input indices of the patch's vertices, sorted
  std::vector<Vec3> points_;             ///< their positions
  std::vector<Tri> tris_;                ///< patch triangles over local indices
  Vec3 normal_ = Vec3::UnitZ();          ///< unit area-weighted normal of the patch
  double offset_ = 0.0;                  ///< normal_ . (area-weighted centroid)
  std::vector<Vec2> flat_points_;        ///< flat: positions in the plane's frame
  ConvexPolytope hull_;                  ///< not flat: the hull (original = local index)
  std::vector<std::vector<int>> loops_;  ///< boundary loops, local vertex indices
  /// Per loop edge i (loop[i] -> loop[i + 1]): the patch triangle and edge index
  /// it reverses.
  std::vector<std::vector<std::array<int, 2>>> loop_edges_;
  /// Loop edges (patch triangle, edge index) and the apex of the virtual face
  /// built on each.
  std::vector<std::array<int, 3>> edge_apex_;
  double thickness_ = 0.0;    ///< extent of the vertices along normal_
  std::vector<Tri> virtual_;  ///< virtual faces over local indices
  std::vector<char> front_;   ///< flat: the virtual face is a pocket
  PatchPolytope out_;
};

void Builder::collectVertices() {
  const int n = patch_.count;
  verts_.reserve(3 * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const Tri& f = mesh_.triangles[patch_.faces[i]];
    verts_.insert(verts_.end(), {f[0], f[1], f[2]});
  }
  std::sort(verts_.begin(), verts_.end());
  verts_.erase(std::unique(verts_.begin(), verts_.end()), verts_.end());
  points_.reserve(verts_.size());
  for (int v : verts_) points_.push_back(mesh_.vertices[v]);
  tris_.reserve(n);
  for (int i = 0; i < n; ++i) {
    const Tri& f = mesh_.triangles[patch_.faces[i]];
    tris_.emplace_back(localOf(f[0]), localOf(f[1]), localOf(f[2]));
  }
}

void Builder::classifyFlat() {
  Vec3 normal_sum = Vec3::Zero(), weighted_centre = Vec3::Zero();
  double area_sum = 0.0;
  for (const Tri& f : tris_) {
    const Vec3 twice = (points_[f[1]] - points_[f[0]]).cross(points_[f[2]] - points_[f[0]]);
    normal_sum += twice;
    area_sum += twice.norm();
    weighted_centre += twice.norm() * (points_[f[0]] + points_[f[1]] + points_[f[2]]) / 3.0;
  }
  // Validated meshes have no degenerate triangle, so area_sum > 0.
  if (!(area_sum > 0.0)) return;
  normal_ = normalizedOr(normal_sum, Vec3::UnitZ());
  offset_ = normal_.dot(weighted_centre / area_sum);
  // A patch folded onto itself has cancelling normals: not a flat polygon, and
  // not thin along normal_ either.
  if (!(normal_sum.norm() > 0.5 * area_sum)) {
    thickness_ = kInfinity;
    return;
  }
  double deviation = 0.0, lowest = kInfinity, highest = -kInfinity;
  for (const Vec3& p : points_) {
    deviation = std::max(deviation, std::abs(normal_.dot(p) - offset_));
    lowest = std::min(lowest, normal_.dot(p));
    highest = std::max(highest, normal_.dot(p));
  }
  thickness_ = highest - lowest;
  if (deviation > kFlatFactor * tol_) return;
  out_.flat = true;
  const Vec3 u = anyOrthogonal(normal_);
  const Vec3 w = normal_.cross(u);
  flat_points_.reserve(points_.size());
  for (const Vec3& p : points_) flat_points_.emplace_back(u.dot(p), w.dot(p));
}

double Builder::support(const Vec3& n) const {
  if (use_qhull_) {
    int hint = 0;
    return n.dot(hull_.vertices[hull_.support(n, hint)]);
  }
  double best = -kInfinity;
  for (const Vec3& p : points_) best = std::max(best, n.dot(p));
  return best;
}

Status Builder::buildHull() {
  use_qhull_ = check_ == HullCheck::Qhull || static_cast<int>(points_.size()) > kScanVertices;
  if (use_qhull_) {
    // One workspace per thread: the growth builds thousands of hulls per region.
    thread_local QuickHullWorkspace work;
    if (!quickHull(points_, {}, work, hull_)) {
      Result<ConvexPolytope> hull = convexHull(points_);
      if (!hull.ok()) return fail("patch: qhull found no volume");
      hull_ = std::move(hull.value());
    }
  }
  if (use_qhull_) facePlanes();
  return Status::success();
}

// Condition (1) once more, on the finished patch: every patch triangle supports
// the vertices.
bool Builder::trianglesSupport() const {
  for (const Tri& f : tris_) {
    const Vec3& a = points_[f[0]];
    const Vec3 n = normalizedOr((points_[f[1]] - a).cross(points_[f[2]] - a), Vec3::Zero());
    if (support(n) - n.dot(a) > tol_) return false;
  }
  return true;
}

// Outward planes of the hull's faces: qhull's, or without qhull those of the
// patch triangles and virtual faces (all on supporting planes by construction).
void Builder::facePlanes() {
  const Vec3* vertices = use_qhull_ ? hull_.vertices.data() : points_.data();
  std::vector<Tri> faces =
      use_qhull_ ? std::vector<Tri>(hull_.faces.begin(), hull_.faces.end()) : tris_;
  if (!use_qhull_) faces.insert(faces.end(), virtual_.begin(), virtual_.end());
  for (const Tri& f : faces) {
    const Vec3& a = vertices[f[0]];
    const Vec3 e1 = vertices[f[1]] - a, e2 = vertices[f[2]] - a;
    const Vec3 twice = e1.cross(e2);
    const double longest2 = std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
    // A sliver's normal is rounding noise; the other triangles of its facet bound
    // the hull there. Dropping a plane only enlarges the polytope (conservative).
    if (!(twice.norm() > 1e-10 * longest2)) continue;
    const Vec3 n = twice / twice.norm();
    out_.planes.push_back({n, n.dot(a)});
  }
}

// Boundary edges of the patch, reversed, chained into loops. From a loop edge
// x -> w, rotate about w (clockwise seen from outside) through the triangles not
// in the patch until the next patch triangle: its edge into w, reversed, is the
// next loop edge. Following the mesh's own fans keeps each loop simple where the
// patch touches a vertex more than once.
void Builder::traceLoops() {
  const int n = patch_.count;
  std::vector<char> used(3 * static_cast<std::size_t>(n), 0);
  for (int i = 0; i < n; ++i) {
    const int t0 = patch_.faces[i];
    for (int k0 = 0; k0 < 3; ++k0) {
      if (used[3 * i + k0] || patch_.contains(adjacency_.neighbour(t0, k0))) continue;
      std::vector<int> loop;
      std::vector<std::array<int, 2>> edges;
      int t = t0, k = k0;
      do {
        used[3 * patch_.rank[t] + k] = 1;
        loop.push_back(localOf(mesh_.triangles[t][(k + 1) % 3]));
        edges.push_back({t, k});
        // Edge `e` of triangle `cur` runs x -> w; edge e + 1 leaves w.
        int cur = adjacency_.neighbour(t, k);
        int e = adjacency_.neighbourEdge(t, k);
        for (;;) {
          const int out = (e + 1) % 3;
          const int next = adjacency_.neighbour(cur, out);
          const int next_edge = adjacency_.neighbourEdge(cur, out);
          if (patch_.contains(next)) {
            t = next;
            k = next_edge;
            break;
          }
          cur = next;
          e = next_edge;
        }
      } while (t != t0 || k != k0);
      loops_.push_back(std::move(loop));
      loop_edges_.push_back(std::move(edges));
    }
  }
}

bool Builder::isEar3d(int a, int b, int c) const {
  const Vec3 &pa = points_[a], &pb = points_[b], &pc = points_[c];
  const Vec3 ab = pb - pa, bc = pc - pb, ca = pa - pc;
  const Vec3 twice = ab.cross(pc - pa);
  const double lab = ab.norm(), lbc = bc.norm(), lca = ca.norm();
  const double twice_area = twice.norm();
  if (!(twice_area > 2.0 * kSliver * tol_ * std::max({lab, lbc, lca}))) return false;
  const Vec3 n = twice / twice_area;
  if (support(n) - n.dot(pa) > tol_) return false;
  const double margin = kOnEdge * tol_;
  for (int i = 0; i < static_cast<int>(points_.size()); ++i) {
    if (i == a || i == b || i == c) continue;
    const Vec3& p = points_[i];
    if (std::abs(n.dot(p - pa)) > tol_) continue;
    if (ab.cross(p - pa).dot(n) >= -margin * lab && bc.cross(p - pb).dot(n) >= -margin * lbc &&
        ca.cross(p - pc).dot(n) >= -margin * lca) {
      return false;
    }
  }
  return true;
}

// Flat patches work in the plane's 2-D frame. Front ears (counter-clockwise) fill
// pockets and must avoid every patch vertex; back ears only the remaining loop.
// A nearly flat patch's back is still a hull's: the 3-D supporting test decides
// which diagonals it takes.
bool Builder::isEar2d(int a, int b, int c, bool front, const std::vector<int>& ring, int ring_start,
                      const std::vector<int>& next) const {
  const Vec2 &pa = flat_points_[a], &pb = flat_points_[b], &pc = flat_points_[c];
  const double twice_area = cross2(pa, pb, pc);
  const double lab = (pb - pa).norm(), lbc = (pc - pb).norm(), lca = (pa - pc).norm();
  if (!(std::abs(twice_area) > 2.0 * kSliver * tol_ * std::max({lab, lbc, lca}))) return false;
  if ((twice_area > 0.0) != front) return false;
  // The patch is only flat within kFlatFactor tolerances: the ear must still lie
  // on a supporting plane of the vertices, like any hull face.
  const Vec3& qa = points_[a];
  const Vec3 n = normalizedOr((points_[b] - qa).cross(points_[c] - qa), Vec3::Zero());
  if (support(n) - n.dot(qa) > tol_) return false;
  const double sign = front ? 1.0 : -1.0;
  const double margin = kOnEdge * tol_;
  auto inside = [&](int i) {
    if (i == a || i == b || i == c) return false;
    const Vec2& p = flat_points_[i];
    return sign * cross2(pa, pb, p) >= -margin * lab && sign * cross2(pb, pc, p) >= -margin * lbc &&
           sign * cross2(pc, pa, p) >= -margin * lca;
  };
  if (front) {
    for (int i = 0; i < static_cast<int>(flat_points_.size()); ++i) {
      if (inside(i)) return false;
    }
    return true;
  }
  int node = ring_start;
  do {
    if (inside(ring[node])) return false;
    node = next[node];
  } while (node != ring_start);
  return true;
}

// Ear clipping over a circular list of the loop's vertices. side[i] is the loop
// edge from node i to its successor, or -1 once that side is a diagonal.
bool Builder::clipLoop(const std::vector<int>& loop, const std::vector<std::array<int, 2>>& edges) {
  const int m = static_cast<int>(loop.size());
  std::vector<int> next(m), prev(m), side(m);
  for (int i = 0; i < m; ++i) {
    next[i] = (i + 1) % m;
    prev[i] = (i + m - 1) % m;
    side[i] = i;
  }
  auto ear = [&](int node, bool front) {
    const int a = loop[prev[node]], b = loop[node], c = loop[next[node]];
    return out_.flat ? isEar2d(a, b, c, front, loop, node, next) : isEar3d(a, b, c);
  };
  auto emit = [&](int node, bool front, bool last) {
    const int a = loop[prev[node]], b = loop[node], c = loop[next[node]];
    virtual_.emplace_back(a, b, c);
    front_.push_back(out_.flat && front ? 1 : 0);
    if (const int i = side[prev[node]]; i >= 0) edge_apex_.push_back({edges[i][0], edges[i][1], c});
    if (const int i = side[node]; i >= 0) edge_apex_.push_back({edges[i][0], edges[i][1], a});
    if (const int i = side[next[node]]; last && i >= 0)
      edge_apex_.push_back({edges[i][0], edges[i][1], b});
  };
  int remaining = m;
  int node = 0;
  bool front = true;  // flat patches: pockets first
  int misses = 0;
  while (remaining > 3) {
    if (ear(node, front)) {
      emit(node, front, false);
      const int na = prev[node], nc = next[node];
      side[na] = -1;
      next[na] = nc;
      prev[nc] = na;
      --remaining;
      misses = 0;
      node = na;
      continue;
    }
    node = next[node];
    if (++misses > remaining) {
      if (!out_.flat || !front) return false;
      front = false;
      misses = 0;
    }
  }
  bool last_front = false;
  if (out_.flat) {
    last_front = cross2(flat_points_[loop[prev[node]]], flat_points_[loop[node]],
                        flat_points_[loop[next[node]]]) > 0.0;
  }
  if (!ear(node, last_front)) return false;
  emit(node, last_front, true);
  return true;
}

// At a boundary edge the solid is the wedge from the patch triangle, turning
// inwards, to its neighbour; the hull's wedge ends at the virtual face on that
// edge. Where the neighbour bends down (convex edge), the hull's wedge fits iff
// the neighbour's plane supports it there: the virtual face's apex lies on or
// below that plane.
bool Builder::wedgesFit() const {
  // Thick hulls: the caller's interior test catches a neighbour inside the wedge.
  if (!out_.flat && thickness_ >= 2.0 * kProbeDepth * tol_) return true;
  auto unitNormal = [&](const Tri& t) {
    const Vec3& a = mesh_.vertices[t[0]];
    return normalizedOr((mesh_.vertices[t[1]] - a).cross(mesh_.vertices[t[2]] - a), Vec3::Zero());
  };
  for (const std::array<int, 3>& edge : edge_apex_) {
    const Tri& f = mesh_.triangles[edge[0]];
    const int g = adjacency_.neighbour(edge[0], edge[1]);
    const Tri& h = mesh_.triangles[g];
    const Vec3& w = mesh_.vertices[f[edge[1]]];
    const Vec3& far = mesh_.vertices[h[(adjacency_.neighbourEdge(edge[0], edge[1]) + 2) % 3]];
    if (unitNormal(f).dot(far - w) >= -tol_) continue;  // flat or concave: a wide wedge
    if (unitNormal(h).dot(points_[edge[2]] - w) > tol_) return false;
  }
  return true;
}

// Winding number of the closed faces about the vertices' centroid, which lies
// inside the hull of points that span a volume: 1 when the faces cover the hull
// once (the sum of the faces' solid angles, Van Oosterom and Strackee, is 4 pi).
bool Builder::windsOnce() const {
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : points_) centre += p;
  centre /= static_cast<double>(points_.size());
  double solid_angle = 0.0;
  auto add = [&](const Tri& f) {
    const Vec3 a = points_[f[0]] - centre, b = points_[f[1]] - centre, c = points_[f[2]] - centre;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    solid_angle += 2.0 * std::atan2(numerator, denominator);
  };
  for (const Tri& f : tris_) add(f);
  for (const Tri& f : virtual_) add(f);
  constexpr double kFourPi = 4.0 * kPi;
  return std::abs(solid_angle / kFourPi - 1.0) < 0.5;
}

bool Builder::areaMatches() const {
  if (out_.flat) {
    double front = 0.0, back = 0.0;
    for (const Tri& f : tris_) {
      const double twice = cross2(flat_points_[f[0]], flat_points_[f[1]], flat_points_[f[2]]);
      if (!(twice > 0.0)) return false;  // a patch triangle facing away from the plane
      front += 0.5 * twice;
    }
    for (std::size_t i = 0; i < virtual_.size(); ++i) {
      const Tri& f = virtual_[i];
      const double area = 0.5 * cross2(flat_points_[f[0]], flat_points_[f[1]], flat_points_[f[2]]);
      if (front_[i]) {
        front += area;
      } else {
        back -= area;
      }
    }
    const double hull = convexArea2d(flat_points_);
    const double allowed = kAreaTolerance * hull;
    return std::abs(front - hull) <= allowed && std::abs(back - hull) <= allowed;
  }
  if (!use_qhull_) return windsOnce();
  double faces = 0.0, hull = 0.0;
  for (const Tri& f : tris_) faces += triangleArea(points_[f[0]], points_[f[1]], points_[f[2]]);
  for (const Tri& f : virtual_) faces += triangleArea(points_[f[0]], points_[f[1]], points_[f[2]]);
  for (const Tri& f : hull_.faces) {
    hull += triangleArea(hull_.vertices[f[0]], hull_.vertices[f[1]], hull_.vertices[f[2]]);
  }
  return std::abs(faces - hull) <= kAreaTolerance * hull;
}

// The prism under a virtual face that looks the patch's way, from kFlatFactor
// tolerances deep (high for flat patches) to kProbeDepth tolerances deep, bounded by planes through
// the face's edges perpendicular to it. Flat patches use the patch's plane (their pockets' own
// normals may be noise); thin hulls the face's plane.
void Builder::addProbes() {
  if (!out_.flat && thickness_ >= 2.0 * kProbeDepth * tol_) return;
  for (std::size_t i = 0; i < virtual_.size(); ++i) {
    const Tri& f = virtual_[i];
    const Vec3 &a = points_[f[0]], &b = points_[f[1]], &c = points_[f[2]];
    Vec3 n = normal_;
    if (out_.flat) {
      if (!front_[i]) continue;
    } else {
      n = normalizedOr((b - a).cross(c - a), Vec3::Zero());
      if (!(n.dot(normal_) > 0.0)) continue;
    }
    const double top = std::max({n.dot(a), n.dot(b), n.dot(c)});
    std::array<Plane, 5> prism;
    // A flat patch's prism starts above its plane: a triangle of that plane left in
    // a pocket (the patch did not take it, e.g. it is in another region) is refused.
    // Such a triangle may end at a convex edge whose wall goes down along the seam
    // of two pockets' prisms, seen by neither, with air under the pocket.
    prism[0] = {n, top + (out_.flat ? kFlatFactor : -kFlatFactor) * tol_};
    prism[1] = {-n, -(top - kProbeDepth * tol_)};
    const Vec3* corners[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = *corners[k];
      const Vec3& q = *corners[(k + 1) % 3];
      const Vec3 side = normalizedOr((q - p).cross(n), Vec3::Zero());
      prism[2 + k] = {side, side.dot(p)};
    }
    out_.probes.push_back(prism);
  }
}

Result<PatchPolytope> Builder::run() {
  if (patch_.count <= 0) return fail("patch: empty");
  collectVertices();
  classifyFlat();
  if (!out_.flat) {
    if (Status s = buildHull(); !s.ok()) return s;
  }
  if (!trianglesSupport()) return fail("patch: a triangle is not on its hull's boundary");
  traceLoops();
  for (std::size_t i = 0; i < loops_.size(); ++i) {
    if (!clipLoop(loops_[i], loop_edges_[i]))
      return fail("patch: no ear left while closing its hull");
  }
  if (!areaMatches()) return fail("patch: its faces do not cover the hull once");
  if (!wedgesFit()) return fail("patch: its hull leaves the solid at a boundary edge");
  if (!out_.flat && !use_qhull_) facePlanes();
  out_.used_qhull = use_qhull_;
  addProbes();

  PolytopeParts poly;
  poly.vertices = std::move(points_);
  poly.original = std::move(verts_);
  poly.faces = std::move(tris_);
  poly.face_source.assign(patch_.faces.begin(), patch_.faces.begin() + patch_.count);
  poly.faces.insert(poly.faces.end(), virtual_.begin(), virtual_.end());
  poly.face_source.resize(poly.faces.size(), -1);
  out_.virtual_faces = static_cast<int>(virtual_.size());
  out_.polytope = ConvexPolytope::build(poly);
  return std::move(out_);
}

}  // namespace

double decompositionTolerance(const MeshData& mesh) {
  Aabb box;
  for (const Tri& f : mesh.triangles) {
    for (int k = 0; k < 3; ++k) box.extend(mesh.vertices[f[k]]);
  }
  return box.empty() ? 0.0 : kDecompositionRelativeTolerance * (box.max - box.min).norm();
}

Result<PatchPolytope> buildPatchPolytope(const MeshData& mesh, const TriangleAdjacency& adjacency,
                                         const PatchRef& patch, double tolerance, HullCheck check) {
  return Builder(mesh, adjacency, patch, tolerance, check).run();
}

}  // namespace sc::detail
