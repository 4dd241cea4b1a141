// SPDX-License-Identifier: MIT
// ScBulletShape: recentring on the principal frame, AABB, inertia and the triangle
// walk that Bullet's ray tests, debug drawer and convex-concave pairs use.
#include "smartcollision/bullet/sc_bullet_shape.h"

#include <LinearMath/btConvexHullComputer.h>

#include <algorithm>
#include <cmath>

namespace sc::bullet {

namespace {

btVector3 toBt(const Vec3& v) {
  return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
}

btMatrix3x3 toBt(const Mat3& m) {
  return btMatrix3x3(btScalar(m(0, 0)), btScalar(m(0, 1)), btScalar(m(0, 2)),
                     btScalar(m(1, 0)), btScalar(m(1, 1)), btScalar(m(1, 2)),
                     btScalar(m(2, 0)), btScalar(m(2, 1)), btScalar(m(2, 2)));
}

}  // namespace

Result<std::shared_ptr<ScBulletShape>> ScBulletShape::create(ModelKind kind, const MeshData& mesh,
                                                             const ShapeOptions& options) {
  if (!std::isfinite(options.aabb_margin) || options.aabb_margin < 0.0)
    return Status(ErrorCode::InvalidArgument, "aabb_margin must be finite and >= 0");
  std::shared_ptr<ScBulletShape> shape(new ScBulletShape());
  shape->m_shapeType = kShapeType;
  shape->aabb_margin_ = options.aabb_margin;

  MeshData stored = mesh;
  if (kind == ModelKind::ClosedPolyhedron) {
    Result<MassProperties> mass = computeMassProperties(mesh);
    if (!mass.ok()) return mass.status();
    shape->mass_ = mass.value();
    shape->has_mass_ = true;
    if (options.recenter) {
      // shape frame = principal frame: v_shape = R^T (v_mesh - c).
      const Mat3& r = shape->mass_.principal_axes;
      for (Vec3& v : stored.vertices) v = r.transpose() * (v - shape->mass_.center);
      shape->mesh_from_shape_ = btTransform(toBt(r), toBt(shape->mass_.center));
      shape->recentered_ = true;
    }
  }
  Result<PiecePtr> piece = buildPiece(kind, std::move(stored), options.build);
  if (!piece.hasValue()) return piece.status();
  shape->model_ = std::make_shared<const Model>(kind, std::vector<PiecePtr>{piece.value()});

  const MeshData& m = piece.value()->mesh();  // as stored (inside-out closed meshes flipped)
  shape->vertices_.reserve(m.vertices.size());
  for (const Vec3& v : m.vertices) shape->vertices_.push_back(toBt(v));
  shape->indices_.reserve(3 * m.triangles.size());
  for (const Tri& t : m.triangles)
    for (int k = 0; k < 3; ++k) shape->indices_.push_back(t[k]);
  const Aabb& b = shape->model_->bounds();
  shape->local_min_ = toBt(b.min);
  shape->local_max_ = toBt(b.max);
  shape->box_half_ = 0.5 * (shape->local_max_ - shape->local_min_);
  return shape;
}

const std::vector<btVector3>& ScBulletShape::hullVertices() const {
  std::call_once(hull_once_, [this] {
    btConvexHullComputer computer;
    const int n = static_cast<int>(vertices_.size());
    if (n > 0 && computer.compute(vertices_[0].m_floats, static_cast<int>(sizeof(btVector3)), n,
                                  0, 0) >= 0 &&
        computer.vertices.size() > 0) {
      for (int i = 0; i < computer.vertices.size(); ++i) hull_vertices_.push_back(computer.vertices[i]);
    } else {
      hull_vertices_ = vertices_;  // flat or degenerate input: every vertex is a candidate
    }
  });
  return hull_vertices_;
}

Status ScBulletShape::setAabbMargin(double margin) {
  if (!(std::isfinite(margin) && margin >= 0.0))
    return Status(ErrorCode::InvalidArgument, "aabb margin must be finite and >= 0");
  aabb_margin_ = margin;
  return {};
}

void ScBulletShape::getAabb(const btTransform& t, btVector3& aabb_min, btVector3& aabb_max) const {
  // The local box rotated: centre moved, half extents through |R|.
  const btVector3 half = 0.5 * (local_max_ - local_min_);
  const btVector3 center = t(0.5 * (local_max_ + local_min_));
  const btMatrix3x3 abs_basis = t.getBasis().absolute();
  const btVector3 extent = btVector3(abs_basis[0].dot(half), abs_basis[1].dot(half),
                                     abs_basis[2].dot(half)) +
                           btVector3(1, 1, 1) * btScalar(aabb_margin_);
  aabb_min = center - extent;
  aabb_max = center + extent;
}

void ScBulletShape::setLocalScaling(const btVector3& /*scaling*/) {
  // Ignored on purpose: rescaling would need a new preprocessed model.
}

void ScBulletShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const {
  if (has_mass_) {
    // In the principal frame the tensor is diagonal; without recentring, its diagonal
    // in mesh axes is all Bullet (diagonal local inertia only) can take.
    const Vec3 d = recentered_ ? mass_.principal_moments : Vec3(mass_.inertia.diagonal());
    inertia = btScalar(mass) * toBt(d);
    return;
  }
  // Soup: a solid box of the AABB.
  const btVector3 e = 2 * box_half_;
  const btScalar k = mass / btScalar(12);
  inertia = k * btVector3(e.y() * e.y() + e.z() * e.z(), e.x() * e.x() + e.z() * e.z(),
                          e.x() * e.x() + e.y() * e.y());
}

void ScBulletShape::processAllTriangles(btTriangleCallback* callback, const btVector3& aabb_min,
                                        const btVector3& aabb_max) const {
  btVector3 tri[3];
  const int count = static_cast<int>(indices_.size() / 3);
  for (int i = 0; i < count; ++i) {
    btVector3 lo(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
    btVector3 hi = -lo;
    for (int k = 0; k < 3; ++k) {
      tri[k] = vertices_[static_cast<std::size_t>(indices_[static_cast<std::size_t>(3 * i + k)])];
      lo.setMin(tri[k]);
      hi.setMax(tri[k]);
    }
    if (TestAabbAgainstAabb2(lo, hi, aabb_min, aabb_max)) callback->processTriangle(tri, 0, i);
  }
}

}  // namespace sc::bullet
