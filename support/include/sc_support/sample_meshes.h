// SPDX-License-Identifier: MIT
// Procedural closed meshes shared by the tests and the benchmarks: a bowl and a torus
// whose exact solids are known, so overlaps can be measured analytically.
#pragma once

#include <vector>

#include "smartcollision/model.h"

namespace sc::samples {

/// Closed hemispherical bowl (opening up, rim at y = 0): outer radius `outer`, inner
/// `inner`, `rings` latitude rings per surface and `segments` around.
MeshData bowlMesh(double inner, double outer, int rings, int segments);
/// Closed torus around the y axis: radii `major` (of the tube's centre line) and
/// `minor` (of the tube), `around` x `tube` quads, outward.
MeshData torusMesh(double major, double minor, int around, int tube);
/// Depth of point `q` (the torus's own frame) inside the smooth torus of torusMesh's
/// radii (<= 0 outside); the mesh is inscribed in it, so this over-reports the mesh's
/// depth by at most the facets' sagitta.
double torusDepth(double major, double minor, const Vec3& q);

/// Depth of a point in the shell of bowlMesh(inner, outer, rings, segments) through
/// its inner surface, measured on the mesh's own facets (inscribed in the sphere, they
/// lie up to a few millimetres inside it for the bowls the tests use): the largest
/// distance beyond the facet planes around the point's direction.
class BowlInnerDepth {
 public:
  BowlInnerDepth(const MeshData& bowl, double inner, double outer, int rings, int segments);
  /// <= 0 in the hollow or above the rim (y > 0).
  double operator()(const Vec3& p) const;

 private:
  struct Plane {
    Vec3 normal;  ///< away from the centre, into the shell
    double offset;
  };
  int cellOf(const Vec3& direction, int& ring, int& segment) const;
  std::vector<std::vector<Plane>> cells_;  ///< ring-major, rings_ x segments_
  double inner_, outer_;
  int rings_, segments_;
};

}  // namespace sc::samples
