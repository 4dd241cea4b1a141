// SPDX-License-Identifier: MIT
// A set contact_stiffness is a spring at any depth: a box rests at sag = M g / kT
// whatever Bullet's split impulse (which moves the depth term of rows deeper than its
// threshold, 4 cm by default, out of the velocity solve), and StackingSolver keeps
// every other row exactly as Bullet splits it. The sag is measured on the box's
// corners, never from SmartCollision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include "bullet_world.h"

namespace sc::test {
namespace {

constexpr double kHalf = 0.25;  // box half edge [m]
constexpr double kMass = 1.0;   // [kg]
constexpr double kGravity = 9.81;
constexpr double kSettle = 2.0;                            // [s]
constexpr double kWatch = SC_TEST_SANITIZED ? 2.0 : 10.0;  // [s]

/// The statics of Bullet's implicit row are exactly the spring's: at rest its impulse
/// dt (k x + c v') with v' = 0 carries the load, so x = load / kT at any dt, whatever
/// the damping. What is left: the solver's iterations on the few rows of one body (a soft
/// spring converges well within 100) and single-precision poses (1e-7 m near the
/// origin). 0.01 mm is 0.03 % of the smallest sag here; the sinking that split
/// impulse caused left 1 kg on 100 N/m 369 mm deep after 5 s.
constexpr double kSagTolerance = 1e-5;  // [m]

struct SagRun {
  double lowest = 1e9, deepest = -1e9;  ///< sag range while watched [m]
  double speed = 0.0;                   ///< largest speed while watched [m/s]
};

/// A 1 kg, 0.5 m box set on the ground (touching) with kT on its pair, settled for
/// kSettle, then watched for kWatch. `configure` may change the world's solver info.
template <class Configure>
SagRun restOnGround(double hz, double kT, Configure configure) {
  BulletWorld w(bullet::ContactModel::Potential, -kGravity, hz);
  configure(w.world->getSolverInfo());
  w.addGround();
  btRigidBody* box =
      w.addBody(boxShape(btVector3(kHalf, kHalf, kHalf)), kMass, btVector3(0, btScalar(kHalf), 0));
  bullet::ContactSettings c = w.plugin->settings().contact;
  c.contact_stiffness = kT;
  EXPECT_TRUE(w.plugin->setBodySettings(box, c).ok());
  w.step(static_cast<int>(std::lround(kSettle * hz)));
  SagRun r;
  for (int i = 0; i < static_cast<int>(std::lround(kWatch * hz)); ++i) {
    w.step();
    const double sag = boxCornerDepth(*box, nullptr, kHalf);
    r.lowest = std::min(r.lowest, sag);
    r.deepest = std::max(r.deepest, sag);
    r.speed = std::max(r.speed, double(box->getLinearVelocity().length()));
  }
  return r;
}

void expectSpringSag(const SagRun& r, double kT) {
  const double expected = kMass * kGravity / kT;
  std::printf("[sag] kT %g N/m: expected %.3f mm, watched %.4f..%.4f mm, speed <= %.1e m/s\n", kT,
              1e3 * expected, 1e3 * r.lowest, 1e3 * r.deepest, r.speed);
  EXPECT_NEAR(r.lowest, expected, kSagTolerance);
  EXPECT_NEAR(r.deepest, expected, kSagTolerance);
}

class SetStiffnessSag : public ::testing::TestWithParam<std::tuple<double, double>> {};

// Bullet's solver settings as ScDynamicsWorld leaves them: split impulse on at -4 cm.
// 100 and 200 N/m sag 98 and 49 mm, beyond the threshold (they sank through before);
// 300 N/m sags 33 mm, within it.
TEST_P(SetStiffnessSag, RestsAtLoadOverStiffness) {
  const auto [hz, kT] = GetParam();
  expectSpringSag(restOnGround(hz, kT, [](btContactSolverInfo&) {}), kT);
}

std::string sagName(const ::testing::TestParamInfo<std::tuple<double, double>>& p) {
  return std::to_string(int(std::get<0>(p.param))) + "Hz" +
         std::to_string(int(std::get<1>(p.param))) + "Npm";
}

INSTANTIATE_TEST_SUITE_P(Rates, SetStiffnessSag,
                         ::testing::Combine(::testing::Values(60.0, 240.0),
                                            ::testing::Values(100.0, 200.0, 300.0)),
                         sagName);

TEST(SetStiffnessSplitImpulse, SagIsTheSpringsWhateverTheSplitSettings) {
  // 300 N/m (33 mm) against a threshold above and below its sag, and split impulse off.
  const double kT = 300.0;
  for (const btScalar threshold : {btScalar(-0.04), btScalar(-0.01), btScalar(-0.001)}) {
    SCOPED_TRACE(double(threshold));
    expectSpringSag(restOnGround(60.0, kT,
                                 [&](btContactSolverInfo& info) {
                                   info.m_splitImpulsePenetrationThreshold = threshold;
                                 }),
                    kT);
  }
  expectSpringSag(
      restOnGround(60.0, kT, [](btContactSolverInfo& info) { info.m_splitImpulse = 0; }), kT);
}

// ---------------------------------------------------------------- one row, solved once

/// A box 6 cm deep in a static ground, sinking at 0.1 m/s, with one row under its centre
/// (a spring row of ContactSettings' kind, or a row with its own cfm and erp, as the
/// derived stiffness sets them), solved once by `solver`.
struct DeepRow {
  btBoxShape ground_shape{btVector3(50, 1, 50)};
  btBoxShape box_shape{btVector3(btScalar(kHalf), btScalar(kHalf), btScalar(kHalf))};
  btRigidBody ground{0, nullptr, &ground_shape};
  btRigidBody box{btRigidBody::btRigidBodyConstructionInfo(1, nullptr, &box_shape,
                                                           btVector3(1, 1, 1) / btScalar(24))};
  btPersistentManifold manifold{&box, &ground, 0, btScalar(0.04), btScalar(0.04)};

  DeepRow(bool spring, btSequentialImpulseConstraintSolver& solver,
          const btContactSolverInfo& info) {
    const btScalar depth = btScalar(0.06);
    ground.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
    box.setWorldTransform(
        btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(kHalf) - depth, 0)));
    box.setLinearVelocity(btVector3(0, btScalar(-0.1), 0));
    btManifoldPoint p(btVector3(0, -btScalar(kHalf), 0), btVector3(0, 1, 0), btVector3(0, 1, 0),
                      -depth);
    p.m_positionWorldOnA = btVector3(0, -depth, 0);
    p.m_positionWorldOnB = btVector3(0, 0, 0);
    p.m_combinedFriction = btScalar(0.5);
    if (spring) {
      p.m_contactPointFlags = BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING;
      p.m_combinedContactStiffness1 = 100;
      p.m_combinedContactDamping1 = 20;
    } else {
      p.m_contactPointFlags = BT_CONTACT_FLAG_HAS_CONTACT_CFM | BT_CONTACT_FLAG_HAS_CONTACT_ERP;
      p.m_contactCFM = 0;
      p.m_contactERP = btScalar(0.24);
    }
    manifold.addManifoldPoint(p);
    btCollisionObject* bodies[] = {&box, &ground};
    btPersistentManifold* manifolds[] = {&manifold};
    solver.solveGroup(bodies, 2, manifolds, 1, nullptr, 0, info, nullptr, nullptr);
  }
  double y() const { return double(box.getWorldTransform().getOrigin().y()); }
  double vy() const { return double(box.getLinearVelocity().y()); }
};

btContactSolverInfo splitInfo(bool split) {
  btContactSolverInfo info;
  info.m_timeStep = btScalar(1.0 / 60.0);
  info.m_splitImpulse = split ? 1 : 0;  // threshold: Bullet's -4 cm, shallower than the row
  return info;
}

TEST(SetStiffnessSplitImpulse, StackingSolverUnsplitsSpringRowsOnly) {
  bullet::StackingSolver stacking;
  btSequentialImpulseConstraintSolver plain, plain_unsplit, plain_split;
  // A spring row: as Bullet solves it without split impulse, to the bit.
  const DeepRow spring(true, stacking, splitInfo(true));
  const DeepRow spring_unsplit(true, plain_unsplit, splitInfo(false));
  const DeepRow spring_split(true, plain, splitInfo(true));
  EXPECT_EQ(spring.y(), spring_unsplit.y());
  EXPECT_EQ(spring.vy(), spring_unsplit.vy());
  // (Split, its depth term moves the box instead of the spring's push on its velocity.)
  EXPECT_NE(spring_split.y(), spring_unsplit.y());
  EXPECT_LT(spring_split.vy(), spring_unsplit.vy());
  // Any other row: as Bullet splits it, to the bit.
  const DeepRow rigid(false, stacking, splitInfo(true));
  const DeepRow rigid_split(false, plain_split, splitInfo(true));
  const DeepRow rigid_unsplit(false, plain, splitInfo(false));
  EXPECT_EQ(rigid.y(), rigid_split.y());
  EXPECT_EQ(rigid.vy(), rigid_split.vy());
  EXPECT_NE(rigid_split.y(), rigid_unsplit.y());
}

}  // namespace
}  // namespace sc::test
