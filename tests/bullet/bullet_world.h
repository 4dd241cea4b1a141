// SPDX-License-Identifier: MIT
// A small Bullet world with the SmartCollision plugin for the plugin's tests:
// owns the Bullet objects, adds bodies, steps at a fixed rate, measures energy.
#pragma once

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "smartcollision/bullet/bullet.h"

namespace sc::test {

struct BulletWorld {
  explicit BulletWorld(bullet::ContactModel model, double gravity = -9.81, double hz = 240.0);
  ~BulletWorld();
  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  /// Dynamic when mass > 0. Sleeping is disabled so measurements see the model.
  btRigidBody* addBody(const std::shared_ptr<btCollisionShape>& shape, double mass,
                       const btVector3& position, const btQuaternion& rotation = btQuaternion::getIdentity());
  /// Static btBoxShape whose top face is y = 0.
  btRigidBody* addGround();
  void step(int steps = 1);
  /// Kinetic energy of the dynamic bodies [J].
  double kineticEnergy() const;

  double dt;
  std::unique_ptr<btDefaultCollisionConfiguration> config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btBroadphaseInterface> broadphase;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
  std::shared_ptr<bullet::Plugin> plugin;
  std::unique_ptr<bullet::ScDynamicsWorld> world;
  std::vector<std::shared_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
};

/// Parameter name of tests run for both contact models.
inline std::string contactModelName(const ::testing::TestParamInfo<bullet::ContactModel>& info) {
  return info.param == bullet::ContactModel::Potential ? "Potential" : "Manifold";
}

/// Deepest corner of box `a` inside box `b` (both cubes of half edge `half`), or below
/// the ground (y < 0) when `b` is null; 0 when none is inside. Exact, for overlaps
/// measured independently of SmartCollision.
double boxCornerDepth(const btRigidBody& a, const btRigidBody* b, double half);

/// An ScBulletShape of a closed box mesh (half extents h); fails the test on error.
std::shared_ptr<bullet::ScBulletShape> boxShape(const btVector3& h);

}  // namespace sc::test
