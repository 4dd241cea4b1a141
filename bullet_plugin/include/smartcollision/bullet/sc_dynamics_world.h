// SPDX-License-Identifier: MIT
// ScDynamicsWorld: a btDiscreteDynamicsWorld that applies the potential model's
// impulses right after collision detection, in the same substep.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <memory>

#include "smartcollision/bullet/plugin.h"

namespace sc::bullet {

class ScDynamicsWorld : public btDiscreteDynamicsWorld {
 public:
  /// `plugin` comes from registerSmartCollision on `dispatcher`.
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
