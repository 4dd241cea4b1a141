// SPDX-License-Identifier: MIT
// Bullet's triangle mesh shapes (btBvhTriangleMeshShape and the other
// btTriangleMeshShape, btScaledBvhTriangleMeshShape) as SmartCollision triangle soups,
// read from their btStridingMeshInterface.
#pragma once

#include <btBulletCollisionCommon.h>

#include <vector>

#include "smartcollision/model.h"

namespace sc::bullet::detail {

/// TRIANGLE_MESH_SHAPE_PROXYTYPE or SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE.
bool isTriangleMesh(int shape_type);

/// Appends what the soup depends on and what can be read without walking the
/// triangles: the scaling, the shape's local bounds (a refit after an edit moves
/// them), and each subpart's counts, types, strides and buffers.
void appendTriangleMeshKey(const btCollisionShape* shape, std::vector<double>& key);

/// The triangles of every subpart as one soup, the shape's scaling applied (what
/// Bullet's processAllTriangles reports); unreferenced vertices are left out.
/// InvalidArgument when the shape has no triangles, an index is out of its
/// subpart's range or a type is not one Bullet reads; buildPiece's status when the
/// core refuses the soup (a non-finite coordinate, an extent out of the supported
/// scales).
Result<ModelPtr> triangleMeshModel(const btCollisionShape* shape);

}  // namespace sc::bullet::detail
