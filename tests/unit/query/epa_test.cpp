// SPDX-License-Identifier: MIT
#include "query/epa.h"

#include <gtest/gtest.h>

#include "preprocess/convex_hull.h"
#include "query/gjk.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

using test::boxMesh;
using test::polytopeFromMesh;

Rigid translation(const Vec3& t) { return {Mat3::Identity(), t}; }

TEST(Epa, OverlappingBoxesGiveTheOverlapAlongTheShallowAxis) {
  const ConvexPolytope a = polytopeFromMesh(boxMesh(Vec3(1, 1, 1)));
  const ConvexPolytope b = polytopeFromMesh(boxMesh(Vec3(1, 2, 3)));
  const EpaResult r = penetrationDepth(a, translation(Vec3(1.7, 0.2, -0.1)), b, Rigid());
  EXPECT_EQ(r.status, EpaStatus::Converged);
  EXPECT_NEAR(r.depth, 0.3, 1e-12);
  EXPECT_VEC_NEAR(r.normal, Vec3::UnitX(), 1e-12);
  EXPECT_NEAR(r.point_a.x() - r.point_b.x(), -0.3, 1e-12);
}

TEST(Epa, CoincidentBoxesExitThroughTheNearestFace) {
  const ConvexPolytope a = polytopeFromMesh(boxMesh(Vec3(1, 2, 3)));
  const EpaResult r = penetrationDepth(a, Rigid(), a, Rigid());
  EXPECT_NEAR(r.depth, 2.0, 1e-12);  // 2 * half extent along x
  EXPECT_NEAR(std::abs(r.normal.x()), 1.0, 1e-12);
}

TEST(Epa, TouchingFacesGiveZeroDepthNeverNan) {
  const ConvexPolytope a = polytopeFromMesh(boxMesh(Vec3(1, 1, 1)));
  const EpaResult r = penetrationDepth(a, translation(Vec3(2, 0.5, 0)), a, Rigid());
  EXPECT_NEAR(r.depth, 0.0, 1e-12);
  EXPECT_TRUE(r.normal.allFinite());
  EXPECT_NEAR(r.normal.norm(), 1.0, 1e-12);
}

TEST(Epa, CoplanarTrianglesAreTouching) {
  PolytopeParts parts;
  parts.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  parts.original = {0, 1, 2};
  parts.faces = {Tri(0, 1, 2), Tri(0, 2, 1)};
  parts.face_source = {0, 0};
  const ConvexPolytope t = ConvexPolytope::build(parts);
  const EpaResult r = penetrationDepth(t, translation(Vec3(0.2, 0.2, 0)), t, Rigid());
  EXPECT_EQ(r.status, EpaStatus::Touching);
  EXPECT_EQ(r.depth, 0.0);
}

TEST(Epa, RandomPairsMatchTheExactMinkowskiHull) {
  test::Rng rng(7);
  int checked = 0;
  for (int i = 0; i < 200; ++i) {
    const double size = test::logUniform(rng, 1e-2, 1e2);
    const auto sa = test::randomConvexShape(rng, size);
    const auto sb = test::randomConvexShape(rng, size);
    const Rigid fa{test::randomRotation(rng).toRotationMatrix(),
                   0.5 * size * test::randomDirection(rng)};
    const Rigid fb{test::randomRotation(rng).toRotationMatrix(), Vec3::Zero()};
    SimplexCache cache;
    if (gjkDistance(sa.poly, fa, sb.poly, fb, {}, cache).status != GjkStatus::Intersecting) continue;
    std::vector<Vec3> diff;
    for (const Vec3& p : sa.poly.vertices)
      for (const Vec3& q : sb.poly.vertices) diff.push_back(fa * p - fb * q);
    const auto hull = convexHull(diff);
    ASSERT_TRUE(hull.ok());
    double exact = kInfinity;
    for (const Tri& f : hull.value().faces) {
      const auto& v = hull.value().vertices;
      const Vec3 n = (v[f[1]] - v[f[0]]).cross(v[f[2]] - v[f[0]]).normalized();
      exact = std::min(exact, n.dot(v[f[0]]));
    }
    const EpaResult r = penetrationDepth(sa.poly, fa, sb.poly, fb);
    EXPECT_NEAR(r.depth, exact, 1e-9 * size) << "case " << i;
    // Moving A by the depth along the normal leaves them touching, not overlapping.
    const Rigid moved{fa.rotation, fa.translation + (r.depth + 1e-9 * size) * r.normal};
    SimplexCache c2;
    EXPECT_NE(gjkDistance(sa.poly, moved, sb.poly, fb, {}, c2).status, GjkStatus::Intersecting)
        << "case " << i;
    ++checked;
  }
  EXPECT_GE(checked, 50);
}

}  // namespace
}  // namespace sc::detail
