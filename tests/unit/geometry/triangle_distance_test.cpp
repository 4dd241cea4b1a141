// SPDX-License-Identifier: MIT
// Closest points of segments and triangles against analytic answers, plus a
// sampled check on random and degenerate triangle pairs.
#include "geometry/triangle_distance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "support/test_support.h"

namespace sc::detail {
namespace {

constexpr double kTol = 1e-12;

/// `r` has the distance and the closest points on P and on Q given.
void expectClosest(const SegmentPair& r, double distance, const Vec3& on_p, const Vec3& on_q) {
  EXPECT_NEAR(std::sqrt(r.distance_squared), distance, kTol);
  EXPECT_VEC_NEAR(r.point_p, on_p, kTol);
  EXPECT_VEC_NEAR(r.point_q, on_q, kTol);
}

TEST(SegmentDistance, CrossingSegmentsMeetAtTheirMiddles) {
  const SegmentPair r =
      closestSegmentSegment(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 1), Vec3(0, 1, 1));
  expectClosest(r, 1.0, Vec3(0, 0, 0), Vec3(0, 0, 1));
  EXPECT_NEAR(r.s, 0.5, kTol);
  EXPECT_NEAR(r.t, 0.5, kTol);
}

TEST(SegmentDistance, ParallelSegmentsPickMidpointOfOverlap) {
  expectClosest(closestSegmentSegment(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 1, 0), Vec3(3, 1, 0)),
                1.0, Vec3(1.5, 0, 0), Vec3(1.5, 1, 0));
}

TEST(SegmentDistance, AntiparallelSegmentsPickMidpointOfOverlap) {
  expectClosest(closestSegmentSegment(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 1), Vec3(1, 0, 1)),
                1.0, Vec3(1.5, 0, 0), Vec3(1.5, 0, 1));
}

TEST(SegmentDistance, ParallelDisjointSegmentsUseNearestEnds) {
  const SegmentPair r =
      closestSegmentSegment(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0), Vec3(3, 1, 0));
  EXPECT_NEAR(std::sqrt(r.distance_squared), std::sqrt(2.0), kTol);
  EXPECT_EQ(r.s, 1.0);
  EXPECT_EQ(r.t, 0.0);
}

TEST(SegmentDistance, NearlyParallelSegmentsStayExact) {
  // Lines 1e-9 rad apart: the closest pair is at the x = 0 end, distance 1.
  const SegmentPair r =
      closestSegmentSegment(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1 + 1e-9, 0));
  EXPECT_NEAR(std::sqrt(r.distance_squared), 1.0, kTol);
  EXPECT_VEC_NEAR(r.point_p, Vec3(0, 0, 0), 1e-9);
  // 1e-13 rad: handled as parallel, still exact at the nearer end.
  const SegmentPair p =
      closestSegmentSegment(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1 + 1e-13, 0));
  EXPECT_NEAR(std::sqrt(p.distance_squared), 1.0, kTol);
  // Skew, 1e-7 rad apart, crossing above the middle at height 0.5.
  const SegmentPair q = closestSegmentSegment(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(-1, -1e-7, 0.5),
                                              Vec3(1, 1e-7, 0.5));
  EXPECT_NEAR(std::sqrt(q.distance_squared), 0.5, kTol);
  EXPECT_NEAR(q.point_p.x(), 0.0, 1e-6);
}

TEST(SegmentDistance, CollinearOverlappingSegmentsTouch) {
  const SegmentPair r =
      closestSegmentSegment(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0, 0), Vec3(5, 0, 0));
  EXPECT_NEAR(r.distance_squared, 0.0, kTol);
  EXPECT_VEC_NEAR(r.point_p, r.point_q, kTol);
}

TEST(SegmentDistance, ZeroLengthSegmentsActAsPoints) {
  const SegmentPair a =
      closestSegmentSegment(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 1, 0), Vec3(1, 1, 0));
  EXPECT_NEAR(std::sqrt(a.distance_squared), 1.0, kTol);
  EXPECT_VEC_NEAR(a.point_p, Vec3(1, 0, 0), kTol);
  const SegmentPair b =
      closestSegmentSegment(Vec3(1, 1, 0), Vec3(1, 1, 0), Vec3(0, 0, 0), Vec3(2, 0, 0));
  EXPECT_VEC_NEAR(b.point_q, Vec3(1, 0, 0), kTol);
  const SegmentPair c =
      closestSegmentSegment(Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 5), Vec3(1, 2, 5));
  EXPECT_NEAR(std::sqrt(c.distance_squared), 2.0, kTol);
}

const Vec3 kUnitTriangle[3] = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};

TEST(PointTriangleDistance, AboveTheInteriorProjectsOntoTheFace) {
  const TrianglePoint r = closestPointOnTriangle(Vec3(0.5, 0.5, 3), kUnitTriangle);
  EXPECT_VEC_NEAR(r.point, Vec3(0.5, 0.5, 0), kTol);
  EXPECT_EQ(r.feature.type, FeatureType::Face);
  EXPECT_NEAR(r.barycentric.sum(), 1.0, kTol);
}

TEST(PointTriangleDistance, VertexRegionGivesTheVertex) {
  const TrianglePoint r = closestPointOnTriangle(Vec3(3, -1, 1), kUnitTriangle);
  EXPECT_VEC_NEAR(r.point, Vec3(2, 0, 0), kTol);
  EXPECT_EQ(r.feature.type, FeatureType::Vertex);
  EXPECT_EQ(r.feature.vertices[0], 1);
}

TEST(PointTriangleDistance, EdgeRegionGivesTheEdge) {
  const TrianglePoint r = closestPointOnTriangle(Vec3(2, 2, -1), kUnitTriangle);
  EXPECT_VEC_NEAR(r.point, Vec3(1, 1, 0), kTol);
  EXPECT_EQ(r.feature.type, FeatureType::Edge);
  EXPECT_EQ(std::min(r.feature.vertices[0], r.feature.vertices[1]), 1);
  EXPECT_EQ(std::max(r.feature.vertices[0], r.feature.vertices[1]), 2);
}

TEST(PointTriangleDistance, DegenerateTrianglesActAsSegmentsAndPoints) {
  const Vec3 segment[3] = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  EXPECT_NEAR(pointTriangleDistance(Vec3(1.5, 3, 4), segment), 5.0, kTol);
  const Vec3 point[3] = {Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)};
  const TrianglePoint r = closestPointOnTriangle(Vec3(1, 1, 3), point);
  EXPECT_NEAR((r.point - Vec3(1, 1, 3)).norm(), 2.0, kTol);
  EXPECT_EQ(r.feature.type, FeatureType::Vertex);
}

TEST(TriangleDistance, ParallelStackedFacesAreOneApart) {
  const Vec3 b[3] = {Vec3(0.2, 0.2, 1), Vec3(1.2, 0.2, 1), Vec3(0.2, 1.2, 1)};
  const TriangleDistance r = triangleDistance(kUnitTriangle, b);
  EXPECT_NEAR(r.distance, 1.0, kTol);
  EXPECT_NEAR(r.point_b.z() - r.point_a.z(), 1.0, kTol);
  EXPECT_NEAR(pointTriangleDistance(r.point_a, kUnitTriangle), 0.0, kTol);
  EXPECT_NEAR(pointTriangleDistance(r.point_b, b), 0.0, kTol);
}

TEST(TriangleDistance, VertexAboveFaceGivesVertexFace) {
  const Vec3 b[3] = {Vec3(0.5, 0.5, 0.25), Vec3(0.5, 0.0, 3), Vec3(0.0, 0.5, 3)};
  const TriangleDistance r = triangleDistance(kUnitTriangle, b);
  EXPECT_NEAR(r.distance, 0.25, kTol);
  EXPECT_VEC_NEAR(r.point_a, Vec3(0.5, 0.5, 0), kTol);
  EXPECT_EQ(r.feature_a.type, FeatureType::Face);
  EXPECT_EQ(r.feature_b.type, FeatureType::Vertex);
  EXPECT_EQ(r.feature_b.vertices[0], 0);
}

TEST(TriangleDistance, CrossedEdgesGiveEdgeEdge) {
  const Vec3 a[3] = {Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, -1)};
  const Vec3 b[3] = {Vec3(0, -1, 1), Vec3(0, 1, 1), Vec3(0, 0, 2)};
  const TriangleDistance r = triangleDistance(a, b);
  EXPECT_NEAR(r.distance, 1.0, kTol);
  EXPECT_VEC_NEAR(r.point_a, Vec3(0, 0, 0), kTol);
  EXPECT_VEC_NEAR(r.point_b, Vec3(0, 0, 1), kTol);
  EXPECT_EQ(r.feature_a.type, FeatureType::Edge);
  EXPECT_EQ(r.feature_b.type, FeatureType::Edge);
}

TEST(TriangleDistance, PiercingTrianglesIntersectAtZero) {
  const Vec3 a[3] = {Vec3(-2, -2, 0), Vec3(2, -2, 0), Vec3(0, 3, 0)};
  const Vec3 b[3] = {Vec3(0, 0, -1), Vec3(0.5, 0, 1), Vec3(-0.5, 0.3, 1)};
  const TriangleDistance r = triangleDistance(a, b);
  EXPECT_NEAR(r.distance, 0.0, kTol);
  EXPECT_NEAR(r.point_a.z(), 0.0, kTol);
  EXPECT_NEAR(pointTriangleDistance(r.point_a, a), 0.0, kTol);
  EXPECT_NEAR(pointTriangleDistance(r.point_b, b), 0.0, kTol);
}

TEST(TriangleDistance, TouchingVertexOnFaceIsZero) {
  const Vec3 b[3] = {Vec3(0.5, 0.5, 0), Vec3(1, 0.5, 2), Vec3(0.5, 1, 2)};
  const TriangleDistance r = triangleDistance(kUnitTriangle, b);
  EXPECT_EQ(r.distance, 0.0);
  EXPECT_VEC_NEAR(r.point_a, Vec3(0.5, 0.5, 0), kTol);
}

TEST(TriangleDistance, CoplanarOverlapAndCoplanarGap) {
  const Vec3 overlap[3] = {Vec3(1, 1, 0), Vec3(3, 1, 0), Vec3(1, 3, 0)};
  EXPECT_NEAR(triangleDistance(kUnitTriangle, overlap).distance, 0.0, kTol);
  const Vec3 apart[3] = {Vec3(3, 0, 0), Vec3(5, 0, 0), Vec3(3, 2, 0)};
  const TriangleDistance r = triangleDistance(kUnitTriangle, apart);
  EXPECT_NEAR(r.distance, 1.0, kTol);
  EXPECT_VEC_NEAR(r.point_a, Vec3(2, 0, 0), kTol);
}

TEST(TriangleDistance, DegenerateTrianglesMatchSegmentAndPointAnswers) {
  const Vec3 segment[3] = {Vec3(0.5, 0.5, 1), Vec3(0.5, 0.5, 1), Vec3(0.5, 0.5, 4)};
  EXPECT_NEAR(triangleDistance(kUnitTriangle, segment).distance, 1.0, kTol);
  const Vec3 point[3] = {Vec3(3, 3, 0), Vec3(3, 3, 0), Vec3(3, 3, 0)};
  EXPECT_NEAR(triangleDistance(point, kUnitTriangle).distance, std::sqrt(2.0 * 2.0 * 2.0), kTol);
  const Vec3 segment_b[3] = {Vec3(0.5, 0.5, -1), Vec3(0.5, 0.5, 1), Vec3(0.5, 0.5, 0.2)};
  EXPECT_NEAR(triangleDistance(kUnitTriangle, segment_b).distance, 0.0, kTol);  // pierces
}

/// Minimum distance over a barycentric grid of both triangles.
double sampledDistance(const Vec3 a[3], const Vec3 b[3], int n) {
  std::vector<Vec3> pa, pb;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) {
      const double u = double(i) / n, v = double(j) / n;
      pa.push_back(a[0] + u * (a[1] - a[0]) + v * (a[2] - a[0]));
      pb.push_back(b[0] + u * (b[1] - b[0]) + v * (b[2] - b[0]));
    }
  }
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& p : pa) {
    for (const Vec3& q : pb) best = std::min(best, (p - q).norm());
  }
  return best;
}

double longestEdge(const Vec3 t[3]) {
  return std::max({(t[1] - t[0]).norm(), (t[2] - t[1]).norm(), (t[0] - t[2]).norm()});
}

TEST(TriangleDistance, RandomPairsAgreeWithSampling) {
  const std::uint64_t seed = 20240611;
  SCOPED_TRACE(::testing::Message() << "seed " << seed);
  test::Rng rng(seed);
  constexpr int kGrid = 24;
  int degenerate = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Vec3 a[3], b[3];
    for (Vec3& p : a)
      p = Vec3(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1), test::uniform(rng, -1, 1));
    const Vec3 shift = 1.5 * test::randomDirection(rng) * test::uniform(rng, 0, 1);
    for (Vec3& p : b)
      p = shift +
          Vec3(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1), test::uniform(rng, -1, 1));
    if (trial % 5 == 0) {  // collapse one triangle to a segment or a point
      a[2] = trial % 10 == 0 ? a[0] : Vec3(0.5 * (a[0] + a[1]));
      if (trial % 10 == 0) a[1] = a[0];
      ++degenerate;
    }
    const TriangleDistance r = triangleDistance(a, b);
    const TriangleDistance swapped = triangleDistance(b, a);
    const double sampled = sampledDistance(a, b, kGrid);
    const double spacing = (longestEdge(a) + longestEdge(b)) / kGrid;
    EXPECT_LE(r.distance, sampled + 1e-12) << "trial " << trial;
    EXPECT_GE(r.distance, sampled - spacing) << "trial " << trial;
    EXPECT_NEAR(r.distance, swapped.distance, 1e-12) << "trial " << trial;
    EXPECT_NEAR((r.point_a - r.point_b).norm(), r.distance, 1e-12);
    EXPECT_NEAR(pointTriangleDistance(r.point_a, a), 0.0, 1e-12);
    EXPECT_NEAR(pointTriangleDistance(r.point_b, b), 0.0, 1e-12);
  }
  EXPECT_GT(degenerate, 30);
}

}  // namespace
}  // namespace sc::detail
