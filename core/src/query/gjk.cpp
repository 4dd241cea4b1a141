// SPDX-License-Identifier: MIT
// GJK distance between two convex polytopes. Outline (van den Bergen 1999):
//  1. work in A's frame, so precision depends on the relative placement only;
//  2. start from the cached vertex pairs re-evaluated in the current poses
//     (affinely dependent ones dropped), or from one support point;
//  3. repeat: w = support of A - B in -v; stop when w is already in the simplex,
//     gives no progress (v.v - v.w <= eps v.v), or the lower bound v.w/|v|
//     exceeds max_distance; else add w and reduce the simplex to the smallest
//     one holding the point closest to the origin.
// The reduction is the signed-volumes idea of Montanari et al. (2017): the
// barycentric coordinates of the origin's projection decide the region, and
// only sub-simplices the origin lies beyond are searched. Departure: we solve
// every sub-simplex by plain barycentric coordinates (no projection to the best
// axis-aligned plane), and a degenerate (sub-)simplex searches all its faces.
#include "query/gjk.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/math_util.h"
#include "query/minkowski.h"

namespace sc::detail {
namespace {

// Converged when v.v - v.w <= kRelativeGap * v.v: relative distance error <= kRelativeGap.
constexpr double kRelativeGap = 1e-12;
// The origin is on the CSO when |v| <= kTouching * (size of the pair).
constexpr double kTouching = 1e-12;
// Squared lengths below this are zero (keeps every ratio finite).
constexpr double kTiny = 1e-300;
// sin^2 (triangle) and |sin| (tetrahedron) of a simplex treated as degenerate.
constexpr double kFlatTriangle = 1e-20;
constexpr double kFlatTetrahedron = 1e-12;
// Cached vertices closer than this to affine dependence are dropped.
constexpr double kWarmIndependence = 1e-6;

using Vertex = MinkowskiVertex;

struct Simplex {
  Vertex v[4];
  double lambda[4] = {1.0, 0.0, 0.0, 0.0};
  int count = 0;
  Vec3 closest = Vec3::Zero();  ///< point of the simplex nearest the origin
  double vv = 0.0;              ///< |closest|^2
};

/// Sub-simplex of `s` (indices into s.v) and the weights of its nearest point.
struct Reduced {
  int count = 0;
  int idx[4] = {0, 0, 0, 0};
  double lambda[4] = {1.0, 0.0, 0.0, 0.0};
  Vec3 closest = Vec3::Zero();
  double vv = std::numeric_limits<double>::infinity();
};

Reduced single(const Vertex* s, int i) {
  Reduced r;
  r.count = 1;
  r.idx[0] = i;
  r.closest = s[i].w;
  r.vv = r.closest.squaredNorm();
  return r;
}

Reduced solveSegment(const Vertex* s, int i, int j) {
  const Vec3 d = s[j].w - s[i].w;
  const double dd = d.squaredNorm();
  const double num = -s[i].w.dot(d);  // projection parameter times dd
  if (dd <= kTiny || num <= 0.0) return single(s, i);
  if (num >= dd) return single(s, j);
  const double t = num / dd;
  Reduced r;
  r.count = 2;
  r.idx[0] = i;
  r.idx[1] = j;
  r.lambda[0] = 1.0 - t;
  r.lambda[1] = t;
  r.closest = s[i].w + t * d;
  r.vv = r.closest.squaredNorm();
  return r;
}

void keepNearer(const Reduced& candidate, Reduced& best) {
  if (candidate.vv < best.vv) best = candidate;
}

Reduced solveTriangle(const Vertex* s, int i, int j, int k) {
  const Vec3 e1 = s[j].w - s[i].w, e2 = s[k].w - s[i].w;
  const Vec3 n = e1.cross(e2);
  const double nn = n.squaredNorm();
  Reduced best;
  if (nn <= kFlatTriangle * e1.squaredNorm() * e2.squaredNorm() || nn <= kTiny) {
    keepNearer(solveSegment(s, i, j), best);
    keepNearer(solveSegment(s, j, k), best);
    keepNearer(solveSegment(s, k, i), best);
    return best;
  }
  // Origin's projection = s_i + a e1 + b e2.
  const Vec3 q = -s[i].w;
  const double a = n.dot(q.cross(e2)) / nn;
  const double b = n.dot(e1.cross(q)) / nn;
  const double c = 1.0 - a - b;
  if (a > 0.0 && b > 0.0 && c > 0.0) {
    best.count = 3;
    best.idx[0] = i;
    best.idx[1] = j;
    best.idx[2] = k;
    best.lambda[0] = c;
    best.lambda[1] = a;
    best.lambda[2] = b;
    best.closest = n * (n.dot(s[i].w) / nn);  // exactly along the normal
    best.vv = best.closest.squaredNorm();
    return best;
  }
  // The nearest point is on an edge whose line the origin is beyond.
  if (c <= 0.0) keepNearer(solveSegment(s, j, k), best);
  if (a <= 0.0) keepNearer(solveSegment(s, k, i), best);
  if (b <= 0.0) keepNearer(solveSegment(s, i, j), best);
  return best;
}

Reduced solveTetrahedron(const Vertex* s) {
  const Vec3 e1 = s[1].w - s[0].w, e2 = s[2].w - s[0].w, e3 = s[3].w - s[0].w;
  const double det = e1.dot(e2.cross(e3));
  const double size = e1.norm() * e2.norm() * e3.norm();
  bool beyond[4] = {true, true, true, true};
  if (std::abs(det) > kFlatTetrahedron * size && std::abs(det) > kTiny) {
    const Vec3 q = -s[0].w;
    const double l1 = q.dot(e2.cross(e3)) / det;
    const double l2 = e1.dot(q.cross(e3)) / det;
    const double l3 = e1.dot(e2.cross(q)) / det;
    const double l0 = 1.0 - l1 - l2 - l3;
    if (l0 > 0.0 && l1 > 0.0 && l2 > 0.0 && l3 > 0.0) {
      Reduced inside;
      inside.count = 4;
      for (int m = 0; m < 4; ++m) inside.idx[m] = m;
      inside.lambda[0] = l0;
      inside.lambda[1] = l1;
      inside.lambda[2] = l2;
      inside.lambda[3] = l3;
      inside.vv = 0.0;
      return inside;
    }
    beyond[0] = l0 <= 0.0;
    beyond[1] = l1 <= 0.0;
    beyond[2] = l2 <= 0.0;
    beyond[3] = l3 <= 0.0;
  }
  // Face opposite vertex m, searched when the origin is beyond it.
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  Reduced best;
  for (int m = 0; m < 4; ++m) {
    if (beyond[m]) keepNearer(solveTriangle(s, kFace[m][0], kFace[m][1], kFace[m][2]), best);
  }
  return best;
}

/// Replaces `s` by its sub-simplex nearest the origin.
void reduce(Simplex& s) {
  Reduced r;
  switch (s.count) {
    case 1:
      r = single(s.v, 0);
      break;
    case 2:
      r = solveSegment(s.v, 0, 1);
      break;
    case 3:
      r = solveTriangle(s.v, 0, 1, 2);
      break;
    default:
      r = solveTetrahedron(s.v);
      break;
  }
  Vertex kept[4];
  for (int m = 0; m < r.count; ++m) kept[m] = s.v[r.idx[m]];
  for (int m = 0; m < r.count; ++m) {
    s.v[m] = kept[m];
    s.lambda[m] = r.lambda[m];
  }
  s.count = r.count;
  s.closest = r.closest;
  s.vv = r.count == 4 ? 0.0 : r.vv;
}

using Cso = MinkowskiSupport;

bool contains(const Simplex& s, const Vertex& w) {
  for (int m = 0; m < s.count; ++m) {
    if (s.v[m].ia == w.ia && s.v[m].ib == w.ib) return true;
  }
  return false;
}

/// True when w is affinely independent of the simplex, well enough to keep.
bool independent(const Simplex& s, const Vertex& w, double scale) {
  if (s.count == 0) return true;
  const Vec3 e = w.w - s.v[0].w;
  if (e.norm() <= kWarmIndependence * scale) return false;
  if (s.count == 1) return true;
  const Vec3 e1 = s.v[1].w - s.v[0].w;
  if (s.count == 2) return e1.cross(e).norm() > kWarmIndependence * e1.norm() * e.norm();
  const Vec3 e2 = s.v[2].w - s.v[0].w;
  return s.count == 3 &&
         std::abs(e1.dot(e2.cross(e))) > kWarmIndependence * e1.norm() * e2.norm() * e.norm();
}

/// The cached vertex pairs re-evaluated in the current poses, or one support point.
Simplex startSimplex(const SimplexCache& cache, Cso& cso, double scale) {
  Simplex s;
  const int na = static_cast<int>(cso.a.vertices.size());
  const int nb = static_cast<int>(cso.b.vertices.size());
  for (int m = 0; m < std::min(cache.count, 4); ++m) {
    if (cache.a[m] < 0 || cache.a[m] >= na || cache.b[m] < 0 || cache.b[m] >= nb) continue;
    const Vertex w = cso.pair(cache.a[m], cache.b[m]);
    if (!contains(s, w) && independent(s, w, scale)) s.v[s.count++] = w;
  }
  if (s.count == 0) {
    // Towards B's centre: the part of A - B nearest the origin.
    const Vec3 d = cso.a_from_b * cso.b.center - cso.a.center;
    s.v[s.count++] = cso.support(normalizedOr(d, Vec3::UnitX()));
  }
  reduce(s);
  return s;
}

/// Writes the simplex's vertex pairs into the result and the cache.
void record(const Simplex& s, const Cso& cso, GjkResult& result, SimplexCache& cache) {
  result.count = s.count;
  cache.count = s.count;
  for (int m = 0; m < 4; ++m) {
    const bool used = m < s.count;
    result.a[m] = used ? s.v[m].ia : -1;
    result.b[m] = used ? s.v[m].ib : -1;
    cache.a[m] = used ? s.v[m].ia : 0;
    cache.b[m] = used ? s.v[m].ib : 0;
  }
  cache.hint_a = cso.hint_a;
  cache.hint_b = cso.hint_b;
}

/// Closest points from the barycentric weights, mapped to the common frame.
void writePoints(const Simplex& s, const Rigid& frame_from_a, GjkResult& result) {
  Vec3 pa = Vec3::Zero(), pb = Vec3::Zero();
  for (int m = 0; m < s.count; ++m) {
    pa += s.lambda[m] * s.v[m].pa;
    pb += s.lambda[m] * s.v[m].pb;
  }
  const Vec3 d = pa - pb;
  result.distance = d.norm();
  result.lower_bound = std::min(result.lower_bound, result.distance);
  result.point_a = frame_from_a * pa;
  result.point_b = frame_from_a * pb;
  result.normal = frame_from_a.rotation * normalizedOr(d, Vec3::UnitX());
}

/// Finite coefficients, tested without arithmetic (inf - inf would trap).
template <class M>
bool finite(const M& m) {
  for (int k = 0; k < m.size(); ++k) {
    if (!std::isfinite(m.data()[k])) return false;
  }
  return true;
}

bool usable(const ConvexPolytope& p, const Rigid& frame_from_p) {
  return !p.vertices.empty() && finite(frame_from_p.rotation) && finite(frame_from_p.translation);
}

}  // namespace

GjkResult gjkDistance(const ConvexPolytope& a, const Rigid& frame_from_a, const ConvexPolytope& b,
                      const Rigid& frame_from_b, const GjkSettings& settings, SimplexCache& cache) {
  GjkResult result;
  if (!usable(a, frame_from_a) || !usable(b, frame_from_b)) {
    result.status = GjkStatus::NotConverged;
    return result;
  }
  const Rigid a_from_b = frame_from_a.inverse() * frame_from_b;
  const int na = static_cast<int>(a.vertices.size());
  const int nb = static_cast<int>(b.vertices.size());
  Cso cso{a,
          b,
          a_from_b,
          a_from_b.rotation.transpose(),
          std::clamp(cache.hint_a, 0, na - 1),
          std::clamp(cache.hint_b, 0, nb - 1)};
  const double scale = a.radius + b.radius + (a_from_b * b.center - a.center).norm();
  const double touching2 = kTouching * kTouching * scale * scale;
  const double within2 =
      settings.within_distance >= 0.0 ? settings.within_distance * settings.within_distance : -1.0;

  // The motion in A's frame, where the support points live.
  const bool sweeping = std::isfinite(settings.motion_clearance);
  const Vec3 motion_a =
      sweeping ? Vec3(frame_from_a.rotation.transpose() * settings.motion) : Vec3::Zero();
  Simplex s = startSimplex(cache, cso, scale);
  double lower = 0.0;
  GjkStatus status = GjkStatus::NotConverged;
  for (;;) {
    if (s.count == 4 || s.vv <= touching2) {
      status = GjkStatus::Intersecting;
      break;
    }
    if (s.vv <= within2) {  // s.vv bounds the squared distance from above
      status = GjkStatus::WithinDistance;
      break;
    }
    if (result.iterations >= settings.max_iterations) break;
    ++result.iterations;
    const Vertex w = cso.support(-s.closest);
    const double vw = s.closest.dot(w.w);
    if (vw > 0.0) lower = std::max(lower, vw / std::sqrt(s.vv));
    // Every point x of A - B has x . v >= v . w: moved by part of the motion, at least
    // that plus the motion's least (negative) share along v.
    if (lower > settings.max_distance ||
        (sweeping && vw + std::min(0.0, motion_a.dot(s.closest)) >
                         settings.motion_clearance * std::sqrt(s.vv))) {
      status = GjkStatus::BeyondMaxDistance;
      break;
    }
    if (contains(s, w) || s.vv - vw <= kRelativeGap * s.vv) {
      status = GjkStatus::Separated;
      break;
    }
    Simplex next = s;
    next.v[next.count++] = w;
    reduce(next);
    if (next.count < 4 && next.vv >= s.vv) {
      // No progress: rounding has the last word; the current simplex is the answer.
      status = GjkStatus::Separated;
      break;
    }
    s = next;
  }

  result.status = status;
  record(s, cso, result, cache);
  if (status == GjkStatus::Intersecting) return result;  // distance and bound stay 0
  result.lower_bound = lower;
  if (status == GjkStatus::BeyondMaxDistance || status == GjkStatus::WithinDistance) {
    result.distance = std::sqrt(s.vv);  // an upper bound; only lower_bound is promised
    return result;
  }
  writePoints(s, frame_from_a, result);
  return result;
}

}  // namespace sc::detail
