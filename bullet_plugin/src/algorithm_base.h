// SPDX-License-Identifier: MIT
// AlgorithmBase: what the plugin's two collision algorithms (ScCollisionAlgorithm,
// ScPlaneAlgorithm) share: the plugin, the closest-point flag with its manifold, and
// no time of impact of their own.
#pragma once

#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <btBulletCollisionCommon.h>

namespace sc::bullet {

class Plugin;

class AlgorithmBase : public btActivatingCollisionAlgorithm {
 public:
  /// `closest_points`: created for contactTest / closest-point queries: report points
  /// to the result, never impulses; the manifold is made at once.
  AlgorithmBase(const btCollisionAlgorithmConstructionInfo& ci,
                const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                Plugin* plugin, bool closest_points)
      : btActivatingCollisionAlgorithm(ci, body0, body1),
        plugin_(plugin),
        closest_points_(closest_points) {
    if (closest_points_)
      manifold_ =
          m_dispatcher->getNewManifold(body0->getCollisionObject(), body1->getCollisionObject());
  }
  ~AlgorithmBase() override {
    if (manifold_ != nullptr) m_dispatcher->releaseManifold(manifold_);
  }

  /// Bullet's time-of-impact query: 1, no impact before the end of the step.
  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return btScalar(1);
  }
  /// The one manifold, unless the algorithm serves closest-point queries.
  void getAllContactManifolds(btManifoldArray& manifolds) override {
    if (manifold_ != nullptr && !closest_points_) manifolds.push_back(manifold_);
  }

 protected:
  Plugin* plugin_;
  btPersistentManifold* manifold_ = nullptr;
  bool closest_points_;
};

}  // namespace sc::bullet
