// SPDX-License-Identifier: MIT
// Brute-force references: all triangle pairs through the exact triangle distance.
#include "support/brute_force.h"

#include <algorithm>
#include <limits>
#include <map>
#include <utility>

#include "geometry/triangle_distance.h"
#include "preprocess/convex_hull.h"

namespace sc::test {
namespace {

struct PlacedTriangle {
  Vec3 corners[3];
  Vec3 centre;
  double radius;
};

std::vector<PlacedTriangle> place(const MeshData& mesh, const Rigid& frame_from_mesh) {
  std::vector<PlacedTriangle> out;
  out.reserve(mesh.triangles.size());
  for (const Tri& t : mesh.triangles) {
    PlacedTriangle p;
    for (int k = 0; k < 3; ++k) p.corners[k] = frame_from_mesh * mesh.vertices[t[k]];
    p.centre = (p.corners[0] + p.corners[1] + p.corners[2]) / 3.0;
    p.radius = 0.0;
    for (const Vec3& c : p.corners) p.radius = std::max(p.radius, (c - p.centre).norm());
    out.push_back(p);
  }
  return out;
}

}  // namespace

SurfaceDistance meshSurfaceDistance(const MeshData& a, const Rigid& frame_from_a, const MeshData& b,
                                    const Rigid& frame_from_b) {
  const std::vector<PlacedTriangle> ta = place(a, frame_from_a);
  const std::vector<PlacedTriangle> tb = place(b, frame_from_b);
  SurfaceDistance best;
  best.distance = std::numeric_limits<double>::infinity();
  for (const PlacedTriangle& x : ta) {
    for (const PlacedTriangle& y : tb) {
      // The sphere bound is conservative: skipping never loses the minimum.
      if ((x.centre - y.centre).norm() - x.radius - y.radius > best.distance) continue;
      const detail::TriangleDistance d = detail::triangleDistance(x.corners, y.corners);
      if (d.distance < best.distance) {
        best.distance = d.distance;
        best.point_a = d.point_a;
        best.point_b = d.point_b;
      }
    }
  }
  return best;
}

double pointSurfaceDistance(const MeshData& mesh, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Tri& t : mesh.triangles) {
    const Vec3 corners[3] = {mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
    best = std::min(best, detail::pointTriangleDistance(p, corners));
  }
  return best;
}

double supportValue(const detail::ConvexPolytope& poly, const Vec3& d) {
  double best = -kInfinity;
  for (const Vec3& p : poly.vertices) best = std::max(best, p.dot(d));
  return best;
}

bool pointInConvexPolytope(const detail::ConvexPolytope& poly, const Vec3& p, double tolerance) {
  for (const Tri& t : poly.faces) {
    const Vec3& a = poly.vertices[t[0]];
    const Vec3 n = (poly.vertices[t[1]] - a).cross(poly.vertices[t[2]] - a);
    const double len = n.norm();
    if (len == 0.0) continue;  // a zero-area face bounds nothing
    if (n.dot(p - a) / len > tolerance) return false;
  }
  return true;
}

double pointFeatureDistance(const std::vector<Vec3>& points, const Feature& f, const Vec3& p) {
  switch (f.type) {
    case FeatureType::Vertex:
      return (points[f.vertices[0]] - p).norm();
    case FeatureType::Edge:
      return detail::pointSegmentDistance(p, points[f.vertices[0]], points[f.vertices[1]]);
    case FeatureType::Face: {
      const Vec3 corners[3] = {points[f.vertices[0]], points[f.vertices[1]], points[f.vertices[2]]};
      return detail::pointTriangleDistance(p, corners);
    }
  }
  return std::numeric_limits<double>::infinity();
}

ExactDepth exactPenetrationDepth(const detail::ConvexPolytope& a, const Rigid& wa,
                                 const detail::ConvexPolytope& b, const Rigid& wb) {
  std::vector<Vec3> diff;
  for (const Vec3& p : a.vertices)
    for (const Vec3& q : b.vertices) diff.push_back(wa * p - wb * q);
  const auto hull = detail::convexHull(diff);
  ExactDepth out;
  if (!hull.ok()) return out;
  const auto& h = hull.value();
  for (const Tri& f : h.faces) {
    const Vec3 n = (h.vertices[f[1]] - h.vertices[f[0]]).cross(h.vertices[f[2]] - h.vertices[f[0]]);
    if (n.norm() < 1e-300) continue;
    const Vec3 u = n.normalized();
    const double d = u.dot(h.vertices[f[0]]);
    if (d < out.depth) {
      if ((u - out.normal).norm() > 1e-9) out.runner_up = out.depth;
      out.depth = d;
      out.normal = u;
    } else if (d < out.runner_up && (u - out.normal).norm() > 1e-9) {
      out.runner_up = d;
    }
  }
  return out;
}

bool eachEdgeOnceEachWay(const std::vector<Tri>& faces) {
  std::map<std::pair<int, int>, int> directed;
  for (const Tri& f : faces) {
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  }
  for (const auto& [edge, uses] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (uses != 1 || reverse == directed.end() || reverse->second != 1) return false;
  }
  return true;
}

}  // namespace sc::test
