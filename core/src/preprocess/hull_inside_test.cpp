// SPDX-License-Identifier: MIT
#include "preprocess/hull_inside_test.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>

namespace sc::detail {
namespace {

/// Normals of the outer planes: the 3 axes, 6 face and 4 body diagonals of a cube.
const std::array<Vec3, 13>& outerDirections() {
  static const std::array<Vec3, 13> directions = [] {
    std::array<Vec3, 13> d = {Vec3(1, 0, 0),  Vec3(0, 1, 0), Vec3(0, 0, 1),  Vec3(1, 1, 0),
                              Vec3(1, -1, 0), Vec3(1, 0, 1), Vec3(1, 0, -1), Vec3(0, 1, 1),
                              Vec3(0, 1, -1), Vec3(1, 1, 1), Vec3(1, 1, -1), Vec3(1, -1, 1),
                              Vec3(-1, 1, 1)};
    for (Vec3& v : d) v.normalize();
    return d;
  }();
  return directions;
}

/// Planes of the largest faces kept among the outer planes.
constexpr int kOuterFaces = 8;
/// Face normals closer than this cosine count as one direction.
constexpr double kSameDirection = 0.999;

}  // namespace

std::vector<Plane> outerPlanes(const ConvexPolytope& poly) {
  auto support = [&](const Vec3& n) {
    double best = -kInfinity;
    for (const Vec3& v : poly.vertices) best = std::max(best, n.dot(v));
    return best;
  };
  std::vector<Plane> planes;
  for (const Vec3& d : outerDirections()) {
    planes.push_back({d, support(d)});
    planes.push_back({-d, support(-d)});
  }
  std::vector<std::pair<double, Vec3>> faces;
  for (const Tri& f : poly.faces) {
    const Vec3 twice = (poly.vertices[f[1]] - poly.vertices[f[0]])
                           .cross(poly.vertices[f[2]] - poly.vertices[f[0]]);
    if (twice.norm() > 0.0) faces.emplace_back(twice.norm(), twice.normalized());
  }
  // Largest first, one per direction: a flat cap is many faces of one plane.
  std::sort(faces.begin(), faces.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<Vec3> kept;
  for (const auto& face : faces) {
    const Vec3& n = face.second;  // a named reference: lambdas cannot capture bindings
    if (static_cast<int>(kept.size()) == kOuterFaces) break;
    const bool repeated = std::any_of(kept.begin(), kept.end(),
                                      [&](const Vec3& m) { return m.dot(n) > kSameDirection; });
    if (repeated) continue;
    kept.push_back(n);
    planes.push_back({n, support(n)});
  }
  return planes;
}

bool reachesInside(const SharedMesh& shared, const RegionTree& tree, PatchInTree patch,
                   std::vector<Plane> planes, const Aabb& bounds, int also_skip,
                   std::vector<Plane> outer) {
  const MeshData& mesh = shared.mesh;
  HalfspacePolytope region(std::move(planes), shared.tol);
  const bool pruned = !outer.empty();
  HalfspacePolytope prune(std::move(outer), shared.tol);
  HalfspacePolytope& filter = pruned ? prune : region;
  bool reached = false;
  tree.query(
      patch.counted,
      [&](const Aabb& box) { return boxesOverlap(box, bounds) && filter.boxMayReachInterior(box); },
      [&](int t) {
        if (patch.patch.contains(t) || t == also_skip) return true;
        if (pruned && !prune.boxMayReachInterior(tree.box(t))) return true;
        const Tri& f = mesh.triangles[t];
        if (!region.triangleReachesInterior(mesh.vertices[f[0]], mesh.vertices[f[1]],
                                            mesh.vertices[f[2]])) {
          return true;
        }
        reached = true;
        return false;
      });
  return reached;
}

bool reachesAnyInside(const SharedMesh& shared, const RegionTree& tree, PatchInTree patch,
                      std::vector<HalfspacePolytope>& polytopes, const std::vector<Aabb>& bounds,
                      int also_skip) {
  const MeshData& mesh = shared.mesh;
  const std::size_t count = bounds.size();  // polytopes may hold spares beyond it
  auto mayReach = [&](std::size_t i, const Aabb& box) {
    return boxesOverlap(box, bounds[i]) && polytopes[i].boxMayReachInterior(box);
  };
  // Bit i: polytope i may still be reached. A box walks the open ones in order up
  // to the first it may reach, as a plain walk would; the ones it cannot reach are
  // closed for its subtree. Past 64 polytopes, nothing is closed.
  const bool few = count <= 64;
  auto open = [&](const Aabb& box, std::uint64_t mask) -> std::uint64_t {
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint64_t bit = few ? std::uint64_t{1} << i : 0;
      if (few && !(mask & bit)) continue;
      if (mayReach(i, box)) return mask;
      mask &= ~bit;
    }
    return 0;
  };
  const std::uint64_t all = few && count < 64 ? (std::uint64_t{1} << count) - 1 : ~std::uint64_t{0};
  bool reached = false;
  tree.queryMasked(patch.counted, all, open, [&](int t, std::uint64_t mask) {
    if (patch.patch.contains(t) || t == also_skip) return true;
    const Aabb& box = tree.box(t);
    const Tri& f = mesh.triangles[t];
    for (std::size_t i = 0; i < count && !reached; ++i) {
      reached = (!few || (mask >> i & 1)) && mayReach(i, box) &&
                polytopes[i].triangleReachesInterior(mesh.vertices[f[0]], mesh.vertices[f[1]],
                                                     mesh.vertices[f[2]]);
    }
    return !reached;
  });
  return reached;
}

}  // namespace sc::detail
