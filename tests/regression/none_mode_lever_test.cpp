// SPDX-License-Identifier: MIT
// NONE mode on the manual's Fig. 5-11 lever: a bar turning about one bottom edge held
// 1 cm above a slab. While the bar is free the result must be apart; once it
// penetrates, the orientation kept is that of the impact, so the RPDV is the turn
// since the bar touched. The stability matrix found NONE freezing one step early;
// it then froze the last free pose's orientation, up to a step away from contact.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "smartcollision/collision.h"
#include "support/shapes.h"

namespace sc::test {
namespace {


Placement leverAt(double angle) {
  Placement p;
  p.setOrientation(Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ())));
  p.local_center = Vec3(-1.0, -0.05, 0.0);  // the bar's lower left edge
  p.world_center = Vec3(-1.0, 0.01, 0.0);   // held 1 cm above the slab
  return p;
}

TEST(NoneModeLever, FreezesTheImpactOrientation) {
  const BarOnSlab scene(Vec3(1.0, 0.05, 0.05));
  ASSERT_TRUE(scene.ok());
  SceneSettings settings;
  settings.rotation_mode = RotationMode::None;
  PairTracker tracker;
  DirectedResult out[2];
  // The far end's lower edge (2 m from the pivot) reaches the slab at asin(0.01 / 2).
  const double touch = -std::asin(0.01 / 2.0);
  for (int step = 0; step <= 60; ++step) {
    const double angle = (10.0 - 0.25 * step) * kPi / 180.0;
    scene.query(tracker, leverAt(angle), settings, out);
    ASSERT_EQ(out[0].code, ErrorCode::Ok) << "step " << step;
    if (angle > touch + 1e-9) {
      EXPECT_FALSE(out[0].penetrating()) << "free pose reported penetrating at step " << step;
      EXPECT_GT(out[0].distance, 0.0) << "step " << step;
    }
  }
  // The final pose (-5 degrees) penetrates; NONE turns it back to the impact, found
  // to within the tolerance at the far end, 2 m from the pivot.
  EXPECT_TRUE(out[0].penetrating());
  EXPECT_NEAR(out[0].rpdv.norm(), touch - (-5.0 * kPi / 180.0), settings.tolerance / 2.0);
}

}  // namespace
}  // namespace sc::test
