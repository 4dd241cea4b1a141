// SPDX-License-Identifier: MIT
// ScCollisionAlgorithm: one per broadphase pair involving an ScBulletShape; runs the
// pair's sc::PairTracker and turns its results into impulses or manifold points.
#pragma once

#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <btBulletCollisionCommon.h>

#include "smartcollision/collision.h"
#include "smartcollision/model.h"

namespace sc::bullet {

class Plugin;

class ScCollisionAlgorithm : public btActivatingCollisionAlgorithm {
 public:
  /// `closest_points`: created for contactTest / closest-point queries: report points
  /// to the result, never impulses, no owned manifold.
  ScCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                       const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                       Plugin* plugin, bool closest_points);
  ~ScCollisionAlgorithm() override;

  void processCollision(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                        const btDispatcherInfo& info, btManifoldResult* result) override;
  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return btScalar(1);
  }
  void getAllContactManifolds(btManifoldArray& manifolds) override;

 private:
  Plugin* plugin_;
  const btCollisionObject* objects_[2];
  ModelPtr models_[2];  ///< per side; null: a shape the algorithm cannot take (ignored)
  btPersistentManifold* manifold_ = nullptr;
  bool closest_points_;
  /// Per direction: the spring (or the manifold) responds; set once the pair is seen
  /// apart or within detail::springReach. Before that a depth (a pair that starts
  /// deeply intersecting) gets the bounded recovery push.
  bool spring_on_[2] = {false, false};
  PairTracker tracker_;
};

}  // namespace sc::bullet
