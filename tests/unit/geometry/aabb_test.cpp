// SPDX-License-Identifier: MIT
// transformBox and boxDistance (smartcollision/types.h) against brute force: the
// bounds of a box's eight moved corners, and the distance along the one separating
// axis of boxes apart along it.
#include <gtest/gtest.h>

#include "smartcollision/types.h"
#include "support/test_support.h"

namespace sc {
namespace {

TEST(TransformBox, IsTheBoundOfTheEightMovedCorners) {
  test::Rng rng(2026);
  for (int k = 0; k < 200; ++k) {
    SCOPED_TRACE(k);
    Aabb local;
    for (int corner = 0; corner < 2; ++corner) {
      Vec3 p;
      for (int i = 0; i < 3; ++i) p[i] = test::uniform(rng, -2, 2);
      local.extend(p);
    }
    Rigid moved;
    moved.rotation = test::randomRotation(rng).toRotationMatrix();
    moved.translation = 3.0 * test::randomDirection(rng);
    Aabb corners;
    for (int i = 0; i < 8; ++i) {
      const Vec3 c((i & 1) ? local.max.x() : local.min.x(), (i & 2) ? local.max.y() : local.min.y(),
                   (i & 4) ? local.max.z() : local.min.z());
      corners.extend(moved * c);
    }
    const Aabb box = transformBox(local, moved);
    EXPECT_LE((box.min - corners.min).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LE((box.max - corners.max).cwiseAbs().maxCoeff(), 1e-12);
  }
  EXPECT_TRUE(transformBox(Aabb(), Rigid()).empty());
}

TEST(BoxDistance, IsTheGapAlongTheSeparatingAxesAndSymmetric) {
  Aabb a, b;
  a.extend(Vec3(0, 0, 0));
  a.extend(Vec3(1, 1, 1));
  b.extend(Vec3(4, 5, 0.5));
  b.extend(Vec3(6, 7, 2));
  EXPECT_DOUBLE_EQ(boxDistance(a, b), 5.0);  // gaps 3 and 4 along x and y
  EXPECT_EQ(boxDistance(a, b), boxDistance(b, a));
  b.min.x() = 0.5;
  b.min.y() = 0.5;
  EXPECT_EQ(boxDistance(a, b), 0.0);  // overlapping
}

}  // namespace
}  // namespace sc
