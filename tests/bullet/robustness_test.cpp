// SPDX-License-Identifier: MIT
// Overlap recovery (bodies spawned 25% overlapping separate with bounded energy)
// and no tunnelling (a small mesh at 50 m/s against a thin soup wall), with
// Bullet's btGImpactMeshShape in the same scene for comparison.
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bullet_world.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

class Recovery : public ::testing::TestWithParam<bullet::ContactModel> {};

TEST_P(Recovery, QuarterOverlapSeparatesWithBoundedEnergy) {
  BulletWorld w(GetParam(), 0.0);  // no gravity: all energy comes from the recovery
  auto box = boxShape(btVector3(0.5, 0.5, 0.5));
  btRigidBody* a = w.addBody(box, 1.0, btVector3(0, 0, 0));
  btRigidBody* b = w.addBody(box, 1.0, btVector3(0.75, 0.1, 0.05));  // 25% overlap along x
  const double speed = w.plugin->settings().recovery_speed;
  const double m_red = 0.5;
  double max_energy = 0.0;
  int separated_at = -1;
  for (int i = 0; i < 240 * 3; ++i) {
    w.step();
    max_energy = std::max(max_energy, w.kineticEnergy());
    const double gap = double(b->getCenterOfMassPosition().x() - a->getCenterOfMassPosition().x()) - 1.0;
    if (separated_at < 0 && gap > 0.0) separated_at = i;
  }
  const double gap = double(b->getCenterOfMassPosition().x() - a->getCenterOfMassPosition().x()) - 1.0;
  std::printf("[recovery] separated after %d steps, gap %.4f m, max kinetic energy %.4f J "
              "(bound 1/2 m_red v^2 = %.4f J)\n",
              separated_at, gap, max_energy, 0.5 * m_red * speed * speed);
  EXPECT_GE(separated_at, 0);
  EXPECT_GT(gap, 0.0);
  // The push leaves the pair at the recovery speed at most: relative kinetic energy
  // 1/2 m_red v^2 (the centre of mass does not move).
  EXPECT_LE(max_energy, 0.5 * m_red * speed * speed * (1.0 + 1e-3));
  EXPECT_LT(b->getAngularVelocity().length(), 1e-3);
}

// Boxes spawned exactly touching: the pairs are first seen intersecting (touching
// counts), get their depth at once (resolve_initial_intersection) and, being within
// the spring's reach, the contact model at once. Nothing may pop: the kinetic plus
// gravitational energy never rises above the spawn's.
TEST_P(Recovery, TowerSpawnedTouchingDoesNotPop) {
  BulletWorld w(GetParam());
  w.addGround();
  auto box = boxShape(btVector3(0.5, 0.5, 0.5));
  std::vector<btRigidBody*> boxes;
  for (int i = 0; i < 5; ++i) boxes.push_back(w.addBody(box, 1.0, btVector3(0, btScalar(i + 0.5), 0)));
  auto heights = [&] {
    double h = 0.0;
    for (btRigidBody* b : boxes) h += double(b->getCenterOfMassPosition().y());
    return h;
  };
  const double h0 = heights();
  double max_energy = 0.0, max_speed = 0.0;
  for (int i = 0; i < 480; ++i) {
    w.step();
    max_energy = std::max(max_energy, w.kineticEnergy() + 9.81 * (heights() - h0));
    for (btRigidBody* b : boxes) max_speed = std::max(max_speed, double(b->getLinearVelocity().length()));
  }
  const double top = double(boxes.back()->getCenterOfMassPosition().y());
  std::printf("[touching spawn] max speed %.4f m/s, energy above spawn %.2e J, top at %.4f m "
              "(spawned at 4.5)\n", max_speed, max_energy, top);
  EXPECT_LE(max_energy, 1e-3);
  // Both models: the rows hold the load at the velocity level (docs/bullet.md), so
  // the stack stays where it was spawned, within Bullet's slop.
  EXPECT_NEAR(top, 4.5, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Models, Recovery, bothContactModels(), contactModelName);

/// A 2 m x 2 m single-sheet wall (two triangles, zero thickness) in the plane x = 0.
MeshData wallMesh() {
  MeshData m;
  m.vertices = {Vec3(0, -1, -1), Vec3(0, 1, -1), Vec3(0, 1, 1), Vec3(0, -1, 1)};
  m.triangles = {Tri(0, 1, 2), Tri(0, 2, 3)};
  return m;
}

constexpr double kHalf = 0.05;   // 10 cm cube
constexpr double kSpeed = 50.0;  // 0.21 m per substep at 240 Hz: two cube sizes
constexpr int kPhases = 8;       // start offsets spread over one substep's travel

/// Where a shot ended: the wall is the plane x = 0, shots come from x > 0.
struct Shot {
  double min_x = 1e9;   ///< smallest centre x seen
  double final_x = 0.0;
  double final_vx = 0.0;
  bool passed() const { return final_x < 0.0; }
};

/// Fires `body` from x = start at -50 m/s and follows it for 0.5 s.
Shot fire(BulletWorld& w, btRigidBody* body, double start) {
  body->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(btScalar(start), 0, 0)));
  body->setLinearVelocity(btVector3(btScalar(-kSpeed), 0, 0));
  Shot s;
  for (int i = 0; i < 120; ++i) {
    w.step();
    s.min_x = std::min(s.min_x, double(body->getCenterOfMassPosition().x()));
  }
  s.final_x = double(body->getCenterOfMassPosition().x());
  s.final_vx = double(body->getLinearVelocity().x());
  return s;
}

double phaseStart(const BulletWorld& w, int phase) { return 1.0 + phase * kSpeed * w.dt / kPhases; }

TEST(Tunnelling, SmallMeshAtFiftyMetresPerSecondNeverPassesThinWall) {
  for (bullet::ContactModel model : {bullet::ContactModel::Potential}) {
    int passes = 0;
    double deepest = 1e9;
    for (int phase = 0; phase < kPhases; ++phase) {
      BulletWorld w(model, 0.0);
      auto wall = bullet::ScBulletShape::create(ModelKind::TriangleSoup, wallMesh());
      ASSERT_TRUE(wall.ok()) << wall.status().message();
      w.addBody(wall.value(), 0.0, btVector3(0, 0, 0));
      btRigidBody* shot = w.addBody(boxShape(btVector3(kHalf, kHalf, kHalf)), 0.1, btVector3(1, 0, 0));
      const Shot s = fire(w, shot, phaseStart(w, phase));
      passes += s.passed() ? 1 : 0;
      deepest = std::min(deepest, s.min_x);
      // Stopped in the substep it hit (at most one substep's travel behind the wall,
      // even when the cube was sampled wholly behind it), then pushed back out.
      EXPECT_GT(s.min_x, -kSpeed * w.dt) << "phase " << phase;
      EXPECT_GT(s.final_x, 0.0) << "phase " << phase;
    }
    std::printf("[tunnel %s] %d of %d shots passed; deepest centre x %.4f m\n",
                model == bullet::ContactModel::Potential ? "potential" : "manifold", passes,
                kPhases, deepest);
    EXPECT_EQ(passes, 0);
  }
}

/// Lowest point of `shape` (its stored vertices) placed at `pose`.
double lowestPoint(const bullet::ScBulletShape& shape, const btTransform& pose) {
  double y = 1e30;
  for (const btVector3& v : shape.vertices()) y = std::min(y, double(pose(v).y()));
  return y;
}

// A 30 cm cow landing at 6 m/s on a 1 cm plate at 60 Hz moves ten plate thicknesses
// a step. The detection after the integration skips a pair apart by more than its
// motion since its last query; once the motion may have closed the gap it must query
// the pair and put the cow back on the plate within the step: after every step the
// cow is no deeper than the tolerance the projection leaves (twice it, for the rows'
// spring), never a step's travel.
TEST(Tunnelling, MeshLandingFastOnThinPlateIsPutBackWithinTheStep) {
  constexpr double kFall = 6.0, kHz = 60.0, kThickness = 0.01;
  auto cow = bullet::ScBulletShape::create(ModelKind::ClosedPolyhedron, scaledOff("cow.off", 0.3));
  ASSERT_TRUE(cow.ok()) << cow.status().message();
  const double bottom = lowestPoint(*cow.value(), btTransform::getIdentity());
  double deepest = 0.0, tolerance = 0.0;
  int deepest_phase = -1;
  for (int phase = 0; phase < kPhases; ++phase) {
    BulletWorld w(bullet::ContactModel::Potential, 0.0, kHz);
    tolerance = w.plugin->settings().query.tolerance;
    auto plate = bullet::ScBulletShape::create(ModelKind::ClosedPolyhedron,
                                               boxMesh(Vec3(0.5, 0.5 * kThickness, 0.5)));
    ASSERT_TRUE(plate.ok()) << plate.status().message();
    w.addBody(plate.value(), 0.0, btVector3(0, btScalar(-0.5 * kThickness), 0));  // top at y = 0
    const double gap = 0.2 + phase * kFall / kHz / kPhases;  // spread over one step's travel
    btRigidBody* body = w.addBody(cow.value(), 1.0, btVector3(0, btScalar(gap - bottom), 0));
    body->setLinearVelocity(btVector3(0, btScalar(-kFall), 0));
    for (int i = 0; i < 30; ++i) {
      w.step();
      const double low = lowestPoint(*cow.value(), body->getWorldTransform());
      if (low < deepest) deepest = low, deepest_phase = phase;
    }
    EXPECT_GT(lowestPoint(*cow.value(), body->getWorldTransform()), -tolerance)
        << "phase " << phase;
  }
  std::printf("[thin plate] deepest after a step %.3f mm (phase %d), tolerance %.1f mm\n",
              -1e3 * deepest, deepest_phase, 1e3 * tolerance);
  EXPECT_GT(deepest, -2.0 * tolerance);
}

TEST(Tunnelling, ManifoldModelInTheSameSceneForComparison) {
  // Manifold model: the depth reaches Bullet's solver as one corner point; recorded,
  // not asserted (known to let the shot through today, see docs/bullet.md).
  int passes = 0;
  for (int phase = 0; phase < kPhases; ++phase) {
    BulletWorld w(bullet::ContactModel::Manifold, 0.0);
    auto wall = bullet::ScBulletShape::create(ModelKind::TriangleSoup, wallMesh());
    ASSERT_TRUE(wall.ok()) << wall.status().message();
    w.addBody(wall.value(), 0.0, btVector3(0, 0, 0));
    btRigidBody* shot = w.addBody(boxShape(btVector3(kHalf, kHalf, kHalf)), 0.1, btVector3(1, 0, 0));
    passes += fire(w, shot, phaseStart(w, phase)).passed() ? 1 : 0;
  }
  std::printf("[tunnel manifold] %d of %d shots passed through the wall\n", passes, kPhases);
  ::testing::Test::RecordProperty("manifold_passes", std::to_string(passes));
  SUCCEED();
}

TEST(Tunnelling, GImpactInTheSameSceneForComparison) {
  // Bullet's own concave-concave path: btGImpactMeshShape for both the wall and the cube.
  auto mesh_of = [](const MeshData& m) {
    auto tm = std::make_shared<btTriangleMesh>();
    for (const Tri& t : m.triangles) {
      btVector3 v[3];
      for (int k = 0; k < 3; ++k) {
        const Vec3& p = m.vertices[static_cast<std::size_t>(t[k])];
        v[k] = btVector3(btScalar(p.x()), btScalar(p.y()), btScalar(p.z()));
      }
      tm->addTriangle(v[0], v[1], v[2]);
    }
    return tm;
  };
  auto wall_mesh = mesh_of(wallMesh());
  auto cube_mesh = mesh_of(boxMesh(Vec3::Constant(kHalf)));
  int passes = 0;
  for (int phase = 0; phase < kPhases; ++phase) {
    BulletWorld w(bullet::ContactModel::Potential, 0.0);
    btGImpactCollisionAlgorithm::registerAlgorithm(w.dispatcher.get());
    auto wall = std::make_shared<btGImpactMeshShape>(wall_mesh.get());
    auto cube = std::make_shared<btGImpactMeshShape>(cube_mesh.get());
    wall->updateBound();
    cube->updateBound();
    w.addBody(wall, 0.0, btVector3(0, 0, 0));
    btRigidBody* shot = w.addBody(cube, 0.1, btVector3(1, 0, 0));
    passes += fire(w, shot, phaseStart(w, phase)).passed() ? 1 : 0;
  }
  std::printf("[tunnel gimpact] %d of %d shots passed through the wall\n", passes, kPhases);
  ::testing::Test::RecordProperty("gimpact_passes", std::to_string(passes));
  // Only a record: GImpact's outcome is Bullet's, reported in docs/bullet.md.
  SUCCEED();
}

}  // namespace
}  // namespace sc::test
