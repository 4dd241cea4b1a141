// SPDX-License-Identifier: MIT
// The conformance tests' axis-aligned cube, as sc.h's AddTriangles takes it.
#pragma once

#include <vector>

namespace sc_conformance {

/// Triangles of the cube of cubeVertices, outward winding.
inline constexpr int kCubeTriangles[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                           3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};

/// Vertices of an axis-aligned cube with lower corner (x, y, z) and edge `size`.
inline std::vector<double> cubeVertices(double x, double y, double z, double size = 1.0) {
  std::vector<double> v;
  const double corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (const auto& c : corners) {
    v.push_back(x + size * c[0]);
    v.push_back(y + size * c[1]);
    v.push_back(z + size * c[2]);
  }
  return v;
}

}  // namespace sc_conformance
