// SPDX-License-Identifier: MIT
// A convex pair first seen intersecting (resolve_initial_intersection on) takes the
// convex fast path: its depth equals the exact Minkowski-hull depth to 1e-9 relative
// and the general path's (initial resolution, then the proxy) to the tolerance, on
// random poses and degenerate ones; tracking goes on from it as from the general path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "penetration/initial_resolution.h"
#include "penetration/proxy_tracker.h"
#include "penetration/result_invariants.h"
#include "smartcollision/collision.h"
#include "support/brute_force.h"
#include "support/placements.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

/// The general path of one direction first seen intersecting: initial resolution,
/// then the proxy from the free pose to the goal; later goals as on any frame.
struct GeneralPath {
  detail::GroupPairQuery query;
  detail::ProxyTracker tracker;

  /// The depth at the goal, or -1.
  double update(const GroupView& target, const GroupView& opponent, const SceneSettings& settings) {
    query.bind(target, opponent);
    const Rigid goal =
        opponent.placement.worldFromLocal().inverse() * target.placement.worldFromLocal();
    const Vec3& center = target.placement.local_center;
    const bool first = !tracker.tracking();
    detail::ProxyOutcome out;
    tracker.update(query, goal, center, settings, out);
    if (first) {
      if (out.code != ErrorCode::InvalidInitialTransformation) return -1.0;
      Rigid free_pose;
      detail::ResolutionScratch scratch;
      if (!detail::resolveInitialIntersection(query, goal, settings, free_pose, scratch))
        return -1.0;
      tracker.update(query, free_pose, center, settings, out);
      tracker.update(query, goal, center, settings, out);
    }
    return out.code == ErrorCode::Ok && out.penetrating ? -out.distance : -1.0;
  }
};

double generalPathDepth(const GroupView& target, const GroupView& opponent,
                        const SceneSettings& settings) {
  GeneralPath path;
  return path.update(target, opponent, settings);
}

struct Tally {
  int cases = 0, general_within = 0, next_within = 0;
  double worst_exact = 0.0, worst_general = 0.0;
};

/// One intersecting pose: the fast path against the exact depth and the general path,
/// then one more update slightly deeper.
void checkPair(const detail::ConvexPolytope& a, const detail::ConvexPolytope& b,
               const Placement& pa, const Placement& pb, double size, RotationMode mode,
               Tally& tally) {
  const ExactDepth exact = exactPenetrationDepth(a, pa.worldFromLocal(), b, pb.worldFromLocal());
  if (!(exact.depth > 0.0)) return;
  const ModelPtr ma = convexModel(a), mb = convexModel(b);
  ASSERT_TRUE(ma && mb);
  const Part part_a{ma.get(), Rigid(), 1}, part_b{mb.get(), Rigid(), 2};
  SceneSettings settings;
  settings.tolerance = 1e-3 * size;
  settings.rotation_mode = mode;
  settings.resolve_initial_intersection = true;
  PairTracker tracker;
  DirectedResult out[2];
  const GroupView ga{&part_a, 1, pa}, gb{&part_b, 1, pb};
  tracker.update(ga, gb, {true, false}, settings, out);
  ASSERT_EQ(out[0].code, ErrorCode::Ok);
  ASSERT_TRUE(out[0].penetrating());
  const Status s = detail::checkResult(out[0], pa, pb);
  EXPECT_TRUE(s.ok()) << s.message();
  const double depth = -out[0].distance;
  const double scale = size + pa.world_center.norm();
  EXPECT_NEAR(depth, exact.depth, 1e-9 * exact.depth + 1e-13 * scale);
  EXPECT_EQ(out[0].rpdv, Vec3::Zero());
  tally.worst_exact = std::max(tally.worst_exact, std::abs(depth - exact.depth) / exact.depth);
  GeneralPath general_path;
  const double general = general_path.update(ga, gb, settings);
  EXPECT_GE(general, 0.0);
  tally.worst_general =
      std::max(tally.worst_general, std::abs(general - depth) / settings.tolerance);
  tally.general_within += std::abs(general - depth) <= settings.tolerance;
  ++tally.cases;
  // Tracking goes on from the fast path's proxy as from the general path's: a little
  // deeper along the exit, both follow the same contact.
  Placement deeper = pa;
  deeper.world_center -= 0.1 * depth * out[0].normal;
  const GroupView next_a{&part_a, 1, deeper};
  tracker.update(next_a, gb, {true, false}, settings, out);
  ASSERT_EQ(out[0].code, ErrorCode::Ok);
  EXPECT_TRUE(detail::checkResult(out[0], deeper, pb).ok());
  const ExactDepth next = exactPenetrationDepth(a, deeper.worldFromLocal(), b, pb.worldFromLocal());
  EXPECT_GE(-out[0].distance, next.depth - settings.tolerance);  // never below the global depth
  const double general_next = general_path.update(next_a, gb, settings);
  tally.next_within += std::abs(-out[0].distance - general_next) <= settings.tolerance;
}

void report(const char* what, const Tally& t) {
  std::printf(
      "%s: %d cases, worst relative error against the exact depth %.3g; general path "
      "within the tolerance in %d (worst %.3g tolerances); next update within the tolerance "
      "of the general path's in %d\n",
      what, t.cases, t.worst_exact, t.general_within, t.worst_general, t.next_within);
}

TEST(ConvexFastPath, RandomPosesMatchTheExactDepthAndTheGeneralPath) {
  Rng rng(19022026);
  Tally tally;
  const int wanted = SC_TEST_SANITIZED ? 40 : 300;
  for (int i = 0; tally.cases < wanted && i < 20 * wanted; ++i) {
    const double size = logUniform(rng, 1e-2, 1e2);
    const ConvexShape a = randomConvexShape(rng, size);
    const ConvexShape b = randomConvexShape(rng, size * uniform(rng, 0.5, 2.0));
    const Placement pb = placementOf(randomRotation(rng).toRotationMatrix(), Vec3::Zero());
    const Placement pa = placementOf(randomRotation(rng).toRotationMatrix(),
                                     size * uniform(rng, 0.0, 0.9) * randomDirection(rng));
    const RotationMode mode = i % 4 == 0 ? RotationMode::None : RotationMode::Input;
    checkPair(a.poly, b.poly, pa, pb, size, mode, tally);
  }
  report("convex fast path, random", tally);
  EXPECT_GE(tally.cases, wanted);
  EXPECT_GE(tally.general_within, tally.cases * 99 / 100);
  EXPECT_GE(tally.next_within, tally.cases * 95 / 100);
}

TEST(ConvexFastPath, DegeneratePosesMatchTheExactDepth) {
  // Boxes: coincident (every face ties), coplanar faces sliding, a face just inside
  // a face (tiny), deep along an axis, rotated as a whole at random.
  Rng rng(1919);
  const detail::ConvexPolytope a = polytopeFromMesh(boxMesh(Vec3(0.5, 0.7, 0.9)));
  const detail::ConvexPolytope b = polytopeFromMesh(boxMesh(Vec3(2, 1, 1.5)));
  const Vec3 offsets[] = {Vec3(0, 0, 0),          Vec3(1.5, 1.7 - 0.3, 0.6),
                          Vec3(0, 1.7 - 1e-6, 0), Vec3(0.2, 0.1, 0.05),
                          Vec3(2.5 - 1e-3, 0, 0), Vec3(-1, -1.7 + 1e-8, 1)};
  Tally tally;
  for (int i = 0; i < 60; ++i) {
    const Mat3 r = i < 6 ? Mat3::Identity() : randomRotation(rng).toRotationMatrix();
    const Vec3 shift = i < 6 ? Vec3::Zero() : Vec3(uniform(rng, 0.0, 5.0) * randomDirection(rng));
    const Vec3& local = offsets[i % 6];
    checkPair(a, b, placementOf(r, r * local + shift), placementOf(r, shift), 3.0,
              RotationMode::Input, tally);
  }
  report("convex fast path, degenerate", tally);
  EXPECT_EQ(tally.cases, 60);
  EXPECT_GE(tally.general_within, tally.cases * 9 / 10);
}

TEST(ConvexFastPath, TouchingAndFreeModeTakeTheGeneralPath) {
  // Touching faces have no depth to resolve; Free turns the proxy, which the fast
  // path does not: both report what the general path reports.
  const detail::ConvexPolytope box = polytopeFromMesh(boxMesh(Vec3(1, 1, 1)));
  const ModelPtr m = convexModel(box);
  const Part pa{m.get(), Rigid(), 1}, pb{m.get(), Rigid(), 2};
  SceneSettings settings;
  settings.resolve_initial_intersection = true;
  const Placement origin = placementOf(Mat3::Identity(), Vec3::Zero());
  PairTracker touching;
  DirectedResult out[2];
  touching.update({&pa, 1, placementOf(Mat3::Identity(), Vec3(2, 0.3, 0))}, {&pb, 1, origin},
                  {true, false}, settings, out);
  EXPECT_EQ(out[0].code, ErrorCode::Ok);
  EXPECT_NEAR(out[0].distance, 0.0, settings.tolerance);
  settings.rotation_mode = RotationMode::Free;
  const Placement inside = placementOf(Mat3::Identity(), Vec3(1.5, 0.2, 0.1));
  PairTracker free_mode;
  free_mode.update({&pa, 1, inside}, {&pb, 1, origin}, {true, false}, settings, out);
  ASSERT_EQ(out[0].code, ErrorCode::Ok);
  EXPECT_NEAR(-out[0].distance, 0.5, settings.tolerance);
  EXPECT_NEAR(-out[0].distance, generalPathDepth({&pa, 1, inside}, {&pb, 1, origin}, settings),
              1e-12);
}

}  // namespace
}  // namespace sc::test
