// SPDX-License-Identifier: MIT
// A convex polytope given by its vertices and triangulated boundary: the leaf of
// every closed-polyhedron query (a convex piece, or one patch hull of a
// non-convex piece). Support mapping by hill climbing over vertex adjacency.
#pragma once

#include <vector>

#include "smartcollision/types.h"

namespace sc::detail {

/// Working arrays of ConvexPolytope::finalize, reusable from one polytope to the next.
struct FinalizeScratch {
  std::vector<int> fill, mark, entries;
};

struct ConvexPolytope {
  std::vector<Vec3> vertices;  ///< in the model's local frame
  std::vector<int> original;   ///< per vertex: its index in the input piece
  std::vector<Tri> faces;      ///< outward counter-clockwise, indices into `vertices`
  /// Per face: the index of the input triangle it equals, or -1 for a virtual face.
  std::vector<int> face_source;
  /// Vertex adjacency in CSR form: neighbours of v are
  /// adjacency[adjacency_start[v] .. adjacency_start[v + 1]).
  std::vector<int> adjacency_start;
  std::vector<int> adjacency;
  /// Faces around each vertex, CSR like adjacency: where a closest point is found
  /// from GJK's simplex without scanning every face.
  std::vector<int> vertex_face_start;
  std::vector<int> vertex_faces;
  Aabb bounds;
  Vec3 center = Vec3::Zero();  ///< centre of the bounding sphere
  double radius = 0.0;         ///< bounding sphere radius about `center`

  /// Builds adjacencies, bounds and bounding sphere from vertices and faces. Without
  /// faces (a bare point set) the adjacency and vertex-face arrays are left empty.
  void finalize();
  /// The same with the caller's working arrays: no allocation beyond the results.
  void finalize(FinalizeScratch& scratch);

  /// Index of a vertex maximising dot(direction, vertex). `hint` (in/out) is the
  /// vertex to start hill climbing from; any value in range is valid.
  int support(const Vec3& direction, int& hint) const;

 private:
  void buildAdjacency(FinalizeScratch& scratch);
};

}  // namespace sc::detail
