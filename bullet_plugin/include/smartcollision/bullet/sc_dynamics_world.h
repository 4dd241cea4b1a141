// SPDX-License-Identifier: MIT
// ScDynamicsWorld: a btDiscreteDynamicsWorld that applies the plugin's direct
// corrections (recovery pushes, impact projections) right after collision detection,
// in the same substep, and keeps fast bodies' pairs across the step they cross a wall.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <unordered_map>

#include "smartcollision/bullet/plugin.h"

namespace sc::bullet {

/// Bullet's solver settings under which stacks stand in the manifold model: 100
/// iterations, two friction directions, randomised constraint order (Bullet's defaults
/// let a 10-box tower creep 4 cm and a 1:100 stack topple in 20 s, with Bullet's own
/// box-box contacts as well). Costs solver time only where the solver has contacts.
void useStackingSolverSettings(btContactSolverInfo& info);

class ScDynamicsWorld : public btDiscreteDynamicsWorld {
 public:
  /// `plugin` comes from registerSmartCollision on `dispatcher`. Applies
  /// useStackingSolverSettings to the world's solver info (change it afterwards to
  /// override).
  ScDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphase,
                  btConstraintSolver* solver, btCollisionConfiguration* configuration,
                  std::shared_ptr<Plugin> plugin);
  ~ScDynamicsWorld() override;

  Plugin& plugin() { return *plugin_; }
  const Plugin& plugin() const { return *plugin_; }

  /// Bullet's detection, then the buffered recovery impulses and impact projections,
  /// before the solver and the integration of this substep; then the poses the next
  /// detection sweeps from.
  void performDiscreteCollisionDetection() override;
  /// Bullet's AABBs (current pose and, for moving bodies, the predicted one) widened
  /// to the pose of the last detection: a body that crossed a thin wall within one
  /// step keeps its pair with the wall, whose dynamic PD then sees the crossing.
  void updateAabbs() override;
  /// Bullet's integration; then, when a body moved further than its contact
  /// threshold since the last detection, the plugin's impact pass (see .cpp).
  void integrateTransforms(btScalar timeStep) override;
  /// Bullet's removal; the world and its plugin then hold nothing of the body (its
  /// last pose, its settings override): it may be deleted at once, and a body later
  /// built at its address starts with the world's settings.
  void removeRigidBody(btRigidBody* body) override;
  void removeCollisionObject(btCollisionObject* object) override;

 private:
  bool movedFar() const;
  /// Dispatches again so that pairs with a body just projected measure their rows at
  /// its new pose (Plugin::setRowsPass).
  void measureRowsAgain();
  void forget(const btCollisionObject* object);
  std::shared_ptr<Plugin> plugin_;
  std::unordered_map<const btCollisionObject*, btTransform> last_poses_;
};

}  // namespace sc::bullet
