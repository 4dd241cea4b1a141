// SPDX-License-Identifier: MIT
// Input checks of manual 6.2: arrays of every piece; manifoldness, winding, one
// shell and orientation of closed pieces; the exact convexity test.
#include "geometry/mesh_validation.h"

#include "geometry/math_util.h"
#include "geometry/triangle_adjacency.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace sc::detail {
namespace {

/// A triangle is degenerate when its area is at most this times its longest edge squared.
constexpr double kDegenerateArea = 1e-12;
/// A closed surface encloses no volume when |6 V| is at most this times the scale of
/// the volume sum (sum of |a| |(b - a) x (c - a)|), i.e. V is rounding noise.
constexpr double kFlatVolume = 1e-10;
/// Plane tolerance of the convexity test, relative to the bounding-box diagonal.
constexpr double kConvexTolerance = 1e-9;

std::string edgeName(int a, int b) {
  return "(" + std::to_string(a) + "," + std::to_string(b) + ")";
}

/// Reports a failed closed-polyhedron rule.
Status invalidGeometry(const std::string& what) {
  return {ErrorCode::InvalidGeometry, "closed polyhedron: " + what};
}

/// Vertices referenced by at least one triangle.
std::vector<bool> referencedVertices(const MeshData& mesh) {
  std::vector<bool> used(mesh.vertices.size(), false);
  for (const Tri& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(t[k])] = true;
  }
  return used;
}

/// The referenced vertices moved to the centre of their box and scaled into
/// [-1, 1]^3 (the others set to zero). Every test below is invariant under this
/// similarity, and in these units squares and cubes neither overflow nor underflow.
std::vector<Vec3> unitBoxVertices(const MeshData& mesh) {
  const std::vector<bool> used = referencedVertices(mesh);
  Aabb box;
  for (std::size_t i = 0; i < used.size(); ++i) {
    if (used[i]) box.extend(mesh.vertices[i]);
  }
  std::vector<Vec3> unit(mesh.vertices.size(), Vec3::Zero());
  if (box.empty()) return unit;
  const Vec3 center = 0.5 * box.min + 0.5 * box.max;
  double scale = (box.max - center).cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) scale = 1.0;  // a single point: all its triangles are degenerate
  for (std::size_t i = 0; i < used.size(); ++i) {
    if (used[i]) unit[i] = (mesh.vertices[i] - center) / scale;
  }
  return unit;
}

std::uint64_t edgeKey(int from, int to) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(from)) << 32) |
         static_cast<std::uint32_t>(to);
}

/// Position of vertex v in triangle t (v must be one of its corners).
int cornerOf(const Tri& t, int v) { return t[0] == v ? 0 : t[1] == v ? 1 : 2; }

/// Union-find with path halving; small and local to these checks.
class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(int a, int b) { parent_[find(a)] = find(b); }

 private:
  std::vector<int> parent_;
};

/// Degenerate triangles: a repeated index, or an area that is rounding noise
/// compared with the triangle's own size (collinear or coincident vertices).
Status checkTriangles(const MeshData& mesh, const std::vector<Vec3>& p) {
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Tri& f = mesh.triangles[t];
    const char* why = nullptr;
    if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) {
      why = "it repeats a vertex index";
    } else {
      const Vec3 &a = p[f[0]], &b = p[f[1]], &c = p[f[2]];
      const double longest2 =
          std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
      const double area = 0.5 * (b - a).cross(c - a).norm();
      if (area <= kDegenerateArea * longest2) why = "its vertices are collinear or coincide";
    }
    if (why != nullptr) {
      return invalidGeometry("triangle " + std::to_string(t) + " is degenerate: " + why);
    }
  }
  return Status::success();
}

/// The first faulty edge in (lo, hi) order and why: an edge not in exactly two
/// triangles once in each direction. Only run once the adjacency found a fault, so
/// the message names the same edge whatever the mesh's order.
Status edgeFault(const MeshData& mesh) {
  struct EdgeUse {
    int lo, hi, tri;
    bool forward;
  };
  std::vector<EdgeUse> uses;
  uses.reserve(3 * mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Tri& f = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      uses.push_back({std::min(a, b), std::max(a, b), static_cast<int>(t), a < b});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return edgeKey(x.lo, x.hi) != edgeKey(y.lo, y.hi) ? edgeKey(x.lo, x.hi) < edgeKey(y.lo, y.hi)
                                                      : x.tri < y.tri;
  });
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) ++j;
    const std::size_t count = j - i;
    if (count == 2 && uses[i].forward != uses[i + 1].forward) {
      i = j;
      continue;
    }
    const std::string edge = "edge " + edgeName(uses[i].lo, uses[i].hi);
    if (count == 1) {
      return invalidGeometry(edge + " belongs only to triangle " + std::to_string(uses[i].tri) +
                             ": the surface is open");
    }
    if (count > 2) {
      return invalidGeometry(edge + " is shared by " + std::to_string(count) +
                             " triangles (" + std::to_string(uses[i].tri) + ", " +
                             std::to_string(uses[i + 1].tri) + ", " +
                             std::to_string(uses[i + 2].tri) + (count > 3 ? ", ...)" : ")"));
    }
    return invalidGeometry(edge + " runs the same way in triangles " +
                           std::to_string(uses[i].tri) + " and " +
                           std::to_string(uses[i + 1].tri) + ": inconsistent winding");
  }
  return Status::success();
}

/// Every vertex's triangles form one fan (over a built adjacency).
///
/// Why a pinched vertex is rejected: where two fans meet at one point (e.g. two
/// tetrahedra touching at a vertex) the surface is not a
/// 2-manifold, the solid's interior is not locally one piece there, and the
/// "single boundary" rule of manual 6.2 fails even though every edge is fine.
/// Later stages rely on manifold vertices: the convex decomposition grows patches
/// around vertices, and hill climbing and feature reporting assume each vertex
/// has one ring of neighbours.
Status checkFans(const MeshData& mesh, const TriangleAdjacency& adjacency) {
  // Corner (t, k) is joined to the corner at the same vertex in the triangle across
  // t's edge entering that vertex; each resulting set is one fan.
  DisjointSets fans(3 * mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Tri& f = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int v = f[k];
      const int other = adjacency.neighbour(static_cast<int>(t), (k + 2) % 3);
      const int other_corner = cornerOf(mesh.triangles[other], v);
      fans.unite(static_cast<int>(3 * t) + k, 3 * other + other_corner);
    }
  }
  std::vector<int> fan_count(mesh.vertices.size(), 0);
  for (std::size_t c = 0; c < 3 * mesh.triangles.size(); ++c) {
    if (fans.find(static_cast<int>(c)) != static_cast<int>(c)) continue;
    const int v = mesh.triangles[c / 3][static_cast<int>(c % 3)];
    if (++fan_count[v] > 1) {
      return invalidGeometry("vertex " + std::to_string(v) +
                             " is pinched: its triangles form separate fans that touch only "
                             "at this vertex");
    }
  }
  return Status::success();
}

/// All triangles connected through shared edges (over a built adjacency).
Status checkOneShell(const MeshData& mesh, const TriangleAdjacency& adjacency) {
  DisjointSets shells(mesh.triangles.size());
  for (int t = 0; t < adjacency.triangleCount(); ++t) {
    for (int k = 0; k < 3; ++k) shells.unite(t, adjacency.neighbour(t, k));
  }
  const int first = shells.find(0);
  int count = 1;
  int example = -1;
  std::vector<bool> seen(mesh.triangles.size(), false);
  seen[first] = true;
  for (std::size_t t = 1; t < mesh.triangles.size(); ++t) {
    const int root = shells.find(static_cast<int>(t));
    if (seen[root]) continue;
    seen[root] = true;
    ++count;
    if (example < 0) example = static_cast<int>(t);
  }
  if (count == 1) return Status::success();
  return invalidGeometry("the piece has " + std::to_string(count) +
                         " separate shells (triangles 0 and " + std::to_string(example) +
                         " share no path of edges); add each shell as its own piece");
}

/// 6 x the signed volume, and the scale its rounding error is relative to.
struct VolumeSum {
  double six_volume = 0.0;
  double scale = 0.0;
};

VolumeSum volumeSum(const MeshData& mesh, const std::vector<Vec3>& p) {
  VolumeSum sum;
  for (const Tri& f : mesh.triangles) {
    const Vec3 &a = p[f[0]], &b = p[f[1]], &c = p[f[2]];
    const Vec3 twice_area = (b - a).cross(c - a);
    sum.six_volume += a.dot(twice_area);
    sum.scale += a.norm() * twice_area.norm();
  }
  return sum;
}

Vec3 faceNormal(const std::vector<Vec3>& p, const Tri& f) {
  return normalizedOr((p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]), Vec3::Zero());
}

/// Every edge convex or flat: the far vertex of the neighbour across each edge lies
/// on or below the triangle's plane.
bool edgesConvex(const MeshData& mesh, const std::vector<Vec3>& p, double tolerance) {
  const Result<TriangleAdjacency> adjacency = TriangleAdjacency::build(mesh);
  if (!adjacency.ok()) return false;  // not closed: not a convex polyhedron either
  for (int t = 0; t < adjacency.value().triangleCount(); ++t) {
    const Tri& f = mesh.triangles[t];
    const Vec3 n = faceNormal(p, f);
    for (int k = 0; k < 3; ++k) {
      // The neighbour's copy of edge k runs the other way; its third corner is far.
      const Tri& g = mesh.triangles[adjacency.value().neighbour(t, k)];
      const int far = g[(adjacency.value().neighbourEdge(t, k) + 2) % 3];
      if (n.dot(p[far] - p[f[k]]) > tolerance) return false;
    }
  }
  return true;
}

/// Points in a tree of boxes (median splits), to ask whether any point lies above
/// a plane without visiting the points of boxes wholly below it.
class PointTree {
 public:
  explicit PointTree(std::vector<Vec3> points) : points_(std::move(points)) {
    if (!points_.empty()) build(0, static_cast<int>(points_.size()));
  }

  /// True when some point p has dot(n, p) > limit.
  bool anyAbove(const Vec3& n, double limit) const {
    if (nodes_.empty()) return false;
    int stack[64];  // holds at most depth + 1 <= 33 nodes
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      const Vec3 center = 0.5 * (node.box.min + node.box.max);
      const Vec3 half = 0.5 * (node.box.max - node.box.min);
      if (n.dot(center) + n.cwiseAbs().dot(half) <= limit) continue;
      if (node.left < 0) {
        for (int i = node.begin; i < node.end; ++i) {
          if (n.dot(points_[i]) > limit) return true;
        }
      } else {
        stack[top++] = node.left;
        stack[top++] = node.right;
      }
    }
    return false;
  }

 private:
  static constexpr int kLeafSize = 8;

  struct Node {
    Aabb box;
    int begin, end;  ///< range of points_
    int left = -1;   ///< children, -1 for a leaf
    int right = -1;
  };

  /// Builds the subtree of points_[begin, end) and returns its root.
  int build(int begin, int end) {
    const int index = static_cast<int>(nodes_.size());
    Aabb box;
    for (int i = begin; i < end; ++i) box.extend(points_[i]);
    nodes_.push_back({box, begin, end});
    if (end - begin <= kLeafSize) return index;
    int axis = 0;
    (box.max - box.min).maxCoeff(&axis);
    const int mid = begin + (end - begin) / 2;
    std::nth_element(points_.begin() + begin, points_.begin() + mid, points_.begin() + end,
                     [axis](const Vec3& a, const Vec3& b) { return a[axis] < b[axis]; });
    const int left = build(begin, mid);
    const int right = build(mid, end);
    nodes_[index].left = left;
    nodes_[index].right = right;
    return index;
  }

  std::vector<Vec3> points_;
  std::vector<Node> nodes_;
};

/// Every referenced vertex on or below every face plane. Together with convex edges
/// this rules out surfaces that are locally convex but wind around more than once.
bool verticesBelowFaces(const MeshData& mesh, const std::vector<Vec3>& p, double tolerance) {
  const std::vector<bool> used = referencedVertices(mesh);
  std::vector<Vec3> points;
  for (std::size_t i = 0; i < used.size(); ++i) {
    if (used[i]) points.push_back(p[i]);
  }
  const PointTree tree(std::move(points));
  for (const Tri& f : mesh.triangles) {
    const Vec3 n = faceNormal(p, f);
    if (tree.anyAbove(n, n.dot(p[f[0]]) + tolerance)) return false;
  }
  return true;
}

/// The piece's extent within the supported scales (model.h); 0 is left to the
/// geometry rules (a closed piece is then degenerate, a soup one point).
Status checkExtent(const MeshData& mesh) {
  Aabb box;
  for (const Tri& f : mesh.triangles) {
    for (int k = 0; k < 3; ++k) box.extend(mesh.vertices[static_cast<std::size_t>(f[k])]);
  }
  const double extent = (box.max - box.min).maxCoeff();
  if (extent == 0.0 || (extent >= kMinPieceExtent && extent <= kMaxPieceExtent))
    return Status::success();
  char text[64];
  std::snprintf(text, sizeof text, "%.3g", extent);
  return {ErrorCode::InvalidArgument,
          std::string("the piece's extent ") + text +
              (extent < kMinPieceExtent ? " is below 1e-9" : " is beyond 1e9") +
              ", outside the supported scales [1e-9, 1e9]: rescale the model's units"};
}

}  // namespace

Status validateArrays(const MeshData& mesh) {
  // Component-wise std::isfinite: Eigen's allFinite computes x - x, which raises
  // FE_INVALID on an infinity.
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& v = mesh.vertices[i];
    if (!std::isfinite(v.x()) || !std::isfinite(v.y()) || !std::isfinite(v.z())) {
      return {ErrorCode::InvalidArgument,
              "vertex " + std::to_string(i) + " has a non-finite coordinate"};
    }
    // Squared distances and cross products of such coordinates overflow to inf.
    if (v.cwiseAbs().maxCoeff() > kMaxCoordinate) {
      return {ErrorCode::InvalidArgument, "vertex " + std::to_string(i) +
                                              " has a coordinate beyond 1e100 in magnitude"};
    }
  }
  if (mesh.triangles.empty()) return {ErrorCode::InvalidArgument, "the piece has no triangles"};
  const long long n = static_cast<long long>(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int index = mesh.triangles[t][k];
      if (index < 0 || index >= n) {
        return {ErrorCode::InvalidArgument,
                "triangle " + std::to_string(t) + " has vertex index " + std::to_string(index) +
                    ", outside [0, " + std::to_string(n) + ")"};
      }
    }
  }
  return checkExtent(mesh);
}

Status validateClosed(MeshData& mesh, bool& flipped) {
  flipped = false;
  const std::vector<Vec3> p = unitBoxVertices(mesh);
  if (Status s = checkTriangles(mesh, p); !s.ok()) return s;
  const Result<TriangleAdjacency> adjacency = TriangleAdjacency::build(mesh);
  if (!adjacency.ok()) {
    const Status fault = edgeFault(mesh);
    return fault.ok() ? adjacency.status() : fault;
  }
  if (Status s = checkFans(mesh, adjacency.value()); !s.ok()) return s;
  if (Status s = checkOneShell(mesh, adjacency.value()); !s.ok()) return s;
  const VolumeSum volume = volumeSum(mesh, p);
  if (std::abs(volume.six_volume) <= kFlatVolume * volume.scale) {
    return invalidGeometry("the surface encloses no volume (it is flat or folded onto itself)");
  }
  if (volume.six_volume < 0.0) {
    for (Tri& f : mesh.triangles) std::swap(f[1], f[2]);
    flipped = true;
  }
  return Status::success();
}

bool isConvex(const MeshData& mesh) {
  if (mesh.triangles.empty()) return false;
  const std::vector<Vec3> p = unitBoxVertices(mesh);
  Aabb box;
  for (const Tri& f : mesh.triangles) {
    for (int k = 0; k < 3; ++k) box.extend(p[f[k]]);
  }
  const double tolerance = kConvexTolerance * (box.max - box.min).norm();
  return edgesConvex(mesh, p, tolerance) && verticesBelowFaces(mesh, p, tolerance);
}

}  // namespace sc::detail
