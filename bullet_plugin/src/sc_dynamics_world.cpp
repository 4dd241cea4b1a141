// SPDX-License-Identifier: MIT
// ScDynamicsWorld: collision detection followed by the potential model's impulses.
#include "smartcollision/bullet/sc_dynamics_world.h"

#include <utility>

namespace sc::bullet {

ScDynamicsWorld::ScDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphase,
                                 btConstraintSolver* solver, btCollisionConfiguration* configuration,
                                 std::shared_ptr<Plugin> plugin)
    : btDiscreteDynamicsWorld(dispatcher, broadphase, solver, configuration),
      plugin_(std::move(plugin)) {
  if (plugin_) plugin_->attachWorld(true);
}

ScDynamicsWorld::~ScDynamicsWorld() {
  if (plugin_) plugin_->attachWorld(false);
}

void ScDynamicsWorld::performDiscreteCollisionDetection() {
  if (plugin_) plugin_->beginStep();
  btDiscreteDynamicsWorld::performDiscreteCollisionDetection();
  if (plugin_) plugin_->applyImpulses();
}

}  // namespace sc::bullet
