// SPDX-License-Identifier: MIT
// ScBulletShape and the registration: principal frame, AABB, inertia, ray tests
// through processAllTriangles, closest-point queries, pool-size check.
#include "smartcollision/bullet/bullet.h"

#include <LinearMath/btPoolAllocator.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <algorithm>
#include <vector>

#include "bullet_world.h"
#include "sc_collision_algorithm.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

TEST(ScBulletShape, StoresMeshInPrincipalFrame) {
  Rng rng(3);
  const Mat3 r = randomRotation(rng).toRotationMatrix();
  const Vec3 c(1.0, 2.0, -3.0);
  MeshData mesh = boxMesh(Vec3(0.5, 1.0, 2.0));
  for (Vec3& v : mesh.vertices) v = r * v + c;
  auto s = bullet::ScBulletShape::create(ModelKind::ClosedPolyhedron, mesh);
  ASSERT_TRUE(s.ok()) << s.status().message();
  const bullet::ScBulletShape& shape = *s.value();
  EXPECT_EQ(shape.getShapeType(), int(FAST_CONCAVE_MESH_PROXYTYPE));
  EXPECT_TRUE(shape.isConcave());
  const btVector3 origin = shape.meshFromShape().getOrigin();
  EXPECT_VEC_NEAR(Vec3(origin.x(), origin.y(), origin.z()), c, 1e-5);
  // In the principal frame the box is axis aligned again: its AABB is the box, and
  // each axis has the moment of the box edges across it (mass 12: I = a^2 + b^2).
  btVector3 lo, hi;
  shape.getAabb(btTransform::getIdentity(), lo, hi);
  const double m = shape.aabbMargin();
  const btVector3 ext = hi - lo;
  btVector3 inertia;
  shape.calculateLocalInertia(12.0, inertia);
  double volume = 1.0;
  for (int k = 0; k < 3; ++k) {
    const double e = double(ext[k]) - 2 * m;
    const double f = double(ext[(k + 1) % 3]) - 2 * m, g = double(ext[(k + 2) % 3]) - 2 * m;
    volume *= e;
    EXPECT_NEAR(double(inertia[k]), f * f + g * g, 1e-4);
  }
  EXPECT_NEAR(volume, 8.0, 1e-4);
  // Every stored vertex maps back onto an input vertex.
  for (const btVector3& v : shape.vertices()) {
    const btVector3 w = shape.meshFromShape() * v;
    double best = 1e9;
    for (const Vec3& u : mesh.vertices) best = std::min(best, (Vec3(w.x(), w.y(), w.z()) - u).norm());
    EXPECT_LT(best, 1e-5);
  }
}

TEST(ScBulletShape, RejectsOpenClosedMesh) {
  MeshData mesh = boxMesh(Vec3(1, 1, 1));
  mesh.triangles.pop_back();
  auto s = bullet::ScBulletShape::create(ModelKind::ClosedPolyhedron, mesh);
  EXPECT_FALSE(s.ok());
  auto soup = bullet::ScBulletShape::create(ModelKind::TriangleSoup, mesh);
  EXPECT_TRUE(soup.ok()) << soup.status().message();
}

TEST(ScBulletShape, RefusesABadAabbMarginAndKeepsItsOwn) {
  const auto shape = boxShape(btVector3(0.5f, 0.5f, 0.5f));
  ASSERT_TRUE(shape->setAabbMargin(0.01).ok());
  for (double bad : {-5.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    const Status s = shape->setAabbMargin(bad);
    EXPECT_EQ(s.code(), ErrorCode::InvalidArgument) << bad;
    EXPECT_FALSE(s.message().empty());
    EXPECT_EQ(shape->aabbMargin(), 0.01) << bad;
  }
}

TEST(ScBulletShape, RayTestHitsTheMesh) {
  BulletWorld w(bullet::ContactModel::Potential, 0.0);
  auto shape = boxShape(btVector3(1, 1, 1));
  w.addBody(shape, 0.0, btVector3(5, 0, 0));
  btCollisionWorld::ClosestRayResultCallback hit(btVector3(0, 0.3, 0.2), btVector3(10, 0.3, 0.2));
  w.world->rayTest(hit.m_rayFromWorld, hit.m_rayToWorld, hit);
  ASSERT_TRUE(hit.hasHit());
  EXPECT_NEAR(hit.m_hitPointWorld.x(), 4.0, 1e-5);
  EXPECT_NEAR(hit.m_hitNormalWorld.x(), -1.0, 1e-5);
  btCollisionWorld::ClosestRayResultCallback miss(btVector3(0, 1.5, 0), btVector3(10, 1.5, 0));
  w.world->rayTest(miss.m_rayFromWorld, miss.m_rayToWorld, miss);
  EXPECT_FALSE(miss.hasHit());
}

TEST(Registration, RefusesTooSmallAlgorithmPool) {
  btDefaultCollisionConfiguration config;  // default pool: may be too small
  btCollisionDispatcher dispatcher(&config);
  const int pool = config.getCollisionAlgorithmPool()->getElementSize();
  auto p = bullet::registerSmartCollision(&dispatcher);
  if (pool < int(sizeof(bullet::ScCollisionAlgorithm))) {
    EXPECT_EQ(p.status().code(), ErrorCode::InvalidOperation);
  } else {
    EXPECT_TRUE(p.ok());
  }
  btDefaultCollisionConfiguration sized(bullet::collisionConstructionInfo());
  btCollisionDispatcher d2(&sized);
  EXPECT_TRUE(bullet::registerSmartCollision(&d2).ok());
  EXPECT_EQ(bullet::registerSmartCollision(nullptr).status().code(), ErrorCode::InvalidArgument);
}

/// Collects contactPairTest points.
struct Points : btCollisionWorld::ContactResultCallback {
  btScalar addSingleResult(btManifoldPoint& p, const btCollisionObjectWrapper*, int, int,
                           const btCollisionObjectWrapper*, int, int) override {
    distance = std::min(distance, double(p.getDistance()));
    ++count;
    return 0;
  }
  double distance = 1e9;
  int count = 0;
};

TEST(Registration, ASecondPluginOnOneDispatcherIsRefusedAndTheFirstKept) {
  btDefaultCollisionConfiguration config(bullet::collisionConstructionInfo());
  btCollisionDispatcher dispatcher(&config), other(&config);
  btDbvtBroadphase broadphase;
  btCollisionWorld world(&dispatcher, &broadphase, &config);
  auto first = bullet::registerSmartCollision(&dispatcher);
  ASSERT_TRUE(first.ok());
  // Before, the second call returned Ok and replaced the first's create functions, and
  // once that second plugin was released the dispatcher called freed ones.
  EXPECT_EQ(bullet::registerSmartCollision(&dispatcher).status().code(),
            ErrorCode::InvalidOperation);
  EXPECT_TRUE(bullet::registerSmartCollision(&other).ok());  // one per dispatcher
  const auto box = boxShape(btVector3(0.5f, 0.5f, 0.5f));
  btCollisionObject a, b;
  a.setCollisionShape(box.get());
  b.setCollisionShape(box.get());
  b.getWorldTransform().setOrigin(btVector3(0, 1.2f, 0));
  Points points;
  points.m_closestDistanceThreshold = 0.5f;
  world.contactPairTest(&a, &b, points);  // the first plugin's closest points
  EXPECT_NEAR(points.distance, 0.2, 1e-4);
  // Once the first plugin is gone, the dispatcher takes a new one.
  first.value().reset();
  EXPECT_TRUE(bullet::registerSmartCollision(&dispatcher).ok());
}

TEST(Registration, ContactPairTestUsesTheClosestPointsTable) {
  BulletWorld w(bullet::ContactModel::Potential, 0.0);
  auto shape = boxShape(btVector3(0.5, 0.5, 0.5));
  auto box = std::make_shared<btBoxShape>(btVector3(0.5, 0.5, 0.5));
  btRigidBody* a = w.addBody(shape, 0.0, btVector3(0, 0, 0));
  btRigidBody* b = w.addBody(box, 0.0, btVector3(1.01, 0, 0));
  Points near;
  near.m_closestDistanceThreshold = 0.1f;
  w.world->contactPairTest(a, b, near);
  ASSERT_GE(near.count, 1);
  EXPECT_NEAR(near.distance, 0.01, 1e-4);
  b->getWorldTransform().setOrigin(btVector3(2.0, 0, 0));
  Points far;
  w.world->contactPairTest(a, b, far);
  EXPECT_EQ(far.count, 0);
}

}  // namespace
}  // namespace sc::test
