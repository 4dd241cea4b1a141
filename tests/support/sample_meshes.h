// SPDX-License-Identifier: MIT
// Procedural closed meshes shared by the tests and the benchmarks: a bowl and a torus
// whose exact solids are known, so overlaps can be measured analytically.
#pragma once

#include "smartcollision/model.h"

namespace sc::samples {

/// Closed hemispherical bowl (opening up, rim at y = 0): outer radius `outer`, inner
/// `inner`, `rings` latitude rings per surface and `segments` around.
MeshData bowlMesh(double inner, double outer, int rings, int segments);
/// Closed torus around the y axis: radii `major` (of the tube's centre line) and
/// `minor` (of the tube), `around` x `tube` quads, outward.
MeshData torusMesh(double major, double minor, int around, int tube);

}  // namespace sc::samples
