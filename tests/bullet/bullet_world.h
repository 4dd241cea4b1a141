// SPDX-License-Identifier: MIT
// A small Bullet world with the SmartCollision plugin for the plugin's tests:
// owns the Bullet objects, adds bodies, steps at a fixed rate, measures energy.
#pragma once

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
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

/// Both contact models: the parameter of tests run for each.
inline auto bothContactModels() {
  return ::testing::Values(bullet::ContactModel::Potential, bullet::ContactModel::Manifold);
}

/// Parameter name of tests run for both contact models.
inline std::string contactModelName(const ::testing::TestParamInfo<bullet::ContactModel>& info) {
  return info.param == bullet::ContactModel::Potential ? "Potential" : "Manifold";
}

/// Parameter name of tests run for both contact models at each of several rates (Hz).
inline std::string contactModelRateName(
    const ::testing::TestParamInfo<std::tuple<bullet::ContactModel, int>>& info) {
  return contactModelName({std::get<0>(info.param), info.index}) + "At" +
         std::to_string(std::get<1>(info.param)) + "Hz";
}

/// How a column of bodies moved while stepped: the largest horizontal distance of a
/// centre from the y axis over the whole run, and the RMS speed over its last steps.
struct ColumnMotion {
  double drift = 0.0;      ///< [m]
  double rms_speed = 0.0;  ///< [m/s]
};

/// Steps `w` `steps` times; the RMS speed is over the last `last` steps, after each of
/// which `each_last()` runs (the caller's own figures, such as overlaps).
template <class EachLast>
ColumnMotion stepColumn(BulletWorld& w, const std::vector<btRigidBody*>& column, int steps,
                        int last, EachLast each_last) {
  ColumnMotion m;
  double s2 = 0.0;
  int samples = 0;
  for (int i = 0; i < steps; ++i) {
    w.step();
    for (btRigidBody* b : column) {
      const btVector3 p = b->getCenterOfMassPosition();
      m.drift = std::max(m.drift, std::hypot(double(p.x()), double(p.z())));
    }
    if (i < steps - last) continue;
    each_last();
    for (btRigidBody* b : column) s2 += double(b->getLinearVelocity().length2());
    samples += static_cast<int>(column.size());
  }
  m.rms_speed = std::sqrt(s2 / std::max(1, samples));
  return m;
}

/// "None", "Input", "Free" or "Mix": a rotation mode in test names and reports.
inline const char* modeName(RotationMode m) {
  constexpr std::pair<RotationMode, const char*> kNames[] = {{RotationMode::None, "None"},
                                                             {RotationMode::Input, "Input"},
                                                             {RotationMode::Free, "Free"},
                                                             {RotationMode::Mix, "Mix"}};
  for (const auto& [mode, name] : kNames)
    if (mode == m) return name;
  return "?";
}

/// Deepest corner of box `a` inside box `b` (both cubes of half edge `half`), or below
/// the ground (y < 0) when `b` is null; 0 when none is inside. Exact, for overlaps
/// measured independently of SmartCollision.
double boxCornerDepth(const btRigidBody& a, const btRigidBody* b, double half);

/// Closest distance of a pair through Bullet's contactPairTest (the closest-points
/// table), or NaN when nothing was reported within `threshold`.
double closestDistance(BulletWorld& w, btCollisionObject* a, btCollisionObject* b,
                       double threshold = 2.0);

/// An ScBulletShape of a closed box mesh (half extents h); fails the test on error.
std::shared_ptr<bullet::ScBulletShape> boxShape(const btVector3& h);

}  // namespace sc::test
