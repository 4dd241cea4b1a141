// SPDX-License-Identifier: MIT
// Mass properties by the divergence theorem: each triangle (a, b, c) closes a signed
// tetrahedron with a reference point; their sums are exact for a closed mesh.
#include "smartcollision/bullet/mass_properties.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace sc::bullet {

Result<MassProperties> computeMassProperties(const MeshData& mesh) {
  const int n = static_cast<int>(mesh.vertices.size());
  if (n == 0 || mesh.triangles.empty()) return Status(ErrorCode::InvalidGeometry, "empty mesh");
  Aabb box;
  for (const Vec3& v : mesh.vertices) {
    if (!v.allFinite()) return Status(ErrorCode::InvalidArgument, "non-finite vertex");
    box.extend(v);
  }
  // Sums relative to the box centre keep the round-off small for offset meshes.
  const Vec3 ref = 0.5 * (box.min + box.max);
  double volume6 = 0.0;  // 6 V
  Vec3 first = Vec3::Zero();   // 24 * integral of x
  Mat3 second = Mat3::Zero();  // 120 * integral of x x^T
  for (const Tri& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= n) return Status(ErrorCode::InvalidArgument, "bad vertex index");
    const Vec3 a = mesh.vertices[t[0]] - ref;
    const Vec3 b = mesh.vertices[t[1]] - ref;
    const Vec3 c = mesh.vertices[t[2]] - ref;
    const double d = a.dot(b.cross(c));  // 6 x signed volume of (ref, a, b, c)
    const Vec3 s = a + b + c;
    volume6 += d;
    first += d * s;  // integral of x = V s / 4 = d s / 24
    // Integral of x x^T over the tetrahedron = V/20 (a a^T + b b^T + c c^T + s s^T).
    second += d * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  const double scale = (box.max - box.min).norm();
  // Inside-out meshes give a negative volume; the ratios below cancel the sign.
  if (!(std::abs(volume6) > 1e-12 * scale * scale * scale))
    return Status(ErrorCode::InvalidGeometry, "closed mesh encloses no volume");

  MassProperties m;
  m.volume = std::abs(volume6) / 6.0;
  const Vec3 center_rel = first / (4.0 * volume6);            // (d s / 24) / (d / 6)
  const Mat3 cov = second / (20.0 * volume6) - center_rel * center_rel.transpose();
  m.center = ref + center_rel;
  m.inertia = cov.trace() * Mat3::Identity() - cov;
  m.inertia = 0.5 * (m.inertia + m.inertia.transpose());
  m.principal_axes = Mat3::Identity();
  m.principal_moments = m.inertia.diagonal().cwiseMax(0.0);
  const double off = std::abs(m.inertia(0, 1)) + std::abs(m.inertia(0, 2)) + std::abs(m.inertia(1, 2));
  if (off <= 1e-9 * m.inertia.trace()) return m;  // already principal: keep the mesh axes
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(m.inertia);
  // Each mesh axis takes the eigenvector closest to it, pointing its way, so a
  // nearly aligned mesh keeps its up axis (and degenerate moments change nothing).
  const Mat3 v = eig.eigenvectors();
  int best[3] = {0, 1, 2};
  double best_score = -1.0;
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& p : perms) {
    double score = 0.0;
    for (int k = 0; k < 3; ++k) score += std::abs(v(k, p[k]));
    if (score > best_score) {
      best_score = score;
      std::copy(p, p + 3, best);
    }
  }
  for (int k = 0; k < 3; ++k) {
    m.principal_axes.col(k) = v.col(best[k]) * (v(k, best[k]) < 0.0 ? -1.0 : 1.0);
    m.principal_moments[k] = std::max(0.0, eig.eigenvalues()[best[k]]);
  }
  if (m.principal_axes.determinant() < 0.0) m.principal_axes.col(2) *= -1.0;
  return m;
}

}  // namespace sc::bullet
