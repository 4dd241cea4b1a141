// SPDX-License-Identifier: MIT
#include "preprocess/decomposition_mesh.h"

#include <algorithm>
#include <cmath>

#include "geometry/math_util.h"
#include "preprocess/patch_polytope.h"

namespace sc::detail {

Status SharedMesh::prepare() {
  const int n = static_cast<int>(mesh.triangles.size());
  if (n < 4) return {ErrorCode::InvalidGeometry, "decomposition: fewer than four triangles"};
  for (const Tri& f : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      if (f[k] < 0 || f[k] >= static_cast<int>(mesh.vertices.size())) {
        return {ErrorCode::InvalidArgument, "decomposition: vertex index out of range"};
      }
      // Component-wise: Eigen's allFinite() computes x - x, which traps on infinity.
      const Vec3& p = mesh.vertices[f[k]];
      if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
        return {ErrorCode::InvalidArgument, "decomposition: non-finite vertex"};
      }
    }
  }
  Result<TriangleAdjacency> built = TriangleAdjacency::build(mesh);
  if (!built.ok()) return built.status();
  adjacency = std::move(built.value());
  tol = decompositionTolerance(mesh);

  normals.resize(n);
  offsets.resize(n);
  std::vector<Aabb> boxes(n);
  std::vector<Vec3> centres(n);
  for (int t = 0; t < n; ++t) {
    const Tri& f = mesh.triangles[t];
    const Vec3 &a = mesh.vertices[f[0]], &b = mesh.vertices[f[1]], &c = mesh.vertices[f[2]];
    normals[t] = normalizedOr((b - a).cross(c - a), Vec3::Zero());
    if (normals[t].isZero()) {
      return {ErrorCode::InvalidGeometry, "decomposition: degenerate triangle"};
    }
    offsets[t] = normals[t].dot(a);
    boxes[t].extend(a);
    boxes[t].extend(b);
    boxes[t].extend(c);
    centres[t] = (a + b + c) / 3.0;
  }
  convex_edge.resize(n);
  for (int t = 0; t < n; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int g = adjacency.neighbour(t, k);
      const int apex = mesh.triangles[g][(adjacency.neighbourEdge(t, k) + 2) % 3];
      convex_edge[t][k] = normals[t].dot(mesh.vertices[apex]) - offsets[t] <= tol ? 1 : 0;
    }
  }
  tree = AabbTree(boxes);
  edge_triangle.reserve(3 * static_cast<std::size_t>(n));
  for (int t = 0; t < n; ++t) {
    const Tri& f = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      edge_triangle.emplace_back(
          static_cast<std::uint64_t>(f[k]) << 32 | static_cast<std::uint32_t>(f[(k + 1) % 3]), t);
    }
  }
  std::sort(edge_triangle.begin(), edge_triangle.end());
  region_order.resize(n);
  for (int t = 0; t < n; ++t) region_order[t] = t;
  region_start = {0};
  splitRegions(region_order, 0, n, centres);
  region_of.resize(n);
  for (int r = 0; r < regionCount(); ++r) {
    for (int i = region_start[r]; i < region_start[r + 1]; ++i) region_of[region_order[i]] = r;
  }
  return Status::success();
}

// Median splits of the centres along the box's longest side until a region has
// at most kRegionTriangles: compact regions that depend on the mesh alone.
void SharedMesh::splitRegions(std::vector<int>& ids, int begin, int end,
                              const std::vector<Vec3>& centres) {
  if (end - begin <= kRegionTriangles) {
    region_start.push_back(end);
    return;
  }
  Aabb box;
  for (int i = begin; i < end; ++i) box.extend(centres[ids[i]]);
  int axis = 0;
  (box.max - box.min).maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(ids.begin() + begin, ids.begin() + mid, ids.begin() + end, [&](int a, int b) {
    const double ca = centres[a][axis], cb = centres[b][axis];
    return ca != cb ? ca < cb : a < b;
  });
  splitRegions(ids, begin, mid, centres);
  splitRegions(ids, mid, end, centres);
}

}  // namespace sc::detail
