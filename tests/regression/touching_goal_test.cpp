// SPDX-License-Identifier: MIT
// Every mode at a goal that only touches. FREE and MIX failed: the proxy turned a
// little more at every update at the same goal (stability matrix: |RPDV| 0.17 rad
// after 10 updates). The touching pair counted as intersecting, and so did the
// previous proxy, so its exit normal fell back to the direction between the boxes'
// centres; one row along that direction, 0.35 deep, made the cheap rotation of FREE
// turn by the step cap.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "smartcollision/collision.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

ModelPtr cube() { return boxModel(Vec3(0.5, 0.5, 0.5)); }

class TouchingGoal : public ::testing::TestWithParam<RotationMode> {};

TEST_P(TouchingGoal, StaticTouchingGoalStaysPut) {
  const ModelPtr m = cube();
  ASSERT_TRUE(m);
  const Part a{m.get(), Rigid(), 1}, b{m.get(), Rigid(), 2};
  SceneSettings settings;
  settings.rotation_mode = GetParam();
  PairTracker tracker;
  DirectedResult out[2];
  const Placement fixed;
  // Face on face, offset sideways: approach along x to exactly touching at update 40,
  // then stay there.
  for (int i = 0; i <= 50; ++i) {
    Placement p;
    p.world_center = Vec3(1.0 + 2.0 * std::max(0, 40 - i) / 40.0, 0.3, 0.2);
    tracker.update({&a, 1, p}, {&b, 1, fixed}, {true, false}, settings, out);
    ASSERT_EQ(out[0].code, ErrorCode::Ok) << "update " << i;
    if (i < 40) continue;
    EXPECT_NEAR(out[0].distance, 0.0, 1e-9) << "update " << i;
    EXPECT_LT(out[0].tpdv.norm(), 1e-9) << "update " << i;
    EXPECT_LT(out[0].rpdv.norm(), 1e-9) << "update " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Modes, TouchingGoal,
                         ::testing::Values(RotationMode::Free, RotationMode::Mix,
                                           RotationMode::Input, RotationMode::None));

}  // namespace
}  // namespace sc::test
