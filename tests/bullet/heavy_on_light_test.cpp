// SPDX-License-Identifier: MIT
// A heavy mesh body on a light box comes to rest: a CGAL cow (0.5 m, 100 or 1000 kg) on
// a 1 kg slab or box at 60 Hz with the StackingSolver, in both contact models, as 1:1000 stacks of
// boxes stand. The cow's feet on the box are one patch of rows that must stay the same from step to
// step: a step whose rows lose part of the support drops a 1000 kg cow by a good part
// of g dt^2 (2.7 mm at 60 Hz) onto a 1 kg body, and it comes back up kicked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <tuple>

#include "bullet_world.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

struct HeavyOnLight {
  double cow_mass;      ///< [kg]
  double light_half_x;  ///< half extents of the 1 kg box under the cow [m]
  double light_half_y;
  double rms_bound;  ///< on the RMS speed over the last second [m/s]
};

struct Rest {
  double rms_speed = 0.0;  ///< of both bodies over the last second [m/s]
  double max_speed = 0.0;  ///< largest speed of either body after settling [m/s]
};

constexpr double kHz = 60.0;
constexpr double kSettle = 2.0;   // [s] the landing from 5 mm and its rocking
constexpr double kWatched = 3.0;  // [s] after settling

Rest standCow(bullet::ContactModel model, const HeavyOnLight& p,
              const std::shared_ptr<bullet::ScBulletShape>& cow) {
  BulletWorld w(model, -9.81, kHz);
  w.addGround();
  const double hx = p.light_half_x, hy = p.light_half_y;
  btRigidBody* light = w.addBody(boxShape(btVector3(btScalar(hx), btScalar(hy), btScalar(hx))), 1.0,
                                 btVector3(0, btScalar(hy), 0));
  double lowest = std::numeric_limits<double>::infinity();
  for (const btVector3& v : cow->vertices()) lowest = std::min(lowest, double(v.y()));
  btRigidBody* heavy =
      w.addBody(cow, p.cow_mass, btVector3(0, btScalar(2 * hy + 0.005 - lowest), 0));
  Rest r;
  const int settle = static_cast<int>(kSettle * kHz), watched = static_cast<int>(kWatched * kHz);
  const int last_second = static_cast<int>(kHz);
  double sum_v2 = 0.0;
  for (int k = 0; k < settle + watched; ++k) {
    w.step();
    if (k < settle) continue;
    for (const btRigidBody* b : {light, heavy}) {
      const double v2 = double(b->getLinearVelocity().length2());
      r.max_speed = std::max(r.max_speed, std::sqrt(v2));
      if (k >= settle + watched - last_second) sum_v2 += v2;
    }
  }
  r.rms_speed = std::sqrt(sum_v2 / (2.0 * last_second));
  return r;
}

using Case = std::tuple<bullet::ContactModel, HeavyOnLight>;

std::string caseName(const ::testing::TestParamInfo<Case>& c) {
  const bool tonne = std::get<1>(c.param).cow_mass >= 1000.0;
  return contactModelName({std::get<0>(c.param), c.index}) +
         (tonne ? "TonneOnSlab" : "HundredKgOnBox");
}

class HeavyCowOnLightBox : public ::testing::TestWithParam<Case> {};

// Bounds. RMS: below the 1:1000 stack of boxes' figure at 60 Hz (docs/bullet.md: 5.4e-3
// m/s potential, 4.7e-3 manifold), and below what the cow did while one of its patch's
// five rows took another's place in the manifold every step (1000 kg: 2.5e-3 m/s
// potential; 100 kg: 8.5e-4; now 1.7e-3 and 3.6e-4). Over the light box the 1000 kg
// cow still rocks on its four feet by a few mm/s where boxes stand on a face (on the
// static ground it rests at 1e-6). Kicks: a step whose rows lose a share s of the weight leaves the
// cow falling at s g dt (0.16 m/s for all of it at 60 Hz); the kicks of a patch that came and went
// reached 0.04-0.08 m/s. None above a tenth of g dt.
TEST_P(HeavyCowOnLightBox, ComesToRestWithoutKicks) {
  const bullet::ContactModel model = std::get<0>(GetParam());
  const HeavyOnLight p = std::get<1>(GetParam());
  const MeshData mesh = scaledOff("cow.off", 0.5);
  ASSERT_FALSE(mesh.triangles.empty()) << "cow.off missing from " SC_MESH_DIR;
  auto cow = bullet::ScBulletShape::create(ModelKind::ClosedPolyhedron, mesh);
  ASSERT_TRUE(cow.ok()) << cow.status().message();
  const Rest r = standCow(model, p, cow.value());
  std::printf(
      "[%s: %.0f kg cow on a 1 kg box %.1f x %.1f m] rms speed (last second) %.2e m/s, "
      "largest speed after %.0f s %.2e m/s\n",
      model == bullet::ContactModel::Potential ? "potential" : "manifold", p.cow_mass,
      2 * p.light_half_x, 2 * p.light_half_y, r.rms_speed, kSettle, r.max_speed);
  EXPECT_LT(r.rms_speed, p.rms_bound);
  EXPECT_LT(r.max_speed, 0.1 * 9.81 / kHz);
}

INSTANTIATE_TEST_SUITE_P(
    Cows, HeavyCowOnLightBox,
    ::testing::Combine(bothContactModels(),
                       ::testing::Values(HeavyOnLight{1000.0, 0.6, 0.05, 2.1e-3},
                                         HeavyOnLight{100.0, 0.25, 0.25, 6e-4})),
    caseName);

}  // namespace
}  // namespace sc::test
