// SPDX-License-Identifier: MIT
// PairTracker::contactPoints: one point per leaf pair within the margin at the
// contact configuration, carried to the current pose; the main one agrees with the
// result.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "sc_support/off_mesh.h"
#include "smartcollision/collision.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

Placement at(const Vec3& c) {
  Placement p;
  p.world_center = c;
  return p;
}

TEST(ContactPoints, LPrismOnASlabTouchesWithBothPatches) {
  auto prism = support::readOff(std::string(SC_TEST_DATA_DIR) + "/l_prism.off");
  ASSERT_TRUE(prism.ok());
  const ModelPtr l = closedModel(prism.value());
  ASSERT_EQ(l->pieces()[0]->stats().patches, 2);
  const ModelPtr slab = closedModel(boxMesh(Vec3(10, 10, 1)));
  const Part a{l.get(), Rigid(), 7}, b{slab.get(), Rigid(), 9};
  // Lowest point of the prism, so it can be set just above the slab's top (z = 1).
  const double bottom = l->bounds().min.z();
  SceneSettings settings;
  PairTracker tracker;
  DirectedResult out[2];
  tracker.update({&a, 1, at(Vec3(0, 0, 1.0 + 1e-4 - bottom))}, {&b, 1, at(Vec3::Zero())},
                 {true, false}, settings, out);
  ASSERT_EQ(out[0].code, ErrorCode::Ok);
  const Placement pressed = at(Vec3(0, 0, 1.0 - 0.01 - bottom));
  tracker.update({&a, 1, pressed}, {&b, 1, at(Vec3::Zero())}, {true, false}, settings, out);
  ASSERT_EQ(out[0].code, ErrorCode::Ok);
  ASSERT_NEAR(out[0].distance, -0.01, settings.tolerance);

  std::vector<ContactPoint> points;
  tracker.contactPoints(0, settings.tolerance, points);
  // The prism's flat bottom spans both convex patches: one point each.
  ASSERT_EQ(points.size(), 2u);
  for (const ContactPoint& p : points) {
    EXPECT_EQ(p.target_object, 7);
    EXPECT_EQ(p.opponent_object, 9);
    EXPECT_VEC_NEAR(p.normal, Vec3::UnitZ(), 1e-9);
    EXPECT_NEAR(p.separation, -0.01, settings.tolerance);
    EXPECT_NEAR(p.point_on_opponent.z(), 1.0, settings.tolerance);
    EXPECT_NEAR(p.point_on_target.z(), 1.0 - 0.01, settings.tolerance);
  }
  // Direction 1 was not computed: no points.
  tracker.contactPoints(1, settings.tolerance, points);
  EXPECT_TRUE(points.empty());
}

TEST(ContactPoints, ApartGivesTheClosestPairAndANegativeMarginNothing) {
  const ModelPtr box = closedModel(boxMesh(Vec3(1, 1, 1)));
  const Part a{box.get(), Rigid(), 1}, b{box.get(), Rigid(), 2};
  PairTracker tracker;
  DirectedResult out[2];
  tracker.update({&a, 1, at(Vec3(3, 0, 0))}, {&b, 1, at(Vec3::Zero())}, {true, true}, {}, out);
  std::vector<ContactPoint> points;
  tracker.contactPoints(1, 0.0, points);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_NEAR(points[0].separation, 1.0, 1e-12);
  EXPECT_VEC_NEAR(points[0].normal, -Vec3::UnitX(), 1e-12);
  tracker.contactPoints(1, -1.0, points);
  EXPECT_TRUE(points.empty());
}

}  // namespace
}  // namespace sc::test
