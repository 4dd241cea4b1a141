// SPDX-License-Identifier: MIT
// Bullet's triangle mesh shapes as SmartCollision triangle soups: every subpart of
// the btStridingMeshInterface, float or double vertices, 32-, 16- or 8-bit indices,
// read as Bullet's own processAllTriangles reads them.
#include "triangle_mesh_model.h"

#include <cstdint>
#include <cstring>
#include <string>

namespace sc::bullet::detail {

namespace {

/// The mesh of a triangle mesh shape and the scaling Bullet applies to its vertices.
struct Source {
  const btTriangleMeshShape* shape = nullptr;
  const btStridingMeshInterface* mesh = nullptr;
  btVector3 scaling{1, 1, 1};
};

Source sourceOf(const btCollisionShape* shape) {
  Source s;
  btVector3 outer(1, 1, 1);
  if (shape->getShapeType() == SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE) {
    const auto* scaled = static_cast<const btScaledBvhTriangleMeshShape*>(shape);
    s.shape = scaled->getChildShape();
    outer = scaled->getLocalScaling();  // on top of the child's own (its mesh's)
  } else {
    s.shape = static_cast<const btTriangleMeshShape*>(shape);
  }
  if (s.shape != nullptr) s.mesh = s.shape->getMeshInterface();
  if (s.mesh != nullptr) s.scaling = s.mesh->getScaling() * outer;
  return s;
}

/// One subpart's arrays as the mesh hands them out; unlocked when destroyed.
class Subpart {
 public:
  Subpart(const btStridingMeshInterface& mesh, int part) : mesh_(mesh), part_(part) {
    mesh.getLockedReadOnlyVertexIndexBase(&vertices, vertex_count, vertex_type, vertex_stride,
                                          &indices, index_stride, face_count, index_type, part);
  }
  ~Subpart() { mesh_.unLockReadOnlyVertexBase(part_); }
  Subpart(const Subpart&) = delete;
  Subpart& operator=(const Subpart&) = delete;

  const unsigned char* vertices = nullptr;
  const unsigned char* indices = nullptr;
  int vertex_count = 0, vertex_stride = 0, index_stride = 0, face_count = 0;
  PHY_ScalarType vertex_type = PHY_FLOAT, index_type = PHY_INTEGER;

 private:
  const btStridingMeshInterface& mesh_;
  int part_;
};

template <class T>
T readAt(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);  // the buffers need not be aligned for T
  return v;
}

/// Vertex `i` of the subpart, scaled (Bullet reads float or double).
Vec3 vertexAt(const Subpart& s, unsigned i, const btVector3& scaling) {
  const unsigned char* p = s.vertices + std::size_t(i) * std::size_t(s.vertex_stride);
  Vec3 v;
  for (int k = 0; k < 3; ++k)
    v[k] = s.vertex_type == PHY_DOUBLE ? readAt<double>(p + k * sizeof(double))
                                       : double(readAt<float>(p + k * sizeof(float)));
  return v.cwiseProduct(Vec3(double(scaling.x()), double(scaling.y()), double(scaling.z())));
}

/// Corner `k` of face `f` (Bullet reads the index types as unsigned).
unsigned indexAt(const Subpart& s, int f, int k) {
  const unsigned char* p = s.indices + std::size_t(f) * std::size_t(s.index_stride);
  switch (s.index_type) {
    case PHY_SHORT:
      return readAt<unsigned short>(p + k * sizeof(unsigned short));
    case PHY_UCHAR:
      return p[k];
    default:
      return readAt<unsigned int>(p + k * sizeof(unsigned int));
  }
}

/// Why the subpart cannot be read as Bullet reads it; empty when it can.
std::string unreadable(const Subpart& s) {
  if (s.face_count < 0 || s.vertex_count < 0) return "negative count";
  if (s.face_count == 0) return "";
  if (s.vertices == nullptr || s.indices == nullptr) return "null vertex or index buffer";
  if (s.vertex_stride < 0 || s.index_stride < 0) return "negative stride";
  if (s.vertex_type != PHY_FLOAT && s.vertex_type != PHY_DOUBLE)
    return "vertex type is neither float nor double";
  if (s.index_type != PHY_INTEGER && s.index_type != PHY_SHORT && s.index_type != PHY_UCHAR)
    return "index type is not 32, 16 or 8 bits";
  return "";
}

/// Appends the subpart's triangles and the vertices they use to `out`; `remap` is
/// scratch (subpart vertex -> soup vertex). Empty, or why it cannot.
std::string appendSubpart(const Subpart& s, const btVector3& scaling, std::vector<int>& remap,
                          MeshData& out) {
  if (std::string why = unreadable(s); !why.empty()) return why;
  remap.assign(std::size_t(s.vertex_count), -1);
  for (int f = 0; f < s.face_count; ++f) {
    Tri t;
    for (int k = 0; k < 3; ++k) {
      const unsigned i = indexAt(s, f, k);
      if (i >= unsigned(s.vertex_count))
        return "face " + std::to_string(f) + ": index " + std::to_string(i) + " beyond its " +
               std::to_string(s.vertex_count) + " vertices";
      if (remap[i] < 0) {
        remap[i] = static_cast<int>(out.vertices.size());
        out.vertices.push_back(vertexAt(s, i, scaling));
      }
      t[k] = remap[i];
    }
    out.triangles.push_back(t);
  }
  return "";
}

}  // namespace

bool isTriangleMesh(int shape_type) {
  return shape_type == TRIANGLE_MESH_SHAPE_PROXYTYPE ||
         shape_type == SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE;
}

void appendTriangleMeshKey(const btCollisionShape* shape, std::vector<double>& key) {
  const Source src = sourceOf(shape);
  if (src.mesh == nullptr) return;
  auto add = [&key](const btVector3& v) { key.insert(key.end(), {v.x(), v.y(), v.z()}); };
  add(src.scaling);
  add(src.shape->getLocalAabbMin());
  add(src.shape->getLocalAabbMax());
  const int parts = src.mesh->getNumSubParts();
  key.push_back(parts);
  for (int part = 0; part < parts; ++part) {
    const Subpart s(*src.mesh, part);
    // Addresses below 2^53 (every user-space address) are exact as doubles.
    key.insert(key.end(), {double(s.vertex_count), double(s.vertex_stride), double(s.vertex_type),
                           double(s.face_count), double(s.index_stride), double(s.index_type),
                           double(reinterpret_cast<std::uintptr_t>(s.vertices)),
                           double(reinterpret_cast<std::uintptr_t>(s.indices))});
  }
}

Result<ModelPtr> triangleMeshModel(const btCollisionShape* shape) {
  const Source src = sourceOf(shape);
  auto refused = [](const std::string& why) { return Status(ErrorCode::InvalidArgument, why); };
  if (src.mesh == nullptr) return refused("no mesh interface");
  MeshData mesh;
  std::vector<int> remap;
  for (int part = 0; part < src.mesh->getNumSubParts(); ++part) {
    const Subpart s(*src.mesh, part);
    if (std::string why = appendSubpart(s, src.scaling, remap, mesh); !why.empty())
      return refused("subpart " + std::to_string(part) + ": " + why);
  }
  if (mesh.triangles.empty()) return refused("no triangles");
  Result<PiecePtr> piece = buildPiece(ModelKind::TriangleSoup, std::move(mesh));
  if (!piece.hasValue()) return piece.status();
  return ModelPtr(
      std::make_shared<const Model>(ModelKind::TriangleSoup, std::vector<PiecePtr>{piece.value()}));
}

}  // namespace sc::bullet::detail
