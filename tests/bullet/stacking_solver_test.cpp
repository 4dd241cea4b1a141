// SPDX-License-Identifier: MIT
// StackingSolver: Bullet's own btBoxShape boxes in a 1:1000 stack (1, 1000, 1, 1000 kg,
// 0.5 m, 60 Hz) stand with it and fall with Bullet's plain sequential-impulse solver;
// solve groups without a large mass ratio, or without gravity, move exactly as under
// Bullet's solver. Overlaps are measured exactly from the boxes' corners.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "bullet_world.h"

namespace sc::test {
namespace {

constexpr double kHalf = 0.25;  // box half edge [m]
constexpr double kSeconds = SC_TEST_SANITIZED ? 2.0 : 10.0;

/// Swaps the world's solver for Bullet's plain one.
void usePlainSolver(BulletWorld& w) {
  auto plain = std::make_unique<btSequentialImpulseConstraintSolver>();
  w.world->setConstraintSolver(plain.get());
  w.solver = std::move(plain);
}

std::vector<btRigidBody*> addBoxColumn(BulletWorld& w, const std::vector<double>& masses,
                                       double shift = 0.0) {
  w.addGround();
  auto box = std::make_shared<btBoxShape>(btVector3(kHalf, kHalf, kHalf));
  std::vector<btRigidBody*> column;
  for (std::size_t i = 0; i < masses.size(); ++i) {
    const double y = (2.0 * double(i) + 1.0) * kHalf + 0.002 * double(i + 1);
    const double x = shift * double(i);
    column.push_back(w.addBody(box, masses[i], btVector3(btScalar(x), btScalar(y), 0)));
  }
  return column;
}

struct Outcome {
  double overlap = 0.0;  ///< largest overlap over the last second [m]
  double drift = 0.0;    ///< largest horizontal displacement [m]
  double rms = 0.0;      ///< RMS speed over the last second [m/s]
};

Outcome runBoxColumn(bool stacking, double hz) {
  BulletWorld w(bullet::ContactModel::Potential, -9.81, hz);
  if (!stacking) usePlainSolver(w);
  const std::vector<btRigidBody*> column = addBoxColumn(w, {1.0, 1000.0, 1.0, 1000.0});
  Outcome o;
  const int steps = static_cast<int>(std::lround(kSeconds * hz));
  const int last = static_cast<int>(std::lround(hz));
  const ColumnMotion m = stepColumn(w, column, steps, last, [&] {
    o.overlap = std::max(o.overlap, boxCornerDepth(*column[0], nullptr, kHalf));
    for (std::size_t k = 1; k < column.size(); ++k) {
      o.overlap = std::max(o.overlap, boxCornerDepth(*column[k], column[k - 1], kHalf));
      o.overlap = std::max(o.overlap, boxCornerDepth(*column[k - 1], column[k], kHalf));
    }
  });
  o.drift = m.drift;
  o.rms = m.rms_speed;
  std::printf(
      "[btBoxShape 1:1000 %.0f Hz, %s] overlap %.2f mm, rms speed %.2e m/s, drift %.2f mm\n", hz,
      stacking ? "StackingSolver" : "plain solver", 1e3 * o.overlap, o.rms, 1e3 * o.drift);
  return o;
}

TEST(StackingSolver, BulletBoxesAtOneToThousandStand) {
  for (const double hz : {60.0, 240.0}) {
    const Outcome o = runBoxColumn(true, hz);
    EXPECT_LE(o.overlap, 0.005) << hz << " Hz";
    EXPECT_LE(o.rms, 0.01) << hz << " Hz";
    EXPECT_LE(o.drift, 0.01) << hz << " Hz";
  }
  // The scene is one Bullet's plain solver cannot hold (the light boxes are squeezed out).
  const Outcome plain = runBoxColumn(false, 60.0);
  EXPECT_GT(plain.drift, 0.1);
}

/// Final poses of a run, for exact comparison between solvers.
std::vector<btTransform> finalPoses(bool stacking, const std::vector<double>& masses,
                                    double gravity) {
  BulletWorld w(bullet::ContactModel::Potential, gravity, 60.0);
  if (!stacking) usePlainSolver(w);
  // Shifted boxes: the contacts are not symmetric, the tower leans and settles.
  const std::vector<btRigidBody*> column = addBoxColumn(w, masses, 0.03);
  if (gravity == 0.0) column.back()->setLinearVelocity(btVector3(0, -1, 0));
  w.step(120);
  std::vector<btTransform> poses;
  for (btRigidBody* b : column) poses.push_back(b->getWorldTransform());
  return poses;
}

TEST(StackingSolver, WithoutAMassRatioOrGravityBulletsSolutionIsKept) {
  const std::vector<std::vector<double>> cases = {{1.0, 1.0, 1.0, 1.0}, {1.0, 5.0, 1.0, 9.0}};
  for (const auto& masses : cases) {
    const std::vector<btTransform> a = finalPoses(true, masses, -9.81);
    const std::vector<btTransform> b = finalPoses(false, masses, -9.81);
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].getOrigin(), b[i].getOrigin()) << "body " << i;
      EXPECT_EQ(a[i].getRotation(), b[i].getRotation()) << "body " << i;
    }
  }
  // No gravity: no up, no sweeps, even at 1:1000.
  const std::vector<btTransform> a = finalPoses(true, {1.0, 1000.0, 1.0, 1000.0}, 0.0);
  const std::vector<btTransform> b = finalPoses(false, {1.0, 1000.0, 1.0, 1000.0}, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].getOrigin(), b[i].getOrigin());
}

// A 1000 kg box dropped 0.1 m onto a 1 kg box on the ground, off centre by 0.1 m, at
// 60 Hz, through the plugin's contacts: the sweeps take the impact without adding
// energy (kinetic plus gravitational never above the drop's), and the pair ends at rest
// with millimetre overlaps, the light box in place.
class StackingSolverDrop : public ::testing::TestWithParam<bullet::ContactModel> {};

TEST_P(StackingSolverDrop, HeavyOnLightGainsNoEnergy) {
  BulletWorld w(GetParam(), -9.81, 60.0);
  w.addGround();
  auto box = boxShape(btVector3(kHalf, kHalf, kHalf));
  btRigidBody* light = w.addBody(box, 1.0, btVector3(0, btScalar(kHalf + 0.002), 0));
  btRigidBody* heavy = w.addBody(box, 1000.0, btVector3(0.1f, btScalar(3 * kHalf + 0.1), 0));
  auto energy = [&] {
    return w.kineticEnergy() + 9.81 * (double(light->getCenterOfMassPosition().y()) +
                                       1000.0 * double(heavy->getCenterOfMassPosition().y()));
  };
  const double start = energy();
  double rise = 0.0, drift = 0.0, overlap = 0.0;
  const int steps = static_cast<int>(std::lround(kSeconds * 60.0));
  for (int i = 0; i < steps; ++i) {
    w.step();
    rise = std::max(rise, energy() - start);
    const btVector3 p = light->getCenterOfMassPosition();
    drift = std::max(drift, std::hypot(double(p.x()), double(p.z())));
    if (i >= steps - 60) overlap = std::max(overlap, boxCornerDepth(*heavy, light, kHalf));
  }
  const double rms = std::sqrt(w.kineticEnergy() / 1001.0 * 2.0);
  std::printf(
      "[drop 1000 kg on 1 kg, 60 Hz, %s] energy rise %.2e J (of %.0f J), light box "
      "drift %.2f mm, overlap %.2f mm, speed %.1e m/s\n",
      GetParam() == bullet::ContactModel::Potential ? "potential" : "manifold", rise, start,
      1e3 * drift, 1e3 * overlap, rms);
  // Allowance: the heavy box's height rounded in Bullet's floats (spacing 1.2e-7 m at 1 m).
  EXPECT_LE(rise, 1000.0 * 9.81 * 2.4e-7);
  EXPECT_LE(drift, 0.01);
  EXPECT_LE(overlap, 0.005);
  EXPECT_LE(rms, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Models, StackingSolverDrop, bothContactModels(), contactModelName);

}  // namespace
}  // namespace sc::test
