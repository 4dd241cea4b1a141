// SPDX-License-Identifier: MIT
// convexDepth (GJK, then EPA on the two vertex sets) against the exact depth of the
// Minkowski difference's hull (qhull over every vertex pair) and against the
// hull-based EPA, on random and degenerate poses.
#include "query/convex_pair.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "support/brute_force.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

using test::boxMesh;
using test::polytopeFromMesh;

Rigid translation(const Vec3& t) { return {Mat3::Identity(), t}; }

/// The allowed error: 1e-9 of the depth, and rounding of the coordinates (some
/// 1e-13 of the pair's size) for depths too small to carry 1e-9 relative.
double allowed(double depth, double size) { return 1e-9 * depth + 1e-13 * size; }

bool intersects(const ConvexPolytope& a, const Rigid& fa, const ConvexPolytope& b,
                const Rigid& fb) {
  SimplexCache cache;
  return gjkDistance(a, fa, b, fb, {}, cache).status == GjkStatus::Intersecting;
}

/// Poses whose depth came from the expansion itself (not its hull-based fallback).
int g_expanded = 0;

/// convexDepth on one pose checked against the exact depth and the hull-based EPA;
/// true when the pair intersects (and so was checked).
bool checkPose(const ConvexPolytope& a, const Rigid& fa, const ConvexPolytope& b, const Rigid& fb,
               double size, ConvexPairCache& cache, double* worst) {
  EpaResult r;
  const ConvexDepthStatus status = convexDepth(a, fa, b, fb, cache, r);
  g_expanded += status != ConvexDepthStatus::Separated && r.face_count == 3;
  if (status == ConvexDepthStatus::Separated) {
    EXPECT_FALSE(intersects(a, fa, b, fb));
    return false;
  }
  const test::ExactDepth exact = test::exactPenetrationDepth(a, fa, b, fb);
  EXPECT_NEAR(r.depth, exact.depth, allowed(exact.depth, size));
  const EpaResult general = penetrationDepth(a, fa, b, fb);
  EXPECT_NEAR(r.depth, general.depth, allowed(exact.depth, size));
  EXPECT_NEAR(r.normal.norm(), 1.0, 1e-12);
  // The exit is the facet's: A moved by the depth (and a little) along it is free.
  if (exact.runner_up - exact.depth > 1e-6 * size) {
    const Rigid moved{fa.rotation, fa.translation + (r.depth + 1e-9 * size) * r.normal};
    EXPECT_FALSE(intersects(a, moved, b, fb));
  }
  if (exact.depth > 0.0) *worst = std::max(*worst, std::abs(r.depth - exact.depth) / exact.depth);
  return true;
}

TEST(ConvexPair, RandomPairsMatchTheExactMinkowskiDepth) {
  test::Rng rng(190219);
  g_expanded = 0;
  int checked = 0;
  double worst = 0.0;
  for (int i = 0; i < (SC_TEST_SANITIZED ? 150 : 600); ++i) {
    SCOPED_TRACE(testing::Message() << "case " << i);
    const double size = test::logUniform(rng, 1e-3, 1e3);
    const auto sa = test::randomConvexShape(rng, size);
    const auto sb = test::randomConvexShape(rng, size * test::uniform(rng, 0.5, 2.0));
    // Deep to shallow, and far from the origin now and then (rounding of the frame).
    const Vec3 offset = (i % 5 == 0 ? 1e3 * size : 0.0) * test::randomDirection(rng);
    const Rigid fa{test::randomRotation(rng).toRotationMatrix(),
                   offset + test::uniform(rng, 0.0, 0.9) * size * test::randomDirection(rng)};
    const Rigid fb{test::randomRotation(rng).toRotationMatrix(), offset};
    ConvexPairCache cache;
    checked += checkPose(sa.poly, fa, sb.poly, fb, size + offset.norm(), cache, &worst);
  }
  std::printf(
      "convexDepth: %d intersecting pairs (%d by the expansion), worst relative error "
      "%.3g\n",
      checked, g_expanded, worst);
  EXPECT_GE(checked, SC_TEST_SANITIZED ? 50 : 250);
  EXPECT_GE(g_expanded, checked * 9 / 10);  // the fallback stays the exception
}

TEST(ConvexPair, LargeHullsClimbTheAdjacency) {
  // Over 32 vertices the support mapping climbs the hull instead of scanning it.
  test::Rng rng(1902);
  g_expanded = 0;
  int checked = 0;
  double worst = 0.0;
  ConvexPairCache cache;  // carried from pose to pose: the warm start must not matter
  for (int i = 0; i < (SC_TEST_SANITIZED ? 5 : 20); ++i) {
    const ConvexPolytope a = test::hullOf(test::randomPoints(rng, 120, 1.0));
    const ConvexPolytope b = test::hullOf(test::randomPoints(rng, 120, 1.0));
    ASSERT_GT(a.vertices.size(), 32u);
    for (int k = 0; k < 5; ++k) {
      const Rigid fa{test::randomRotation(rng).toRotationMatrix(),
                     test::uniform(rng, 0.0, 0.8) * test::randomDirection(rng)};
      const Rigid fb{test::randomRotation(rng).toRotationMatrix(), Vec3::Zero()};
      checked += checkPose(a, fa, b, fb, 1.0, cache, &worst);
    }
  }
  std::printf(
      "convexDepth, large hulls: %d intersecting poses (%d by the expansion), worst "
      "relative error %.3g\n",
      checked, g_expanded, worst);
  EXPECT_GE(checked, SC_TEST_SANITIZED ? 10 : 50);
  EXPECT_GE(g_expanded, checked * 9 / 10);
}

TEST(ConvexPair, DegeneratePosesMatchTheExactDepth) {
  const ConvexPolytope unit = polytopeFromMesh(boxMesh(Vec3(1, 1, 1)));
  const ConvexPolytope slab = polytopeFromMesh(boxMesh(Vec3(3, 0.5, 2)));
  ConvexPairCache cache;
  double worst = 0.0;
  // Coincident boxes (every face ties), coplanar side faces sliding, deep along an
  // axis, a corner just inside, a tiny overlap, a face just inside a face.
  const Vec3 offsets[] = {Vec3(0, 0, 0),       Vec3(0.7, 1.2, 0),         Vec3(0, 0.05, 0),
                          Vec3(1.9, 1.2, 0.3), Vec3(0, 1.5 - 1e-7, 0.2),  Vec3(0.3, 1.5 - 1e-12, 0),
                          Vec3(3.9, 0.4, 2.5), Vec3(3.5, 1.4999, -2.9999)};
  for (const Vec3& t : offsets) {
    SCOPED_TRACE(testing::Message() << "offset " << t.transpose());
    EXPECT_TRUE(checkPose(unit, translation(t), slab, Rigid(), 4.0, cache, &worst));
  }
  // Touching faces: depth 0, reported as touching.
  EpaResult r;
  const ConvexDepthStatus s =
      convexDepth(unit, translation(Vec3(0, 1.5, 0)), slab, Rigid(), cache, r);
  if (s != ConvexDepthStatus::Separated) {
    EXPECT_EQ(s, ConvexDepthStatus::Touching);
    EXPECT_NEAR(r.depth, 0.0, 1e-12);
  }
  // A frame that is not finite: no depth, nothing read through it.
  const Rigid broken = translation(Vec3(0.0, std::numeric_limits<double>::quiet_NaN(), 0.0));
  EXPECT_EQ(convexDepth(unit, broken, slab, Rigid(), cache, r), ConvexDepthStatus::Separated);
  // Apart by a hair.
  EXPECT_EQ(convexDepth(unit, translation(Vec3(0, 1.5 + 1e-9, 0)), slab, Rigid(), cache, r),
            ConvexDepthStatus::Separated);
  EXPECT_LE(worst, 1e-9);
}

TEST(ConvexPair, RotatedCoplanarAndTinyContacts) {
  // Random rotations of a pose whose nearest facets are parallel faces: the same
  // face-on-face depth from every orientation of the pair as a whole.
  test::Rng rng(77);
  const ConvexPolytope a = polytopeFromMesh(boxMesh(Vec3(0.5, 0.7, 0.9)));
  const ConvexPolytope b = polytopeFromMesh(boxMesh(Vec3(2, 1, 1.5)));
  ConvexPairCache cache;
  for (int i = 0; i < 50; ++i) {
    const double depth = i % 2 ? test::logUniform(rng, 1e-9, 1e-3) : test::uniform(rng, 0.01, 0.4);
    const Vec3 local(test::uniform(rng, -1.0, 1.0), 1.0 + 0.7 - depth,
                     test::uniform(rng, -0.5, 0.5));
    const Mat3 r = test::randomRotation(rng).toRotationMatrix();
    const Vec3 shift = test::uniform(rng, -10.0, 10.0) * test::randomDirection(rng);
    const Rigid fa{r, r * local + shift}, fb{r, shift};
    SCOPED_TRACE(testing::Message() << "case " << i << " depth " << depth);
    EpaResult out;
    ASSERT_EQ(convexDepth(a, fa, b, fb, cache, out), ConvexDepthStatus::Penetrating);
    EXPECT_NEAR(out.depth, depth, allowed(depth, 12.0));
    EXPECT_VEC_NEAR(out.normal, Vec3(r.col(1)), 1e-9);
  }
}

}  // namespace
}  // namespace sc::detail
