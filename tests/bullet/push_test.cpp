// SPDX-License-Identifier: MIT
// A 0.3 m box on the ground, moved along it at 60, 120 and 240 Hz, in both contact
// models. Set sliding fast, it stays on its four corners. Pushed by a kinematic box
// (the scene of a user's report), a centred push moves it straight and an off-centre
// one turns it as Bullet's own boxes turn in the same scene. The pusher is no target
// of the pair (only dynamic bodies are): the rows must include its corners pressing
// on the box's face, since the box's own corners lie beyond the pusher's smaller face.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <tuple>

#include "bullet_world.h"

namespace sc::test {
namespace {

class BoxOnTheGround : public ::testing::TestWithParam<std::tuple<bullet::ContactModel, int>> {};

/// The largest turn from `spawn` over the run so far and `body`'s turn now [rad].
double turnFrom(const btRigidBody& body, const btQuaternion& spawn) {
  return double((body.getWorldTransform().getRotation() * spawn.inverse()).getAngleShortestPath());
}

/// A 1 kg box resting on the ground set sliding along +x at `speed`: its largest turn
/// while it slides and comes to rest (friction 0.25 cannot tip a cube: that takes 1).
double slidingTilt(bullet::ContactModel model, double hz, double speed) {
  BulletWorld w(model, -9.81, hz);
  w.addBody(boxShape(btVector3(20, 1, 20)), 0.0, btVector3(0, -1, 0));
  btRigidBody* box =
      w.addBody(boxShape(btVector3(0.15f, 0.15f, 0.15f)), 1.0, btVector3(0, 0.1505f, 0));
  w.step(static_cast<int>(std::lround(0.25 * hz)));  // settled on its four corners
  box->setLinearVelocity(btVector3(btScalar(speed), 0, 0));
  const btQuaternion spawn = box->getWorldTransform().getRotation();
  double tilt = 0.0;
  for (int k = 0; k < static_cast<int>(std::lround(hz)); ++k) {
    w.step();
    tilt = std::max(tilt, turnFrom(*box, spawn));
  }
  return tilt;
}

TEST_P(BoxOnTheGround, SlidingFastItStaysOnItsFourCorners) {
  // At 60 Hz, 1 m/s is 17 mm a step, beyond the manifold's breaking threshold (6.6 mm
  // for this box): every step's ground rows are new points. 1e-3 rad moves a corner
  // 0.2 mm, a fifth of the contact tolerance.
  const auto [model, hz] = GetParam();
  const double tilt = slidingTilt(model, hz, 1.0);
  std::printf("box sliding from 1 m/s, %d Hz: largest turn %.2e rad\n", hz, tilt);
  EXPECT_LT(tilt, 1e-3);
}

struct Push {
  double turn = 0.0;  ///< the pushed box's turn from its spawn at the end [rad]
  double yaw = 0.0;   ///< its signed turn about the vertical (+y) [rad]
  double x = 0.0;     ///< how far it was pushed [m]
};

/// A 1 kg box resting on the ground, pushed for 2 s at 0.5 m/s along +x by a
/// kinematic 0.2 m box whose centre is `offset` to the side (+z) and 0.11 m up, moved
/// through its motion state every step. `bullet_boxes`: Bullet's btBoxShape for every
/// body (Bullet's own pairs, the plugin not involved), else ScBulletShape boxes.
Push push(bool bullet_boxes, bullet::ContactModel model, double hz, double offset) {
  BulletWorld w(model, -9.81, hz);
  auto box = [&](const btVector3& half) -> std::shared_ptr<btCollisionShape> {
    if (bullet_boxes) return std::make_shared<btBoxShape>(half);
    return boxShape(half);
  };
  w.addBody(box(btVector3(20, 1, 20)), 0.0, btVector3(0, -1, 0));
  btRigidBody* target =
      w.addBody(box(btVector3(0.15f, 0.15f, 0.15f)), 1.0, btVector3(0, 0.1505f, 0));
  // 0.1 m apart before the push meets the box.
  btRigidBody* pusher =
      w.addBody(box(btVector3(0.1f, 0.1f, 0.1f)), 0.0, btVector3(-0.35f, 0.11f, btScalar(offset)));
  pusher->setCollisionFlags(pusher->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  btDefaultMotionState motion(pusher->getWorldTransform());
  pusher->setMotionState(&motion);
  const btQuaternion spawn = target->getWorldTransform().getRotation();
  btTransform at = pusher->getWorldTransform();
  for (int k = 0; k < static_cast<int>(std::lround(2.0 * hz)); ++k) {
    at.setOrigin(at.getOrigin() + btVector3(btScalar(0.5 / hz), 0, 0));
    motion.setWorldTransform(at);
    w.step();
  }
  pusher->setMotionState(nullptr);
  Push p;
  p.turn = turnFrom(*target, spawn);
  const btVector3 x_axis = target->getWorldTransform().getBasis().getColumn(0);
  p.yaw = std::atan2(-double(x_axis.z()), double(x_axis.x()));  // +y turns +x towards -z
  p.x = double(target->getWorldTransform().getOrigin().x());
  return p;
}

TEST_P(BoxOnTheGround, ACentredPushMovesItStraight) {
  const auto [model, hz] = GetParam();
  const Push p = push(false, model, hz, 0.0);
  std::printf("centred push, %d Hz: pushed to x %.3f m, turn %.2e rad\n", hz, p.x, p.turn);
  EXPECT_GT(p.x, 0.8);  // pushed along the 0.9 m the pusher went beyond it
  // A symmetric push turns the box by rounding only: 1e-3 rad moves its corners
  // 0.2 mm, a fifth of the contact tolerance. With its rows at one corner of the
  // pusher's face the box turned 0.5-0.9 rad.
  EXPECT_LT(p.turn, 1e-3);
}

TEST_P(BoxOnTheGround, AnOffCentrePushTurnsItAsBulletsBoxesTurn) {
  const auto [model, hz] = GetParam();
  // The pusher's face covers the box's from 0.1 to 0.15 m off its centre.
  for (double offset : {0.2, -0.2}) {
    const Push ours = push(false, model, hz, offset);
    const Push bullets = push(true, model, hz, offset);
    std::printf("push %+.2f m off centre, %d Hz: yaw %.3f rad (Bullet's boxes %.3f)\n", offset, hz,
                ours.yaw, bullets.yaw);
    ASSERT_GT(std::abs(bullets.yaw), 0.3);  // the scene does turn a box
    EXPECT_GT(ours.yaw * bullets.yaw, 0.0);
    EXPECT_LT(std::abs(ours.yaw - bullets.yaw), 0.3 * std::abs(bullets.yaw));
  }
}

INSTANTIATE_TEST_SUITE_P(Rates, BoxOnTheGround,
                         ::testing::Combine(bothContactModels(), ::testing::Values(60, 120, 240)),
                         contactModelRateName);

}  // namespace
}  // namespace sc::test
