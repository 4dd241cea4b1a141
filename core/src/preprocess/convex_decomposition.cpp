// SPDX-License-Identifier: MIT
// Convex surface decomposition by greedy patch growth (SWIFT++: S. Ehmann and
// M. Lin, "Accurate and Fast Proximity Queries Between Polyhedra Using Convex
// Surface Decomposition", Eurographics 2001). Outline:
//  1. edge adjacency, face planes, convex edges, an AABB tree of the triangles;
//  2. every edge convex: try the whole surface as one patch;
//  3. grow each patch breadth-first from a seed across convex (or flat) edges. A
//     face joins when condition (1) holds: its new vertex lies below every patch
//     face's plane and every patch vertex below its plane. Both are checked
//     incrementally, skipping whole chunks of the patch by bounding spheres and
//     normal cones;
//  4. condition (2), the hull stays inside the solid, is checked in batches: at
//     patch sizes doubling since the last verified size, build the patch's
//     polytope (patch_polytope.h) and test the other triangles against it with
//     the AABB tree: none may reach deeper than the tolerance into the hull, nor
//     into the probe prisms of flat or thin hulls. Hulls only grow with the
//     patch, so a failure is bracketed by binary search; the face after the
//     longest good prefix is banned from this patch and growth resumes there.
//     Between checks, a cheap sound filter: the tetrahedron spanned by a face's
//     new vertex and a face of the last verified hull that the vertex sees lies
//     inside the new hull, so a triangle reaching into it bans the face at once;
//  5. seeds are taken next to finished patches, so patches tile the surface;
//     patches grow within one region (median splits of the triangles' centres,
//     at most kRegionTriangles each) while condition (2) still tests the whole
//     mesh: a region's patches depend on it alone, so regions run in parallel
//     and the result is the same for any thread count, and a patch's size, with
//     the cost of its checks, is bounded, so the work grows linearly;
//  6. a hull face that equals an input triangle of another patch is a model face
//     too: it gets that triangle as face_source, so only faces off the surface
//     count as virtual.
//
// "Inside" for self-intersecting input: the hull, shrunk by the tolerance, meets
// no triangle outside its patch, so it lies in one cell of the space the surface
// divides, the cell directly behind its own faces. A patch whose own triangles
// are crossed by other triangles is therefore flat (usually one triangle).
//
// Departures from the paper: no patch merging or post-optimisation; regions cut
// patches at their borders; the tolerance is relative to the mesh size
// (patch_polytope.h).
#include "preprocess/convex_decomposition.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <deque>
#include <thread>
#include <utility>

#include "geometry/aabb_tree.h"
#include "geometry/halfspace_polytope.h"
#include "geometry/math_util.h"
#include "geometry/triangle_adjacency.h"
#include "preprocess/patch_polytope.h"

namespace sc::detail {
namespace {

/// Patch faces and vertices are grouped in chunks of this many (in order of
/// addition, so spatially compact) for the condition (1) bounds.
constexpr int kChunk = 32;

/// Bounding sphere of a chunk of patch vertices.
struct VertexChunk {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
};

/// A chunk of patch faces: max over its faces of (n . p - d) is at most
/// cone(p - centre) + offset, where cone() bounds n . w over the normal cone.
struct FaceChunk {
  Vec3 centre = Vec3::Zero();
  Vec3 axis = Vec3::UnitZ();
  double cos_half = -1.0;
  double sin_half = 0.0;
  double offset = 0.0;  ///< max over the chunk's faces of n . centre - d

  double bound(const Vec3& p) const {
    const Vec3 w = p - centre;
    const double length = w.norm();
    if (!(length > 0.0)) return offset;
    const double cos_phi = std::clamp(axis.dot(w) / length, -1.0, 1.0);
    if (cos_phi >= cos_half) return length + offset;
    const double sin_phi = std::sqrt(std::max(0.0, 1.0 - cos_phi * cos_phi));
    return length * (cos_phi * cos_half + sin_phi * sin_half) + offset;
  }
};

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

/// Patches grow within regions of at most this many triangles (their hulls are still
/// tested against the whole mesh). It bounds a patch's size, and with it the cost
/// of its checks, so the work grows linearly with the mesh; and regions are
/// independent, so they run in parallel.
constexpr int kRegionTriangles = 8192;

/// Planes of the largest faces kept among the outer planes.
constexpr int kOuterFaces = 8;
/// Face normals closer than this cosine count as one direction.
constexpr double kSameDirection = 0.999;
/// Hulls with at most this many planes prune the tree with their own.
constexpr std::size_t kOwnPlanesUpTo = 64;

/// A few planes that contain the hull of `poly`'s vertices: both ways along each
/// outer direction and along the normals of its largest faces, each through the
/// vertices' support. Pruning the tree with them costs O(1) planes per node where
/// the hull's own planes cost O(hull size), which made each condition (2) check
/// quadratic in the patch. They contain the hull, so the hull shrunk by the
/// tolerance lies in them shrunk by it: no triangle reaching it is pruned.
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

/// Per-triangle data every region's worker reads; built once, then read-only.
struct SharedMesh {
  explicit SharedMesh(const MeshData& m) : mesh(m) {}
  Status prepare();
  void splitRegions(std::vector<int>& ids, int begin, int end, const std::vector<Vec3>& centres);
  int regionCount() const { return static_cast<int>(region_start.size()) - 1; }

  const MeshData& mesh;
  double tol = 0.0;
  TriangleAdjacency adjacency;
  std::vector<Vec3> normals;
  std::vector<double> offsets;
  std::vector<std::array<char, 3>> convex_edge;
  /// Directed edges (from << 32 | to) and their triangles, sorted, for triangleOf.
  std::vector<std::pair<std::uint64_t, int>> edge_triangle;
  AabbTree tree;
  /// Regions: triangles region_start[r] .. region_start[r + 1] of region_order.
  std::vector<int> region_of;
  std::vector<int> region_order;
  std::vector<int> region_start;
};

/// What one region's patch growth produced; patch indices are local to it.
struct RegionResult {
  std::vector<ConvexPolytope> patches;
  int virtual_faces = 0;
  Status status;
};

/// State every worker shares: the stop flag and the count of assigned triangles.
struct SharedProgress {
  std::atomic<bool> stop{false};
  std::atomic<int> assigned{0};
};

/// Grows the patches of one region at a time; one object per thread. Writes only
/// the entries of `triangle_patch` that belong to its current region, and reads
/// no other region's entries, so workers on different regions never race.
class Decomposer {
 public:
  Decomposer(const SharedMesh& shared, std::vector<int>& triangle_patch, SharedProgress& state,
             const ProgressCallback* progress, const CancelCallback* cancel);

  bool tryWholeSurface(std::vector<ConvexPolytope>& patches);
  Status decompose(int region, RegionResult& out);

 private:
  Status growPatch(int seed, HullCheck mode);
  int nextSeed();

  bool canJoin(int t) const;
  bool pointBelowPatch(const Vec3& p) const;
  bool patchBelowPlane(const Vec3& n, double d) const;
  void addFace(int t);
  void enqueueNeighbours(int t);
  void truncate(int count);
  void rebuildFrontier();
  /// Condition (2) on the first `count` faces: the polytope when it holds.
  Result<PatchPolytope> evaluate(int count, HullCheck mode);
  bool reachesInside(const PatchRef& patch, std::vector<Plane> planes, const Aabb& bounds,
                     int also_skip = -1, std::vector<Plane> outer = {});
  void setVerified(const ConvexPolytope& hull);
  bool swallows(int t);
  void finishPatch(PatchPolytope patch);
  /// Triangle t and its reverse: the patch of one triangle, built directly for a
  /// triangle too thin for the ear tests.
  PatchPolytope twoSided(int t) const;
  /// The input triangle running a -> b -> c (any rotation), or -1.
  int triangleOf(int a, int b, int c) const;
  /// After each patch: reports progress and asks `cancel` when this worker runs on
  /// the calling thread alone; true when the build is to stop.
  bool pollStop();

  const SharedMesh& shared_;
  const MeshData& mesh_;
  const double tol_;
  const TriangleAdjacency& adjacency_;
  const std::vector<Vec3>& normals_;
  const std::vector<double>& offsets_;
  const std::vector<std::array<char, 3>>& convex_edge_;
  const AabbTree& tree_;
  std::vector<int>& triangle_patch_;
  SharedProgress& state_;
  const ProgressCallback* progress_;  ///< null on worker threads
  const CancelCallback* cancel_;      ///< null on worker threads
  double reported_ = -1.0;

  int region_ = -1;
  RegionResult* out_ = nullptr;
  std::deque<int> seeds_;
  int seed_scan_ = 0;

  // The patch being grown.
  int serial_ = 0;                ///< patch counter, for banned_
  int epoch_ = 0;                 ///< frontier generation, for seen_
  std::vector<int> faces_;        ///< in order of addition
  std::vector<int> rank_;         ///< per triangle: index in faces_, or -1
  std::vector<int> verts_;        ///< patch vertices in order of addition
  std::vector<int> verts_after_;  ///< per face: verts_.size() once it was added
  std::vector<char> in_patch_;    ///< per vertex
  std::vector<int> seen_;         ///< per triangle: epoch it was queued in
  std::vector<int> banned_;       ///< per triangle: patch it failed condition (2) for
  std::vector<VertexChunk> vertex_chunks_;
  std::vector<FaceChunk> face_chunks_;
  std::deque<int> frontier_;
  /// Faces (corners and outward plane) of the last verified hull.
  std::vector<std::array<Vec3, 3>> verified_corners_;
  std::vector<Plane> verified_planes_;
};

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

Decomposer::Decomposer(const SharedMesh& shared, std::vector<int>& triangle_patch,
                       SharedProgress& state, const ProgressCallback* progress,
                       const CancelCallback* cancel)
    : shared_(shared),
      mesh_(shared.mesh),
      tol_(shared.tol),
      adjacency_(shared.adjacency),
      normals_(shared.normals),
      offsets_(shared.offsets),
      convex_edge_(shared.convex_edge),
      tree_(shared.tree),
      triangle_patch_(triangle_patch),
      state_(state),
      progress_(progress),
      cancel_(cancel) {
  const std::size_t n = mesh_.triangles.size();
  rank_.assign(n, -1);
  seen_.assign(n, -1);
  banned_.assign(n, -1);
  in_patch_.assign(mesh_.vertices.size(), 0);
}

bool Decomposer::pointBelowPatch(const Vec3& p) const {
  const int full = static_cast<int>(face_chunks_.size());
  for (int c = 0; c < full; ++c) {
    if (face_chunks_[c].bound(p) <= tol_) continue;
    for (int i = c * kChunk; i < (c + 1) * kChunk; ++i) {
      const int t = faces_[i];
      if (normals_[t].dot(p) - offsets_[t] > tol_) return false;
    }
  }
  for (int i = full * kChunk; i < static_cast<int>(faces_.size()); ++i) {
    const int t = faces_[i];
    if (normals_[t].dot(p) - offsets_[t] > tol_) return false;
  }
  return true;
}

bool Decomposer::patchBelowPlane(const Vec3& n, double d) const {
  const int full = static_cast<int>(vertex_chunks_.size());
  for (int c = 0; c < full; ++c) {
    const VertexChunk& chunk = vertex_chunks_[c];
    if (n.dot(chunk.centre) + chunk.radius - d <= tol_) continue;
    for (int i = c * kChunk; i < (c + 1) * kChunk; ++i) {
      if (n.dot(mesh_.vertices[verts_[i]]) - d > tol_) return false;
    }
  }
  for (int i = full * kChunk; i < static_cast<int>(verts_.size()); ++i) {
    if (n.dot(mesh_.vertices[verts_[i]]) - d > tol_) return false;
  }
  return true;
}

bool Decomposer::canJoin(int t) const {
  const Tri& f = mesh_.triangles[t];
  for (int k = 0; k < 3; ++k) {
    if (!in_patch_[f[k]] && !pointBelowPatch(mesh_.vertices[f[k]])) return false;
  }
  return patchBelowPlane(normals_[t], offsets_[t]);
}

void Decomposer::addFace(int t) {
  rank_[t] = static_cast<int>(faces_.size());
  faces_.push_back(t);
  for (int k = 0; k < 3; ++k) {
    const int v = mesh_.triangles[t][k];
    if (in_patch_[v]) continue;
    in_patch_[v] = 1;
    verts_.push_back(v);
    if (verts_.size() % kChunk != 0) continue;
    Aabb box;
    for (std::size_t i = verts_.size() - kChunk; i < verts_.size(); ++i)
      box.extend(mesh_.vertices[verts_[i]]);
    VertexChunk chunk;
    chunk.centre = 0.5 * (box.min + box.max);
    for (std::size_t i = verts_.size() - kChunk; i < verts_.size(); ++i) {
      chunk.radius = std::max(chunk.radius, (mesh_.vertices[verts_[i]] - chunk.centre).norm());
    }
    vertex_chunks_.push_back(chunk);
  }
  verts_after_.push_back(static_cast<int>(verts_.size()));
  if (faces_.size() % kChunk == 0) {
    FaceChunk chunk;
    Vec3 normal_sum = Vec3::Zero(), centre = Vec3::Zero();
    for (std::size_t i = faces_.size() - kChunk; i < faces_.size(); ++i) {
      const Tri& f = mesh_.triangles[faces_[i]];
      normal_sum += normals_[faces_[i]];
      centre += (mesh_.vertices[f[0]] + mesh_.vertices[f[1]] + mesh_.vertices[f[2]]) / 3.0;
    }
    chunk.centre = centre / kChunk;
    chunk.axis = normalizedOr(normal_sum, Vec3::UnitZ());
    chunk.cos_half = 1.0;
    chunk.offset = -kInfinity;
    for (std::size_t i = faces_.size() - kChunk; i < faces_.size(); ++i) {
      const int f = faces_[i];
      chunk.cos_half = std::min(chunk.cos_half, chunk.axis.dot(normals_[f]));
      chunk.offset = std::max(chunk.offset, normals_[f].dot(chunk.centre) - offsets_[f]);
    }
    chunk.cos_half = std::clamp(chunk.cos_half, -1.0, 1.0);
    chunk.sin_half = std::sqrt(1.0 - chunk.cos_half * chunk.cos_half);
    face_chunks_.push_back(chunk);
  }
  enqueueNeighbours(t);
}

void Decomposer::enqueueNeighbours(int t) {
  for (int k = 0; k < 3; ++k) {
    if (!convex_edge_[t][k]) continue;
    const int g = adjacency_.neighbour(t, k);
    if (shared_.region_of[g] != region_ || triangle_patch_[g] >= 0 || rank_[g] >= 0 ||
        banned_[g] == serial_ || seen_[g] == epoch_) {
      continue;
    }
    seen_[g] = epoch_;
    frontier_.push_back(g);
  }
}

void Decomposer::truncate(int count) {
  for (int i = count; i < static_cast<int>(faces_.size()); ++i) rank_[faces_[i]] = -1;
  faces_.resize(count);
  const int keep = count > 0 ? verts_after_[count - 1] : 0;
  verts_after_.resize(count);
  for (int i = keep; i < static_cast<int>(verts_.size()); ++i) in_patch_[verts_[i]] = 0;
  verts_.resize(keep);
  vertex_chunks_.resize(verts_.size() / kChunk);
  face_chunks_.resize(faces_.size() / kChunk);
}

void Decomposer::rebuildFrontier() {
  ++epoch_;
  frontier_.clear();
  for (int t : faces_) enqueueNeighbours(t);
}

// Other triangles that reach the polytope given by `planes`, shrunk by the
// tolerance; `bounds` encloses it. Non-empty `outer` planes contain it and prune
// the tree in its place.
bool Decomposer::reachesInside(const PatchRef& patch, std::vector<Plane> planes, const Aabb& bounds,
                               int also_skip, std::vector<Plane> outer) {
  HalfspacePolytope region(std::move(planes), tol_);
  const bool pruned = !outer.empty();
  HalfspacePolytope prune(std::move(outer), tol_);
  HalfspacePolytope& filter = pruned ? prune : region;
  bool reached = false;
  tree_.query(
      [&](const Aabb& box) {
        if ((box.min.array() > bounds.max.array()).any() ||
            (box.max.array() < bounds.min.array()).any()) {
          return false;
        }
        return filter.boxMayReachInterior(box);
      },
      [&](int t) {
        if (patch.contains(t) || t == also_skip) return true;
        if (pruned && !prune.boxMayReachInterior(tree_.box(t))) return true;
        const Tri& f = mesh_.triangles[t];
        if (!region.triangleReachesInterior(mesh_.vertices[f[0]], mesh_.vertices[f[1]],
                                            mesh_.vertices[f[2]])) {
          return true;
        }
        reached = true;
        return false;
      });
  return reached;
}

Result<PatchPolytope> Decomposer::evaluate(int count, HullCheck mode) {
  const PatchRef patch{faces_, rank_, count};
  Result<PatchPolytope> built = buildPatchPolytope(mesh_, adjacency_, patch, tol_, mode);
  if (!built.ok() || count == 1) return built;  // one triangle is the surface itself
  const PatchPolytope& poly = built.value();
  // Small hulls have fewer planes than the outer bound: prune with their own.
  std::vector<Plane> outer;
  if (poly.planes.size() > kOwnPlanesUpTo) outer = outerPlanes(poly.polytope);
  if (!poly.flat && reachesInside(patch, poly.planes, poly.polytope.bounds, -1, std::move(outer))) {
    return Status(ErrorCode::InvalidGeometry, "patch: a triangle reaches into its hull");
  }
  for (const std::array<Plane, 5>& prism : poly.probes) {
    Aabb bounds = poly.polytope.bounds;
    const Vec3 depth = Vec3::Constant(kProbeDepth * tol_);
    bounds.min -= depth;
    bounds.max += depth;
    if (reachesInside(patch, std::vector<Plane>(prism.begin(), prism.end()), bounds)) {
      return Status(ErrorCode::InvalidGeometry, "patch: a triangle reaches under a pocket");
    }
  }
  return built;
}

// Grows with HullCheck::Quick checks; the finished patch is built once more on
// qhull's hull. Should that disagree (rounding at the tolerance), the patch is
// grown again from its seed with qhull throughout.
void Decomposer::setVerified(const ConvexPolytope& hull) {
  verified_corners_.clear();
  verified_planes_.clear();
  for (const Tri& f : hull.faces) {
    const Vec3 &a = hull.vertices[f[0]], &b = hull.vertices[f[1]], &c = hull.vertices[f[2]];
    const Vec3 twice = (b - a).cross(c - a);
    if (!(twice.norm() > 0.0)) continue;
    verified_corners_.push_back({a, b, c});
    const Vec3 n = twice / twice.norm();
    verified_planes_.push_back({n, n.dot(a)});
  }
}

// True when triangle t's new vertex would make the hull swallow another triangle:
// for each verified face the vertex sees, the tetrahedron they span is in the new
// hull. Finds most failures of condition (2) before the batch check does.
bool Decomposer::swallows(int t) {
  const Tri& f = mesh_.triangles[t];
  int fresh = -1;
  for (int k = 0; k < 3; ++k) {
    if (!in_patch_[f[k]]) fresh = f[k];
  }
  if (fresh < 0) return false;
  const Vec3& v = mesh_.vertices[fresh];
  const PatchRef patch{faces_, rank_, static_cast<int>(faces_.size())};
  for (std::size_t i = 0; i < verified_planes_.size(); ++i) {
    const Plane& base = verified_planes_[i];
    if (base.signedDistance(v) <= tol_) continue;
    const std::array<Vec3, 3>& corner = verified_corners_[i];
    std::vector<Plane> tetra = {{-base.normal, -base.offset}};
    Aabb bounds;
    bounds.extend(v);
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = corner[k];
      const Vec3& q = corner[(k + 1) % 3];
      bounds.extend(p);
      Vec3 n = normalizedOr((q - p).cross(v - p), Vec3::Zero());
      if (n.dot(corner[(k + 2) % 3] - p) > 0.0) n = -n;
      tetra.push_back({n, n.dot(p)});
    }
    if (reachesInside(patch, std::move(tetra), bounds, t)) return true;
  }
  return false;
}

Status Decomposer::growPatch(int seed, HullCheck mode) {
  ++serial_;
  ++epoch_;
  frontier_.clear();
  addFace(seed);
  Result<PatchPolytope> best = evaluate(1, mode);
  if (!best.ok()) best = twoSided(seed);
  setVerified(best.value().polytope);
  int verified = 1;
  int next_check = 2;
  // Condition (2) on the whole patch; on failure, keep the longest good prefix.
  auto check = [&]() {
    const int size = static_cast<int>(faces_.size());
    Result<PatchPolytope> trial = evaluate(size, mode);
    if (trial.ok()) {
      best = std::move(trial);
      setVerified(best.value().polytope);
      verified = size;
      next_check = 2 * size;
      return;
    }
    // The first failing prefix lies in (verified, size].
    int lo = verified, hi = size;
    while (hi - lo > 1) {
      const int mid = lo + (hi - lo) / 2;
      Result<PatchPolytope> probe = evaluate(mid, mode);
      if (probe.ok()) {
        best = std::move(probe);
        lo = mid;
      } else {
        hi = mid;
      }
    }
    // Every patch containing prefix lo + 1 fails too: ban its last face.
    setVerified(best.value().polytope);
    banned_[faces_[lo]] = serial_;
    truncate(lo);
    verified = lo;
    next_check = lo + std::max(1, (size - lo) / 2);
    rebuildFrontier();
  };
  for (;;) {
    while (!frontier_.empty()) {
      const int t = frontier_.front();
      frontier_.pop_front();
      if (triangle_patch_[t] >= 0 || rank_[t] >= 0 || banned_[t] == serial_) continue;
      if (!canJoin(t)) continue;
      if (swallows(t)) {
        banned_[t] = serial_;
        continue;
      }
      addFace(t);
      if (static_cast<int>(faces_.size()) >= next_check) check();
    }
    if (static_cast<int>(faces_.size()) == verified) break;
    check();
  }
  if (!best.value().flat && !best.value().used_qhull) {
    best = evaluate(verified, HullCheck::Qhull);
    if (!best.ok()) {
      if (mode == HullCheck::Qhull) return best.status();
      truncate(0);
      return growPatch(seed, HullCheck::Qhull);
    }
  }
  finishPatch(std::move(best.value()));
  return Status::success();
}

PatchPolytope Decomposer::twoSided(int t) const {
  PatchPolytope patch;
  patch.flat = true;
  patch.virtual_faces = 1;
  ConvexPolytope& poly = patch.polytope;
  for (int k = 0; k < 3; ++k) {
    poly.vertices.push_back(mesh_.vertices[mesh_.triangles[t][k]]);
    poly.original.push_back(mesh_.triangles[t][k]);
  }
  poly.faces = {Tri(0, 1, 2), Tri(0, 2, 1)};
  poly.face_source = {t, -1};
  poly.finalize();
  return patch;
}

int Decomposer::triangleOf(int a, int b, int c) const {
  const std::uint64_t key = static_cast<std::uint64_t>(a) << 32 | static_cast<std::uint32_t>(b);
  const auto it = std::lower_bound(shared_.edge_triangle.begin(), shared_.edge_triangle.end(),
                                   std::make_pair(key, -1));
  if (it == shared_.edge_triangle.end() || it->first != key) return -1;
  const Tri& f = mesh_.triangles[it->second];
  return f[0] == c || f[1] == c || f[2] == c ? it->second : -1;
}

void Decomposer::finishPatch(PatchPolytope patch) {
  const int index = static_cast<int>(out_->patches.size());
  ConvexPolytope& poly = patch.polytope;
  for (std::size_t f = 0; f < poly.faces.size(); ++f) {
    if (poly.face_source[f] >= 0) continue;
    const Tri& face = poly.faces[f];
    const int t =
        triangleOf(poly.original[face[0]], poly.original[face[1]], poly.original[face[2]]);
    if (t < 0) continue;
    poly.face_source[f] = t;
    --patch.virtual_faces;
  }
  for (int t : faces_) {
    triangle_patch_[t] = index;
    for (int k = 0; k < 3; ++k) {
      const int g = adjacency_.neighbour(t, k);
      if (shared_.region_of[g] == region_) seeds_.push_back(g);
    }
  }
  state_.assigned += static_cast<int>(faces_.size());
  out_->virtual_faces += patch.virtual_faces;
  out_->patches.push_back(std::move(patch.polytope));
  truncate(0);
}

int Decomposer::nextSeed() {
  while (!seeds_.empty()) {
    const int t = seeds_.front();
    seeds_.pop_front();
    if (triangle_patch_[t] < 0) return t;
  }
  const int end = shared_.region_start[region_ + 1];
  while (seed_scan_ < end && triangle_patch_[shared_.region_order[seed_scan_]] >= 0) ++seed_scan_;
  return seed_scan_ < end ? shared_.region_order[seed_scan_] : -1;
}

bool Decomposer::pollStop() {
  if (progress_ && *progress_) {
    const double fraction =
        static_cast<double>(state_.assigned) / static_cast<double>(mesh_.triangles.size());
    if (fraction - reported_ >= 0.01 || fraction >= 1.0) {
      reported_ = fraction;
      (*progress_)(fraction, "decompose");
    }
  }
  if (cancel_ && *cancel_ && (*cancel_)()) state_.stop = true;
  return state_.stop;
}

// A convex surface is one patch without virtual faces; buildPatchPolytope checks
// condition (1) for every face on the hull of all vertices.
bool Decomposer::tryWholeSurface(std::vector<ConvexPolytope>& patches) {
  for (const std::array<char, 3>& edges : convex_edge_) {
    if (!edges[0] || !edges[1] || !edges[2]) return false;
  }
  const int n = static_cast<int>(mesh_.triangles.size());
  for (int t = 0; t < n; ++t) {
    rank_[t] = t;
    faces_.push_back(t);
  }
  Result<PatchPolytope> whole =
      buildPatchPolytope(mesh_, adjacency_, PatchRef{faces_, rank_, n}, tol_);
  for (int t = 0; t < n; ++t) rank_[t] = -1;
  faces_.clear();
  if (!whole.ok() || whole.value().virtual_faces != 0) return false;
  std::fill(triangle_patch_.begin(), triangle_patch_.end(), 0);
  patches.push_back(std::move(whole.value().polytope));
  state_.assigned = n;
  return true;
}

Status Decomposer::decompose(int region, RegionResult& out) {
  region_ = region;
  out_ = &out;
  seeds_.clear();
  seed_scan_ = shared_.region_start[region];
  for (int seed = nextSeed(); seed >= 0; seed = nextSeed()) {
    if (Status s = growPatch(seed, HullCheck::Quick); !s.ok()) return s;
    if (pollStop()) return Status(ErrorCode::InvalidOperation, "build cancelled");
  }
  return Status::success();
}

/// Runs the regions on `threads` threads (the calling one alone for 1), each
/// region's result in its own slot, so the output does not depend on the count.
class RegionRunner {
 public:
  RegionRunner(const SharedMesh& shared, std::vector<int>& triangle_patch,
               const ProgressCallback& progress, const CancelCallback& cancel)
      : shared_(shared),
        triangle_patch_(triangle_patch),
        progress_(progress),
        cancel_(cancel),
        results_(shared.regionCount()) {}

  std::vector<RegionResult>& run(int threads) {
    if (threads <= 1 || shared_.regionCount() == 1) {
      work(&progress_, &cancel_);
      return results_;
    }
    std::vector<std::thread> workers;
    running_ = threads;
    for (int i = 0; i < threads; ++i) workers.emplace_back([this] { work(nullptr, nullptr); });
    // The caller's callbacks run on the calling thread only.
    double reported = -1.0;
    while (running_ > 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      const double fraction =
          static_cast<double>(state_.assigned) / static_cast<double>(shared_.mesh.triangles.size());
      if (progress_ && fraction - reported >= 0.01) {
        reported = fraction;
        progress_(fraction, "decompose");
      }
      if (cancel_ && cancel_()) state_.stop = true;
    }
    for (std::thread& worker : workers) worker.join();
    return results_;
  }

 private:
  void work(const ProgressCallback* progress, const CancelCallback* cancel) {
    Decomposer decomposer(shared_, triangle_patch_, state_, progress, cancel);
    for (int r = next_++; r < shared_.regionCount() && !state_.stop; r = next_++) {
      results_[r].status = decomposer.decompose(r, results_[r]);
      if (!results_[r].status.ok()) state_.stop = true;
    }
    --running_;
  }

  const SharedMesh& shared_;
  std::vector<int>& triangle_patch_;
  const ProgressCallback& progress_;
  const CancelCallback& cancel_;
  std::vector<RegionResult> results_;
  SharedProgress state_;
  std::atomic<int> next_{0};
  std::atomic<int> running_{0};
};

/// The first region's failure, preferring a real error to the stops it caused.
Status firstFailure(const std::vector<RegionResult>& results) {
  Status stopped;
  for (const RegionResult& r : results) {
    if (r.status.ok()) continue;
    if (r.status.code() != ErrorCode::InvalidOperation) return r.status;
    if (stopped.ok()) stopped = r.status;
  }
  return stopped;
}

}  // namespace

Result<Decomposition> decomposeConvexSurface(const MeshData& mesh, const ProgressCallback& progress,
                                             const CancelCallback& cancel, int threads) {
  SharedMesh shared(mesh);
  if (Status s = shared.prepare(); !s.ok()) return s;
  if (progress) progress(0.0, "decompose");
  Decomposition result;
  result.triangle_patch.assign(mesh.triangles.size(), -1);
  {
    SharedProgress state;
    Decomposer whole(shared, result.triangle_patch, state, nullptr, nullptr);
    if (whole.tryWholeSurface(result.patches)) {
      if (progress) progress(1.0, "decompose");
      return result;
    }
  }
  RegionRunner runner(shared, result.triangle_patch, progress, cancel);
  std::vector<RegionResult>& regions = runner.run(threads);
  if (Status s = firstFailure(regions); !s.ok()) return s;
  if (cancel && cancel()) return Status(ErrorCode::InvalidOperation, "build cancelled");
  // Region r's patches follow those of the regions before it.
  std::vector<int> base(regions.size() + 1, 0);
  for (std::size_t r = 0; r < regions.size(); ++r) {
    base[r + 1] = base[r] + static_cast<int>(regions[r].patches.size());
    result.virtual_faces += regions[r].virtual_faces;
    for (ConvexPolytope& patch : regions[r].patches) result.patches.push_back(std::move(patch));
  }
  for (std::size_t t = 0; t < result.triangle_patch.size(); ++t) {
    result.triangle_patch[t] += base[shared.region_of[t]];
  }
  if (progress) progress(1.0, "decompose");
  return result;
}

}  // namespace sc::detail
