// SPDX-License-Identifier: MIT
// ScDynamicsWorld: a btDiscreteDynamicsWorld that applies the potential model's
// impulses right after collision detection, in the same substep.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <memory>

#include "smartcollision/bullet/plugin.h"

namespace sc::bullet {

/// Bullet's solver settings under which stacks stand in the manifold model: 50
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

  /// Bullet's detection, then the buffered impulses (F dt, tau dt): velocities change
  /// before the solver and the integration of this substep. Forces would pile up
  /// across substeps, since Bullet clears them once per stepSimulation.
  void performDiscreteCollisionDetection() override;

 private:
  std::shared_ptr<Plugin> plugin_;
};

}  // namespace sc::bullet
