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
#include "support/off_reader.h"

namespace sc::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Closed hemispherical bowl (opening up, rim at y = 0): outer radius `outer`, inner
/// `inner`, `rings` latitude rings per surface and `segments` around.
MeshData bowlMesh(double inner, double outer, int rings, int segments) {
  MeshData m;
  auto ring = [&](double r, int k) {  // vertex index of ring k's first vertex on radius r
    const int first = static_cast<int>(m.vertices.size());
    const double phi = 0.5 * kPi * k / rings;  // from the bottom pole
    for (int j = 0; j < segments; ++j) {
      const double theta = 2 * kPi * j / segments;
      m.vertices.emplace_back(r * std::sin(phi) * std::cos(theta), -r * std::cos(phi),
                              r * std::sin(phi) * std::sin(theta));
    }
    return first;
  };
  // Orients each triangle so that its normal agrees with `outward` (solid's outside).
  auto add = [&](int a, int b, int c, const Vec3& outward) {
    const Vec3& pa = m.vertices[static_cast<std::size_t>(a)];
    const Vec3 n = (m.vertices[static_cast<std::size_t>(b)] - pa)
                       .cross(m.vertices[static_cast<std::size_t>(c)] - pa);
    m.triangles.push_back(n.dot(outward) >= 0 ? Tri(a, b, c) : Tri(a, c, b));
  };
  auto centroid = [&](int a, int b, int c) {
    return Vec3((m.vertices[static_cast<std::size_t>(a)] + m.vertices[static_cast<std::size_t>(b)] +
                 m.vertices[static_cast<std::size_t>(c)]) /
                3.0);
  };
  int rims[2] = {0, 0};
  for (int s = 0; s < 2; ++s) {
    const double r = s == 0 ? outer : inner;
    const double sign = s == 0 ? 1.0 : -1.0;  // outer faces away from the centre, inner towards
    const int pole = static_cast<int>(m.vertices.size());
    m.vertices.emplace_back(0, -r, 0);
    int prev = -1;
    for (int k = 1; k <= rings; ++k) {
      const int cur = ring(r, k);
      for (int j = 0; j < segments; ++j) {
        const int j1 = (j + 1) % segments;
        if (prev < 0) {
          add(pole, cur + j, cur + j1, sign * centroid(pole, cur + j, cur + j1));
        } else {
          add(prev + j, cur + j, cur + j1, sign * centroid(prev + j, cur + j, cur + j1));
          add(prev + j, cur + j1, prev + j1, sign * centroid(prev + j, cur + j1, prev + j1));
        }
      }
      prev = cur;
    }
    rims[s] = prev;
  }
  for (int j = 0; j < segments; ++j) {  // the flat rim joins the two surfaces
    const int j1 = (j + 1) % segments;
    add(rims[0] + j, rims[1] + j, rims[1] + j1, Vec3::UnitY());
    add(rims[0] + j, rims[1] + j1, rims[0] + j1, Vec3::UnitY());
  }
  return m;
}

/// The bunny scaled so that its largest extent is `size`, centred on its bounds.
MeshData scaledBunny(double size) {
  Result<MeshData> read = readOff(std::string(SC_MESH_DIR) + "/bunny00.off");
  if (!read.ok()) return {};
  MeshData m = read.value();
  Vec3 lo = m.vertices[0], hi = m.vertices[0];
  for (const Vec3& v : m.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const double scale = size / (hi - lo).maxCoeff();
  for (Vec3& v : m.vertices) v = (v - 0.5 * (lo + hi)) * scale;
  return m;
}

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

// Jitter bound at rest (both models): the centre stays within 1 mm of where it settled
// and moves at under 5 mm/s RMS over 1.5 s; the bunny is 80 mm long.
TEST(BunnyInBowl, RestsWithoutJitterInBothModels) {
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
  for (bullet::ContactModel model :
       {bullet::ContactModel::Potential, bullet::ContactModel::Manifold}) {
    const Rest r = dropIntoBowl(model, bowl.value(), bunny.value(), 3.0, 1.5);
    const char* name = model == bullet::ContactModel::Potential ? "potential" : "manifold";
    std::printf(
        "[bunny in bowl %s] wander %.3f mm, rms speed %.2e m/s, max spin %.2e rad/s, "
        "centre at y %.4f m, %.3f ms/step\n",
        name, 1e3 * r.wander, r.rms_speed, r.max_spin, r.height, r.ms_per_step);
    EXPECT_LT(r.wander, 1e-3) << name;
    EXPECT_LT(r.rms_speed, 5e-3) << name;
    // In the bowl, near its bottom (inner radius 0.12 m): neither out nor through it.
    EXPECT_LT(r.height, -0.06) << name;
    EXPECT_GT(r.height, -0.12) << name;
  }
}

}  // namespace
}  // namespace sc::test
