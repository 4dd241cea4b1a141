// SPDX-License-Identifier: MIT
// GJK on hand-made poses with analytic answers: cube faces, vertices and edges at
// known offsets, touching and overlapping pairs, early out, cap and warm start.
#include "query/gjk.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "geometry/triangle_distance.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

constexpr double kTol = 1e-12;

Rigid pose(const Mat3& rotation, const Vec3& translation) { return {rotation, translation}; }
Rigid at(const Vec3& translation) { return pose(Mat3::Identity(), translation); }
Mat3 about(const Vec3& axis, double degrees) {
  return Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()).toRotationMatrix();
}

class GjkCubes : public ::testing::Test {
 protected:
  ConvexPolytope cube_ = test::polytopeFromMesh(test::boxMesh(Vec3(1, 1, 1)));

  GjkResult run(const Rigid& frame_from_a, const Rigid& frame_from_b, GjkSettings settings = {}) {
    SimplexCache cache;
    return gjkDistance(cube_, frame_from_a, cube_, frame_from_b, settings, cache);
  }
};

void expectConsistent(const GjkResult& r) {
  ASSERT_EQ(r.status, GjkStatus::Separated);
  EXPECT_NEAR((r.point_a - r.point_b).norm(), r.distance, kTol);
  EXPECT_VEC_NEAR(r.normal * r.distance, r.point_a - r.point_b, kTol);
  EXPECT_NEAR(r.normal.norm(), 1.0, kTol);
  EXPECT_LE(r.lower_bound, r.distance);
  EXPECT_GE(r.count, 1);
  EXPECT_LE(r.count, 3);
}

TEST_F(GjkCubes, FaceFaceAtKnownOffsetIsOneApart) {
  const GjkResult r = run(at(Vec3::Zero()), at(Vec3(3, 0.5, 0.2)));
  expectConsistent(r);
  EXPECT_NEAR(r.distance, 1.0, kTol);
  EXPECT_VEC_NEAR(r.normal, Vec3(-1, 0, 0), kTol);
  EXPECT_NEAR(r.point_a.x(), 1.0, kTol);
  EXPECT_NEAR(r.point_b.x(), 2.0, kTol);
  // On the overlap of the two facing squares.
  EXPECT_GE(r.point_a.y(), -0.5 - kTol);
  EXPECT_LE(r.point_a.y(), 1.0 + kTol);
  EXPECT_GE(r.point_a.z(), -0.8 - kTol);
  EXPECT_LE(r.point_a.z(), 1.0 + kTol);
  EXPECT_NEAR(r.lower_bound, 1.0, 1e-9);
}

TEST_F(GjkCubes, VertexFacePointsAtTheCorner) {
  // B's corner (1,1,1) turned to face -x, 0.5 in front of A's +x face.
  const Mat3 rot = Quat::FromTwoVectors(Vec3(1, 1, 1), Vec3(-1, 0, 0)).toRotationMatrix();
  const GjkResult r = run(at(Vec3::Zero()), pose(rot, Vec3(1.5 + std::sqrt(3.0), 0.3, -0.2)));
  expectConsistent(r);
  EXPECT_NEAR(r.distance, 0.5, kTol);
  EXPECT_VEC_NEAR(r.point_b, Vec3(1.5, 0.3, -0.2), 1e-12);
  EXPECT_VEC_NEAR(r.point_a, Vec3(1.0, 0.3, -0.2), 1e-12);
  EXPECT_VEC_NEAR(r.normal, Vec3(-1, 0, 0), kTol);
}

TEST_F(GjkCubes, CrossedEdgesMeetAtTheirCommonPerpendicular) {
  // A's edge x = sqrt2, y = 0 (along z); B's edge x = c - sqrt2, z = 0.2 (along y).
  const double c = 2.0 * std::sqrt(2.0) + 0.7;
  const GjkResult r = run(pose(about(Vec3::UnitZ(), 45), Vec3::Zero()),
                          pose(about(Vec3::UnitY(), 45), Vec3(c, 0.1, 0.2)));
  expectConsistent(r);
  EXPECT_NEAR(r.distance, 0.7, kTol);
  EXPECT_VEC_NEAR(r.point_a, Vec3(std::sqrt(2.0), 0, 0.2), 1e-12);
  EXPECT_VEC_NEAR(r.point_b, Vec3(c - std::sqrt(2.0), 0, 0.2), 1e-12);
}

TEST_F(GjkCubes, PosedFrameOfBothGivesTheSameAnswer) {
  // The whole scene moved far away and turned: nothing but the frame changes.
  const Rigid world = pose(about(Vec3(1, 2, 3), 37), Vec3(1e3, -2e3, 5e2));
  const GjkResult r = run(world * at(Vec3::Zero()), world * at(Vec3(3, 0.5, 0.2)));
  expectConsistent(r);
  EXPECT_NEAR(r.distance, 1.0, 1e-12);
  EXPECT_VEC_NEAR(r.normal, world.rotation * Vec3(-1, 0, 0), 1e-12);
}

TEST_F(GjkCubes, TouchingIsIntersecting) {
  EXPECT_EQ(run(at(Vec3::Zero()), at(Vec3(2, 0.3, 0.1))).status, GjkStatus::Intersecting);
  const double c = 2.0 * std::sqrt(2.0);  // crossed edges touching
  const GjkResult r = run(pose(about(Vec3::UnitZ(), 45), Vec3::Zero()),
                          pose(about(Vec3::UnitY(), 45), Vec3(c, 0.1, 0.2)));
  EXPECT_EQ(r.status, GjkStatus::Intersecting);
  EXPECT_EQ(r.distance, 0.0);
  EXPECT_EQ(r.lower_bound, 0.0);
  // Corner on corner.
  EXPECT_EQ(run(at(Vec3::Zero()), at(Vec3(2, 2, 2))).status, GjkStatus::Intersecting);
}

TEST_F(GjkCubes, OverlappingIsIntersecting) {
  EXPECT_EQ(run(at(Vec3::Zero()), at(Vec3(1.5, 0.2, 0.1))).status, GjkStatus::Intersecting);
  EXPECT_EQ(run(at(Vec3::Zero()), at(Vec3::Zero())).status, GjkStatus::Intersecting);
  EXPECT_EQ(
      run(at(Vec3(0.1, 0.2, 0.3)), pose(about(Vec3(1, 1, 0), 30), Vec3(0.5, -0.4, 0.2))).status,
      GjkStatus::Intersecting);
}

TEST_F(GjkCubes, MaxDistanceStopsEarlyWithAValidLowerBound) {
  GjkSettings settings;
  settings.max_distance = 0.5;
  const GjkResult far = run(at(Vec3::Zero()), at(Vec3(3, 0.5, 0.2)), settings);
  EXPECT_EQ(far.status, GjkStatus::BeyondMaxDistance);
  EXPECT_GT(far.lower_bound, 0.5);
  EXPECT_LE(far.lower_bound, 1.0 + kTol);
  settings.max_distance = 1.5;
  const GjkResult near = run(at(Vec3::Zero()), at(Vec3(3, 0.5, 0.2)), settings);
  EXPECT_EQ(near.status, GjkStatus::Separated);
  EXPECT_NEAR(near.distance, 1.0, kTol);
}

TEST_F(GjkCubes, WithinDistanceStopsEarlyWithBothBounds) {
  const Rigid b = pose(about(Vec3(1, 2, 3), 40), Vec3(2.5, 1.9, 1.7));
  const GjkResult full = run(at(Vec3::Zero()), b);
  ASSERT_EQ(full.status, GjkStatus::Separated);
  GjkSettings settings;
  settings.within_distance = 10.0 * full.distance;  // known at once from the start simplex
  const GjkResult r = run(at(Vec3::Zero()), b, settings);
  EXPECT_EQ(r.status, GjkStatus::WithinDistance);
  EXPECT_LT(r.iterations, full.iterations);
  EXPECT_LE(r.lower_bound, full.distance + kTol);
  EXPECT_GE(r.distance, full.distance - kTol);
  EXPECT_LE(r.distance, settings.within_distance);
  // Closer than the true distance: GJK cannot stop early and converges as without it.
  settings.within_distance = 0.5 * full.distance;
  const GjkResult exact = run(at(Vec3::Zero()), b, settings);
  EXPECT_EQ(exact.status, GjkStatus::Separated);
  EXPECT_NEAR(exact.distance, full.distance, kTol);
}

// A sweep asks whether A stays clear of B while it translates: a separating plane
// that keeps it so ends the run early, whatever the distance.
TEST_F(GjkCubes, MotionAlongTheSeparatingPlaneStopsEarlyWithAValidLowerBound) {
  const Rigid b = at(Vec3(3, 0.5, 0.2));  // faces one apart along x
  const GjkResult full = run(at(Vec3::Zero()), b);
  GjkSettings settings;
  settings.motion_clearance = 0.5;
  for (const Vec3& motion : {Vec3(0, 10, 0), Vec3(0.3, 5, -5), Vec3(-2, 0, 0)}) {
    settings.motion = motion;  // along the faces, or closing by 0.3, or opening
    const GjkResult r = run(at(Vec3::Zero()), b, settings);
    EXPECT_EQ(r.status, GjkStatus::BeyondMaxDistance) << motion.transpose();
    EXPECT_LE(r.iterations, full.iterations);
    EXPECT_LE(r.lower_bound, 1.0 + kTol);
  }
  // Closing by 0.8 of the gap of 1 leaves 0.2 < 0.5: GJK runs to the exact distance.
  settings.motion = Vec3(0.8, 1, 0);
  const GjkResult closing = run(at(Vec3::Zero()), b, settings);
  EXPECT_EQ(closing.status, GjkStatus::Separated);
  EXPECT_NEAR(closing.distance, 1.0, kTol);
  // The motion is A's in the common frame: A turned, the same answer.
  const Rigid turned = pose(about(Vec3(0, 0, 1), 90), Vec3::Zero());
  settings.motion = Vec3(0, 10, 0);
  EXPECT_EQ(run(turned, b, settings).status, GjkStatus::BeyondMaxDistance);
  settings.motion = Vec3(0.8, 0, 0);
  EXPECT_EQ(run(turned, b, settings).status, GjkStatus::Separated);
}

TEST_F(GjkCubes, FarApartPairStopsAfterOneIterationBeyondMaxDistance) {
  GjkSettings settings;
  settings.max_distance = 1.0;
  const GjkResult r = run(at(Vec3::Zero()), at(Vec3(50, 3, -2)), settings);
  EXPECT_EQ(r.status, GjkStatus::BeyondMaxDistance);
  EXPECT_EQ(r.iterations, 1);
}

TEST_F(GjkCubes, IterationCapGivesFiniteNotConverged) {
  GjkSettings settings;
  settings.max_iterations = 1;
  const Rigid b = pose(about(Vec3(1, 2, 3), 40), Vec3(2.5, 1.9, 1.7));
  const GjkResult r = run(at(Vec3::Zero()), b, settings);
  const GjkResult full = run(at(Vec3::Zero()), b);
  ASSERT_EQ(full.status, GjkStatus::Separated);
  EXPECT_EQ(r.status, GjkStatus::NotConverged);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_TRUE(r.point_a.allFinite() && r.point_b.allFinite() && r.normal.allFinite());
  EXPECT_LE(r.lower_bound, full.distance + kTol);
  EXPECT_GE(r.distance, full.distance - kTol);  // a point of the CSO: an upper bound
}

TEST_F(GjkCubes, NonFinitePoseGivesFiniteNotConvergedWithoutTrapping) {
  // FP traps stay on: the check itself must not compute with the bad values.
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), kInfinity}) {
    Rigid pose_b = at(Vec3(bad, 0, 0));
    const GjkResult r = run(at(Vec3::Zero()), pose_b);
    EXPECT_EQ(r.status, GjkStatus::NotConverged);
    pose_b = at(Vec3(3, 0, 0));
    pose_b.rotation(1, 2) = bad;
    EXPECT_EQ(run(pose_b, at(Vec3::Zero())).status, GjkStatus::NotConverged);
    EXPECT_TRUE(std::isfinite(r.distance) && std::isfinite(r.lower_bound));
    EXPECT_TRUE(std::isfinite(r.point_a.squaredNorm()) && std::isfinite(r.normal.squaredNorm()));
  }
}

TEST_F(GjkCubes, TinyGapIsSeparatedAndAccurate) {
  const GjkResult r = run(at(Vec3::Zero()), at(Vec3(2 + 1e-9, 0.5, 0.2)));
  ASSERT_EQ(r.status, GjkStatus::Separated);
  EXPECT_NEAR(r.distance, 1e-9, 1e-15);
  EXPECT_VEC_NEAR(r.normal, Vec3(-1, 0, 0), 1e-6);
}

TEST_F(GjkCubes, SimplexIdsSpanTheClosestPoints) {
  const Rigid b = pose(about(Vec3(1, 2, 3), 40), Vec3(2.5, 1.9, 1.7));
  const GjkResult r = run(at(Vec3::Zero()), b);
  expectConsistent(r);
  // point_a lies in the hull of the A-side simplex vertices (a point, segment or triangle).
  Vec3 ta[3], tb[3];
  for (int k = 0; k < 3; ++k) {
    const int m = std::min(k, r.count - 1);
    ta[k] = cube_.vertices[r.a[m]];
    tb[k] = b * cube_.vertices[r.b[m]];
  }
  EXPECT_LE(pointTriangleDistance(r.point_a, ta), 1e-12);
  EXPECT_LE(pointTriangleDistance(r.point_b, tb), 1e-12);
  for (int k = r.count; k < 4; ++k) EXPECT_EQ(r.a[k], -1);
}

TEST_F(GjkCubes, SwappingArgumentsMirrorsTheResult) {
  const Rigid a = pose(about(Vec3(0, 1, 1), 20), Vec3(0.1, 0.2, 0.3));
  const Rigid b = pose(about(Vec3(1, 2, 3), 40), Vec3(2.5, 1.9, 1.7));
  const GjkResult ab = run(a, b);
  const GjkResult ba = run(b, a);
  expectConsistent(ab);
  expectConsistent(ba);
  EXPECT_NEAR(ab.distance, ba.distance, kTol);
  EXPECT_VEC_NEAR(ab.point_a, ba.point_b, 1e-12);
  EXPECT_VEC_NEAR(ab.point_b, ba.point_a, 1e-12);
  EXPECT_VEC_NEAR(ab.normal, -ba.normal, 1e-12);
}

TEST(Gjk, WarmStartOnSlowlyMovingPairIsExactAndCheaper) {
  const std::uint64_t seed = 99;
  SCOPED_TRACE(::testing::Message() << "seed " << seed);
  test::Rng rng(seed);
  const ConvexPolytope a = test::hullOf(test::randomPoints(rng, 60, 1.0));
  const ConvexPolytope b = test::hullOf(test::randomPoints(rng, 60, 1.0));
  SimplexCache warm;
  long cold_iterations = 0, warm_iterations = 0;
  int frames = 0;
  for (int frame = 0; frame < 300; ++frame) {
    const double t = 0.01 * frame;
    const Rigid frame_from_a = pose(about(Vec3(0, 0, 1), 10 * t), Vec3::Zero());
    const Rigid frame_from_b =
        pose(about(Vec3(1, 1, 0), 25 * t),
             Vec3(3.0 * std::cos(0.3 * t), 3.0 * std::sin(0.3 * t), 0.2 * t));
    SimplexCache cold;
    const GjkResult rc = gjkDistance(a, frame_from_a, b, frame_from_b, {}, cold);
    const GjkResult rw = gjkDistance(a, frame_from_a, b, frame_from_b, {}, warm);
    ASSERT_EQ(rc.status, GjkStatus::Separated) << "frame " << frame;
    ASSERT_EQ(rw.status, GjkStatus::Separated) << "frame " << frame;
    EXPECT_NEAR(rw.distance, rc.distance, 1e-12 * rc.distance) << "frame " << frame;
    cold_iterations += rc.iterations;
    warm_iterations += rw.iterations;
    ++frames;
  }
  const double cold_mean = double(cold_iterations) / frames;
  const double warm_mean = double(warm_iterations) / frames;
  std::printf("[ gjk warm start ] mean iterations cold %.2f warm %.2f over %d frames\n", cold_mean,
              warm_mean, frames);
  EXPECT_LT(warm_mean, 0.6 * cold_mean);
}

TEST(Gjk, WarmStartOnTheSamePoseConvergesInOneIteration) {
  test::Rng rng(3);
  const ConvexPolytope a = test::hullOf(test::randomPoints(rng, 40, 1.0));
  const ConvexPolytope b = test::hullOf(test::randomPoints(rng, 40, 1.0));
  const Rigid fa = pose(test::randomRotation(rng).toRotationMatrix(), Vec3::Zero());
  const Rigid fb = pose(test::randomRotation(rng).toRotationMatrix(), Vec3(2.5, 0.5, -0.3));
  SimplexCache cache;
  const GjkResult first = gjkDistance(a, fa, b, fb, {}, cache);
  ASSERT_EQ(first.status, GjkStatus::Separated);
  EXPECT_EQ(cache.count, first.count);
  const GjkResult second = gjkDistance(a, fa, b, fb, {}, cache);
  ASSERT_EQ(second.status, GjkStatus::Separated);
  EXPECT_EQ(second.iterations, 1);
  EXPECT_NEAR(second.distance, first.distance, 1e-14 * first.distance);
}

TEST(Gjk, StaleOrGarbageCacheIsHarmless) {
  const ConvexPolytope cube = test::polytopeFromMesh(test::boxMesh(Vec3(1, 1, 1)));
  SimplexCache cache;
  cache.count = 4;
  const int garbage_a[4] = {7, 7, -3, 99};
  const int garbage_b[4] = {0, 0, 5, 1000};
  for (int k = 0; k < 4; ++k) {
    cache.a[k] = garbage_a[k];
    cache.b[k] = garbage_b[k];
  }
  cache.hint_a = -4;
  cache.hint_b = 1 << 20;
  const GjkResult r = gjkDistance(cube, at(Vec3::Zero()), cube, at(Vec3(3, 0.5, 0.2)), {}, cache);
  ASSERT_EQ(r.status, GjkStatus::Separated);
  EXPECT_NEAR(r.distance, 1.0, kTol);
}

}  // namespace
}  // namespace sc::detail
