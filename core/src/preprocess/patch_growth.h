// SPDX-License-Identifier: MIT
// Greedy patch growth within one region of a closed mesh (steps 3 to 6 of the
// outline in convex_decomposition.cpp): condition (1) by chunked bounds, condition
// (2) by the swallow filter and batch checks with bisection.
#pragma once

#include <array>
#include <atomic>
#include <deque>
#include <vector>

#include "geometry/convex_polytope.h"
#include "geometry/halfspace_polytope.h"
#include "preprocess/decomposition_mesh.h"
#include "preprocess/patch_polytope.h"
#include "preprocess/region_tree.h"
#include "smartcollision/model.h"

namespace sc::detail {

/// Patch faces and vertices are grouped in chunks of this many (in order of
/// addition, so spatially compact) for the condition (1) bounds.
inline constexpr int kChunk = 32;

/// A patch stops growing at this many triangles. Checking a patch costs more per
/// triangle as it grows (its polytope is rebuilt at each check and bisection), and
/// large patches on finely tessellated convex bands failed their checks ever more
/// often: uncapped, the cost per triangle doubled from 40k to 1M triangles. At 512
/// a torus's cost per triangle stays flat, for 13-26% more (still convex) patches.
inline constexpr int kMaxPatchTriangles = 512;

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
  void setVerified(const ConvexPolytope& hull);
  bool swallows(int t);
  /// After swallows(t) was false and before t joins: the growing hull takes t's new
  /// vertex (the faces it sees give way to a cone from it over their horizon).
  void extendHull();
  struct HullFace {
    std::array<Vec3, 3> corners;
    std::array<int, 3> ids;
    Plane plane;
  };
  void replaceSeenFaces();
  void setHullFace(int slot, const HullFace& face);
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
  std::vector<int>& triangle_patch_;
  SharedProgress& state_;
  const ProgressCallback* progress_;  ///< null on worker threads
  const CancelCallback* cancel_;      ///< null on worker threads
  double reported_ = -1.0;

  int region_ = -1;
  RegionResult* out_ = nullptr;
  /// The triangles the current region's hulls can meet; counts the patch's faces.
  RegionTree region_tree_;
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
  /// Faces (corners, their vertex indices and outward plane) of the growing hull:
  /// the last verified hull, extended by each vertex added since. Every corner is
  /// a patch vertex, so each tetrahedron below lies in the patch's hull.
  std::vector<std::array<Vec3, 3>> hull_corners_;
  std::vector<std::array<int, 3>> hull_ids_;
  std::vector<Plane> hull_planes_;
  int hull_vertices_ = 0;
  int fresh_ = -1;              ///< swallows(): the new vertex
  std::vector<int> visible_;    ///< swallows(): the hull faces it sees
  std::vector<int> horizon_;    ///< extendHull(): 3 * face + edge
  std::vector<HullFace> cone_;  ///< extendHull(): the new faces
  /// swallows(): the tetrahedra of new hull over the hull faces a vertex sees.
  std::vector<HalfspacePolytope> tetras_;
  std::vector<Aabb> tetra_bounds_;
};

}  // namespace sc::detail
