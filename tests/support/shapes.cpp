// SPDX-License-Identifier: MIT
// Shape generators for tests: boxes, tetrahedra and hulls of random points.
#include "support/shapes.h"

#include <cmath>
#include <utility>

#include "preprocess/convex_hull.h"
#include "sc_support/off_mesh.h"
#include "smartcollision/collision.h"

namespace sc::test {

double logUniform(Rng& rng, double lo, double hi) {
  return std::exp(uniform(rng, std::log(lo), std::log(hi)));
}

MeshData boxMesh(const Vec3& h) {
  MeshData m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                            (i & 4) ? h.z() : -h.z());
  }
  // Two triangles per side, counter-clockwise seen from outside.
  m.triangles = {Tri(0, 2, 3), Tri(0, 3, 1), Tri(4, 5, 7), Tri(4, 7, 6),   // -z, +z
                 Tri(0, 1, 5), Tri(0, 5, 4), Tri(2, 6, 7), Tri(2, 7, 3),   // -y, +y
                 Tri(0, 4, 6), Tri(0, 6, 2), Tri(1, 3, 7), Tri(1, 7, 5)};  // -x, +x
  return m;
}

ModelPtr boxModel(const Vec3& half_extents) { return closedModel(boxMesh(half_extents)); }

ModelPtr closedModel(const MeshData& mesh) {
  auto piece = buildPiece(ModelKind::ClosedPolyhedron, mesh);
  EXPECT_TRUE(piece.ok()) << piece.status().message();
  if (!piece.ok()) return nullptr;
  return std::make_shared<Model>(ModelKind::ClosedPolyhedron, std::vector<PiecePtr>{piece.value()});
}

MeshData prismMesh(int sides, double circumradius, double half_height) {
  MeshData m;
  for (int i = 0; i < sides; ++i) {
    const double t = 2.0 * kPi * i / sides;
    const Vec3 rim(circumradius * std::cos(t), circumradius * std::sin(t), 0.0);
    m.vertices.push_back(rim - Vec3(0, 0, half_height));
    m.vertices.push_back(rim + Vec3(0, 0, half_height));
  }
  for (int i = 0; i < sides; ++i) {
    const int j = (i + 1) % sides;
    m.triangles.push_back({2 * i, 2 * j, 2 * j + 1});
    m.triangles.push_back({2 * i, 2 * j + 1, 2 * i + 1});
    if (i > 0 && j > 0) {
      m.triangles.push_back({0, 2 * j, 2 * i});
      m.triangles.push_back({1, 2 * i + 1, 2 * j + 1});
    }
  }
  return m;
}
ModelPtr convexModel(const detail::ConvexPolytope& poly) {
  ModelPtr model = closedModel(meshOf(poly));
  if (model) {
    EXPECT_TRUE(model->pieces().front()->stats().convex);
  }
  return model;
}

namespace {

/// Orients the four triangles of a tetrahedron outward.
MeshData tetrahedronOf(const Vec3 p[4]) {
  MeshData m;
  m.vertices.assign(p, p + 4);
  const Vec3 centre = 0.25 * (p[0] + p[1] + p[2] + p[3]);
  const int faces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  for (const auto& f : faces) {
    const Vec3 n = (p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]);
    if (n.dot(p[f[0]] - centre) > 0) {
      m.triangles.emplace_back(f[0], f[1], f[2]);
    } else {
      m.triangles.emplace_back(f[0], f[2], f[1]);
    }
  }
  return m;
}

}  // namespace

MeshData regularTetrahedronMesh(double r) {
  const double s = r / std::sqrt(3.0);
  const Vec3 p[4] = {Vec3(s, s, s), Vec3(s, -s, -s), Vec3(-s, s, -s), Vec3(-s, -s, s)};
  return tetrahedronOf(p);
}

MeshData randomTetrahedronMesh(Rng& rng, double size) {
  for (;;) {
    Vec3 p[4];
    for (Vec3& q : p) q = size * uniform(rng, 0.3, 1.0) * randomDirection(rng);
    const double volume = std::abs((p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]))) / 6.0;
    if (volume > 0.02 * size * size * size) return tetrahedronOf(p);
  }
}

std::vector<Vec3> randomPoints(Rng& rng, int n, double size) {
  const Vec3 axes(uniform(rng, 0.3, 1.0), uniform(rng, 0.3, 1.0), uniform(rng, 0.3, 1.0));
  const Mat3 rotation = randomRotation(rng).toRotationMatrix();
  std::vector<Vec3> points;
  for (int i = 0; i < n; ++i) {
    const Vec3 unit = randomDirection(rng) * std::cbrt(uniform(rng, 0.0, 1.0));
    points.push_back(size * (rotation * unit.cwiseProduct(axes)));
  }
  return points;
}

detail::ConvexPolytope polytopeFromMesh(const MeshData& mesh) {
  detail::PolytopeParts poly;
  poly.vertices = mesh.vertices;
  poly.faces = mesh.triangles;
  for (int i = 0; i < static_cast<int>(mesh.vertices.size()); ++i) poly.original.push_back(i);
  for (int f = 0; f < static_cast<int>(mesh.triangles.size()); ++f) poly.face_source.push_back(f);
  return detail::ConvexPolytope::build(poly);
}

namespace {

/// Index of the triangle of `mesh` with the same cyclic vertex order, or -1.
int matchingTriangle(const MeshData& mesh, const Tri& t) {
  for (int f = 0; f < static_cast<int>(mesh.triangles.size()); ++f) {
    const Tri& m = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      if (m[k] == t[0] && m[(k + 1) % 3] == t[1] && m[(k + 2) % 3] == t[2]) return f;
    }
  }
  return -1;
}

}  // namespace

detail::ConvexPolytope hullOf(const std::vector<Vec3>& points, const MeshData* real_faces) {
  Result<detail::ConvexPolytope> hull = detail::convexHull(points);
  EXPECT_TRUE(hull.ok()) << hull.status().message();
  detail::ConvexPolytope poly = hull.value();
  if (real_faces != nullptr) {
    for (std::size_t f = 0; f < poly.faces.size(); ++f) {
      const Tri& t = poly.faces[f];
      const Tri input(poly.original[t[0]], poly.original[t[1]], poly.original[t[2]]);
      poly.face_source[f] = matchingTriangle(*real_faces, input);
    }
  }
  return poly;
}

MeshData meshOf(const detail::ConvexPolytope& poly) {
  MeshData m;
  m.vertices.assign(poly.vertices.begin(), poly.vertices.end());
  m.triangles.assign(poly.faces.begin(), poly.faces.end());
  return m;
}

ConvexShape randomConvexShape(Rng& rng, double size) {
  ConvexShape shape;
  const double pick = uniform(rng, 0.0, 1.0);
  if (pick < 0.6) {
    shape.kind = "hull";
    const int n = std::uniform_int_distribution<int>(4, 60)(rng);
    for (;;) {
      shape.points = randomPoints(rng, n, size);
      Result<detail::ConvexPolytope> hull = detail::convexHull(shape.points);
      // Four random points can be too flat to be a useful test body; draw again.
      if (hull.ok() && hull.value().vertices.size() >= 4) {
        shape.poly = hull.value();
        break;
      }
    }
  } else {
    MeshData mesh;
    if (pick < 0.8) {
      shape.kind = "box";
      mesh = boxMesh(size *
                     Vec3(uniform(rng, 0.2, 1.0), uniform(rng, 0.2, 1.0), uniform(rng, 0.2, 1.0)));
    } else {
      shape.kind = "tetrahedron";
      mesh = randomTetrahedronMesh(rng, size);
    }
    shape.points = mesh.vertices;
    shape.poly = hullOf(mesh.vertices, &mesh);
  }
  return shape;
}

MeshData scaledOff(const std::string& name, double size) {
  Result<MeshData> read = support::readOff(std::string(SC_MESH_DIR) + "/" + name);
  if (!read.ok() || read.value().vertices.empty()) return {};
  return support::fitToSize(std::move(read.value()), size);
}

}  // namespace sc::test
