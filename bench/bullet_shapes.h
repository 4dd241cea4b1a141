// SPDX-License-Identifier: MIT
// One mesh as every contact model's collision shape (SmartCollision, GImpact, a HACD
// compound, a Bullet box where the mesh is a box, a static BVH mesh for containers),
// all in the ScBulletShape's principal frame so every model simulates the same body,
// and the geometric overlap checks the stacking bench measures with.
#pragma once

#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

#include "smartcollision/bullet/bullet.h"

namespace sc_bench {

enum class Model { Potential, Manifold, GImpact, Hacd, BtBox };

const char* modelName(Model m);

constexpr double kBulletMargin = 0.01;  // GImpact triangles and HACD hulls [m]

struct ShapeSet {
  std::shared_ptr<sc::bullet::ScBulletShape> sc_shape;
  btTransform mesh_from_shape;
  std::vector<btVector3> vertices;  ///< shape frame
  std::vector<int> indices;
  btVector3 unit_inertia;  ///< principal inertia of 1 kg
  bool convex = false;     ///< body-body overlap by separating axes (convex sets only)
  // Bullet keeps pointers into these.
  std::vector<btScalar> coords;
  std::unique_ptr<btTriangleIndexVertexArray> array;
  std::shared_ptr<btGImpactMeshShape> gimpact;
  std::shared_ptr<btBvhTriangleMeshShape> static_mesh;  ///< for static containers
  std::vector<std::shared_ptr<btConvexHullShape>> parts;
  std::shared_ptr<btCompoundShape> compound;
  std::shared_ptr<btBoxShape> box;  ///< when the mesh is an axis-aligned box
  // Separating-axis candidates (shape frame): face normals and edge directions.
  std::vector<btVector3> normals, edges;

  /// The shape model `m` gives this set as a dynamic body (nullptr: not applicable).
  btCollisionShape* dynamicShape(Model m) const;
  /// The shape model `m` gives this set as a static body.
  btCollisionShape* staticShape(Model m) const;
};

enum class Use { Dynamic, Static };

/// Builds every model's shape of `mesh` (exits on a rejected mesh). Static sets get
/// only our shape and the BVH mesh.
std::unique_ptr<ShapeSet> makeShapeSet(const sc::MeshData& mesh, bool convex, Use use);

/// Penetration depth of two posed copies of a convex set (separating axis theorem;
/// 0 when apart).
double satDepth(const ShapeSet& set, const btTransform& a, const btTransform& b);

}  // namespace sc_bench
