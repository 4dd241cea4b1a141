// SPDX-License-Identifier: MIT
// Passive pairs cost nothing: a pair apart by more than the bodies can have moved
// since its last query is not queried again, nor a pair at rest in contact, and a
// body approaching fast is still caught at the surface (the skip is conservative,
// never a tunnel).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "bullet_world.h"

namespace sc::test {
namespace {

constexpr double kHalf = 0.25;  // 0.5 m boxes
const double kSqrt2 = std::sqrt(2.0);

struct DiagonalPair {
  btRigidBody* a;
  btRigidBody* b;
};

/// Box a axis-aligned at the origin; box b turned 45 degrees about z on the diagonal
/// x = y at `d`: a's corner faces b's face, so their AABBs overlap while the boxes are
/// `gap(d)` apart.
DiagonalPair diagonalPair(BulletWorld& w, double d) {
  auto shape = boxShape(btVector3(btScalar(kHalf), btScalar(kHalf), btScalar(kHalf)));
  btRigidBody* a = w.addBody(shape, 1.0, btVector3(0, 0, 0));
  btRigidBody* b = w.addBody(shape, 1.0, btVector3(btScalar(d), btScalar(d), 0),
                             btQuaternion(btVector3(0, 0, 1), btScalar(0.25 * M_PI)));
  return {a, b};
}

/// Surface gap along the diagonal: centre distance minus a's corner and b's face.
double gap(const DiagonalPair& p) {
  const btVector3 c = p.b->getCenterOfMassPosition() - p.a->getCenterOfMassPosition();
  return double(c.dot(btVector3(1, 1, 0).normalized())) - kSqrt2 * kHalf - kHalf;
}

TEST(PassivePairs, RestingPairApartIsNotQueriedAgain) {
  BulletWorld w(bullet::ContactModel::Potential, 0.0, 60.0);
  const DiagonalPair p = diagonalPair(w, 0.55);
  ASSERT_GT(gap(p), 0.15);
  w.step();
  EXPECT_EQ(w.plugin->stats().pairs, 1);  // the AABBs overlap: the pair is ours
  EXPECT_EQ(w.plugin->stats().skipped, 0);
  for (int i = 0; i < 10; ++i) {
    w.step();
    EXPECT_EQ(w.plugin->stats().pairs, 1);
    EXPECT_EQ(w.plugin->stats().skipped, 1);
  }
}

class RestingPair : public ::testing::TestWithParam<bullet::ContactModel> {};

// A box at rest on a fixed one keeps the rows of its last query (and its figures)
// while it stays within a hundredth of the tolerance of that query's pose; a push, or
// new settings, make the pair measure again.
TEST_P(RestingPair, KeepsItsRowsUntilMovedOrResettled) {
  BulletWorld w(GetParam(), -9.81, 60.0);
  auto shape = boxShape(btVector3(btScalar(kHalf), btScalar(kHalf), btScalar(kHalf)));
  w.addBody(shape, 0.0, btVector3(0, 0, 0));
  btRigidBody* top = w.addBody(shape, 1.0, btVector3(0, btScalar(2 * kHalf + 0.001), 0));
  w.step(120);  // settled
  const btVector3 rest = top->getCenterOfMassPosition();
  int reused = 0;
  for (int i = 0; i < 30; ++i) {
    w.step();
    const bullet::StepStats& s = w.plugin->stats();
    EXPECT_EQ(s.pairs, 1);
    EXPECT_GE(s.rows, 4);  // the kept rows, counted as when measured
    reused += s.reused;
  }
  EXPECT_GE(reused, 25);
  EXPECT_LT(double((top->getCenterOfMassPosition() - rest).length()), 1e-4);  // still held
  top->setLinearVelocity(btVector3(0.5f, 0, 0));  // slides 8 mm a step
  w.step();
  w.step();
  EXPECT_EQ(w.plugin->stats().reused, 0);
  EXPECT_GE(w.plugin->stats().rows, 4);
  top->setLinearVelocity(btVector3(0, 0, 0));
  w.step(60);
  bullet::PluginSettings s = w.plugin->settings();
  s.contact.friction_scale *= 0.5;
  ASSERT_TRUE(w.plugin->setSettings(s).ok());
  w.step();
  EXPECT_EQ(w.plugin->stats().reused, 0);  // rows made under other settings
}

INSTANTIATE_TEST_SUITE_P(Models, RestingPair, bothContactModels(), contactModelName);

class PassiveApproach : public ::testing::TestWithParam<bullet::ContactModel> {};

// b flies at a at 3 m/s (5 cm a step at 60 Hz): skipped while far, queried once its
// motion could close the gap, and stopped at a's corner.
TEST_P(PassiveApproach, FastApproachIsCaughtAtTheSurface) {
  BulletWorld w(GetParam(), 0.0, 60.0);
  const DiagonalPair p = diagonalPair(w, 0.58);
  p.b->setLinearVelocity(btVector3(-1, -1, 0).normalized() * 3.0f);
  int skipped = 0, queried = 0;
  double min_gap = gap(p);
  for (int i = 0; i < 60; ++i) {
    w.step();
    skipped += w.plugin->stats().skipped;
    queried += w.plugin->stats().pairs - w.plugin->stats().skipped;
    min_gap = std::min(min_gap, gap(p));
  }
  EXPECT_GT(skipped, 0);
  EXPECT_GT(queried, 1);
  EXPECT_GT(min_gap, -0.005);  // never through the corner (contact rows hold it)
  // Momentum shared at restitution 0: both end up moving together, apart by < 1 cm.
  const btVector3 rel = p.b->getLinearVelocity() - p.a->getLinearVelocity();
  EXPECT_LT(double(rel.dot(btVector3(-1, -1, 0).normalized())), 0.5);
  EXPECT_LT(gap(p), 0.01);
}

INSTANTIATE_TEST_SUITE_P(Models, PassiveApproach, bothContactModels(), contactModelName);

}  // namespace
}  // namespace sc::test
