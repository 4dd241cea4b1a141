// SPDX-License-Identifier: MIT
// Test shape generators: closed outward meshes and convex polytopes (boxes,
// tetrahedra, hulls of random points) at chosen or random scales.
#pragma once

#include <string>
#include <vector>

#include "geometry/convex_polytope.h"
#include "sc_support/sample_meshes.h"
#include "smartcollision/group.h"
#include "smartcollision/model.h"
#include "smartcollision/pair_tracker.h"
#include "smartcollision/placement.h"
#include "support/test_support.h"

namespace sc::test {

/// exp(uniform(log lo, log hi)).
double logUniform(Rng& rng, double lo, double hi);

/// Axis-aligned box centred at the origin, 12 triangles, outward CCW.
MeshData boxMesh(const Vec3& half_extents);
/// closedModel(boxMesh(half_extents)).
ModelPtr boxModel(const Vec3& half_extents);
/// A one-piece closed-polyhedron model of `mesh`; a test failure and null if the
/// piece cannot be built.
ModelPtr closedModel(const MeshData& mesh);
/// A regular prism about the z axis: `sides` rim vertices at `circumradius` on each of
/// z = -half_height and z = half_height, each end a fan (outward CCW).
MeshData prismMesh(int sides, double circumradius, double half_height);
/// A bar (a box of half extents `bar_half`, part 1) over a 6 m x 1 m x 6 m slab (part
/// 2) whose top face is y = 0: the scene of the bar-on-floor tests.
struct BarOnSlab {
  explicit BarOnSlab(const Vec3& bar_half)
      : bar(boxModel(bar_half)),
        slab(boxModel(Vec3(3, 0.5, 3))),
        a{bar.get(), Rigid(), 1},
        b{slab.get(), Rigid(), 2} {
    slab_at.world_center = Vec3(0, -0.5, 0);
  }
  bool ok() const { return bar && slab; }
  /// The bar at `bar_at` against the slab, target direction only.
  void query(PairTracker& tracker, const Placement& bar_at, const PairSettings& settings,
             DirectedResult out[2]) const {
    tracker.update({&a, 1, bar_at}, {&b, 1, slab_at}, {true, false}, settings, out);
  }

  ModelPtr bar, slab;
  Part a, b;
  Placement slab_at;  ///< the slab's placement
};

/// Regular tetrahedron centred at the origin with the given circumradius.
MeshData regularTetrahedronMesh(double circumradius);
/// Random well-shaped tetrahedron of about `size` around the origin, outward CCW.
MeshData randomTetrahedronMesh(Rng& rng, double size);
/// n random points in a random ellipsoid of radius about `size` around the origin.
std::vector<Vec3> randomPoints(Rng& rng, int n, double size);

/// The polytope with exactly the mesh's vertices and triangles (a convex mesh),
/// every face real (face_source = triangle index), original = vertex index.
detail::ConvexPolytope polytopeFromMesh(const MeshData& mesh);
/// The hull of the points via convexHull (faces virtual, original = point index);
/// hull faces equal to a triangle of `real_faces` are marked real.
detail::ConvexPolytope hullOf(const std::vector<Vec3>& points,
                              const MeshData* real_faces = nullptr);
/// The polytope's faces as a mesh over its own vertex array.
MeshData meshOf(const detail::ConvexPolytope& poly);
/// A one-piece closed-polyhedron model of the polytope, which the build must find
/// convex (a test failure otherwise); null if the piece cannot be built.
ModelPtr convexModel(const detail::ConvexPolytope& poly);

/// A random convex shape for property tests: its polytope and the points its
/// `original` indices refer to.
struct ConvexShape {
  detail::ConvexPolytope poly;
  std::vector<Vec3> points;
  const char* kind = "";
};
/// Hull of 4..60 random points, a box or a tetrahedron, of about `size`.
ConvexShape randomConvexShape(Rng& rng, double size);

using samples::bowlMesh;
using samples::torusMesh;
/// A CGAL mesh from SC_MESH_DIR (e.g. "cow.off") scaled so that its largest extent
/// is `size`, centred on its bounds; empty when it cannot be read.
MeshData scaledOff(const std::string& name, double size);

}  // namespace sc::test
