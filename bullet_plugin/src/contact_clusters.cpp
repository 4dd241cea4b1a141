// SPDX-License-Identifier: MIT
// Contact clusters: patches by normal, each spanned by its deepest point and its
// extremes along two tangent axes.
#include "contact_clusters.h"

#include <algorithm>
#include <cmath>

namespace sc::bullet::detail {

namespace {

/// The deepest unlabelled candidate, or -1.
int deepestFree(const std::vector<RowCandidate>& candidates, const std::vector<int>& labels) {
  int best = -1;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (labels[i] >= 0) continue;
    if (best < 0 ||
        candidates[i].separation < candidates[static_cast<std::size_t>(best)].separation)
      best = static_cast<int>(i);
  }
  return best;
}

/// Moments of a patch's candidates in its tangent frame (u, v), accumulated.
struct Moments {
  double n = 0, su = 0, sv = 0, suu = 0, suv = 0, svv = 0, ss = 0, sus = 0, svs = 0, sh = 0;
  double min_u = kInfinity, max_u = -kInfinity, min_v = kInfinity, max_v = -kInfinity;
  double min_s = kInfinity;
  void add(double u, double v, double h, double s) {
    n += 1;
    su += u, sv += v, sh += h, ss += s;
    suu += u * u, suv += u * v, svv += v * v, sus += u * s, svs += v * s;
    min_u = std::min(min_u, u), max_u = std::max(max_u, u);
    min_v = std::min(min_v, v), max_v = std::max(max_v, v);
    min_s = std::min(min_s, s);
  }
};

/// The convex bodies a patch stands on, a bit each (0, 1): the seed's `s`, and those
/// the candidates near it (`near`) that may join it (`joins`) were measured against.
/// The seed alone would decide by a rounding: the other direction's point at the same
/// spot (measured against the non-convex side) split a cow's feet on a slab into two
/// patches, the next step one, and a patch and its rows came and went.
template <class Joins, class Near>
int supportBodies(const std::vector<RowCandidate>& candidates, const RowCandidate& s,
                  const Joins& joins, const Near& near) {
  int bodies = s.convex_body >= 0 ? 1 << s.convex_body : 0;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (candidates[i].convex_body >= 0 && joins(i) && near(i))
      bodies |= 1 << candidates[i].convex_body;
  return bodies;
}

/// Labels the free candidates within kClusterCos of the seed's normal as `label`. A
/// patch of at most kClusterPoints corners keeps them: they are vertices of convex
/// pieces, stable from step to step (Bullet's manifold picks the deepest and widest
/// 4). Any other patch gets its rows from its moments, not from single candidates (the set of
/// leaf contacts changes from step to step as triangles come and go, its moments
/// barely): the centroid, and the centroid moved by sqrt(3) standard deviations (the
/// edge of a uniform patch) each way along both tangent axes, clamped to the patch's
/// extent. Each row's separation is read off a plane of the candidates' separations,
/// tilted as their least-squares plane and as high as the deepest of them say (see
/// the height below), never deeper than the deepest.
void growCluster(const std::vector<RowCandidate>& candidates, int seed, int label, double radius,
                 double depth_scale, std::vector<int>& labels, ContactCluster& c) {
  const RowCandidate& s = candidates[static_cast<std::size_t>(seed)];
  c.normal = s.normal;
  const Vec3 u = s.normal.unitOrthogonal();
  const Vec3 v = s.normal.cross(u);
  const auto joins = [&](std::size_t i) {
    return labels[i] < 0 && candidates[i].normal.dot(s.normal) >= kClusterCos;
  };
  const auto near = [&](std::size_t i) {
    return (candidates[i].on_b - s.on_b).squaredNorm() <= radius * radius;
  };
  const int bodies = supportBodies(candidates, s, joins, near);
  Moments m;
  Vec3 normal_sum = Vec3::Zero();
  bool all_exact = true;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    // Corners of a convex piece form one support polygon however wide, and so do the
    // regions measured against one convex body: its surface lies between them, where
    // split patches made a body on a few feet rock from one patch to the other.
    const int body = candidates[i].convex_body;
    const bool one_support =
        (s.corner && candidates[i].corner) || (body >= 0 && (bodies >> body & 1) != 0);
    if (!joins(i) || (!one_support && !near(i))) continue;
    labels[i] = label;
    const Vec3& p = candidates[i].on_b;
    m.add(u.dot(p), v.dot(p), s.normal.dot(p), candidates[i].separation);
    normal_sum += candidates[i].normal;
    all_exact = all_exact && candidates[i].exact;
  }
  c.count = static_cast<int>(m.n);
  if (all_exact && c.count <= kClusterPoints) {
    c.point_count = 0;
    for (std::size_t i = 0; i < candidates.size(); ++i)
      if (labels[i] == label) c.points[static_cast<std::size_t>(c.point_count++)] = candidates[i];
    return;
  }
  const Vec3 normal = normal_sum.normalized();
  const double cu = m.su / m.n, cv = m.sv / m.n, ms = m.ss / m.n;
  // Centred second moments; a tiny ridge keeps a line or a point well posed.
  const double var_u = std::max(0.0, m.suu / m.n - cu * cu);
  const double var_v = std::max(0.0, m.svv / m.n - cv * cv);
  const double cov = m.suv / m.n - cu * cv;
  const double cov_us = m.sus / m.n - cu * ms, cov_vs = m.svs / m.n - cv * ms;
  const double ridge = 1e-12 + 1e-9 * (var_u + var_v);
  const double a = var_u + ridge, b = cov, d = var_v + ridge;
  const double det = a * d - b * b;
  const double slope_u = det > 0.0 ? (d * cov_us - b * cov_vs) / det : 0.0;
  const double slope_v = det > 0.0 ? (a * cov_vs - b * cov_us) / det : 0.0;
  // The plane's tilt from every candidate (well posed), its height from the deepest:
  // each candidate's separation carried along the tilt to the centroid, weighed by
  // exp(-(height above the deepest) / depth_scale). Unweighted, the many candidates up
  // to the threshold above the contact (the flanks of a leg standing on a floor) lifted
  // the plane, and a cow settled 4.6 mm deep where its rows read touching; smooth
  // weights let a candidate come or go without a jump.
  double wn = 0.0, ws = 0.0;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (labels[i] != label) continue;
    const RowCandidate& q = candidates[i];
    const double w = std::exp(-(q.separation - m.min_s) / depth_scale);
    wn += w;
    ws += w * (q.separation - slope_u * (u.dot(q.on_b) - cu) - slope_v * (v.dot(q.on_b) - cv));
  }
  const double cs = ws / wn;
  const double ru = std::sqrt(3.0 * var_u), rv = std::sqrt(3.0 * var_v);
  const double ch = m.sh / m.n;
  // The four ends first, the centroid last: a manifold holds four points, and the
  // centroid is the one its widest-area reduction would drop (see kManifoldPoints).
  const double offsets[5][2] = {{-ru, 0.0}, {ru, 0.0}, {0.0, -rv}, {0.0, rv}, {0.0, 0.0}};
  c.point_count = 0;
  for (int k = 0; k < 5; ++k) {
    if (k < 4 && (k < 2 ? ru : rv) <= 0.0) continue;  // no extent along that axis
    const double pu = std::clamp(cu + offsets[k][0], m.min_u, m.max_u);
    const double pv = std::clamp(cv + offsets[k][1], m.min_v, m.max_v);
    RowCandidate& r = c.points[static_cast<std::size_t>(c.point_count++)];
    r.on_b = pu * u + pv * v + ch * s.normal;
    r.normal = normal;
    r.separation = std::max(m.min_s, cs + slope_u * (pu - cu) + slope_v * (pv - cv));
  }
}

}  // namespace

int buildClusters(const std::vector<RowCandidate>& candidates, double radius, double depth_scale,
                  std::vector<int>& labels, std::vector<ContactCluster>& clusters) {
  clusters.clear();
  labels.assign(candidates.size(), -1);
  while (static_cast<int>(clusters.size()) < kMaxClusters) {
    const int seed = deepestFree(candidates, labels);
    if (seed < 0) return 0;
    clusters.emplace_back();
    growCluster(candidates, seed, static_cast<int>(clusters.size()) - 1, radius, depth_scale,
                labels, clusters.back());
  }
  return static_cast<int>(std::count(labels.begin(), labels.end(), -1));
}

}  // namespace sc::bullet::detail
