// SPDX-License-Identifier: MIT
// Bodies removed from an ScDynamicsWorld: nothing of them stays behind (the usual
// despawn deletes a body right after removeRigidBody), so later steps never read
// them and a body later built at the same address starts as a new one.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "bullet_world.h"

namespace sc::test {
namespace {

/// Removes `body` from the world (through removeCollisionObject when `as_object`) and
/// deletes it at once.
void removeAndDelete(BulletWorld& w, btRigidBody* body, bool as_object) {
  if (as_object)
    w.world->removeCollisionObject(body);
  else
    w.world->removeRigidBody(body);
  auto it = std::find_if(w.bodies.begin(), w.bodies.end(),
                         [body](const std::unique_ptr<btRigidBody>& b) { return b.get() == body; });
  ASSERT_NE(it, w.bodies.end());
  w.bodies.erase(it);  // deletes it
}

class LifeCycle : public ::testing::TestWithParam<bool> {};

// Under AddressSanitizer this read freed memory (the world's last poses kept the body
// until its next detection, and updateAabbs read them first).
TEST_P(LifeCycle, ABodyDeletedRightAfterItsRemovalIsNeverReadAgain) {
  BulletWorld w(bullet::ContactModel::Potential, -9.81, 60.0);
  w.addGround();
  const auto box = boxShape(btVector3(0.1f, 0.1f, 0.1f));
  btRigidBody* stays = w.addBody(box, 1.0, btVector3(1, 0.1f, 0));
  btRigidBody* resting = w.addBody(box, 1.0, btVector3(0, 0.1f, 0));
  btRigidBody* falling = w.addBody(box, 1.0, btVector3(-1, 3, 0));
  w.step(30);
  removeAndDelete(w, resting, GetParam());
  removeAndDelete(w, falling, GetParam());
  w.step(60);
  EXPECT_NEAR(stays->getCenterOfMassPosition().y(), 0.1, 2e-3);
}

TEST_P(LifeCycle, ARemovedBodysSettingsDoNotPassToABodyAtItsAddress) {
  BulletWorld w(bullet::ContactModel::Potential, -9.81, 60.0);
  btRigidBody* ground = w.addGround();
  btRigidBody* soft = w.addBody(boxShape(btVector3(0.1f, 0.1f, 0.1f)), 1.0, btVector3(0, 0.1f, 0));
  bullet::ContactSettings s;
  s.contact_stiffness = 100.0;
  ASSERT_TRUE(w.plugin->setBodySettings(soft, s).ok());
  w.step(10);
  ASSERT_EQ(w.plugin->pairSettings(soft, ground).contact_stiffness, 100.0);
  // The address is what the override was kept by: a body built there later (a pool
  // slot, or the allocator's next block) must not inherit it.
  const btCollisionObject* address = soft;
  removeAndDelete(w, soft, GetParam());
  EXPECT_EQ(w.plugin->pairSettings(address, ground).contact_stiffness,
            w.plugin->settings().contact.contact_stiffness);
}

INSTANTIATE_TEST_SUITE_P(Removal, LifeCycle, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& p) {
                           return p.param ? "RemoveCollisionObject" : "RemoveRigidBody";
                         });

}  // namespace
}  // namespace sc::test
