// SPDX-License-Identifier: MIT
// Reads Object File Format (OFF) meshes into MeshData (polygons become triangle
// fans; only what the CGAL sample meshes use: no colours are interpreted), and
// scales a mesh to a given size. The one OFF reader of the tests, demos and benches.
#pragma once

#include <string>

#include "smartcollision/model.h"

namespace sc::support {

/// Parses OFF text: "OFF" (optionally followed by the counts on the same line),
/// then "#vertices #faces #edges", the vertices, and the faces as "n i0 .. i(n-1)"
/// (extra numbers after a face, e.g. a colour, are ignored). '#' starts a comment.
/// InvalidArgument on a bad header, missing or non-numeric data, a non-finite
/// coordinate, a face with fewer than 3 corners or an index out of range.
Result<MeshData> parseOff(const std::string& text);

/// Reads and parses the file; File when it cannot be read.
Result<MeshData> readOff(const std::string& path);

/// readOff for programs that skip what needs a mesh they cannot read: the mesh, or
/// an empty one with the reason on stderr.
MeshData readOffOrEmpty(const std::string& path);

/// The mesh centred on its bounding box and scaled so that the box's largest side is
/// `size` (unscaled when the box is a point; unchanged when there are no vertices).
MeshData fitToSize(MeshData mesh, double size);

}  // namespace sc::support
