// SPDX-License-Identifier: MIT
// ScCollisionAlgorithm: one per broadphase pair involving an ScBulletShape; runs the
// pair's sc::PairTracker and turns its results into impulses or manifold points.
#pragma once

#include <vector>

#include "algorithm_base.h"
#include "smartcollision/bullet/step_stats.h"
#include "smartcollision/collision.h"
#include "smartcollision/model.h"

namespace sc::bullet {

namespace detail {
struct RowPoint;
struct WorldPlane;
struct RowCandidate;
struct ContactCluster;
}  // namespace detail

class ScCollisionAlgorithm : public AlgorithmBase {
 public:
  ScCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                       const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                       Plugin* plugin, bool closest_points);
  ~ScCollisionAlgorithm() override;

  void processCollision(const btCollisionObjectWrapper* body0,
                        const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                        btManifoldResult* result) override;
  /// The patches' manifolds (manifold_ is for closest-point queries only).
  void getAllContactManifolds(btManifoldArray& manifolds) override;

 private:
  const btCollisionObject* objects_[2];
  ModelPtr models_[2];  ///< per side; null: a shape the algorithm cannot take (ignored)
  /// One manifold per contact patch (detail::buildClusters), so that each patch keeps
  /// its rows from step to step, and patch i's rows beyond the four a manifold holds
  /// (a leaf patch's centroid) in manifold kPatches + i; null until a patch needs it.
  static constexpr int kPatches = 4;
  static constexpr int kManifolds = 2 * kPatches;
  btPersistentManifold* manifolds_[kManifolds] = {};
  /// Per direction: the spring (or the manifold) responds; set once the pair is seen
  /// apart or within detail::springReach. Before that a depth (a pair that starts
  /// deeply intersecting) gets the bounded recovery push.
  bool spring_on_[2] = {false, false};
  /// Per direction: penetrating in the last step (an impact is projected: fresh, or
  /// deeper after the integration than the rows held).
  bool in_contact_[2] = {false, false};
  double held_depth_[2] = {0.0, 0.0};  ///< per direction: depth at the step's detection
  /// The last query's poses and its gap (the smallest distance of its directions, or
  /// -1 when not apart): while the bodies' motion since then is bounded by less than
  /// the gap minus the threshold, no query can find anything to respond to.
  btTransform queried_[2];
  double queried_gap_ = -1.0;
  bool ever_queried_ = false;
  double reach_[2] = {0.0, 0.0};  ///< per side: farthest surface point from its origin
  /// The pair's tolerance: the query's, at most PluginSettings::relative_tolerance of
  /// size_, the smaller body's size (half its bounds' diagonal plus a rounding radius).
  double tolerance() const;
  double size_ = kInfinity;
  /// The last query's figures, and whether its rows may be kept while the bodies stay
  /// put (a query that projected an impact or pushed a pair apart may not).
  StepStats queried_stats_;
  bool rows_kept_ = false;
  int kept_version_ = -1;  ///< StepBuffer::settingsVersion() of that query
  PairTracker tracker_;
  PairTracker rows_tracker_;                ///< Input-mode rows of non-convex pairs in Mix and Free
  std::vector<ContactPoint> contacts_;      ///< the core's contacts of a direction (reused)
  std::vector<detail::RowPoint> points_;    ///< a direction's row points (reused)
  std::vector<detail::WorldPlane> planes_;  ///< a convex opponent's face planes (reused)
  std::vector<Vec3> corners_;               ///< a convex target piece's corners (reused)
  std::vector<detail::RowCandidate> candidates_;  ///< both directions' rows (reused)
  std::vector<int> labels_;                       ///< clustering scratch (reused)
  std::vector<detail::ContactCluster> clusters_;  ///< the step's patches (reused)

  /// The patch slot (below kPatches) for patch `c`: the one whose manifold held the
  /// same patch last step (its normal, the nearest points), else an empty one; marks
  /// it taken and gives it a manifold.
  int slotFor(const detail::ContactCluster& c, bool taken[kManifolds]);
  /// Adds patch `c`'s rows [begin, end) to manifold `slot`; returns its points.
  int addPatchRows(int slot, const detail::ContactCluster& c, int begin, int end,
                   double stale_floor, btManifoldResult* result);
  /// Bullet's refresh of manifold `m`'s points at the bodies' current poses.
  void refreshRows(btPersistentManifold* m) const;
  /// Rows of the taken manifolds whose normal is within kClusterCos of `m`'s.
  int rowsAlong(const btPersistentManifold* m, const bool taken[kManifolds]) const;
  /// How much the two bodies' surfaces can have moved relative to each other since
  /// the last query (origin displacements plus rotation chords at their reach).
  double motionSinceQuery(const btCollisionObjectWrapper* const wraps[2]) const;
  /// True when the pair is still surely apart by `threshold` (see queried_gap_).
  bool stillApart(const btCollisionObjectWrapper* const wraps[2], double threshold) const;
  /// True when the last query's rows still hold: the bodies moved by less than a
  /// hundredth of the tolerance since, under the same settings.
  bool rowsStillHold(const btCollisionObjectWrapper* const wraps[2]) const;
  /// Keeps the poses and the gap of this step's query.
  void rememberQuery(const btCollisionObjectWrapper* const wraps[2], const DirectedResult out[2],
                     const Directions& dirs);
};

}  // namespace sc::bullet
