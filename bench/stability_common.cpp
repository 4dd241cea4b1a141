// SPDX-License-Identifier: MIT
// Boxes and their exact penetration depth for the stability matrix.
#include "stability_common.h"

#include <algorithm>
#include <limits>

namespace stab {

Vec3 Box::support(const Vec3& d) const {
  const Vec3 local = rotation.transpose() * d;
  Vec3 corner;
  for (int k = 0; k < 3; ++k) corner[k] = local[k] >= 0 ? half[k] : -half[k];
  return centre + rotation * corner;
}

sc::MeshData boxMesh(const Vec3& half) {
  sc::MeshData m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                            (i & 4) ? half.z() : -half.z());
  // Each face as two triangles; the winding is fixed afterwards from the face's
  // outward direction, which is simpler to get right than twelve literal triples.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    for (const sc::Tri& t : {sc::Tri(f[0], f[1], f[2]), sc::Tri(f[0], f[2], f[3])}) {
      const Vec3& p0 = m.vertices[std::size_t(t[0])];
      const Vec3 n = (m.vertices[std::size_t(t[1])] - p0).cross(m.vertices[std::size_t(t[2])] - p0);
      const Vec3 out = (p0 + m.vertices[std::size_t(t[1])] + m.vertices[std::size_t(t[2])]) / 3.0;
      m.triangles.push_back(n.dot(out) > 0 ? t : sc::Tri(t[0], t[2], t[1]));
    }
  }
  return m;
}

namespace {

/// Half the box's extent along unit n.
double radius(const Box& b, const Vec3& n) {
  double r = 0.0;
  for (int k = 0; k < 3; ++k) r += std::abs(n.dot(b.rotation.col(k))) * b.half[k];
  return r;
}

}  // namespace

double boxDepth(const Box& a, const Box& b, Vec3* axis) {
  std::vector<Vec3> candidates;
  for (int i = 0; i < 3; ++i) {
    candidates.push_back(a.rotation.col(i));
    candidates.push_back(b.rotation.col(i));
    for (int j = 0; j < 3; ++j) {
      const Vec3 c = a.rotation.col(i).cross(b.rotation.col(j));
      if (c.norm() > 1e-9) candidates.push_back(c.normalized());  // parallel edges add nothing
    }
  }
  const Vec3 d = b.centre - a.centre;
  double best = std::numeric_limits<double>::infinity();
  for (Vec3 n : candidates) {
    if (n.dot(d) < 0) n = -n;
    const double overlap = radius(a, n) + radius(b, n) - n.dot(d);
    if (overlap < best) {
      best = overlap;
      if (axis) *axis = n;
    }
  }
  return best;
}

Mat3 rotationZ(double radians) {
  return Eigen::AngleAxisd(radians, Vec3::UnitZ()).toRotationMatrix();
}

}  // namespace stab
