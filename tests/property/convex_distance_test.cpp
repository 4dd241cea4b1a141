// SPDX-License-Identifier: MIT
// GJK on random convex pairs (hulls of 4..60 points, boxes, tetrahedra) at random
// poses and scales 1e-2..1e2, against the brute-force surface distance, with the
// invariants of points, normal, features, symmetry and warm start.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "query/features.h"
#include "query/gjk.h"
#include "support/brute_force.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

constexpr int kCases = 1000;

struct Placed {
  test::ConvexShape shape;
  Rigid frame_from_local;
};

/// Outward unit normal of a face feature, in the common frame.
Vec3 faceNormal(const Placed& p, const Feature& f) {
  const Vec3& a = p.shape.points[f.vertices[0]];
  const Vec3 n = (p.shape.points[f.vertices[1]] - a).cross(p.shape.points[f.vertices[2]] - a);
  return p.frame_from_local.rotation * n.normalized();
}

Vec3 edgeDirection(const Placed& p, const Feature& f) {
  const Vec3 e = p.shape.points[f.vertices[1]] - p.shape.points[f.vertices[0]];
  return p.frame_from_local.rotation * e.normalized();
}

int dimension(const Feature& f) { return f.count() - 1; }

/// The feature holds the point; a face's normal or an edge's direction agrees
/// with the contact normal (from B to A; `sign` is -1 for A, +1 for B).
void expectFeature(const Placed& p, const Feature& f, const Vec3& point, const Vec3& normal,
                   double sign, double scale) {
  const Vec3 local = p.frame_from_local.inverse() * point;
  EXPECT_LE(test::pointFeatureDistance(p.shape.points, f, local), 1e-9 * scale);
  if (f.type == FeatureType::Face) {
    EXPECT_VEC_NEAR(faceNormal(p, f), sign * normal, 1e-8);
  } else if (f.type == FeatureType::Edge) {
    EXPECT_LE(std::abs(edgeDirection(p, f).dot(normal)), 1e-8);
  }
}

Placed randomPlaced(test::Rng& rng, double size) {
  Placed p;
  p.shape = test::randomConvexShape(rng, size);
  p.frame_from_local.rotation = test::randomRotation(rng).toRotationMatrix();
  return p;
}

/// Puts B beyond A along a random direction u, `gap` past A's extent, beside A up
/// to a random sideways offset: a positive gap separates the pair by at least it.
void separate(test::Rng& rng, Placed& a, Placed& b, double gap, double size) {
  a.frame_from_local.translation = size * test::uniform(rng, 0, 5) * test::randomDirection(rng);
  const Vec3 u = test::randomDirection(rng);
  double max_a = -kInfinity, min_b = kInfinity;
  for (const Vec3& v : a.shape.poly.vertices)
    max_a = std::max(max_a, u.dot(a.frame_from_local * v));
  for (const Vec3& v : b.shape.poly.vertices)
    min_b = std::min(min_b, u.dot(b.frame_from_local.rotation * v));
  Vec3 side = test::randomDirection(rng);
  side -= u * u.dot(side);
  const Vec3& ta = a.frame_from_local.translation;
  b.frame_from_local.translation =
      (ta - u * u.dot(ta)) + u * (max_a - min_b + gap) + test::uniform(rng, 0, 0.5) * size * side;
}

TEST(ConvexDistanceProperty, GjkMatchesBruteForceOnRandomPairs) {
  const std::uint64_t seed = 0x5C0117;
  SCOPED_TRACE(::testing::Message() << "seed " << seed);
  test::Rng rng(seed);
  double max_relative_error = 0.0;
  long cold_iterations = 0, warm_same_iterations = 0, moved_cold_iterations = 0,
       moved_warm_iterations = 0;
  int warm_same_checked = 0;
  int kinds[3] = {0, 0, 0};  // hull, box, tetrahedron
  int feature_pairs[3][3] = {};
  for (int c = 0; c < kCases; ++c) {
    SCOPED_TRACE(::testing::Message() << "case " << c);
    const double size = test::logUniform(rng, 1e-2, 1e2);
    Placed a = randomPlaced(rng, size * test::uniform(rng, 0.5, 2.0));
    Placed b = randomPlaced(rng, size * test::uniform(rng, 0.5, 2.0));
    const double gap = test::logUniform(rng, 0.01, 1.0) * size;
    separate(rng, a, b, gap, size);
    for (const Placed* p : {&a, &b}) {
      const std::string kind = p->shape.kind;
      ++kinds[kind == "hull" ? 0 : kind == "box" ? 1 : 2];
    }
    const double scale = std::max(a.shape.poly.radius, b.shape.poly.radius);

    SimplexCache cache;
    const GjkResult r =
        gjkDistance(a.shape.poly, a.frame_from_local, b.shape.poly, b.frame_from_local, {}, cache);
    ASSERT_EQ(r.status, GjkStatus::Separated);
    cold_iterations += r.iterations;
    const test::SurfaceDistance brute =
        test::meshSurfaceDistance(test::meshOf(a.shape.poly), a.frame_from_local,
                                  test::meshOf(b.shape.poly), b.frame_from_local);
    ASSERT_GE(brute.distance, gap * (1 - 1e-9));
    const double relative_error = std::abs(r.distance - brute.distance) / brute.distance;
    max_relative_error = std::max(max_relative_error, relative_error);
    EXPECT_LE(relative_error, 1e-9) << "gjk " << r.distance << " brute " << brute.distance;
    EXPECT_LE(r.lower_bound, r.distance);

    // Points, normal.
    EXPECT_NEAR((r.point_a - r.point_b).norm(), r.distance, 1e-12 * scale);
    EXPECT_VEC_NEAR(r.normal, (r.point_a - r.point_b) / r.distance, 1e-9);
    EXPECT_NEAR(r.normal.norm(), 1.0, 1e-12);
    const Vec3 local_a = a.frame_from_local.inverse() * r.point_a;
    const Vec3 local_b = b.frame_from_local.inverse() * r.point_b;
    EXPECT_LE(test::pointSurfaceDistance(test::meshOf(a.shape.poly), local_a), 1e-9 * scale);
    EXPECT_LE(test::pointSurfaceDistance(test::meshOf(b.shape.poly), local_b), 1e-9 * scale);
    EXPECT_TRUE(test::pointInConvexPolytope(a.shape.poly, local_a, 1e-9 * scale));
    EXPECT_TRUE(test::pointInConvexPolytope(b.shape.poly, local_b, 1e-9 * scale));

    // Features.
    const Feature fa = closestFeature(a.shape.poly, local_a, r.a, r.count, 1e-9 * scale);
    const Feature fb = closestFeature(b.shape.poly, local_b, r.b, r.count, 1e-9 * scale);
    expectFeature(a, fa, r.point_a, r.normal, -1.0, scale);
    expectFeature(b, fb, r.point_b, r.normal, +1.0, scale);
    EXPECT_LE(dimension(fa) + dimension(fb), 2) << "parallel features on random poses";
    ++feature_pairs[dimension(fa)][dimension(fb)];

    // Swapping A and B mirrors the result.
    SimplexCache swapped_cache;
    const GjkResult s = gjkDistance(b.shape.poly, b.frame_from_local, a.shape.poly,
                                    a.frame_from_local, {}, swapped_cache);
    ASSERT_EQ(s.status, GjkStatus::Separated);
    EXPECT_NEAR(s.distance, r.distance, 1e-12 * scale);
    EXPECT_VEC_NEAR(s.point_a, r.point_b, 1e-9 * scale);
    EXPECT_VEC_NEAR(s.point_b, r.point_a, 1e-9 * scale);
    EXPECT_VEC_NEAR(s.normal, -r.normal, 1e-9);

    // Warm start on the same poses: the same distance.
    const GjkResult w =
        gjkDistance(a.shape.poly, a.frame_from_local, b.shape.poly, b.frame_from_local, {}, cache);
    ASSERT_EQ(w.status, GjkStatus::Separated);
    EXPECT_NEAR(w.distance, r.distance, 1e-12 * r.distance);
    warm_same_iterations += w.iterations;
    ++warm_same_checked;

    // A small motion: warm and cold agree, warm is cheaper on average.
    Placed moved = b;
    moved.frame_from_local.rotation =
        Eigen::AngleAxisd(0.01, test::randomDirection(rng)).toRotationMatrix() *
        b.frame_from_local.rotation;
    moved.frame_from_local.translation += 1e-3 * size * test::randomDirection(rng);
    SimplexCache moved_cold_cache;
    const GjkResult mc = gjkDistance(a.shape.poly, a.frame_from_local, moved.shape.poly,
                                     moved.frame_from_local, {}, moved_cold_cache);
    const GjkResult mw = gjkDistance(a.shape.poly, a.frame_from_local, moved.shape.poly,
                                     moved.frame_from_local, {}, cache);
    ASSERT_EQ(mc.status, GjkStatus::Separated);
    ASSERT_EQ(mw.status, GjkStatus::Separated);
    EXPECT_NEAR(mw.distance, mc.distance, 1e-12 * mc.distance);
    moved_cold_iterations += mc.iterations;
    moved_warm_iterations += mw.iterations;
  }
  const double n = kCases;
  std::printf(
      "[ convex distance ] %d cases, max relative error %.3g; mean iterations: cold %.2f, "
      "warm same pose %.2f, after small motion cold %.2f warm %.2f\n",
      kCases, max_relative_error, cold_iterations / n, warm_same_iterations / n,
      moved_cold_iterations / n, moved_warm_iterations / n);
  std::printf(
      "[ convex distance ] shapes: %d hulls, %d boxes, %d tetrahedra; feature pairs "
      "(A dim x B dim): VV %d VE %d VF %d EV %d EE %d FV %d\n",
      kinds[0], kinds[1], kinds[2], feature_pairs[0][0], feature_pairs[0][1], feature_pairs[0][2],
      feature_pairs[1][0], feature_pairs[1][1], feature_pairs[2][0]);
  EXPECT_EQ(warm_same_checked, kCases);
  EXPECT_LT(moved_warm_iterations, moved_cold_iterations);
  // The sample exercises every kind of shape and the generic contact types.
  for (int k : kinds) EXPECT_GT(k, 200);
  EXPECT_GT(feature_pairs[0][2] + feature_pairs[2][0], 100);
  EXPECT_GT(feature_pairs[1][1], 100);
}

/// True when some vertex of `inner` lies strictly inside `outer` (by `margin`).
bool vertexInside(const Placed& inner, const Placed& outer, double margin) {
  const Rigid outer_from_inner = outer.frame_from_local.inverse() * inner.frame_from_local;
  for (const Vec3& v : inner.shape.poly.vertices) {
    if (test::pointInConvexPolytope(outer.shape.poly, outer_from_inner * v, -margin)) return true;
  }
  return false;
}

TEST(ConvexDistanceProperty, NearAndOverlappingPairsAreClassifiedLikeBruteForce) {
  const std::uint64_t seed = 0xC0FFEE;
  SCOPED_TRACE(::testing::Message() << "seed " << seed);
  test::Rng rng(seed);
  int separated = 0, intersecting = 0;
  double max_relative_error = 0.0;
  for (int c = 0; c < kCases; ++c) {
    SCOPED_TRACE(::testing::Message() << "case " << c);
    const double size = test::logUniform(rng, 1e-2, 1e2);
    Placed a = randomPlaced(rng, size * test::uniform(rng, 0.5, 2.0));
    Placed b = randomPlaced(rng, size * test::uniform(rng, 0.5, 2.0));
    // From deep overlap to a gap of 1e-6 of the size.
    const double gap = c % 4 == 0 ? size * test::logUniform(rng, 1e-6, 1e-2)
                                  : -size * test::uniform(rng, 0.0, 2.0);
    separate(rng, a, b, gap, size);
    const double scale = std::max(a.shape.poly.radius, b.shape.poly.radius);
    SimplexCache cache;
    const GjkResult r =
        gjkDistance(a.shape.poly, a.frame_from_local, b.shape.poly, b.frame_from_local, {}, cache);
    const test::SurfaceDistance brute =
        test::meshSurfaceDistance(test::meshOf(a.shape.poly), a.frame_from_local,
                                  test::meshOf(b.shape.poly), b.frame_from_local);
    const bool contained = vertexInside(a, b, 1e-9 * scale) || vertexInside(b, a, 1e-9 * scale);
    if (brute.distance <= 1e-13 * scale || contained) {
      EXPECT_EQ(r.status, GjkStatus::Intersecting) << "brute " << brute.distance;
      ++intersecting;
    } else if (brute.distance > 1e-9 * scale) {
      ASSERT_EQ(r.status, GjkStatus::Separated) << "brute " << brute.distance;
      const double relative_error = std::abs(r.distance - brute.distance) / brute.distance;
      max_relative_error = std::max(max_relative_error, relative_error);
      EXPECT_LE(relative_error, 1e-9) << "gjk " << r.distance << " brute " << brute.distance;
      ++separated;
    }
  }
  std::printf(
      "[ convex distance ] near/overlapping: %d separated (max relative error %.3g), "
      "%d intersecting\n",
      separated, max_relative_error, intersecting);
  EXPECT_GT(separated, 200);
  EXPECT_GT(intersecting, 300);
}

}  // namespace
}  // namespace sc::detail
