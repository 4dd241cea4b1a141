// SPDX-License-Identifier: MIT
// The Bullet world of the demos and the Bullet benches: what Bullet keeps pointers
// to, and the world over them, with the SmartCollision plugin or with Bullet's own
// GImpact collision (for comparisons: the same solver settings, only collision
// differs).
#pragma once

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <btBulletDynamicsCommon.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "smartcollision/bullet/bullet.h"

namespace sc::demo {

/// Members in the order they are made; destroyed the other way round (the world first).
template <class World = btDiscreteDynamicsWorld>
struct BulletWorld {
  std::unique_ptr<btDefaultCollisionConfiguration> config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::shared_ptr<sc::bullet::Plugin> plugin;  ///< null in a world of Bullet's own
  std::unique_ptr<btBroadphaseInterface> broadphase;
  std::unique_ptr<btConstraintSolver> solver;
  std::unique_ptr<World> world;

  /// With the plugin registered with `settings` and an ScDynamicsWorld; `s`: the
  /// solver (Bullet's sequential impulse when null). Exits with the reason when the
  /// plugin cannot be registered.
  void makeSmartCollision(const sc::bullet::PluginSettings& settings,
                          std::unique_ptr<btConstraintSolver> s = nullptr) {
    config =
        std::make_unique<btDefaultCollisionConfiguration>(sc::bullet::collisionConstructionInfo());
    dispatcher = std::make_unique<btCollisionDispatcher>(config.get());
    auto registered = sc::bullet::registerSmartCollision(dispatcher.get(), settings);
    if (!registered.ok()) {
      std::fprintf(stderr, "registerSmartCollision: %s\n", registered.status().message().c_str());
      std::exit(1);
    }
    plugin = registered.value();
    makeDynamics(std::move(s));
    world = std::make_unique<sc::bullet::ScDynamicsWorld>(dispatcher.get(), broadphase.get(),
                                                          solver.get(), config.get(), plugin);
  }

  /// With Bullet's GImpact for meshes and the plugin's solver settings. `sc_config`:
  /// SmartCollision's collision configuration all the same (else Bullet's default).
  void makeGImpact(bool sc_config) {
    config = sc_config ? std::make_unique<btDefaultCollisionConfiguration>(
                             sc::bullet::collisionConstructionInfo())
                       : std::make_unique<btDefaultCollisionConfiguration>();
    dispatcher = std::make_unique<btCollisionDispatcher>(config.get());
    btGImpactCollisionAlgorithm::registerAlgorithm(dispatcher.get());
    makeDynamics(nullptr);
    world = std::make_unique<World>(dispatcher.get(), broadphase.get(), solver.get(), config.get());
    sc::bullet::useStackingSolverSettings(world->getSolverInfo());
  }

  /// Empties it, the world first.
  void reset() {
    world.reset();
    solver.reset();
    broadphase.reset();
    plugin.reset();
    dispatcher.reset();
    config.reset();
  }

 private:
  void makeDynamics(std::unique_ptr<btConstraintSolver> s) {
    broadphase = std::make_unique<btDbvtBroadphase>();
    solver = s ? std::move(s) : std::make_unique<btSequentialImpulseConstraintSolver>();
  }
};

/// A rigid body over `shape` at `pose` (dynamic when mass > 0; never deactivated, so
/// that measurements see the model), added to `world` and owned by `bodies`.
inline btRigidBody* addBody(btDynamicsWorld& world,
                            std::vector<std::unique_ptr<btRigidBody>>& bodies,
                            btCollisionShape* shape, double mass, const btTransform& pose) {
  btVector3 inertia(0, 0, 0);
  if (mass > 0) shape->calculateLocalInertia(btScalar(mass), inertia);
  btRigidBody::btRigidBodyConstructionInfo ci(btScalar(mass), nullptr, shape, inertia);
  ci.m_startWorldTransform = pose;
  bodies.push_back(std::make_unique<btRigidBody>(ci));
  bodies.back()->setActivationState(DISABLE_DEACTIVATION);
  world.addRigidBody(bodies.back().get());
  return bodies.back().get();
}

}  // namespace sc::demo
