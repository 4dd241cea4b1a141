// SPDX-License-Identifier: MIT
#include "support/sample_meshes.h"

#include <cmath>
#include <cstddef>

namespace sc::samples {
namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

MeshData bowlMesh(double inner, double outer, int rings, int segments) {
  MeshData m;
  auto ring = [&](double r, int k) {  // vertex index of ring k's first vertex on radius r
    const int first = static_cast<int>(m.vertices.size());
    const double phi = 0.5 * kPi * k / rings;  // from the bottom pole
    for (int j = 0; j < segments; ++j) {
      const double theta = 2 * kPi * j / segments;
      m.vertices.emplace_back(r * std::sin(phi) * std::cos(theta), -r * std::cos(phi),
                              r * std::sin(phi) * std::sin(theta));
    }
    return first;
  };
  // Orients each triangle so that its normal agrees with `outward` (solid's outside).
  auto add = [&](int a, int b, int c, const Vec3& outward) {
    const Vec3& pa = m.vertices[static_cast<std::size_t>(a)];
    const Vec3 n = (m.vertices[static_cast<std::size_t>(b)] - pa)
                       .cross(m.vertices[static_cast<std::size_t>(c)] - pa);
    m.triangles.push_back(n.dot(outward) >= 0 ? Tri(a, b, c) : Tri(a, c, b));
  };
  auto centroid = [&](int a, int b, int c) {
    return Vec3((m.vertices[static_cast<std::size_t>(a)] + m.vertices[static_cast<std::size_t>(b)] +
                 m.vertices[static_cast<std::size_t>(c)]) /
                3.0);
  };
  int rims[2] = {0, 0};
  for (int s = 0; s < 2; ++s) {
    const double r = s == 0 ? outer : inner;
    const double sign = s == 0 ? 1.0 : -1.0;  // outer faces away from the centre, inner towards
    const int pole = static_cast<int>(m.vertices.size());
    m.vertices.emplace_back(0, -r, 0);
    int prev = -1;
    for (int k = 1; k <= rings; ++k) {
      const int cur = ring(r, k);
      for (int j = 0; j < segments; ++j) {
        const int j1 = (j + 1) % segments;
        if (prev < 0) {
          add(pole, cur + j, cur + j1, sign * centroid(pole, cur + j, cur + j1));
        } else {
          add(prev + j, cur + j, cur + j1, sign * centroid(prev + j, cur + j, cur + j1));
          add(prev + j, cur + j1, prev + j1, sign * centroid(prev + j, cur + j1, prev + j1));
        }
      }
      prev = cur;
    }
    rims[s] = prev;
  }
  for (int j = 0; j < segments; ++j) {  // the flat rim joins the two surfaces
    const int j1 = (j + 1) % segments;
    add(rims[0] + j, rims[1] + j, rims[1] + j1, Vec3::UnitY());
    add(rims[0] + j, rims[1] + j1, rims[0] + j1, Vec3::UnitY());
  }
  return m;
}

MeshData torusMesh(double major, double minor, int around, int tube) {
  MeshData m;
  for (int i = 0; i < around; ++i) {
    const double u = 2 * kPi * i / around;
    for (int j = 0; j < tube; ++j) {
      const double v = 2 * kPi * j / tube;
      const double r = major + minor * std::cos(v);
      m.vertices.emplace_back(r * std::cos(u), minor * std::sin(v), r * std::sin(u));
    }
  }
  auto at = [&](int i, int j) { return (i % around) * tube + (j % tube); };
  for (int i = 0; i < around; ++i) {
    for (int j = 0; j < tube; ++j) {
      // (u, v) increase counter-clockwise seen from outside: outward normals.
      m.triangles.push_back(Tri(at(i, j), at(i, j + 1), at(i + 1, j)));
      m.triangles.push_back(Tri(at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)));
    }
  }
  return m;
}

}  // namespace sc::samples
