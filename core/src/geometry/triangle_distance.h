// SPDX-License-Identifier: MIT
// Exact closest points between points, segments and triangles, robust for parallel
// and degenerate input: the reference for convex queries and the leaf of triangle soups.
#pragma once

#include "smartcollision/types.h"

namespace sc::detail {

/// Closest point of segment [a, b] to p: a + t (b - a), t in [0, 1].
/// A degenerate segment (a == b) gives t = 0.
struct SegmentPoint {
  Vec3 point = Vec3::Zero();
  double t = 0.0;
};
SegmentPoint closestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b);

/// Closest points of segments [p0, p1] and [q0, q1]: point_p = p0 + s (p1 - p0),
/// point_q = q0 + t (q1 - q0). Parallel overlapping segments pick the middle of the
/// overlap; zero-length segments act as points.
struct SegmentPair {
  Vec3 point_p = Vec3::Zero();
  Vec3 point_q = Vec3::Zero();
  double s = 0.0;
  double t = 0.0;
  double distance_squared = 0.0;
};
SegmentPair closestSegmentSegment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

/// Closest point of triangle (t[0], t[1], t[2]) to p, with its barycentric
/// coordinates and the smallest feature holding it (vertices are local, 0..2).
/// A degenerate triangle (a segment or a point) is handled as its edges.
struct TrianglePoint {
  Vec3 point = Vec3::Zero();
  Vec3 barycentric = Vec3(1.0, 0.0, 0.0);
  Feature feature;
};
TrianglePoint closestPointOnTriangle(const Vec3& p, const Vec3 t[3]);

/// Minimum distance between two triangles (degenerate ones included) and the
/// smallest features realising it, with local vertex indices 0..2. Intersecting
/// triangles give distance 0 at a point of the intersection.
struct TriangleDistance {
  double distance = 0.0;
  Vec3 point_a = Vec3::Zero();
  Vec3 point_b = Vec3::Zero();
  Feature feature_a;
  Feature feature_b;
};
TriangleDistance triangleDistance(const Vec3 a[3], const Vec3 b[3]);

/// Distance from p to the segment [a, b] and to the triangle t: helpers for checks.
double pointSegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b);
double pointTriangleDistance(const Vec3& p, const Vec3 t[3]);

}  // namespace sc::detail
