// SPDX-License-Identifier: MIT
// A pair first seen within the tolerance of touching that then moves apart must
// report apart (or a depth pointing into the opponent), never a depth whose TPDV
// points out of the opponent.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "smartcollision/collision.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

ModelPtr cube() { return boxModel(Vec3(0.5, 0.5, 0.5)); }

Placement at(const Vec3& c) {
  Placement p;
  p.world_center = c;
  return p;
}

TEST(TouchingStart, MovingApartNeverReportsAnOutwardDepth) {
  const ModelPtr m = cube();
  ASSERT_TRUE(m);
  const Part a{m.get(), Rigid(), 1}, b{m.get(), Rigid(), 2};
  for (RotationMode mode :
       {RotationMode::None, RotationMode::Input, RotationMode::Free, RotationMode::Mix}) {
    for (double gap : {1e-8, 1e-6, 1e-4}) {
      SceneSettings settings;
      settings.rotation_mode = mode;
      PairTracker tracker;
      DirectedResult out[2];
      tracker.update({&a, 1, at(Vec3::Zero())}, {&b, 1, at(Vec3(1 + gap, 0.1, 0.05))}, {true, true},
                     settings, out);
      tracker.update({&a, 1, at(Vec3::Zero())}, {&b, 1, at(Vec3(1.0042, 0.1, 0.05))}, {true, true},
                     settings, out);
      for (int d = 0; d < 2; ++d) {
        SCOPED_TRACE(testing::Message()
                     << "mode " << static_cast<int>(mode) << " gap " << gap << " direction " << d);
        ASSERT_EQ(out[d].code, ErrorCode::Ok);
        EXPECT_NEAR(out[d].distance, 0.0042, 1e-9);
        EXPECT_EQ(out[d].tpdv.norm(), 0.0);
      }
    }
  }
}

}  // namespace
}  // namespace sc::test
