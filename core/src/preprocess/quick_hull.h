// SPDX-License-Identifier: MIT
// A convex hull of our own (Quickhull, Barber, Dobkin and Huhdanpaa 1996) for the
// hull hierarchy's inner nodes: the same kind of polytope as convexHull's, without
// qhull's set-up per call (about half of a soup's build went there). It only
// answers when it can vouch for its result; otherwise the caller uses qhull.
#pragma once

#include <vector>

#include "geometry/convex_polytope.h"

namespace sc::detail {

/// Reusable scratch space of quickHull (one per thread): no allocation per hull
/// once it has grown to the largest input.
struct QuickHullWorkspace {
  struct Face {
    int v[3];
    int adj[3];  ///< face across edge v[k] -> v[k + 1]
    Vec3 normal;
    double offset;
    int outside;  ///< first point of its outside set (linked by next_point), or -1
    int visit;
    int serial;  ///< creation order: a reused slot's face is a new face
    bool alive;
  };
  /// Depth-first walk over the faces an eye sees: face, first edge, edges done.
  struct Frame {
    int face, first, step;
  };
  std::vector<Face> faces;
  /// Slots of faces removed in earlier steps, reused by new faces: the array holds
  /// about the live faces, not every face ever made (twenty per point on a large
  /// hull of near-coplanar points).
  std::vector<int> free_faces;
  std::vector<Frame> frames;
  std::vector<int> next_point;
  std::vector<int> point_mark;  ///< per point: visit it was last seen on the horizon
  std::vector<int> stack;       ///< pairs (face, serial): a reused slot's old entry is stale
  std::vector<int> visible;
  std::vector<int> horizon;  ///< pairs (face, edge)
  std::vector<int> created;
  std::vector<int> alive;  ///< live faces by serial, for the output
  std::vector<int> orphans;
  std::vector<int> vertex_slot;
  std::vector<int> slot_point;  ///< per output vertex: its point
  std::vector<char> excluded;   ///< per point: dropped as no corner
  std::vector<int> dropped;
  int visit = 0;
};

/// The convex hull of `points` (at least four), triangulated, outward counter-
/// clockwise, each vertex keeping `original[i]` of its point; every vertex a strict
/// corner and every edge convex, as convexHull gives. False, with `out` unspecified,
/// when the points are (nearly) flat or the result fails those checks: then qhull
/// is to decide.
/// `keep` as in ConvexPolytope::build.
bool quickHull(const std::vector<Vec3>& points, const std::vector<int>& original,
               QuickHullWorkspace& work, ConvexPolytope& out,
               PolytopeKeep keep = PolytopeKeep::Everything);

}  // namespace sc::detail
