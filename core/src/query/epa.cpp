// SPDX-License-Identifier: MIT
#include "query/epa.h"

#include <cmath>
#include <vector>

#include "geometry/math_util.h"
#include "preprocess/convex_hull.h"
#include "query/minkowski.h"

namespace sc::detail {

namespace {

struct SupportSet {
  std::vector<Vec3> w;   ///< a - b
  std::vector<Vec3> pa;
  std::vector<Vec3> pb;
};

class Difference {
 public:
  Difference(const ConvexPolytope& a, const Rigid& fa, const ConvexPolytope& b, const Rigid& fb)
      : a_(a), b_(b), fa_(fa), fb_(fb) {}

  void add(const Vec3& d, SupportSet& s) {
    const Vec3 pa = fa_ * a_.vertices[a_.support(fa_.rotation.transpose() * d, hint_a_)];
    const Vec3 pb = fb_ * b_.vertices[b_.support(-(fb_.rotation.transpose() * d), hint_b_)];
    s.w.push_back(pa - pb);
    s.pa.push_back(pa);
    s.pb.push_back(pb);
  }

 private:
  const ConvexPolytope& a_;
  const ConvexPolytope& b_;
  Rigid fa_, fb_;
  int hint_a_ = 0, hint_b_ = 0;
};

}  // namespace

EpaResult penetrationDepth(const ConvexPolytope& a, const Rigid& frame_from_a,
                           const ConvexPolytope& b, const Rigid& frame_from_b,
                           int max_iterations) {
  EpaResult out;
  Difference diff(a, frame_from_a, b, frame_from_b);
  SupportSet set;
  for (int i = 0; i < 3; ++i) {
    diff.add(Vec3::Unit(i), set);
    diff.add(-Vec3::Unit(i), set);
  }
  for (int sx = -1; sx <= 1; sx += 2)
    for (int sy = -1; sy <= 1; sy += 2)
      for (int sz = -1; sz <= 1; sz += 2) diff.add(Vec3(sx, sy, sz).normalized(), set);
  double scale = 0.0;
  for (const Vec3& w : set.w) scale = std::max(scale, w.norm());
  const double eps = 1e-12 * scale;  // relative: the pieces' scale is theirs
  for (int it = 0; it < max_iterations; ++it) {
    out.iterations = it + 1;
    const auto hull = convexHull(set.w);
    if (!hull.ok()) {
      // Flat difference: the pieces only touch within a plane.
      out.status = EpaStatus::Touching;
      return out;
    }
    const ConvexPolytope& h = hull.value();
    int best = -1;
    double best_d = kInfinity;
    Vec3 best_n = Vec3::UnitZ();
    for (int f = 0; f < static_cast<int>(h.faces.size()); ++f) {
      const Tri& t = h.faces[f];
      const Vec3 n = normalizedOr(
          (h.vertices[t[1]] - h.vertices[t[0]]).cross(h.vertices[t[2]] - h.vertices[t[0]]),
          Vec3::Zero());
      if (n.isZero()) continue;
      const double d = n.dot(h.vertices[t[0]]);
      if (d < best_d) {
        best_d = d;
        best = f;
        best_n = n;
      }
    }
    if (best < 0) return out;
    const size_t before = set.w.size();
    diff.add(best_n, set);
    const double gain = best_n.dot(set.w.back()) - best_d;
    const bool done = gain <= eps;
    if (done || it + 1 == max_iterations) {
      set.w.resize(before);  // the last support point is not needed
      out.status = done ? EpaStatus::Converged : EpaStatus::NotConverged;
      out.depth = std::max(0.0, best_d);
      if (out.depth == 0.0) out.status = EpaStatus::Touching;
      // Moving A by -(facet point) separates: the facet's outward normal is n, so
      // the origin leaves through it when A - B shifts by -depth * n.
      out.normal = -best_n;
      const Tri& t = h.faces[best];
      const int i0 = h.original[t[0]], i1 = h.original[t[1]], i2 = h.original[t[2]];
      const Vec3 lambda = triangleWeights(set.w[i0], set.w[i1], set.w[i2], best_d * best_n);
      out.point_a = lambda[0] * set.pa[i0] + lambda[1] * set.pa[i1] + lambda[2] * set.pa[i2];
      out.point_b = lambda[0] * set.pb[i0] + lambda[1] * set.pb[i1] + lambda[2] * set.pb[i2];
      return out;
    }
  }
  return out;
}

}  // namespace sc::detail
