// SPDX-License-Identifier: MIT
// BulletWorld: Bullet's usual objects plus registerSmartCollision and ScDynamicsWorld.
#include "bullet_world.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/shapes.h"

namespace sc::test {

BulletWorld::BulletWorld(bullet::ContactModel model, double gravity, double hz)
    : dt(1.0 / hz) {
  btDefaultCollisionConstructionInfo info = bullet::collisionConstructionInfo();
  config = std::make_unique<btDefaultCollisionConfiguration>(info);
  dispatcher = std::make_unique<btCollisionDispatcher>(config.get());
  broadphase = std::make_unique<btDbvtBroadphase>();
  solver = std::make_unique<bullet::StackingSolver>();
  bullet::PluginSettings settings;
  settings.model = model;
  Result<std::shared_ptr<bullet::Plugin>> p = bullet::registerSmartCollision(dispatcher.get(), settings);
  EXPECT_TRUE(p.ok()) << p.status().message();
  plugin = p.value();
  world = std::make_unique<bullet::ScDynamicsWorld>(dispatcher.get(), broadphase.get(), solver.get(),
                                                    config.get(), plugin);
  world->setGravity(btVector3(0, btScalar(gravity), 0));
}

BulletWorld::~BulletWorld() {
  for (auto& b : bodies) world->removeRigidBody(b.get());
}

btRigidBody* BulletWorld::addBody(const std::shared_ptr<btCollisionShape>& shape, double mass,
                                  const btVector3& position, const btQuaternion& rotation) {
  btVector3 inertia(0, 0, 0);
  if (mass > 0) shape->calculateLocalInertia(btScalar(mass), inertia);
  btRigidBody::btRigidBodyConstructionInfo ci(btScalar(mass), nullptr, shape.get(), inertia);
  ci.m_startWorldTransform = btTransform(rotation, position);
  auto body = std::make_unique<btRigidBody>(ci);
  body->setActivationState(DISABLE_DEACTIVATION);
  world->addRigidBody(body.get());
  shapes.push_back(shape);
  bodies.push_back(std::move(body));
  return bodies.back().get();
}

btRigidBody* BulletWorld::addGround() {
  auto ground = std::make_shared<btBoxShape>(btVector3(50, 1, 50));
  return addBody(ground, 0.0, btVector3(0, -1, 0));
}

void BulletWorld::step(int steps) {
  for (int i = 0; i < steps; ++i) world->stepSimulation(btScalar(dt), 1, btScalar(dt));
}

double BulletWorld::kineticEnergy() const {
  double e = 0.0;
  for (const auto& b : bodies) {
    if (b->getInvMass() <= 0) continue;
    const btVector3 w = b->getAngularVelocity();
    const btVector3 lw = b->getWorldTransform().getBasis().transpose() * w;
    const btVector3 inv = b->getInvInertiaDiagLocal();
    double rot = 0.0;
    for (int k = 0; k < 3; ++k) rot += inv[k] > 0 ? double(lw[k] * lw[k] / inv[k]) : 0.0;
    e += 0.5 * double(b->getLinearVelocity().length2()) / double(b->getInvMass()) + 0.5 * rot;
  }
  return e;
}

double closestDistance(BulletWorld& w, btCollisionObject* a, btCollisionObject* b,
                       double threshold) {
  struct Callback : btCollisionWorld::ContactResultCallback {
    double distance = std::nan("");
    btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int,
                             const btCollisionObjectWrapper*, int, int) override {
      const double d = double(cp.getDistance());
      if (std::isnan(distance) || d < distance) distance = d;
      return 0;
    }
  } callback;
  callback.m_closestDistanceThreshold = btScalar(threshold);
  w.world->contactPairTest(a, b, callback);
  return callback.distance;
}

std::shared_ptr<bullet::ScBulletShape> boxShape(const btVector3& h) {
  Result<std::shared_ptr<bullet::ScBulletShape>> s = bullet::ScBulletShape::create(
      ModelKind::ClosedPolyhedron, boxMesh(Vec3(h.x(), h.y(), h.z())));
  EXPECT_TRUE(s.ok()) << s.status().message();
  return s.value();
}

double boxCornerDepth(const btRigidBody& a, const btRigidBody* b, double half) {
  const btScalar h = btScalar(half);
  double deepest = 0.0;
  for (int i = 0; i < 8; ++i) {
    const btVector3 c((i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h);
    const btVector3 w = a.getWorldTransform() * c;
    if (b == nullptr) {
      deepest = std::max(deepest, -double(w.y()));
      continue;
    }
    const btVector3 l = b->getWorldTransform().inverse() * w;
    double inside = half - std::abs(double(l.x()));
    inside = std::min(inside, half - std::abs(double(l.y())));
    inside = std::min(inside, half - std::abs(double(l.z())));
    deepest = std::max(deepest, inside);
  }
  return deepest;
}

}  // namespace sc::test
