// SPDX-License-Identifier: MIT
// ScBulletShape: a Bullet collision shape wrapping a preprocessed SmartCollision
// model (closed polyhedron or triangle soup), stored in its principal frame.
#pragma once

#include <btBulletCollisionCommon.h>

#include <memory>
#include <mutex>
#include <vector>

#include "smartcollision/bullet/mass_properties.h"
#include "smartcollision/model.h"

namespace sc::bullet {

/// Bullet shape type of ScBulletShape. FAST_CONCAVE_MESH_PROXYTYPE is concave (so ray
/// tests and debug draw use processAllTriangles) and unused by Bullet itself; the
/// custom concave type would be mistaken for an SDF shape (bullet3 #3104).
inline constexpr int kShapeType = FAST_CONCAVE_MESH_PROXYTYPE;

struct ShapeOptions {
  /// Closed polyhedra: move the mesh to its centre of mass and principal axes, as
  /// Bullet's rigid bodies expect. Off: the mesh frame is kept (inertia still exact).
  bool recenter = true;
  /// Added on every side of the AABB [m]: pairs are tracked a little before contact.
  double aabb_margin = 0.04;
  BuildOptions build;  ///< cache file, progress
};

class ScBulletShape : public btConcaveShape {
 public:
  /// Validates, recentres (closed polyhedra) and preprocesses `mesh`. Soups keep
  /// their frame; their inertia is the AABB's solid box. Errors as sc::buildPiece,
  /// plus InvalidGeometry for a closed mesh with no volume.
  static Result<std::shared_ptr<ScBulletShape>> create(ModelKind kind, const MeshData& mesh,
                                                       const ShapeOptions& options = {});

  ModelKind kind() const { return model_->kind(); }
  const Model& model() const { return *model_; }
  const ModelPtr& modelPtr() const { return model_; }
  /// The shape's (principal) frame in the input mesh's frame: a vertex v of the input
  /// is at meshFromShape().inverse() * v in the shape frame, so graphics drawn in
  /// mesh coordinates go at body_world * meshFromShape().inverse().
  const btTransform& meshFromShape() const { return mesh_from_shape_; }
  /// Exact for closed polyhedra (in the input mesh's frame); false for soups.
  bool hasMassProperties() const { return has_mass_; }
  const MassProperties& massProperties() const { return mass_; }
  /// The stored triangles in the shape frame (for drawing).
  const std::vector<btVector3>& vertices() const { return vertices_; }
  const std::vector<int>& indices() const { return indices_; }
  /// Corners of the convex hull of the stored vertices (shape frame), computed on
  /// first use: where the shape meets a plane, only these can be deepest.
  const std::vector<btVector3>& hullVertices() const;

  double aabbMargin() const { return aabb_margin_; }
  /// InvalidArgument (margin kept) unless finite and >= 0, as ShapeOptions::aabb_margin.
  Status setAabbMargin(double margin);

  // btCollisionShape / btConcaveShape.
  void getAabb(const btTransform& t, btVector3& aabb_min, btVector3& aabb_max) const override;
  /// Only (1, 1, 1): a preprocessed model cannot be rescaled in place.
  void setLocalScaling(const btVector3& scaling) override;
  const btVector3& getLocalScaling() const override { return scaling_; }
  void calculateLocalInertia(btScalar mass, btVector3& inertia) const override;
  const char* getName() const override { return "ScBulletShape"; }
  /// Every stored triangle whose bounds meet [aabb_min, aabb_max] (shape frame).
  void processAllTriangles(btTriangleCallback* callback, const btVector3& aabb_min,
                           const btVector3& aabb_max) const override;

 private:
  ScBulletShape() = default;

  ModelPtr model_;
  btTransform mesh_from_shape_ = btTransform::getIdentity();
  MassProperties mass_;
  bool has_mass_ = false;
  bool recentered_ = false;
  btVector3 box_half_ = btVector3(0, 0, 0);  ///< soup inertia: the AABB's half extents
  btVector3 local_min_ = btVector3(0, 0, 0);
  btVector3 local_max_ = btVector3(0, 0, 0);
  btVector3 scaling_ = btVector3(1, 1, 1);
  double aabb_margin_ = 0.04;
  std::vector<btVector3> vertices_;
  std::vector<int> indices_;
  mutable std::once_flag hull_once_;
  mutable std::vector<btVector3> hull_vertices_;
};

}  // namespace sc::bullet
