// SPDX-License-Identifier: MIT
// A btCompoundShape of ScBulletShape children (Bullet's compound algorithm, one pair
// per child) landing on the ground: the children's impacts are one body's, so a drop
// never comes back with more energy than it had, and the body comes to rest.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "bullet_world.h"

namespace sc::test {
namespace {

struct CompoundDrop {
  int children;
  double hz;
};

class CompoundLanding : public ::testing::TestWithParam<CompoundDrop> {};

// Before, each child's impact impulse stopped the whole body: two children landing
// together sent it back up at the speed it came down (99 % of the drop's energy), three
// at twice it (335 %), four launched it 40 m.
TEST_P(CompoundLanding, NeverGainsEnergyAndComesToRest) {
  const CompoundDrop p = GetParam();
  BulletWorld w(bullet::ContactModel::Potential, -9.81, p.hz);
  w.addGround();
  const auto child = boxShape(btVector3(0.1f, 0.1f, 0.1f));
  auto compound = std::make_shared<btCompoundShape>();
  for (int k = 0; k < p.children; ++k) {
    const btScalar x = btScalar((k - (p.children - 1) / 2.0) * 0.3);
    compound->addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(x, 0, 0)),
                            child.get());
  }
  w.shapes.push_back(child);  // the compound holds it by pointer
  const double drop = 0.5, g = 9.81;
  btRigidBody* body = w.addBody(compound, 1.0, btVector3(0, btScalar(0.1 + drop), 0));
  const double start = g * (0.1 + drop);  // per kg, the ground at y = 0
  double most = 0.0, speed = 0.0;
  const int steps = static_cast<int>(5 * p.hz), landed = static_cast<int>(p.hz);
  for (int i = 0; i < steps; ++i) {
    w.step();
    if (i < landed) continue;  // the drop itself
    const double y = body->getCenterOfMassPosition().y();
    const double v = body->getLinearVelocity().length();
    most = std::max(most, g * y + 0.5 * v * v);
    // The largest over the last second: a body that falls one step in four while
    // resting (rows of offset children dropped) can read slow at any one step.
    if (i >= steps - landed) speed = std::max(speed, v);
  }
  EXPECT_LT(most, g * 0.1 + 0.1 * (start - g * 0.1)) << "bounced back up";
  EXPECT_NEAR(body->getCenterOfMassPosition().y(), 0.1, 2e-3);
  EXPECT_LT(speed, 1e-2);
  EXPECT_LT(body->getAngularVelocity().length(), 1e-2);
}

// The same with two bodies under one: a plank landing flat on two static blocks at once
// (two pairs, each measuring the whole approach).
TEST(PlankLanding, OnTwoSupportsAtOnceNeverGainsEnergy) {
  BulletWorld w(bullet::ContactModel::Potential, -9.81, 60.0);
  const auto block = boxShape(btVector3(0.2f, 0.2f, 0.2f));
  w.addBody(block, 0.0, btVector3(-0.6f, 0.2f, 0));
  w.addBody(block, 0.0, btVector3(0.6f, 0.2f, 0));
  btRigidBody* plank =
      w.addBody(boxShape(btVector3(1.0f, 0.05f, 0.2f)), 1.0, btVector3(0, 1.0f, 0));
  const double g = 9.81, rest = 0.45, start = g * 1.0;
  double most = 0.0;
  for (int i = 0; i < 300; ++i) {
    w.step();
    if (i < 60) continue;
    const double v = plank->getLinearVelocity().length();
    most = std::max(most, g * plank->getCenterOfMassPosition().y() + 0.5 * v * v);
  }
  EXPECT_LT(most, g * rest + 0.1 * (start - g * rest)) << "bounced back up";
  EXPECT_NEAR(plank->getCenterOfMassPosition().y(), rest, 2e-3);
}

INSTANTIATE_TEST_SUITE_P(Children, CompoundLanding,
                         ::testing::Values(CompoundDrop{2, 60.0}, CompoundDrop{3, 60.0},
                                           CompoundDrop{4, 60.0}, CompoundDrop{4, 240.0}),
                         [](const ::testing::TestParamInfo<CompoundDrop>& i) {
                           return std::to_string(i.param.children) + "ChildrenAt" +
                                  std::to_string(static_cast<int>(i.param.hz)) + "Hz";
                         });

}  // namespace
}  // namespace sc::test
