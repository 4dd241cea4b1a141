// SPDX-License-Identifier: MIT
// Closest points between segments and triangles. Every division is guarded by a
// clamp test first, so degenerate input cannot divide by zero or overflow.
#include "geometry/triangle_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace sc::detail {
namespace {

// Below this squared length a segment is a point (keeps ratios finite).
constexpr double kTinySquared = 1e-300;
// sin^2 of the angle below which segments are treated as parallel: above it the
// closed form loses at most ~1e-6 of the distance's rounding-level accuracy.
constexpr double kParallelSin2 = 1e-20;
// sin^2 of the smallest angle below which a triangle is treated as degenerate.
constexpr double kDegenerateSin2 = 1e-24;

/// clamp(num / den, 0, 1) for den > 0, without dividing when the clamp decides.
double ratio01(double num, double den) {
  if (num <= 0.0) return 0.0;
  if (num >= den) return 1.0;
  return num / den;
}

Feature vertexFeature(int i) {
  Feature f;
  f.type = FeatureType::Vertex;
  f.vertices[0] = i;
  return f;
}

/// The feature of segment (i, j) at parameter t: an endpoint when clamped.
Feature segmentFeature(int i, int j, double t) {
  if (t <= 0.0) return vertexFeature(i);
  if (t >= 1.0) return vertexFeature(j);
  Feature f;
  f.type = FeatureType::Edge;
  f.vertices[0] = i;
  f.vertices[1] = j;
  return f;
}

Feature faceFeature() {
  Feature f;
  f.type = FeatureType::Face;
  f.vertices[0] = 0;
  f.vertices[1] = 1;
  f.vertices[2] = 2;
  return f;
}

/// Parallel segments: the middle of the overlap of q's projection onto p, or the
/// nearer end when they do not overlap.
double overlapMiddle(const Vec3& p0, const Vec3& d1, double a, const Vec3& q0, const Vec3& q1) {
  const double u0 = (q0 - p0).dot(d1) / a;
  const double u1 = (q1 - p0).dot(d1) / a;
  const double lo = std::max(0.0, std::min(u0, u1));
  const double hi = std::min(1.0, std::max(u0, u1));
  if (lo <= hi) return 0.5 * (lo + hi);
  return std::min(u0, u1) > 1.0 ? 1.0 : 0.0;
}

/// (Nearly) parallel segments, parameters (s, t): the minimum is on the boundary
/// of the parameter square up to |p1 - p0| sin(angle), so the best endpoint pair
/// decides; the middle of the overlap wins ties, as a deterministic choice.
std::pair<double, double> parallelClosest(const Vec3& p0, const Vec3& d1, const Vec3& q0,
                                          const Vec3& d2, double a, double b, double c, double e,
                                          double f) {
  const auto gap = [&](double s, double t) { return (p0 + s * d1 - q0 - t * d2).norm(); };
  const double s_mid = overlapMiddle(p0, d1, a, q0, q0 + d2);
  const double t_mid = ratio01(b * s_mid + f, e);
  std::pair<double, double> middle(ratio01(b * t_mid - c, a), t_mid);
  const std::pair<double, double> ends[4] = {{0.0, ratio01(f, e)},
                                             {1.0, ratio01(b + f, e)},
                                             {ratio01(-c, a), 0.0},
                                             {ratio01(b - c, a), 1.0}};
  std::pair<double, double> best = ends[0];
  double best_gap = gap(best.first, best.second);
  for (const auto& st : ends) {
    const double g = gap(st.first, st.second);
    if (g < best_gap) {
      best_gap = g;
      best = st;
    }
  }
  const double tie = 1e-14 * (std::sqrt(a) + std::sqrt(e));
  return gap(middle.first, middle.second) <= best_gap + tie ? middle : best;
}

/// Closest point of the boundary of triangle t to p, over the edges opposite
/// the vertices flagged in `check` (all three for a degenerate triangle).
TrianglePoint closestOnEdges(const Vec3& p, const Vec3 t[3], const bool check[3]) {
  TrianglePoint best;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (!check[i]) continue;
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const SegmentPoint sp = closestPointOnSegment(p, t[j], t[k]);
    const double d2 = (sp.point - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best.point = sp.point;
      best.barycentric = Vec3::Zero();
      best.barycentric[j] = 1.0 - sp.t;
      best.barycentric[k] = sp.t;
      best.feature = segmentFeature(j, k, sp.t);
    }
  }
  return best;
}

struct Candidate {
  double d2 = std::numeric_limits<double>::infinity();
  TriangleDistance result;

  void offer(double d2_new, const Vec3& pa, const Vec3& pb, const Feature& fa, const Feature& fb) {
    if (d2_new >= d2) return;
    d2 = d2_new;
    result.point_a = pa;
    result.point_b = pb;
    result.feature_a = fa;
    result.feature_b = fb;
  }
};

/// Edges of triangle `e` that cross the plane of the non-degenerate triangle `f`:
/// the crossing point against its closest point on f (zero when inside f).
void offerCrossings(const Vec3 e[3], const Vec3 f[3], bool e_is_a, Candidate& best) {
  const Vec3 n = (f[1] - f[0]).cross(f[2] - f[0]);
  const double scale2 = std::max(
      {(f[1] - f[0]).squaredNorm(), (f[2] - f[0]).squaredNorm(), (f[2] - f[1]).squaredNorm()});
  if (n.squaredNorm() <= kDegenerateSin2 * scale2 * scale2) return;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const double si = n.dot(e[i] - f[0]);
    const double sj = n.dot(e[j] - f[0]);
    if (!((si > 0.0 && sj < 0.0) || (si < 0.0 && sj > 0.0))) continue;
    const double t = si / (si - sj);  // si - sj has the sign of si, never zero
    const Vec3 x = e[i] + t * (e[j] - e[i]);
    const TrianglePoint tp = closestPointOnTriangle(x, f);
    Feature edge;
    edge.type = FeatureType::Edge;
    edge.vertices[0] = i;
    edge.vertices[1] = j;
    const double d2 = (x - tp.point).squaredNorm();
    if (e_is_a) {
      best.offer(d2, x, tp.point, edge, tp.feature);
    } else {
      best.offer(d2, tp.point, x, tp.feature, edge);
    }
  }
}

}  // namespace

SegmentPoint closestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = ab.squaredNorm();
  SegmentPoint r;
  r.t = l2 > kTinySquared ? ratio01((p - a).dot(ab), l2) : 0.0;
  r.point = a + r.t * ab;
  return r;
}

SegmentPair closestSegmentSegment(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  // Minimise |r + s d1 - t d2|^2 over the unit square.
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= kTinySquared && e <= kTinySquared) {
    // Two points.
  } else if (a <= kTinySquared) {
    t = ratio01(f, e);
  } else {
    const double c = d1.dot(r);
    if (e <= kTinySquared) {
      s = ratio01(-c, a);
    } else {
      const double b = d1.dot(d2);
      // Unconstrained s = (b f - c e) / (a e - b^2), written with cross products
      // (Lagrange's identity): no cancellation for nearly parallel segments.
      const Vec3 n = d1.cross(d2);
      const double nn = n.squaredNorm();
      if (nn <= kParallelSin2 * a * e) {
        const std::pair<double, double> st = parallelClosest(p0, d1, q0, d2, a, b, c, e, f);
        s = st.first;
        t = st.second;
      } else {
        s = ratio01(n.dot(d2.cross(r)), nn);
        // Best t for this s; if it clamps, the best s for the clamped t.
        const double t_num = b * s + f;
        if (t_num <= 0.0) {
          t = 0.0;
          s = ratio01(-c, a);
        } else if (t_num >= e) {
          t = 1.0;
          s = ratio01(b - c, a);
        } else {
          t = t_num / e;
        }
      }
    }
  }
  SegmentPair out;
  out.s = s;
  out.t = t;
  out.point_p = p0 + s * d1;
  out.point_q = q0 + t * d2;
  out.distance_squared = (out.point_p - out.point_q).squaredNorm();
  return out;
}

TrianglePoint closestPointOnTriangle(const Vec3& p, const Vec3 t[3]) {
  const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]);
  const double nn = n.squaredNorm();
  const double scale2 = std::max(
      {(t[1] - t[0]).squaredNorm(), (t[2] - t[0]).squaredNorm(), (t[2] - t[1]).squaredNorm()});
  if (nn <= kDegenerateSin2 * scale2 * scale2) {
    const bool all[3] = {true, true, true};
    TrianglePoint r = closestOnEdges(p, t, all);
    if (scale2 <= kTinySquared) {  // a point
      r.barycentric = Vec3(1.0, 0.0, 0.0);
      r.feature = vertexFeature(0);
    }
    return r;
  }
  // Barycentric coordinates of p's projection onto the plane: lambda_i is the
  // signed area of (p, t_j, t_k) over the whole, (i, j, k) cyclic.
  Vec3 lambda;
  for (int i = 0; i < 3; ++i) {
    const Vec3& tj = t[(i + 1) % 3];
    const Vec3& tk = t[(i + 2) % 3];
    lambda[i] = n.dot((tj - p).cross(tk - p)) / nn;
  }
  if (lambda.minCoeff() > 0.0) {
    TrianglePoint r;
    // Projection along n is more accurate than summing the weighted vertices.
    r.point = p - n * (n.dot(p - t[0]) / nn);
    r.barycentric = lambda;
    r.feature = faceFeature();
    return r;
  }
  // Outside: the closest point is on an edge whose line p is beyond.
  const bool beyond[3] = {lambda[0] <= 0.0, lambda[1] <= 0.0, lambda[2] <= 0.0};
  return closestOnEdges(p, t, beyond);
}

TriangleDistance triangleDistance(const Vec3 a[3], const Vec3 b[3]) {
  Candidate best;
  for (int i = 0; i < 3; ++i) {
    const TrianglePoint on_b = closestPointOnTriangle(a[i], b);
    best.offer((a[i] - on_b.point).squaredNorm(), a[i], on_b.point, vertexFeature(i), on_b.feature);
    const TrianglePoint on_a = closestPointOnTriangle(b[i], a);
    best.offer((b[i] - on_a.point).squaredNorm(), on_a.point, b[i], on_a.feature, vertexFeature(i));
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3;
      const SegmentPair sp = closestSegmentSegment(a[i], a[i1], b[j], b[j1]);
      best.offer(sp.distance_squared, sp.point_p, sp.point_q, segmentFeature(i, i1, sp.s),
                 segmentFeature(j, j1, sp.t));
    }
  }
  // Vertex-face and edge-edge pairs realise the distance of disjoint triangles;
  // an edge piercing the other triangle is the remaining (intersecting) case.
  if (best.d2 > 0.0) {
    offerCrossings(a, b, true, best);
    offerCrossings(b, a, false, best);
  }
  TriangleDistance out = best.result;
  out.distance = (out.point_a - out.point_b).norm();
  return out;
}

double pointSegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b) {
  return (closestPointOnSegment(p, a, b).point - p).norm();
}

double pointTriangleDistance(const Vec3& p, const Vec3 t[3]) {
  return (closestPointOnTriangle(p, t).point - p).norm();
}

}  // namespace sc::detail
