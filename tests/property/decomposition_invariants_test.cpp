// SPDX-License-Identifier: MIT
// Convex surface decomposition of the CGAL sample meshes, checked against its
// definition with code independent of the construction: patches partition the
// triangles, lie on their hulls' boundaries, and every hull lies inside the solid
// (ray-parity point-in-mesh on points inside each hull; no other triangle reaches
// into a hull, by clipping in each triangle's own parameter plane).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "geometry/mesh_validation.h"
#include "preprocess/convex_decomposition.h"
#include "preprocess/convex_hull.h"
#include "preprocess/patch_polytope.h"
#include "support/meshes.h"

namespace sc::detail {
namespace {

using Vec2 = Eigen::Vector2d;

/// Triangles binned in a uniform grid of cells by their bounding boxes.
class TriangleGrid {
 public:
  explicit TriangleGrid(const MeshData& mesh) {
    for (const Vec3& p : mesh.vertices) box_.extend(p);
    const Vec3 extent = box_.max - box_.min;
    const double cell_volume =
        extent.prod() / std::max<double>(1.0, static_cast<double>(mesh.triangles.size()));
    const double side = std::max(std::cbrt(cell_volume) * 2.0, 1e-12 * extent.norm());
    for (int k = 0; k < 3; ++k)
      cells_[k] = std::clamp(static_cast<int>(extent[k] / side) + 1, 1, 256);
    bins_.resize(static_cast<std::size_t>(cells_[0]) * cells_[1] * cells_[2]);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      Aabb b;
      for (int k = 0; k < 3; ++k) b.extend(mesh.vertices[mesh.triangles[t][k]]);
      forCells(b, [&](std::vector<int>& bin) { bin.push_back(static_cast<int>(t)); });
    }
  }

  /// Triangles whose box overlaps `b`, each once.
  std::vector<int> near(const Aabb& b) {
    std::vector<int> found;
    forCells(b, [&](std::vector<int>& bin) { found.insert(found.end(), bin.begin(), bin.end()); });
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
  }

 private:
  template <class F>
  void forCells(const Aabb& b, F&& f) {
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      const double scale = cells_[k] / std::max(box_.max[k] - box_.min[k], 1e-300);
      lo[k] = std::clamp(static_cast<int>((b.min[k] - box_.min[k]) * scale), 0, cells_[k] - 1);
      hi[k] = std::clamp(static_cast<int>((b.max[k] - box_.min[k]) * scale), 0, cells_[k] - 1);
    }
    for (int x = lo[0]; x <= hi[0]; ++x) {
      for (int y = lo[1]; y <= hi[1]; ++y) {
        for (int z = lo[2]; z <= hi[2]; ++z)
          f(bins_[(static_cast<std::size_t>(x) * cells_[1] + y) * cells_[2] + z]);
      }
    }
  }

  Aabb box_;
  int cells_[3] = {1, 1, 1};
  std::vector<std::vector<int>> bins_;
};

/// Point in a closed mesh by the parity of crossings of a ray. Rays run along
/// (sx, sy, 1) for a few irrational shears; the majority decides, so a ray that
/// grazes an edge cannot flip the answer.
class PointInMesh {
 public:
  explicit PointInMesh(const MeshData& mesh) : mesh_(mesh) {
    const double shears[kRays][2] = {{0.0137 * std::sqrt(2.0), 0.0071 * std::sqrt(3.0)},
                                     {-0.0113 * std::sqrt(5.0), 0.0191 * std::sqrt(7.0)},
                                     {0.0173 * std::sqrt(11.0), -0.0127 * std::sqrt(13.0)}};
    for (int r = 0; r < kRays; ++r) {
      Ray& ray = rays_[r];
      ray.sx = shears[r][0];
      ray.sy = shears[r][1];
      ray.flat.reserve(mesh.vertices.size());
      for (const Vec3& p : mesh.vertices) {
        ray.flat.emplace_back(p.x() - ray.sx * p.z(), p.y() - ray.sy * p.z());
        ray.lo = ray.lo.cwiseMin(ray.flat.back());
        ray.hi = ray.hi.cwiseMax(ray.flat.back());
      }
      ray.n = std::clamp(
          static_cast<int>(std::sqrt(static_cast<double>(mesh.triangles.size()) / 2.0)), 1, 512);
      ray.bins.resize(static_cast<std::size_t>(ray.n) * ray.n);
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        Vec2 lo = Vec2::Constant(kInfinity), hi = Vec2::Constant(-kInfinity);
        for (int k = 0; k < 3; ++k) {
          lo = lo.cwiseMin(ray.flat[mesh.triangles[t][k]]);
          hi = hi.cwiseMax(ray.flat[mesh.triangles[t][k]]);
        }
        const auto [x0, y0] = ray.cell(lo);
        const auto [x1, y1] = ray.cell(hi);
        for (int x = x0; x <= x1; ++x) {
          for (int y = y0; y <= y1; ++y)
            ray.bins[static_cast<std::size_t>(x) * ray.n + y].push_back(static_cast<int>(t));
        }
      }
    }
  }

  bool inside(const Vec3& p) const {
    int votes = 0;
    for (const Ray& ray : rays_) votes += crossings(ray, p) % 2;
    return 2 * votes > kRays;
  }

 private:
  static constexpr int kRays = 3;
  struct Ray {
    double sx = 0.0, sy = 0.0;
    std::vector<Vec2> flat;
    Vec2 lo = Vec2::Constant(kInfinity), hi = Vec2::Constant(-kInfinity);
    int n = 1;
    std::vector<std::vector<int>> bins;
    std::pair<int, int> cell(const Vec2& q) const {
      const Vec2 s = (q - lo).cwiseQuotient((hi - lo).cwiseMax(Vec2::Constant(1e-300))) * n;
      return {std::clamp(static_cast<int>(s.x()), 0, n - 1),
              std::clamp(static_cast<int>(s.y()), 0, n - 1)};
    }
  };

  int crossings(const Ray& ray, const Vec3& p) const {
    const Vec2 q(p.x() - ray.sx * p.z(), p.y() - ray.sy * p.z());
    if ((q.array() < ray.lo.array()).any() || (q.array() > ray.hi.array()).any()) return 0;
    const auto [x, y] = ray.cell(q);
    int count = 0;
    for (int t : ray.bins[static_cast<std::size_t>(x) * ray.n + y]) {
      const Tri& f = mesh_.triangles[t];
      const Vec2 &a = ray.flat[f[0]], &b = ray.flat[f[1]], &c = ray.flat[f[2]];
      auto edge = [&](const Vec2& u, const Vec2& v) {
        return (v.x() - u.x()) * (q.y() - u.y()) - (v.y() - u.y()) * (q.x() - u.x());
      };
      const double wa = edge(b, c), wb = edge(c, a), wc = edge(a, b);
      if (!((wa > 0 && wb > 0 && wc > 0) || (wa < 0 && wb < 0 && wc < 0))) continue;
      // Height of the triangle above q along the ray, by barycentric weights.
      const double sum = wa + wb + wc;
      const double z = (wa * mesh_.vertices[f[0]].z() + wb * mesh_.vertices[f[1]].z() +
                        wc * mesh_.vertices[f[2]].z()) /
                       sum;
      if (z > p.z()) ++count;
    }
    return count;
  }

  const MeshData& mesh_;
  Ray rays_[kRays];
};

/// True when some point of triangle abc is more than `depth` inside every plane
/// (n, d) (n . x <= d inside): the triangle's parameter square (u, w), u, w >= 0,
/// u + w <= 1, clipped by each plane as a half-plane.
bool reachesDeeperThan(const Vec3& a, const Vec3& b, const Vec3& c,
                       const std::vector<std::pair<Vec3, double>>& planes, double depth) {
  std::vector<Vec2> poly = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)}, next;
  for (const auto& [n, d] : planes) {
    const double alpha = n.dot(b - a), beta = n.dot(c - a), gamma = d - depth - n.dot(a);
    next.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec2& p = poly[i];
      const Vec2& q = poly[(i + 1) % poly.size()];
      const double sp = alpha * p.x() + beta * p.y() - gamma,
                   sq = alpha * q.x() + beta * q.y() - gamma;
      if (sp <= 0) next.push_back(p);
      if ((sp < 0 && sq > 0) || (sp > 0 && sq < 0)) next.push_back(p + (sp / (sp - sq)) * (q - p));
    }
    poly.swap(next);
    if (poly.empty()) return false;
  }
  return true;
}

struct Report {
  int patches = 0, virtual_faces = 0, hull_vertices = 0, flat = 0;
  int samples = 0, shared_real_faces = 0;
  double seconds = 0.0;
};

/// Checks one decomposition; `solid_inside` adds the point-in-mesh checks, which
/// need a surface that does not cross itself.
void checkDecomposition(const MeshData& mesh, const Decomposition& d, bool solid_inside,
                        Report& report) {
  const int n = static_cast<int>(mesh.triangles.size());
  const double tol = decompositionTolerance(mesh);
  ASSERT_EQ(d.triangle_patch.size(), mesh.triangles.size());
  std::map<std::array<int, 3>, int> triangle_of;  // rotated so the smallest index leads
  auto key = [](int a, int b, int c) {
    std::array<int, 3> k = {a, b, c};
    std::rotate(k.begin(), std::min_element(k.begin(), k.end()), k.end());
    return k;
  };
  for (int t = 0; t < n; ++t) {
    const Tri& f = mesh.triangles[t];
    triangle_of[key(f[0], f[1], f[2])] = t;
  }
  TriangleGrid grid(mesh);
  const PointInMesh solid(mesh);
  std::vector<int> covered(n, 0);
  int virtual_faces = 0;
  int failures = 0;
  auto fail = [&](int p, const std::string& what) {
    if (++failures <= 20) ADD_FAILURE() << "patch " << p << ": " << what;
  };
  for (int p = 0; p < static_cast<int>(d.patches.size()); ++p) {
    const ConvexPolytope& poly = d.patches[p];
    report.hull_vertices += static_cast<int>(poly.vertices.size());
    if (poly.vertices.size() != poly.original.size() ||
        poly.faces.size() != poly.face_source.size()) {
      fail(p, "inconsistent array sizes");
      continue;
    }
    for (std::size_t i = 0; i < poly.vertices.size(); ++i) {
      if (poly.vertices[i] != mesh.vertices[poly.original[i]])
        fail(p, "a hull vertex is not an input vertex");
    }
    std::vector<std::pair<Vec3, double>> planes;
    std::map<std::pair<int, int>, int> directed;
    double volume = 0.0, area = 0.0;
    Vec3 real_normal = Vec3::Zero();
    for (std::size_t f = 0; f < poly.faces.size(); ++f) {
      const Tri& face = poly.faces[f];
      const Vec3 &a = poly.vertices[face[0]], &b = poly.vertices[face[1]],
                 &c = poly.vertices[face[2]];
      const Vec3 twice = (b - a).cross(c - a);
      volume += a.dot(twice) / 6.0;
      area += 0.5 * twice.norm();
      for (int k = 0; k < 3; ++k) ++directed[{face[k], face[(k + 1) % 3]}];
      const Vec3 normal = twice.normalized();
      planes.emplace_back(normal, normal.dot(a));
      // Each face lies on the hull's boundary: every vertex on or below its plane.
      for (const Vec3& q : poly.vertices) {
        if (normal.dot(q - a) > tol) {
          fail(p, "face " + std::to_string(f) + " does not support the hull");
          break;
        }
      }
      const int source = poly.face_source[f];
      const auto found = triangle_of.find(
          key(poly.original[face[0]], poly.original[face[1]], poly.original[face[2]]));
      if (source < 0) {
        ++virtual_faces;
        if (found != triangle_of.end())
          fail(p, "virtual face " + std::to_string(f) + " is an input triangle");
        continue;
      }
      real_normal += twice;
      if (source >= n || found == triangle_of.end() || found->second != source) {
        fail(p,
             "real face " + std::to_string(f) + " is not input triangle " + std::to_string(source));
        continue;
      }
      // A hull face may equal a triangle of another patch: still a model face.
      if (d.triangle_patch[source] != p) {
        ++report.shared_real_faces;
        continue;
      }
      ++covered[source];
    }
    // Closed and consistently oriented (a flat patch is double-sided, so an edge
    // may bound one face per side in each direction).
    for (const auto& [edge, uses] : directed) {
      const auto reverse = directed.find({edge.second, edge.first});
      if (uses > 2 || reverse == directed.end() || reverse->second != uses)
        fail(p, "not a closed surface");
    }
    const bool flat = std::abs(volume) <= tol * area;
    if (flat) {
      ++report.flat;
    } else {
      // Faces cover the hull exactly once: the same volume as qhull's hull.
      Result<ConvexPolytope> hull = convexHull({poly.vertices.begin(), poly.vertices.end()});
      if (!hull.ok()) {
        fail(p, "qhull finds no hull of a patch with volume");
      } else {
        double hull_volume = 0.0;
        for (const Tri& f : hull.value().faces) {
          const Vec3& a = hull.value().vertices[f[0]];
          hull_volume +=
              a.dot((hull.value().vertices[f[1]] - a).cross(hull.value().vertices[f[2]] - a)) / 6.0;
        }
        if (std::abs(volume - hull_volume) > tol * area + 1e-9 * hull_volume)
          fail(p, "faces do not cover the hull once");
      }
      // No other triangle reaches more than the tolerance into the hull.
      Aabb box;
      for (const Vec3& q : poly.vertices) box.extend(q);
      for (int t : grid.near(box)) {
        if (d.triangle_patch[t] == p) continue;
        const Tri& f = mesh.triangles[t];
        if (reachesDeeperThan(mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]], planes,
                              tol)) {
          fail(p, "triangle " + std::to_string(t) + " reaches into the hull");
        }
      }
    }
    if (!solid_inside) continue;
    // Points inside the hull must be inside the solid: the vertex centroid, and
    // each virtual face's centroid moved 10 tolerances inwards. A flat patch's
    // pockets (its virtual faces on the patch's side) have the solid under them.
    auto depthInside = [&](const Vec3& q) {
      double depth = kInfinity;
      for (const auto& [normal, offset] : planes) depth = std::min(depth, offset - normal.dot(q));
      return depth;
    };
    std::vector<Vec3> samples;
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& q : poly.vertices) centroid += q;
    centroid /= static_cast<double>(poly.vertices.size());
    if (!flat && depthInside(centroid) > 2.0 * tol) samples.push_back(centroid);
    for (std::size_t f = 0; f < poly.faces.size(); ++f) {
      if (poly.face_source[f] >= 0) continue;
      const Tri& face = poly.faces[f];
      const Vec3 &a = poly.vertices[face[0]], &b = poly.vertices[face[1]],
                 &c = poly.vertices[face[2]];
      const Vec3 normal = (b - a).cross(c - a).normalized();
      // Skip slivers: the centroid must sit well inside the face.
      const double inradius =
          (b - a).cross(c - a).norm() / ((b - a).norm() + (c - b).norm() + (a - c).norm());
      if (inradius < 3.0 * tol) continue;
      if (flat && normal.dot(real_normal) <= 0.0) continue;  // back side of a flat patch
      const Vec3 q = (a + b + c) / 3.0 - 10.0 * tol * normal;
      if (flat || depthInside(q) > 2.0 * tol) samples.push_back(q);
    }
    for (const Vec3& q : samples) {
      ++report.samples;
      if (!solid.inside(q)) fail(p, "a point inside the hull is outside the solid");
    }
  }
  for (int t = 0; t < n; ++t) {
    if (covered[t] != 1) {
      ADD_FAILURE() << "triangle " << t << " is a real face of its own patch " << covered[t]
                    << " times";
      break;
    }
  }
  EXPECT_EQ(virtual_faces, d.virtual_faces);
  EXPECT_EQ(failures, 0);
  report.patches = static_cast<int>(d.patches.size());
  report.virtual_faces = d.virtual_faces;
}

void runMesh(const std::string& name, bool solid_inside) {
  MeshData mesh;
  ASSERT_NO_FATAL_FAILURE(mesh = test::loadTestMesh(name));
#if SC_TEST_SANITIZED
  // Sanitizers slow this 30-fold: the large meshes run in the Release pass only.
  if (mesh.triangles.size() > 15000) GTEST_SKIP() << name << ": too large for a sanitizer build";
#endif
  bool flipped = false;
  const Status valid = validateClosed(mesh, flipped);
  ASSERT_TRUE(valid.ok()) << name << " is not a valid closed piece: " << valid.message();
  const auto start = std::chrono::steady_clock::now();
  const Result<Decomposition> d = decomposeConvexSurface(mesh, {});
  Report report;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(d.ok()) << d.status().message();
  checkDecomposition(mesh, d.value(), solid_inside, report);
  std::printf(
      "[decomposition] %-10s triangles %6zu patches %6d virtual faces %6d hull vertices %6d "
      "flat %5d samples %6d real faces of other patches %d time %.2f s\n",
      name.c_str(), mesh.triangles.size(), report.patches, report.virtual_faces,
      report.hull_vertices, report.flat, report.samples, report.shared_real_faces, report.seconds);
  EXPECT_GT(report.patches, 1) << name << " is not convex";
}

class DecompositionInvariants : public ::testing::TestWithParam<const char*> {};

TEST_P(DecompositionInvariants, PatchesPartitionAndHullsLieInsideTheSolid) {
  runMesh(GetParam(), true);
}

INSTANTIATE_TEST_SUITE_P(CgalMeshes, DecompositionInvariants,
                         ::testing::Values("bunny00", "armadillo", "fandisk", "knot1", "elephant",
                                           "femur"));

// cow and camel cross themselves: "inside" is then defined as the hull, shrunk by
// the tolerance, meeting no triangle outside its patch (checked); parity-based
// point-in-mesh is meaningless there and is skipped.
class SelfIntersectingDecomposition : public ::testing::TestWithParam<const char*> {};

TEST_P(SelfIntersectingDecomposition, IsAcceptedWithHullsClearOfOtherTriangles) {
  runMesh(GetParam(), false);
}

INSTANTIATE_TEST_SUITE_P(CgalMeshes, SelfIntersectingDecomposition,
                         ::testing::Values("cow", "camel"));

}  // namespace
}  // namespace sc::detail
