// SPDX-License-Identifier: MIT
// Minimal reader of OFF meshes (polygons fanned into triangles) for the demos.
#pragma once

#include <string>

#include "smartcollision/model.h"

namespace sc::demo {

/// The mesh of an OFF file; empty on a read error (message on stderr).
MeshData readOff(const std::string& path);

}  // namespace sc::demo
