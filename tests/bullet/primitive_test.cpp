// SPDX-License-Identifier: MIT
// SmartCollision shapes against Bullet's sphere, capsule and static plane without
// tessellating the primitive: a sphere is a point and a capsule a segment, widened by
// the radius; a plane is a half-space. Distances against closed forms, resting
// contact in both models, and a fast sphere against a thin wall.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bullet_world.h"

namespace sc::test {
namespace {

using bullet::ContactModel;

// Bullet is built in single precision: its transforms carry ~1e-7 relative error.
constexpr double kExact = 2e-5;

/// A static SmartCollision box of half extents (5, 0.5, 5) whose top face is y = 0.
btRigidBody* addMeshGround(BulletWorld& w) {
  return w.addBody(boxShape(btVector3(5, 0.5, 5)), 0.0, btVector3(0, -0.5, 0));
}

btRigidBody* addPlaneGround(BulletWorld& w) {
  return w.addBody(std::make_shared<btStaticPlaneShape>(btVector3(0, 1, 0), 0), 0.0,
                   btVector3(0, 0, 0));
}

TEST(PrimitiveModels, SphereAndCapsuleAreTheirCoresNotTriangles) {
  BulletWorld w(ContactModel::Potential);
  btSphereShape sphere(0.3f);
  btCapsuleShapeZ capsule(0.2f, 1.0f);  // half height 0.5 along z
  for (const btCollisionShape* shape : {static_cast<const btCollisionShape*>(&sphere),
                                        static_cast<const btCollisionShape*>(&capsule)}) {
    ModelPtr model = w.plugin->shapeModel(shape).value();
    ASSERT_TRUE(model) << shape->getName();
    ASSERT_EQ(model->pieces().size(), 1u);
    const MeshData& mesh = model->pieces()[0]->mesh();
    EXPECT_EQ(mesh.triangles.size(), 1u) << shape->getName();
    EXPECT_EQ(mesh.vertices.size(), 2u) << shape->getName();
  }
  const MeshData& segment = w.plugin->shapeModel(&capsule).value()->pieces()[0]->mesh();
  EXPECT_NEAR(std::abs(segment.vertices[0].z() - segment.vertices[1].z()), 1.0, 1e-12);
  EXPECT_NEAR(segment.vertices[0].head<2>().norm() + segment.vertices[1].head<2>().norm(), 0.0,
              1e-12);
}

// A hull edited in place gets a new model, even when its point count and coordinate
// sums stay the same (two points trade their x: a box turned into a slanted prism).
TEST(PrimitiveModels, EditedHullGetsANewModel) {
  BulletWorld w(ContactModel::Potential);
  btConvexHullShape hull;
  for (int i = 0; i < 8; ++i)
    hull.addPoint(btVector3((i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f),
                  false);
  hull.recalcLocalAabb();
  ModelPtr box = w.plugin->shapeModel(&hull).value();
  ASSERT_TRUE(box);
  EXPECT_EQ(w.plugin->shapeModel(&hull).value(), box);  // unchanged: the cached model
  btVector3* p = hull.getUnscaledPoints();
  p[1].setX(0.2f);  // x sum unchanged: +0.5 -> 0.2 on one point, -0.5 -> -0.2 on another
  p[0].setX(-0.2f);
  hull.recalcLocalAabb();
  ModelPtr prism = w.plugin->shapeModel(&hull).value();
  ASSERT_TRUE(prism);
  EXPECT_NE(prism, box);
  EXPECT_NEAR(prism->bounds().min.x(), -0.5, 1e-6);
  double lowest_corner_x = 1.0;  // corner 0 (y = z = -0.5) now at x = -0.2
  for (const Vec3& v : prism->pieces()[0]->mesh().vertices)
    if (v.y() < -0.49 && v.z() < -0.49) lowest_corner_x = std::min(lowest_corner_x, v.x());
  EXPECT_NEAR(lowest_corner_x, -0.2, 1e-3);  // the hull is computed in floats
}

TEST(PrimitiveDistance, SphereAboveMeshBoxIsCentreHeightMinusRadius) {
  BulletWorld w(ContactModel::Potential, 0.0);
  btRigidBody* ground = addMeshGround(w);
  for (double y : {1.5, 0.9, 0.31}) {
    btRigidBody* ball =
        w.addBody(std::make_shared<btSphereShape>(0.3f), 1.0, btVector3(0.4f, btScalar(y), -1));
    EXPECT_NEAR(closestDistance(w, ball, ground), y - 0.3, kExact) << "centre height " << y;
    EXPECT_NEAR(closestDistance(w, ground, ball), y - 0.3, kExact) << "centre height " << y;
    w.world->removeRigidBody(ball);
  }
}

TEST(PrimitiveDistance, TiltedCapsuleAboveMeshBoxIsLowestEndMinusRadius) {
  BulletWorld w(ContactModel::Potential, 0.0);
  btRigidBody* ground = addMeshGround(w);
  const double tilt = 0.4, half = 0.6, radius = 0.15, y = 1.2;
  btRigidBody* capsule =
      w.addBody(std::make_shared<btCapsuleShapeX>(btScalar(radius), btScalar(2 * half)), 1.0,
                btVector3(0, btScalar(y), 0), btQuaternion(btVector3(0, 0, 1), btScalar(tilt)));
  const double expected = y - half * std::sin(tilt) - radius;
  EXPECT_NEAR(closestDistance(w, capsule, ground), expected, kExact);
}

TEST(PrimitiveDistance, RotatedMeshBoxAbovePlaneIsLowestCornerHeight) {
  BulletWorld w(ContactModel::Potential, 0.0);
  btRigidBody* plane = addPlaneGround(w);
  const double angle = 0.5, y = 1.3;
  btRigidBody* box =
      w.addBody(boxShape(btVector3(0.5, 0.5, 0.5)), 1.0, btVector3(2, btScalar(y), 3),
                btQuaternion(btVector3(0, 0, 1), btScalar(angle)));
  const double lowest = y - 0.5 * (std::cos(angle) + std::sin(angle));
  EXPECT_NEAR(closestDistance(w, box, plane), lowest, kExact);
  EXPECT_NEAR(closestDistance(w, plane, box), lowest, kExact);
}

class PrimitiveRest : public ::testing::TestWithParam<ContactModel> {};

/// Steps `seconds` and returns the body's largest speed over the last second.
double settle(BulletWorld& w, btRigidBody* body, double seconds) {
  const int steps = static_cast<int>(std::lround(seconds / w.dt));
  const int last = static_cast<int>(std::lround(1.0 / w.dt));
  double speed = 0.0;
  for (int i = 0; i < steps; ++i) {
    w.step();
    if (i >= steps - last) speed = std::max(speed, double(body->getLinearVelocity().length()));
  }
  return speed;
}

// Resting depth of the potential model: m g / k with k = m (2 pi / (10 dt))^2, 0.43 mm at
// 240 Hz; the manifold model rests on Bullet's solver (slop about 1 mm).
constexpr double kRestBound = 2e-3;

TEST_P(PrimitiveRest, SphereRestsOnMeshBox) {
  BulletWorld w(GetParam());
  addMeshGround(w);
  btRigidBody* ball = w.addBody(std::make_shared<btSphereShape>(0.25f), 1.0, btVector3(0, 0.6f, 0));
  const double speed = settle(w, ball, 3.0);
  EXPECT_NEAR(double(ball->getCenterOfMassPosition().y()), 0.25, kRestBound);
  EXPECT_LT(speed, 0.01);
}

TEST_P(PrimitiveRest, LyingCapsuleRestsLevelOnMeshBox) {
  BulletWorld w(GetParam());
  addMeshGround(w);
  btRigidBody* capsule =
      w.addBody(std::make_shared<btCapsuleShapeX>(0.2f, 1.0f), 1.0, btVector3(0, 0.5f, 0));
  const double speed = settle(w, capsule, 3.0);
  const btVector3 axis = capsule->getWorldTransform().getBasis() * btVector3(1, 0, 0);
  EXPECT_NEAR(double(capsule->getCenterOfMassPosition().y()), 0.2, kRestBound);
  EXPECT_LT(std::abs(double(axis.y())), 0.02);  // level: both ends carry it
  EXPECT_LT(speed, 0.01);
}

TEST_P(PrimitiveRest, MeshBoxStackStandsOnStaticPlane) {
  BulletWorld w(GetParam());
  addPlaneGround(w);
  btRigidBody* boxes[3];
  for (int i = 0; i < 3; ++i)
    boxes[i] = w.addBody(boxShape(btVector3(0.5, 0.5, 0.5)), 1.0,
                         btVector3(0, btScalar(0.51 + 1.01 * i), 0));
  const double speed = settle(w, boxes[2], 4.0);
  EXPECT_NEAR(double(boxes[0]->getCenterOfMassPosition().y()), 0.5, kRestBound);
  EXPECT_NEAR(double(boxes[2]->getCenterOfMassPosition().y()), 2.5, 3 * kRestBound);
  const btVector3 top = boxes[2]->getCenterOfMassPosition();
  EXPECT_LT(std::hypot(double(top.x()), double(top.z())), 0.02);
  EXPECT_LT(speed, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Models, PrimitiveRest, bothContactModels(), contactModelName);

TEST(PrimitiveTunnelling, SmallSphereAtFiftyMetresPerSecondNeverPassesThinWall) {
  // The sphere's centre crosses the zero-thickness wall within one substep (0.21 m
  // per step, radius 5 cm); the core follows the point's motion, so it is caught.
  constexpr int kPhases = 8;
  constexpr double kSpeed = 50.0;
  int passes = 0;
  for (int phase = 0; phase < kPhases; ++phase) {
    BulletWorld w(ContactModel::Potential, 0.0);
    MeshData wall;
    wall.vertices = {Vec3(0, -1, -1), Vec3(0, 1, -1), Vec3(0, 1, 1), Vec3(0, -1, 1)};
    wall.triangles = {Tri(0, 1, 2), Tri(0, 2, 3)};
    auto shape = bullet::ScBulletShape::create(ModelKind::TriangleSoup, wall);
    ASSERT_TRUE(shape.ok()) << shape.status().message();
    w.addBody(shape.value(), 0.0, btVector3(0, 0, 0));
    const double start = 1.0 + phase * kSpeed * w.dt / kPhases;
    btRigidBody* ball =
        w.addBody(std::make_shared<btSphereShape>(0.05f), 0.1, btVector3(btScalar(start), 0, 0));
    ball->setLinearVelocity(btVector3(btScalar(-kSpeed), 0, 0));
    double min_x = start;
    for (int i = 0; i < 120; ++i) {
      w.step();
      min_x = std::min(min_x, double(ball->getCenterOfMassPosition().x()));
    }
    const double final_x = double(ball->getCenterOfMassPosition().x());
    passes += final_x < 0.0 ? 1 : 0;
    EXPECT_GT(min_x, -kSpeed * w.dt) << "phase " << phase;
    EXPECT_GT(final_x, 0.0) << "phase " << phase;
  }
  std::printf("[sphere tunnel potential] %d of %d shots passed\n", passes, kPhases);
}

}  // namespace
}  // namespace sc::test
