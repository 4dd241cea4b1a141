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
//     the region's tree (region_tree.h: every triangle that can meet a hull of
//     the region): none may reach deeper than the tolerance into the hull, nor
//     into the probe prisms of flat or thin hulls. Hulls only grow with the
//     patch, so a failure is bracketed by binary search; the face after the
//     longest good prefix is banned from this patch and growth resumes there.
//     Between checks, a cheap sound filter: the tetrahedron spanned by a face's
//     new vertex and a face of the growing hull (the last verified hull, extended
//     by each vertex added since) that the vertex sees lies inside the new hull,
//     so a triangle reaching into it bans the face at once;
//  5. seeds are taken next to finished patches, so patches tile the surface;
//     patches grow within one region (median splits of the triangles' centres,
//     at most kRegionTriangles each) while condition (2) still tests every
//     triangle the hulls can meet, of any region: a region's patches depend on
//     it alone, so regions run in parallel
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
//
// Files: decomposition_mesh (step 1, regions), patch_growth (steps 3 to 6),
// hull_inside_test (condition (2)'s tree walk), patch_polytope (a patch's
// polytope); this one tries the whole surface and runs the regions on threads.
#include "preprocess/convex_decomposition.h"

#include <atomic>
#include <chrono>
#include <thread>
#include <utility>

#include "preprocess/decomposition_mesh.h"
#include "preprocess/patch_growth.h"

namespace sc::detail {
namespace {

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
