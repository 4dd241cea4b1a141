// SPDX-License-Identifier: MIT
#include "preprocess/patch_growth.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "geometry/math_util.h"
#include "preprocess/hull_inside_test.h"

namespace sc::detail {

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
      triangle_patch_(triangle_patch),
      state_(state),
      progress_(progress),
      cancel_(cancel),
      region_tree_(shared) {
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
  region_tree_.markPatch(t, 1);
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
  for (int i = count; i < static_cast<int>(faces_.size()); ++i) {
    rank_[faces_[i]] = -1;
    region_tree_.markPatch(faces_[i], -1);
  }
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

Result<PatchPolytope> Decomposer::evaluate(int count, HullCheck mode) {
  const PatchRef patch{faces_, rank_, count};
  // The tree counts all of faces_: it may skip the patch's subtrees only for all.
  const PatchInTree in_tree{patch, count == static_cast<int>(faces_.size())};
  Result<PatchPolytope> built = buildPatchPolytope(mesh_, adjacency_, patch, tol_, mode);
  if (!built.ok() || count == 1) return built;  // one triangle is the surface itself
  const PatchPolytope& poly = built.value();
  // Small hulls have fewer planes than the outer bound: prune with their own.
  std::vector<Plane> outer;
  if (poly.planes.size() > kOwnPlanesUpTo) outer = outerPlanes(poly.polytope);
  if (!poly.flat && reachesInside(shared_, region_tree_, in_tree, poly.planes,
                                  poly.polytope.bounds(), -1, std::move(outer))) {
    return Status(ErrorCode::InvalidGeometry, "patch: a triangle reaches into its hull");
  }
  for (const std::array<Plane, 5>& prism : poly.probes) {
    Aabb bounds = poly.polytope.bounds();
    const Vec3 depth = Vec3::Constant(kProbeDepth * tol_);
    bounds.min -= depth;
    bounds.max += depth;
    if (reachesInside(shared_, region_tree_, in_tree,
                      std::vector<Plane>(prism.begin(), prism.end()), bounds)) {
      return Status(ErrorCode::InvalidGeometry, "patch: a triangle reaches under a pocket");
    }
  }
  return built;
}

// Grows with HullCheck::Quick checks; the finished patch is built once more on
// qhull's hull. Should that disagree (rounding at the tolerance), the patch is
// grown again from its seed with qhull throughout.
void Decomposer::setVerified(const ConvexPolytope& hull) {
  hull_corners_.clear();
  hull_ids_.clear();
  hull_planes_.clear();
  hull_vertices_ = static_cast<int>(hull.vertices.size());
  for (const Tri& f : hull.faces) {
    const Vec3 &a = hull.vertices[f[0]], &b = hull.vertices[f[1]], &c = hull.vertices[f[2]];
    const Vec3 twice = (b - a).cross(c - a);
    if (!(twice.norm() > 0.0)) continue;
    hull_corners_.push_back({a, b, c});
    hull_ids_.push_back({hull.original[f[0]], hull.original[f[1]], hull.original[f[2]]});
    const Vec3 n = twice / twice.norm();
    hull_planes_.push_back({n, n.dot(a)});
  }
}

// True when triangle t's new vertex would make the hull swallow another triangle:
// for each hull face the vertex sees, the tetrahedron they span is in the new
// hull. Finds most failures of condition (2) before the batch check does.
bool Decomposer::swallows(int t) {
  const Tri& f = mesh_.triangles[t];
  fresh_ = -1;
  visible_.clear();
  for (int k = 0; k < 3; ++k) {
    if (!in_patch_[f[k]]) fresh_ = f[k];
  }
  if (fresh_ < 0) return false;
  const Vec3& v = mesh_.vertices[fresh_];
  tetra_bounds_.clear();  // its size is the tetrahedra's count; tetras_ keeps spares
  for (std::size_t i = 0; i < hull_planes_.size(); ++i) {
    const Plane& base = hull_planes_[i];
    if (base.signedDistance(v) <= tol_) continue;
    visible_.push_back(static_cast<int>(i));
    const std::array<Vec3, 3>& corner = hull_corners_[i];
    std::array<Plane, 4> tetra;
    tetra[0] = {-base.normal, -base.offset};
    Aabb bounds;
    bounds.extend(v);
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = corner[k];
      const Vec3& q = corner[(k + 1) % 3];
      bounds.extend(p);
      Vec3 n = normalizedOr((q - p).cross(v - p), Vec3::Zero());
      if (n.dot(corner[(k + 2) % 3] - p) > 0.0) n = -n;
      tetra[static_cast<std::size_t>(k) + 1] = {n, n.dot(p)};
    }
    if (tetras_.size() == tetra_bounds_.size()) tetras_.emplace_back(std::vector<Plane>{}, tol_);
    tetras_[tetra_bounds_.size()].reset(tetra.data(), 4, tol_);
    tetra_bounds_.push_back(bounds);
  }
  // One walk of the tree for all of them: a vertex sees several faces of a large hull.
  const PatchRef patch{faces_, rank_, static_cast<int>(faces_.size())};
  return !tetra_bounds_.empty() &&
         reachesAnyInside(shared_, region_tree_, {patch, true}, tetras_, tetra_bounds_, t);
}

// Quickhull's step: the seen faces' edges that no other seen face shares (in the
// other direction) are the horizon, and each makes a face with the new vertex. The
// hull only guides the filter (condition (2) is checked on qhull's hull), so
// rounding here costs at most a missed or a late ban. Rounding can make the seen
// faces no disc; a closed triangulated hull has 2V - 4 faces, so a step that
// would leave more than 2V is skipped: the hull stays as it was, its faces still
// spanning patch vertices, and the filter's cost stays bounded.
void Decomposer::extendHull() {
  if (fresh_ < 0 || visible_.empty()) return;
  const Vec3& v = mesh_.vertices[fresh_];
  auto shared_edge = [&](int a, int b) {
    for (int j : visible_) {
      const std::array<int, 3>& ids = hull_ids_[j];
      for (int k = 0; k < 3; ++k) {
        if (ids[k] == b && ids[(k + 1) % 3] == a) return true;
      }
    }
    return false;
  };
  horizon_.clear();
  for (int i : visible_) {
    for (int k = 0; k < 3; ++k) {
      if (!shared_edge(hull_ids_[i][k], hull_ids_[i][(k + 1) % 3])) horizon_.push_back(3 * i + k);
    }
  }
  const std::size_t faces = hull_planes_.size() - visible_.size() + horizon_.size();
  if (faces > 2 * static_cast<std::size_t>(hull_vertices_ + 1)) return;
  ++hull_vertices_;
  cone_.clear();
  for (int edge : horizon_) {
    const int i = edge / 3, k = edge % 3;
    const Vec3 p = hull_corners_[i][k], q = hull_corners_[i][(k + 1) % 3];
    const Vec3 twice = (q - p).cross(v - p);
    if (!(twice.norm() > 0.0)) continue;
    const Vec3 n = twice / twice.norm();
    cone_.push_back(
        {{p, q, v}, {hull_ids_[i][k], hull_ids_[i][(k + 1) % 3], fresh_}, {n, n.dot(p)}});
  }
  replaceSeenFaces();
}

// The cone's faces take the seen faces' slots, then go last, or the seen faces
// left over give way to the last faces (highest slot first, so that the last is
// never one of them): no pass over the whole hull. The order of the faces does not
// change any answer of the filter.
void Decomposer::replaceSeenFaces() {
  std::sort(visible_.begin(), visible_.end());
  const std::size_t reused = std::min(visible_.size(), cone_.size());
  for (std::size_t j = 0; j < reused; ++j) setHullFace(visible_[j], cone_[j]);
  for (std::size_t j = reused; j < cone_.size(); ++j) {
    hull_corners_.push_back(cone_[j].corners);
    hull_ids_.push_back(cone_[j].ids);
    hull_planes_.push_back(cone_[j].plane);
  }
  for (std::size_t j = visible_.size(); j-- > reused;) {
    const std::size_t last = hull_planes_.size() - 1;
    setHullFace(visible_[j], {hull_corners_[last], hull_ids_[last], hull_planes_[last]});
    hull_corners_.pop_back();
    hull_ids_.pop_back();
    hull_planes_.pop_back();
  }
}

void Decomposer::setHullFace(int slot, const HullFace& face) {
  hull_corners_[slot] = face.corners;
  hull_ids_[slot] = face.ids;
  hull_planes_[slot] = face.plane;
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
      extendHull();
      addFace(t);
      if (static_cast<int>(faces_.size()) >= kMaxPatchTriangles) frontier_.clear();
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
  PolytopeParts poly;
  for (int k = 0; k < 3; ++k) {
    poly.vertices.push_back(mesh_.vertices[mesh_.triangles[t][k]]);
    poly.original.push_back(mesh_.triangles[t][k]);
  }
  poly.faces = {Tri(0, 1, 2), Tri(0, 2, 1)};
  poly.face_source = {t, -1};
  patch.polytope = ConvexPolytope::build(poly);
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
  // Hulls, tetrahedra and probes lie in the region's box widened by the probes' depth.
  region_tree_.build(region, (kProbeDepth + 1.0) * tol_);
  seeds_.clear();
  seed_scan_ = shared_.region_start[region];
  for (int seed = nextSeed(); seed >= 0; seed = nextSeed()) {
    if (Status s = growPatch(seed, HullCheck::Quick); !s.ok()) return s;
    if (pollStop()) return Status(ErrorCode::InvalidOperation, "build cancelled");
  }
  return Status::success();
}

}  // namespace sc::detail
