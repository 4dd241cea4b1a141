// SPDX-License-Identifier: MIT
// NONE rotation mode: a bar turning about its lower left edge from a free pose 1 mm
// above a floor to 5 degrees into it, in one update. The contact configuration kept
// the last free update's orientation, 1 mm away from contact; it must be in
// contact (the orientation at the time of impact), as in every other mode: placed
// at its contact configuration, the bar touches the floor within the tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "smartcollision/collision.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

const Vec3 kHalf(1.0, 0.05, 0.05);    // the bar
const Vec3 kPivot(-1.0, -0.05, 0.0);  // its lower left edge, the centre of rotation

Placement barAt(double angle, double height) {
  Placement p;
  p.setOrientation(Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ())));
  p.local_center = kPivot;
  p.world_center = Vec3(-1.0, height, 0.0);
  return p;
}

/// Height of the bar's lowest corner above the floor (y = 0) at a configuration.
double lowestCorner(const Vec3& position, const Quat& orientation) {
  double lowest = kInfinity;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1) ? kHalf.x() : -kHalf.x(), (i & 2) ? kHalf.y() : -kHalf.y(),
                      (i & 4) ? kHalf.z() : -kHalf.z());
    lowest = std::min(lowest, (orientation * (corner - kPivot) + position).y());
  }
  return lowest;
}

TEST(NoneModeImpact, ContactConfigurationTouchesTheFloorInEveryMode) {
  const BarOnSlab scene(kHalf);
  ASSERT_TRUE(scene.ok());
  const double gap = 1e-3;
  for (const RotationMode mode :
       {RotationMode::None, RotationMode::Input, RotationMode::Free, RotationMode::Mix}) {
    SCOPED_TRACE(::testing::Message() << "rotation mode " << static_cast<int>(mode));
    SceneSettings settings;
    settings.rotation_mode = mode;
    settings.tolerance = 1e-4;  // well below the 1 mm the free pose is away
    PairTracker tracker;
    DirectedResult out[2];
    scene.query(tracker, barAt(0.0, gap), settings, out);
    ASSERT_EQ(out[0].code, ErrorCode::Ok);
    ASSERT_NEAR(out[0].distance, gap, 1e-12);
    scene.query(tracker, barAt(-5.0 * kPi / 180.0, gap), settings, out);
    ASSERT_EQ(out[0].code, ErrorCode::Ok);
    ASSERT_TRUE(out[0].penetrating());
    const double height = lowestCorner(out[0].contact_position, out[0].contact_orientation);
    EXPECT_NEAR(height, 0.0, settings.tolerance)
        << "the contact configuration is " << height << " from touching";
  }
}

TEST(NoneModeImpact, NoneKeepsTheOrientationAtTheTimeOfImpact) {
  const BarOnSlab scene(kHalf);
  ASSERT_TRUE(scene.ok());
  SceneSettings settings;
  settings.rotation_mode = RotationMode::None;
  settings.tolerance = 1e-4;
  PairTracker tracker;
  DirectedResult out[2];
  const double gap = 1e-3, end = -5.0 * kPi / 180.0;
  scene.query(tracker, barAt(0.0, gap), settings, out);
  // Deeper frames keep the impact orientation: the far end (2 m from the pivot)
  // reaches the floor at asin(gap / 2).
  const double impact = -std::asin(gap / 2.0);
  for (const double angle : {end, 2.0 * end, end}) {
    scene.query(tracker, barAt(angle, gap), settings, out);
    ASSERT_TRUE(out[0].penetrating());
    const double kept = Eigen::AngleAxisd(out[0].contact_orientation).angle();
    // The orientation is found to within the tolerance at the far end, 2 m away.
    EXPECT_NEAR(kept, -impact, settings.tolerance / 2.0) << "at " << angle;
    EXPECT_NEAR(out[0].rpdv.z(), angle - impact, settings.tolerance / 2.0);
    EXPECT_NEAR(lowestCorner(out[0].contact_position, out[0].contact_orientation), 0.0,
                settings.tolerance);
  }
}

}  // namespace
}  // namespace sc::test
