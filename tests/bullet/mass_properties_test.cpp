// SPDX-License-Identifier: MIT
// Exact mass properties against closed-form boxes and tetrahedra, in any pose.
#include "smartcollision/bullet/mass_properties.h"

#include <gtest/gtest.h>

#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

MeshData transformed(MeshData m, const Mat3& r, const Vec3& t) {
  for (Vec3& v : m.vertices) v = r * v + t;
  return m;
}

TEST(MassProperties, RotatedOffsetBoxMatchesClosedForm) {
  Rng rng(7);
  const Vec3 half(0.5, 1.0, 2.0);
  const Mat3 r = randomRotation(rng).toRotationMatrix();
  const Vec3 t(3.0, -2.0, 10.0);
  Result<bullet::MassProperties> m = bullet::computeMassProperties(transformed(boxMesh(half), r, t));
  ASSERT_TRUE(m.ok()) << m.status().message();
  const Vec3 e = 2.0 * half;
  EXPECT_NEAR(m.value().volume, e.prod(), 1e-9);
  EXPECT_VEC_NEAR(m.value().center, t, 1e-9);
  // Box: I_xx = (ey^2 + ez^2) / 12 per unit mass, about the box's own axes.
  const Vec3 expected((e.y() * e.y() + e.z() * e.z()) / 12.0, (e.x() * e.x() + e.z() * e.z()) / 12.0,
                      (e.x() * e.x() + e.y() * e.y()) / 12.0);
  const Mat3 body_inertia = r.transpose() * m.value().inertia * r;
  EXPECT_NEAR(body_inertia(0, 0), expected.x(), 1e-9);
  EXPECT_NEAR(body_inertia(2, 2), expected.z(), 1e-9);
  EXPECT_NEAR(body_inertia(0, 1), 0.0, 1e-9);
  const Mat3& axes = m.value().principal_axes;
  EXPECT_NEAR(axes.determinant(), 1.0, 1e-12);
  // Each principal axis is a box axis, with the moment about that axis.
  for (int k = 0; k < 3; ++k) {
    int match = 0;
    for (int j = 1; j < 3; ++j)
      if (std::abs(axes.col(k).dot(r.col(j))) > std::abs(axes.col(k).dot(r.col(match)))) match = j;
    EXPECT_NEAR(std::abs(axes.col(k).dot(r.col(match))), 1.0, 1e-9);
    EXPECT_NEAR(m.value().principal_moments[k], expected[match], 1e-9);
  }
}

TEST(MassProperties, TetrahedronMatchesClosedFormAndIgnoresWinding) {
  // Corner tetrahedron (0, e1, e2, e3): V = 1/6, centroid 1/4, covariance known.
  MeshData m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.triangles = {Tri(0, 2, 1), Tri(0, 1, 3), Tri(0, 3, 2), Tri(1, 2, 3)};
  Result<bullet::MassProperties> a = bullet::computeMassProperties(m);
  ASSERT_TRUE(a.ok());
  EXPECT_NEAR(a.value().volume, 1.0 / 6.0, 1e-12);
  EXPECT_VEC_NEAR(a.value().center, Vec3::Constant(0.25), 1e-12);
  // E[x^2] = 1/10, E[xy] = 1/20 over the tetrahedron; about the centroid:
  // var = 1/10 - 1/16 = 3/80, cov = 1/20 - 1/16 = -1/80; I_xx = 2 var, I_xy = -cov.
  EXPECT_NEAR(a.value().inertia(0, 0), 6.0 / 80.0, 1e-12);
  EXPECT_NEAR(a.value().inertia(0, 1), 1.0 / 80.0, 1e-12);
  for (Tri& t : m.triangles) std::swap(t[1], t[2]);  // inside out
  Result<bullet::MassProperties> b = bullet::computeMassProperties(m);
  ASSERT_TRUE(b.ok());
  EXPECT_NEAR(b.value().volume, a.value().volume, 1e-12);
  EXPECT_LE((b.value().inertia - a.value().inertia).norm(), 1e-12);
}

TEST(MassProperties, AlignedMeshKeepsItsAxes) {
  // A cube's moments are all equal: any frame is principal; the mesh's must be kept.
  Result<bullet::MassProperties> m = bullet::computeMassProperties(boxMesh(Vec3(0.5, 0.5, 0.5)));
  ASSERT_TRUE(m.ok());
  EXPECT_LE((m.value().principal_axes - Mat3::Identity()).norm(), 1e-12);
  // A slightly turned long box keeps its long axis where it was (x), not sorted.
  const Mat3 r = Eigen::AngleAxisd(0.1, Vec3::UnitZ()).toRotationMatrix();
  MeshData box = boxMesh(Vec3(2.0, 0.5, 1.0));
  for (Vec3& v : box.vertices) v = r * v;
  Result<bullet::MassProperties> t = bullet::computeMassProperties(box);
  ASSERT_TRUE(t.ok());
  EXPECT_LE((t.value().principal_axes - r).norm(), 1e-9);
}

TEST(MassProperties, FlatMeshHasNoVolume) {
  MeshData m;
  m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  m.triangles = {Tri(0, 1, 2), Tri(0, 2, 1)};
  EXPECT_EQ(bullet::computeMassProperties(m).status().code(), ErrorCode::InvalidGeometry);
  m.triangles = {Tri(0, 1, 5)};
  EXPECT_EQ(bullet::computeMassProperties(m).status().code(), ErrorCode::InvalidArgument);
}

}  // namespace
}  // namespace sc::test
