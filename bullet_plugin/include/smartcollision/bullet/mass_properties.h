// SPDX-License-Identifier: MIT
// Exact mass properties of a closed triangle mesh (divergence theorem) and its
// principal frame, so a Bullet body can store the mesh centred on its centre of mass.
#pragma once

#include "smartcollision/model.h"

namespace sc::bullet {

/// Mass properties of a uniform solid bounded by a closed mesh, in the mesh's frame.
struct MassProperties {
  double volume = 0.0;                ///< > 0 (an inside-out mesh gives the same values)
  Vec3 center = Vec3::Zero();         ///< centre of mass
  Mat3 inertia = Mat3::Zero();        ///< per unit mass, about `center`, mesh axes
  /// Columns: principal axes, det +1 (mesh_from_principal). Column k is the one
  /// closest to mesh axis k (identity when the mesh axes are already principal).
  Mat3 principal_axes = Mat3::Identity();
  Vec3 principal_moments = Vec3::Zero();  ///< per unit mass, about the columns above
};

/// Sums signed tetrahedra (origin, a, b, c) over the triangles: exact for a closed
/// mesh. InvalidGeometry when the enclosed volume is not positive beyond round-off
/// (flat or open mesh), InvalidArgument for a bad index or a non-finite vertex.
Result<MassProperties> computeMassProperties(const MeshData& mesh);

}  // namespace sc::bullet
