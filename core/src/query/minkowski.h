// SPDX-License-Identifier: MIT
// The Minkowski difference A - B of two convex polytopes as GJK and the expanding
// polytope see it: support points in A's frame, each with the vertex pair it came
// from, and the barycentric weights that map a point of a face back to A and B.
#pragma once

#include "geometry/convex_polytope.h"
#include "smartcollision/types.h"

namespace sc::detail {

/// A point of A - B and the vertex pair it came from (A's frame).
struct MinkowskiVertex {
  Vec3 w;   ///< pa - pb
  Vec3 pa;  ///< on A
  Vec3 pb;  ///< on B
  int ia = -1;
  int ib = -1;
};

/// Support mapping of A - B in A's frame; the hill-climbing hints are carried from
/// call to call.
struct MinkowskiSupport {
  const ConvexPolytope& a;
  const ConvexPolytope& b;
  Rigid a_from_b;
  Mat3 b_from_a_rotation;
  int hint_a;
  int hint_b;

  MinkowskiVertex pair(int ia, int ib) const {
    MinkowskiVertex v;
    v.ia = ia;
    v.ib = ib;
    v.pa = a.vertices[ia];
    v.pb = a_from_b * b.vertices[ib];
    v.w = v.pa - v.pb;
    return v;
  }
  MinkowskiVertex support(const Vec3& d) {
    const int ia = a.support(d, hint_a);
    const int ib = b.support(b_from_a_rotation * (-d), hint_b);
    return pair(ia, ib);
  }
};

/// Barycentric weights of the projection of x on triangle (p0, p1, p2); (1, 0, 0)
/// for a degenerate triangle.
inline Vec3 triangleWeights(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& x) {
  const Vec3 e1 = p1 - p0, e2 = p2 - p0, v = x - p0;
  const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0.0)) return Vec3(1.0, 0.0, 0.0);
  const double u = (d22 * v.dot(e1) - d12 * v.dot(e2)) / det;
  const double t = (d11 * v.dot(e2) - d12 * v.dot(e1)) / det;
  return Vec3(1.0 - u - t, u, t);
}

}  // namespace sc::detail
