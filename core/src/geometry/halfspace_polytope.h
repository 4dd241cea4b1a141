// SPDX-License-Identifier: MIT
// A convex polytope as an intersection of half-spaces, and whether boxes and
// triangles reach its interior deeper than a margin (Sutherland-Hodgman clipping).
#pragma once

#include <vector>

#include "smartcollision/types.h"

namespace sc::detail {

/// The half-space normal . x <= offset; `normal` is unit length.
struct Plane {
  Vec3 normal = Vec3::UnitZ();
  double offset = 0.0;

  double signedDistance(const Vec3& p) const { return normal.dot(p) - offset; }
};

/// The points at least `depth` inside every plane (the polytope shrunk by depth).
/// Queries keep scratch buffers: one object per thread.
class HalfspacePolytope {
 public:
  HalfspacePolytope(std::vector<Plane> planes, double depth);

  /// Becomes the polytope of planes [first, first + count) at `depth`, keeping its
  /// arrays' capacity: a loop that makes many small polytopes allocates once.
  void reset(const Plane* first, int count, double depth);

  /// False when some plane has the whole box outside the shrunk polytope.
  bool boxMayReachInterior(const Aabb& box);
  /// True when some point of triangle abc lies in the shrunk polytope (closed).
  bool triangleReachesInterior(const Vec3& a, const Vec3& b, const Vec3& c);
  const std::vector<Plane>& planes() const { return planes_; }

 private:
  /// Whether the box (centre, half extents) lies outside `plane` shrunk by depth_.
  bool separatedBy(int plane, const Vec3& centre, const Vec3& half) const;

  std::vector<Plane> planes_;
  double depth_;
  int hint_ = 0;           ///< plane that separated last time: neighbouring queries share it
  int triangle_hint_ = 0;  ///< the same for triangles
  std::vector<Vec3> polygon_, clipped_;
};

}  // namespace sc::detail
