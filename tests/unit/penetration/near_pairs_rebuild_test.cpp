// SPDX-License-Identifier: MIT
// contactsNear()'s rebuilds take the leaf pairs they already keep with a bound (their
// last gap less the motion since) instead of measuring them again. That only changes
// which pairs are measured when: along a recorded haptic path into a non-convex model,
// a proxy tracker whose query rebuilds that way reports the same depth at every update
// as one whose query measures every pair.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "penetration/proxy_tracker.h"
#include "support/meshes.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

/// One tracker on its own query, bound to the same groups as the other.
struct Tracked {
  GroupPairQuery query;
  ProxyTracker tracker;
};

/// A goal pushed into the opponent at a random point of its surface, then swept
/// across it with a slow turn: `steps` poses at a haptic step of `step`.
std::vector<Rigid> hapticPath(GroupPairQuery& probe, const Vec3& centre, double size,
                              test::Rng& rng, int steps, double step) {
  const Vec3 d = test::randomDirection(rng);
  const Vec3 u = d.unitOrthogonal(), v = d.cross(u);
  const Rigid far{Mat3::Identity(), centre + 1.5 * size * d};
  const double s = probe.translationToi(far, centre - far.translation, 1e-6 * size, {});
  const Vec3 touch = far.translation + s * (centre - far.translation);
  const Mat3 turn = Eigen::AngleAxisd(0.002, test::randomDirection(rng)).toRotationMatrix();
  std::vector<Rigid> path;
  Rigid goal = far;
  goal.translation = touch + 0.01 * size * d;  // just apart
  for (int k = 0; k < steps; ++k) {
    const double depth = std::min(k * step, 0.02 * size);  // in, then along at that depth
    const double a = k * step / (0.05 * size);
    goal.rotation = turn * goal.rotation;
    goal.translation = touch + (0.01 * size - depth) * d +
                       k * step * (std::cos(a) * u + 0.5 * std::sin(2 * a) * v);
    path.push_back(goal);
  }
  return path;
}

TEST(NearPairsRebuild, TakingKeptPairsGivesTheSameDepthAsMeasuringThemAlongAHapticPath) {
  const ModelPtr opponent = test::closedModel(test::loadTestMesh("elephant"));
  ASSERT_TRUE(opponent);
  const Vec3 centre = 0.5 * (opponent->bounds().min + opponent->bounds().max);
  const double size = 0.5 * (opponent->bounds().max - opponent->bounds().min).norm();
  const ModelPtr target = test::boxModel(size * Vec3(0.06, 0.04, 0.03));
  ASSERT_TRUE(target);
  const Part t_part{target.get(), Rigid(), 1}, o_part{opponent.get(), Rigid(), 2};
  const GroupView t_view{&t_part, 1, Placement()}, o_view{&o_part, 1, Placement()};
  PairSettings settings;
  settings.tolerance = 2e-3 * size;
  GroupPairQuery probe;
  probe.bind(t_view, o_view);
  test::Rng rng(0x19);
  int updates = 0, penetrating = 0;
  double worst = 0.0;
  for (int run = 0; run < (SC_TEST_SANITIZED ? 1 : 4); ++run) {
    const std::vector<Rigid> path = hapticPath(probe, centre, size, rng, 200, 1.5e-3 * size);
    Tracked reuse, measure;
    reuse.query.bind(t_view, o_view);
    measure.query.bind(t_view, o_view);
    measure.query.setNearReuseInRebuilds(false);
    for (std::size_t k = 0; k < path.size(); ++k) {
      SCOPED_TRACE(k);
      ProxyOutcome a, b;
      reuse.tracker.update(reuse.query, path[k], Vec3::Zero(), settings, a);
      measure.tracker.update(measure.query, path[k], Vec3::Zero(), settings, b);
      ASSERT_EQ(a.code, b.code);
      ASSERT_EQ(a.penetrating, b.penetrating);
      const double diff = (a.tpdv - b.tpdv).norm() +
                          (a.contact_pose.translation - b.contact_pose.translation).norm();
      worst = std::max(worst, diff);
      EXPECT_LE(diff, 1e-9 * size);
      EXPECT_NEAR(a.distance, b.distance, 1e-9 * size);
      ++updates;
      penetrating += a.penetrating;
    }
  }
  EXPECT_GT(penetrating, updates / 2);
  std::printf(
      "[ near pairs rebuild ] %d updates, %d penetrating, largest difference %.2g of "
      "the size\n",
      updates, penetrating, worst / size);
}

}  // namespace
}  // namespace sc::detail
