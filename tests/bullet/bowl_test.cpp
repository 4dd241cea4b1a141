// SPDX-License-Identifier: MIT
// Real meshes at rest: CGAL's bunny (75k triangles) dropped into a non-convex bowl
// settles and then stays put, in both contact models, with its jitter bounded.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "bullet_world.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

/// The bunny scaled so that its largest extent is `size`, centred on its bounds.
MeshData scaledBunny(double size) { return scaledOff("bunny00.off", size); }

struct Rest {
  double wander = 0.0;     ///< largest distance from the settled position [m]
  double rms_speed = 0.0;  ///< RMS speed of the centre [m/s]
  double max_spin = 0.0;   ///< largest angular speed [rad/s]
  double height = 0.0;     ///< final centre height [m]
  double ms_per_step = 0.0;
};

/// Drops `shape` into the bowl, lets it settle for `settle` s, then measures `watch` s.
Rest dropIntoBowl(bullet::ContactModel model, const std::shared_ptr<bullet::ScBulletShape>& bowl,
                  const std::shared_ptr<bullet::ScBulletShape>& bunny, double settle,
                  double watch) {
  BulletWorld w(model);
  w.addBody(bowl, 0.0, btVector3(0, 0, 0));
  btRigidBody* body = w.addBody(bunny, 0.5, btVector3(0.01f, -0.06f, 0));
  w.step(static_cast<int>(std::lround(settle / w.dt)));
  const btVector3 settled = body->getCenterOfMassPosition();
  Rest r;
  const int steps = static_cast<int>(std::lround(watch / w.dt));
  double sum_v2 = 0.0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) {
    w.step();
    r.wander = std::max(r.wander, double((body->getCenterOfMassPosition() - settled).length()));
    sum_v2 += double(body->getLinearVelocity().length2());
    r.max_spin = std::max(r.max_spin, double(body->getAngularVelocity().length()));
  }
  r.ms_per_step =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() /
      steps;
  r.rms_speed = std::sqrt(sum_v2 / steps);
  r.height = double(body->getCenterOfMassPosition().y());
  return r;
}

TEST(BowlMesh, IsAClosedNonConvexPolyhedron) {
  Result<PiecePtr> piece = buildPiece(ModelKind::ClosedPolyhedron, bowlMesh(0.12, 0.13, 12, 32));
  ASSERT_TRUE(piece.ok()) << piece.status().message();
  EXPECT_FALSE(piece.value()->stats().convex);
  EXPECT_FALSE(piece.value()->stats().flipped);
}

// Jitter bound at rest: the centre stays within 1 mm of where it settled and moves at
// under 5 mm/s RMS over 1.5 s; the bunny is 80 mm long. One test per contact model, so
// that they run side by side.
class BunnyInBowl : public ::testing::TestWithParam<bullet::ContactModel> {};

TEST_P(BunnyInBowl, RestsWithoutJitter) {
  if (SC_TEST_SANITIZED) GTEST_SKIP() << "the 75k-triangle bunny runs in the Release pass only";
  const MeshData bunny_mesh = scaledBunny(0.08);
  ASSERT_FALSE(bunny_mesh.triangles.empty()) << "bunny00.off missing from " SC_MESH_DIR;
  auto bunny = bullet::ScBulletShape::create(ModelKind::ClosedPolyhedron, bunny_mesh);
  ASSERT_TRUE(bunny.ok()) << bunny.status().message();
  bullet::ShapeOptions fixed;
  fixed.recenter = false;  // static: keep the bowl's frame (rim at y = 0)
  auto bowl = bullet::ScBulletShape::create(ModelKind::ClosedPolyhedron,
                                            bowlMesh(0.12, 0.13, 12, 32), fixed);
  ASSERT_TRUE(bowl.ok()) << bowl.status().message();
  const bullet::ContactModel model = GetParam();
  const Rest r = dropIntoBowl(model, bowl.value(), bunny.value(), 3.0, 1.5);
  const char* name = model == bullet::ContactModel::Potential ? "potential" : "manifold";
  std::printf(
      "[bunny in bowl %s] wander %.3f mm, rms speed %.2e m/s, max spin %.2e rad/s, "
      "centre at y %.4f m, %.3f ms/step\n",
      name, 1e3 * r.wander, r.rms_speed, r.max_spin, r.height, r.ms_per_step);
  EXPECT_LT(r.wander, 1e-3);
  EXPECT_LT(r.rms_speed, 5e-3);
  // In the bowl, near its bottom (inner radius 0.12 m): neither out nor through it.
  EXPECT_LT(r.height, -0.06);
  EXPECT_GT(r.height, -0.12);
}

INSTANTIATE_TEST_SUITE_P(Models, BunnyInBowl, bothContactModels(), contactModelName);

}  // namespace
}  // namespace sc::test
