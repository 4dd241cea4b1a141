// SPDX-License-Identifier: MIT
#include "geometry/halfspace_polytope.h"

#include <utility>

namespace sc::detail {

HalfspacePolytope::HalfspacePolytope(std::vector<Plane> planes, double depth)
    : planes_(std::move(planes)), depth_(depth) {}

void HalfspacePolytope::reset(const Plane* first, int count, double depth) {
  planes_.assign(first, first + count);
  depth_ = depth;
  hint_ = 0;
  triangle_hint_ = 0;
}

bool HalfspacePolytope::separatedBy(int plane, const Vec3& centre, const Vec3& half) const {
  const Plane& p = planes_[plane];
  const double lowest = p.normal.dot(centre) - p.normal.cwiseAbs().dot(half);
  return lowest >= p.offset - depth_;
}

bool HalfspacePolytope::boxMayReachInterior(const Aabb& box) {
  const int n = static_cast<int>(planes_.size());
  if (n == 0) return true;
  // Once per box, not per plane: the decomposition's tree walks call this most.
  const Vec3 centre = 0.5 * (box.min + box.max);
  const Vec3 half = 0.5 * (box.max - box.min);
  if (separatedBy(hint_, centre, half)) return false;
  for (int i = 0; i < n; ++i) {
    if (i != hint_ && separatedBy(i, centre, half)) {
      hint_ = i;
      return false;
    }
  }
  return true;
}

bool HalfspacePolytope::triangleReachesInterior(const Vec3& a, const Vec3& b, const Vec3& c) {
  const int n = static_cast<int>(planes_.size());
  // A plane with all three corners outside settles it cheaply, before any clipping;
  // the one that did last time first, as neighbouring triangles share it.
  auto outside = [&](int i) {
    const Plane& p = planes_[i];
    const double limit = p.offset - depth_;
    return p.normal.dot(a) >= limit && p.normal.dot(b) >= limit && p.normal.dot(c) >= limit;
  };
  if (n > 0 && triangle_hint_ < n && outside(triangle_hint_)) return false;
  for (int i = 0; i < n; ++i) {
    if (i != triangle_hint_ && outside(i)) {
      triangle_hint_ = i;
      return false;
    }
  }
  polygon_.assign({a, b, c});
  for (int i = 0; i < n && !polygon_.empty(); ++i) {
    const Plane& p = planes_[i];
    const double limit = p.offset - depth_;
    clipped_.clear();
    const int m = static_cast<int>(polygon_.size());
    for (int k = 0; k < m; ++k) {
      const Vec3& from = polygon_[k];
      const Vec3& to = polygon_[(k + 1) % m];
      const double s_from = p.normal.dot(from) - limit;
      const double s_to = p.normal.dot(to) - limit;
      if (s_from <= 0.0) clipped_.push_back(from);
      // Strict sign change: the quotient below has a non-zero denominator.
      if ((s_from < 0.0 && s_to > 0.0) || (s_from > 0.0 && s_to < 0.0)) {
        clipped_.push_back(from + (s_from / (s_from - s_to)) * (to - from));
      }
    }
    std::swap(polygon_, clipped_);
  }
  return !polygon_.empty();
}

}  // namespace sc::detail
