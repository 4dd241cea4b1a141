// SPDX-License-Identifier: MIT
// Convex hulls through reentrant qhull. Outline:
//  1. run qhull with its default merging (coplanar facets become one polygon),
//     silenced, under a non-stop floating-point environment;
//  2. order each facet polygon counter-clockwise about qhull's outward normal;
//  3. drop vertices on a straight hull edge (not extreme points);
//  4. fan-triangulate each polygon. We triangulate ourselves instead of using
//     qhull's 'Qt', which may emit zero-area triangles on collinear vertices.
#include "preprocess/convex_hull.h"

#include "geometry/math_util.h"

#include <libqhull_r/qhull_ra.h>

#include <algorithm>
#include <cfenv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <utility>

namespace sc::detail {
namespace {

// A polygon vertex less than this (times the input's extent) above the chord of
// its neighbours is no corner, so not an extreme point of the hull.
constexpr double kCollinear = 1e-12;

/// qhull may raise IEEE flags on nearly degenerate input; callers that trap
/// them must not see those. Restores the caller's environment on exit.
class NonStopFloatingPoint {
 public:
  NonStopFloatingPoint() { feholdexcept(&saved_); }
  ~NonStopFloatingPoint() { fesetenv(&saved_); }
  NonStopFloatingPoint(const NonStopFloatingPoint&) = delete;
  NonStopFloatingPoint& operator=(const NonStopFloatingPoint&) = delete;

 private:
  std::fenv_t saved_;
};

/// A FILE that swallows qhull's messages: the library never prints.
class NullSink {
 public:
  NullSink() : file_(std::fopen("/dev/null", "w")) {
    if (file_ == nullptr) file_ = std::tmpfile();
  }
  ~NullSink() {
    if (file_ != nullptr) std::fclose(file_);
  }
  NullSink(const NullSink&) = delete;
  NullSink& operator=(const NullSink&) = delete;
  FILE* get() const { return file_; }

 private:
  FILE* file_;
};

/// One qhull facet: its outward unit normal and its vertices (input indices).
struct FacetPolygon {
  Vec3 normal;
  std::vector<int> ids;
};

/// Runs qhull; false on any qhull error (flat or otherwise unusable input).
bool runQhull(const std::vector<Vec3>& points, std::vector<FacetPolygon>& facets) {
  // One per thread: opening /dev/null per hull cost two system calls per inner node.
  thread_local const NullSink sink;
  if (sink.get() == nullptr) return false;
  NonStopFloatingPoint fp_guard;
  // Centred coordinates keep qhull's roundoff estimates small for far-off input.
  Aabb box;
  for (const Vec3& p : points) box.extend(p);
  const Vec3 centre = 0.5 * (box.min + box.max);
  std::vector<coordT> coords;
  coords.reserve(3 * points.size());
  for (const Vec3& p : points) {
    for (int k = 0; k < 3; ++k) coords.push_back(p[k] - centre[k]);
  }
  auto storage = std::make_unique<qhT>();
  qhT* qh = storage.get();
  qh_zero(qh, sink.get());
  char command[] = "qhull";
  const int exit_code = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False,
                                     command, nullptr, sink.get());
  if (exit_code == 0) {
    facetT* facet;
    vertexT *vertex, **vertexp;
    FORALLfacets {
      FacetPolygon poly;
      poly.normal = Vec3(facet->normal[0], facet->normal[1], facet->normal[2]);
      FOREACHvertex_(facet->vertices) poly.ids.push_back(qh_pointid(qh, vertex->point));
      facets.push_back(std::move(poly));
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int cur_long = 0, tot_long = 0;
  qh_memfreeshort(qh, &cur_long, &tot_long);
  return exit_code == 0 && !facets.empty();
}

/// Sorts the polygon's vertices counter-clockwise seen from outside.
void orderCounterClockwise(const std::vector<Vec3>& points, FacetPolygon& poly) {
  const Vec3 u = anyOrthogonal(normalizedOr(poly.normal, Vec3::UnitZ()));
  const Vec3 w = poly.normal.cross(u);
  Vec3 centroid = Vec3::Zero();
  for (int id : poly.ids) centroid += points[id];
  centroid /= static_cast<double>(poly.ids.size());
  std::vector<std::pair<double, int>> keyed;
  for (int id : poly.ids) {
    const Vec3 d = points[id] - centroid;
    keyed.emplace_back(std::atan2(d.dot(w), d.dot(u)), id);
  }
  std::sort(keyed.begin(), keyed.end());
  for (std::size_t k = 0; k < keyed.size(); ++k) poly.ids[k] = keyed[k].second;
}

/// Flags polygon vertices that are no strict convex corner: on (or, after a
/// rounding-level merge, inside) the line through their neighbours.
void markNonCorners(const std::vector<Vec3>& points, const FacetPolygon& poly, double tolerance,
                    std::vector<char>& redundant) {
  const int n = static_cast<int>(poly.ids.size());
  const Vec3 normal = normalizedOr(poly.normal, Vec3::UnitZ());
  for (int k = 0; k < n; ++k) {
    const Vec3& a = points[poly.ids[(k + n - 1) % n]];
    const Vec3& b = points[poly.ids[k]];
    const Vec3& c = points[poly.ids[(k + 1) % n]];
    const double len = (c - a).norm();
    if (len <= tolerance) continue;
    // Height of corner b over the chord a-c; positive for a convex corner.
    const double turn = (b - a).cross(c - a).dot(normal) / len;
    if (turn <= tolerance) redundant[poly.ids[k]] = 1;
  }
}

/// True when every edge is used once in each direction (a closed, oriented shell).
/// Directed edges grouped by their first vertex (ids below `point_count`): linear
/// in the faces for the small vertex degrees of a hull, and two allocations; this
/// runs on every hull the decomposition and the hierarchy build.
bool isClosed(const std::vector<Tri>& faces, std::size_t point_count) {
  std::vector<int> start(point_count + 1, 0);
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) ++start[f[k] + 1];
  for (std::size_t v = 0; v < point_count; ++v) start[v + 1] += start[v];
  std::vector<int> to(static_cast<std::size_t>(start[point_count]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const Tri& f : faces)
    for (int k = 0; k < 3; ++k) to[static_cast<std::size_t>(fill[f[k]]++)] = f[(k + 1) % 3];
  const auto has = [&](int from, int target, int before) {
    return std::find(to.begin() + start[from], to.begin() + before, target) != to.begin() + before;
  };
  for (std::size_t a = 0; a < point_count; ++a) {
    for (int i = start[a]; i < start[a + 1]; ++i) {
      const int b = to[static_cast<std::size_t>(i)];
      // Each directed edge once, and its reverse present.
      if (has(static_cast<int>(a), b, i) || !has(b, static_cast<int>(a), start[b + 1]))
        return false;
    }
  }
  return true;
}

/// Fan triangles of the facet polygons (input indices), skipping `redundant` ones.
std::vector<Tri> triangulate(const std::vector<FacetPolygon>& facets,
                             const std::vector<char>& redundant) {
  std::vector<Tri> faces;
  std::vector<int> kept;
  for (const FacetPolygon& poly : facets) {
    kept.clear();
    for (int id : poly.ids) {
      if (!redundant[id]) kept.push_back(id);
    }
    for (std::size_t k = 1; k + 1 < kept.size(); ++k)
      faces.emplace_back(kept[0], kept[k], kept[k + 1]);
  }
  return faces;
}

}  // namespace

Result<ConvexPolytope> convexHull(const std::vector<Vec3>& points,
                                  const std::vector<int>& original) {
  if (!original.empty() && original.size() != points.size()) {
    return Status(ErrorCode::InvalidArgument, "convexHull: original has a different size");
  }
  Aabb box;
  for (const Vec3& p : points) {
    if (!allFinite(p)) return Status(ErrorCode::InvalidArgument, "convexHull: non-finite point");
    box.extend(p);
  }
  if (points.size() < 4) {
    return Status(ErrorCode::InvalidGeometry, "convexHull: fewer than four points");
  }
  std::vector<FacetPolygon> facets;
  if (!runQhull(points, facets)) {
    return Status(ErrorCode::InvalidGeometry, "convexHull: the points do not span a volume");
  }
  const double tolerance = kCollinear * (box.max - box.min).norm();
  std::vector<char> redundant(points.size(), 0);
  for (FacetPolygon& poly : facets) {
    orderCounterClockwise(points, poly);
    markNonCorners(points, poly, tolerance, redundant);
  }
  std::vector<Tri> faces = triangulate(facets, redundant);
  if (!isClosed(faces, points.size())) {
    // The facets disagreed about a nearly collinear vertex: keep them all.
    std::fill(redundant.begin(), redundant.end(), 0);
    faces = triangulate(facets, redundant);
  }
  if (faces.size() < 4 || !isClosed(faces, points.size())) {
    return Status(ErrorCode::InvalidGeometry, "convexHull: qhull gave no closed hull");
  }
  // Compact to the vertices the faces use.
  std::vector<int> index_of(points.size(), -1);
  PolytopeParts hull;
  for (Tri& f : faces) {
    for (int k = 0; k < 3; ++k) {
      int& slot = index_of[f[k]];
      if (slot < 0) {
        slot = static_cast<int>(hull.vertices.size());
        hull.vertices.push_back(points[f[k]]);
        hull.original.push_back(original.empty() ? f[k] : original[f[k]]);
      }
      f[k] = slot;
    }
  }
  hull.faces = std::move(faces);
  hull.face_source.assign(hull.faces.size(), -1);
  return ConvexPolytope::build(hull);
}

}  // namespace sc::detail
