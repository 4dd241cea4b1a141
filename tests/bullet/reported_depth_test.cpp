// SPDX-License-Identifier: MIT
// StepStats::max_depth is the bodies' translational depth in every rotation mode: on a
// non-convex pair in Mix and Free it is the Input-mode tracker's (the one the rows
// come from), not the mode's own TPDV, which goes with its RPDV (a turned contact
// configuration's share of the way out, tens of millimetres in a pile of knots where
// the bodies overlap by a few). Two worlds see the same scripted poses: a torus
// pressed into another while turning, both reset before every step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "bullet_world.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

constexpr double kMajor = 0.17, kMinor = 0.08;  // 0.5 m across
constexpr int kSteps = 60;

struct Scripted {
  std::vector<double> depth, rotation;
};

/// The moving torus's pose at step k: tilted, lowered onto the resting one by 1.5 mm a
/// step from 2 cm apart while turning about a tilted axis.
btTransform poseAt(int k) {
  const btVector3 axis = btVector3(1.0f, 0.3f, 0.4f).normalized();
  const btQuaternion q(axis, btScalar(0.3 + 0.004 * k));
  const double y = 2.0 * kMinor + 0.1 - 0.0015 * k;
  return btTransform(q, btVector3(btScalar(kMajor), btScalar(y), 0));
}

Scripted run(RotationMode mode) {
  BulletWorld w(bullet::ContactModel::Potential, 0.0, 240.0);
  bullet::PluginSettings s = w.plugin->settings();
  s.query.rotation_mode = mode;
  EXPECT_TRUE(w.plugin->setSettings(s).ok());
  auto shape =
      bullet::ScBulletShape::create(ModelKind::ClosedPolyhedron, torusMesh(kMajor, kMinor, 32, 12));
  EXPECT_TRUE(shape.ok());
  Scripted out;
  if (!shape.ok()) return out;
  btRigidBody* rest = w.addBody(shape.value(), 1.0, btVector3(0, 0, 0));
  btRigidBody* moving =
      w.addBody(shape.value(), 1.0, poseAt(0).getOrigin(), poseAt(0).getRotation());
  for (int k = 0; k < kSteps; ++k) {
    for (btRigidBody* b : {rest, moving}) {
      b->setWorldTransform(b == rest ? btTransform::getIdentity() : poseAt(k));
      b->setLinearVelocity(btVector3(0, 0, 0));
      b->setAngularVelocity(btVector3(0, 0, 0));
    }
    w.step();
    out.depth.push_back(w.plugin->stats().max_depth);
    out.rotation.push_back(w.plugin->stats().max_rotation);
  }
  return out;
}

TEST(ReportedDepth, IsTheTranslationalDepthInEveryRotationMode) {
  const Scripted input = run(RotationMode::Input);
  ASSERT_EQ(static_cast<int>(input.depth.size()), kSteps);
  double deepest = 0.0;
  for (double d : input.depth) deepest = std::max(deepest, d);
  EXPECT_GT(deepest, 0.01);  // apart for some 25 steps, then pressed in by centimetres
  for (RotationMode mode : {RotationMode::Mix, RotationMode::Free}) {
    const Scripted turned = run(mode);
    ASSERT_EQ(static_cast<int>(turned.depth.size()), kSteps);
    double turn = 0.0;
    for (int k = 0; k < kSteps; ++k) {
      SCOPED_TRACE(k);
      EXPECT_NEAR(turned.depth[k], input.depth[k], 1e-12);
      turn = std::max(turn, turned.rotation[k]);
    }
    EXPECT_GT(turn, 0.0);  // the mode's proxy turned: its own TPDV is another vector
    std::printf("[reported depth] deepest %.2f mm, largest turn %.4f rad\n", 1e3 * deepest, turn);
  }
}

}  // namespace
}  // namespace sc::test
