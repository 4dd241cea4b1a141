// SPDX-License-Identifier: MIT
// Uses the installed Bullet plugin: a SmartCollision cube dropped on a Bullet box
// comes to rest on it in a small world.
#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <cstdio>

#include "smartcollision/bullet/bullet.h"

int main() {
  btDefaultCollisionConfiguration config(sc::bullet::collisionConstructionInfo());
  btCollisionDispatcher dispatcher(&config);
  auto plugin = sc::bullet::registerSmartCollision(&dispatcher);
  if (!plugin.ok()) return 1;
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  sc::bullet::ScDynamicsWorld world(&dispatcher, &broadphase, &solver, &config, plugin.value());
  world.setGravity(btVector3(0, -9.81f, 0));

  btBoxShape ground_shape(btVector3(10, 1, 10));
  btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &ground_shape));
  ground.getWorldTransform().setOrigin(btVector3(0, -1, 0));
  world.addRigidBody(&ground);

  sc::MeshData cube;
  for (int i = 0; i < 8; ++i)
    cube.vertices.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
  cube.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                    {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  auto shape = sc::bullet::ScBulletShape::create(sc::ModelKind::ClosedPolyhedron, cube);
  if (!shape.ok()) {
    std::printf("shape: %s\n", shape.status().message().c_str());
    return 1;
  }
  btVector3 inertia;
  shape.value()->calculateLocalInertia(1, inertia);
  btRigidBody box(btRigidBody::btRigidBodyConstructionInfo(1, nullptr, shape.value().get(), inertia));
  box.getWorldTransform().setOrigin(btVector3(0, 1, 0));
  world.addRigidBody(&box);

  for (int i = 0; i < 240; ++i) world.stepSimulation(1.0f / 240, 1, 1.0f / 240);
  const double y = box.getCenterOfMassPosition().y();
  std::printf("cube at rest at y = %.4f m\n", y);
  world.removeRigidBody(&box);
  world.removeRigidBody(&ground);
  return std::abs(y - 0.5) < 0.02 ? 0 : 1;
}
