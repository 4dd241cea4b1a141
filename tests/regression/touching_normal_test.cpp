// SPDX-License-Identifier: MIT
// Two cubes exactly face to face have coinciding closest points, so the distance
// query alone cannot name a normal; the result must still carry the faces' normal,
// whether the pair was tracked into touching or first seen touching. (A default
// normal here sent a sideways contact to Bullet's solver and made a tower spawned
// touching collapse.)
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "smartcollision/collision.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

ModelPtr cube() { return boxModel(Vec3(0.5, 0.5, 0.5)); }

Placement at(double y) {
  Placement p;
  p.world_center = Vec3(0.1, y, -0.2);
  return p;
}

void expectFaceNormal(const DirectedResult out[2], const char* what) {
  for (int dir = 0; dir < 2; ++dir) {
    ASSERT_EQ(out[dir].code, ErrorCode::Ok) << what << ", direction " << dir;
    EXPECT_NEAR(out[dir].distance, 0.0, 1e-12) << what;
    // Direction 0 has the upper cube as target: its normal points up.
    EXPECT_NEAR(out[dir].normal.y(), dir == 0 ? 1.0 : -1.0, 1e-9) << what << ", direction " << dir;
  }
}

TEST(TouchingNormal, TrackedIntoTouchingKeepsTheFaceNormal) {
  const ModelPtr m = cube();
  ASSERT_TRUE(m);
  const Part a{m.get(), Rigid(), 1}, b{m.get(), Rigid(), 2};
  PairTracker tracker;
  DirectedResult out[2];
  tracker.update({&a, 1, at(1.01)}, {&b, 1, at(0.0)}, {true, true}, SceneSettings(), out);
  tracker.update({&a, 1, at(1.0)}, {&b, 1, at(0.0)}, {true, true}, SceneSettings(), out);
  expectFaceNormal(out, "tracked");
}

TEST(TouchingNormal, FirstSeenTouchingGetsTheFaceNormal) {
  const ModelPtr m = cube();
  ASSERT_TRUE(m);
  const Part a{m.get(), Rigid(), 1}, b{m.get(), Rigid(), 2};
  SceneSettings settings;
  settings.resolve_initial_intersection = true;
  PairTracker tracker;
  DirectedResult out[2];
  tracker.update({&a, 1, at(1.0)}, {&b, 1, at(0.0)}, {true, true}, settings, out);
  expectFaceNormal(out, "first seen");
}

}  // namespace
}  // namespace sc::test
