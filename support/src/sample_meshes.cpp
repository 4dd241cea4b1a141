// SPDX-License-Identifier: MIT
#include "sc_support/sample_meshes.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace sc::samples {

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

double torusDepth(double major, double minor, const Vec3& q) {
  const double ring = std::hypot(q.x(), q.z()) - major;
  return minor - std::hypot(ring, q.y());
}

BowlInnerDepth::BowlInnerDepth(const MeshData& bowl, double inner, double outer, int rings,
                               int segments)
    : cells_(static_cast<std::size_t>(rings * segments)),
      inner_(inner),
      outer_(outer),
      rings_(rings),
      segments_(segments) {
  for (const Tri& t : bowl.triangles) {
    const Vec3& a = bowl.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = bowl.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = bowl.vertices[static_cast<std::size_t>(t[2])];
    const double tol = 1e-9 * inner;
    if (std::abs(a.norm() - inner) > tol || std::abs(b.norm() - inner) > tol ||
        std::abs(c.norm() - inner) > tol)
      continue;  // the outer surface or the rim
    const Vec3 centroid = (a + b + c) / 3.0;
    Vec3 n = (b - a).cross(c - a).normalized();
    if (n.dot(centroid) < 0) n = -n;
    int ring = 0, segment = 0;
    cells_[static_cast<std::size_t>(cellOf(centroid, ring, segment))].push_back({n, n.dot(a)});
  }
}

int BowlInnerDepth::cellOf(const Vec3& direction, int& ring, int& segment) const {
  const double phi = std::acos(std::clamp(-direction.y() / direction.norm(), -1.0, 1.0));
  double theta = std::atan2(direction.z(), direction.x());
  if (theta < 0) theta += 2 * kPi;
  ring = std::clamp(static_cast<int>(phi / (0.5 * kPi / rings_)), 0, rings_ - 1);
  segment = std::clamp(static_cast<int>(theta / (2 * kPi / segments_)), 0, segments_ - 1);
  return ring * segments_ + segment;
}

double BowlInnerDepth::operator()(const Vec3& p) const {
  if (p.y() > 0.0 || !(p.norm() > 0.0)) return 0.0;
  // Deep in the shell or beyond it: the sphere is as good as the facets.
  if (p.norm() > 0.5 * (inner_ + outer_)) return p.norm() - inner_;
  int ring = 0, segment = 0;
  cellOf(p, ring, segment);
  // Near the pole every segment's first triangles meet: look at all of them there.
  const bool pole = ring <= 1;
  double depth = -1e300;
  for (int k = std::max(0, ring - 1); k <= std::min(rings_ - 1, ring + 1); ++k)
    for (int dj = pole ? 0 : -1; dj <= (pole ? segments_ - 1 : 1); ++dj) {
      const int j = pole ? dj : (segment + dj + segments_) % segments_;
      for (const Plane& f : cells_[static_cast<std::size_t>(k * segments_ + j)])
        depth = std::max(depth, f.normal.dot(p) - f.offset);
    }
  return depth;
}

}  // namespace sc::samples
