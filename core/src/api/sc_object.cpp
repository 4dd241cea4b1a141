// SPDX-License-Identifier: MIT
// SCObject: pieces from raw arrays, and the object's own transformation.
#include <cmath>
#include <cstddef>
#include <exception>

#include "api/error_codes.h"
#include "api/facade_impl.h"
#include "api/transformation_io.h"
#include "sc.h"

namespace {

template <class Real>
SCint addTriangles(SCObject::Impl& o, const Real* vertices, SCint vertex_count,
                   const SCint* triangles, SCint triangle_count, const char* bvh_file) {
  if (!o.known_type) return SC_ERROR_INVALID_ARGUMENT;
  if (o.scene != nullptr) return SC_ERROR_INVALID_OPERATION;
  if (vertex_count < 0 || triangle_count < 0) return SC_ERROR_INVALID_ARGUMENT;
  if ((vertex_count > 0 && vertices == nullptr) || (triangle_count > 0 && triangles == nullptr))
    return SC_ERROR_INVALID_ARGUMENT;
  sc::MeshData mesh;
  mesh.vertices.resize(static_cast<std::size_t>(vertex_count));
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    mesh.vertices[i] = sc::Vec3(static_cast<double>(vertices[3 * i]),
                                static_cast<double>(vertices[3 * i + 1]),
                                static_cast<double>(vertices[3 * i + 2]));
  }
  mesh.triangles.resize(static_cast<std::size_t>(triangle_count));
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    mesh.triangles[i] = sc::Tri(triangles[3 * i], triangles[3 * i + 1], triangles[3 * i + 2]);
  sc::BuildOptions options;
  if (bvh_file != nullptr) options.cache_file = bvh_file;
  auto piece = sc::buildPiece(o.kind, std::move(mesh), options);
  if (piece.hasValue()) o.pieces.push_back(piece.value());
  return sc::detail::toScCode(piece.status());
}

}  // namespace

SCObject::SCObject(SCenum type) : impl_(std::make_unique<Impl>()) {
  impl_->type = type;
  impl_->known_type =
      type == SC_OBJECT_TYPE_TRIANGLE_SOUP || type == SC_OBJECT_TYPE_CLOSED_POLYHEDRON;
  impl_->kind = type == SC_OBJECT_TYPE_TRIANGLE_SOUP ? sc::ModelKind::TriangleSoup
                                                     : sc::ModelKind::ClosedPolyhedron;
}

SCObject::~SCObject() {
  if (impl_->scene != nullptr) impl_->scene->DeleteObject(impl_->id);
}

SCint SCObject::AddTriangles(const SCdouble* vertices, SCint vertexCount, const SCint* triangles,
                             SCint triangleCount, const char* bvhFile) {
  try {
    return addTriangles(*impl_, vertices, vertexCount, triangles, triangleCount, bvhFile);
  } catch (const std::exception&) {
    return SC_ERROR_INVALID_ARGUMENT;  // allocation failure for absurd counts
  }
}

SCint SCObject::AddTriangles(const SCfloat* vertices, SCint vertexCount, const SCint* triangles,
                             SCint triangleCount, const char* bvhFile) {
  try {
    return addTriangles(*impl_, vertices, vertexCount, triangles, triangleCount, bvhFile);
  } catch (const std::exception&) {
    return SC_ERROR_INVALID_ARGUMENT;
  }
}

SCint SCObject::SetTransformation(SCenum type, const SCdouble* trans) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  if (impl_->scene != nullptr) return SC_ERROR_INVALID_OPERATION;
  return sc::detail::setTransformation(impl_->placement, type, trans);
}

SCint SCObject::SetTransformation(SCenum type, const SCfloat* trans) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  if (impl_->scene != nullptr) return SC_ERROR_INVALID_OPERATION;
  return sc::detail::setTransformation(impl_->placement, type, trans);
}

SCint SCObject::GetTransformation(SCenum type, SCdouble* trans) const {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  return sc::detail::getTransformation(currentPlacement(), type, trans);
}

SCint SCObject::GetTransformation(SCenum type, SCfloat* trans) const {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  return sc::detail::getTransformation(currentPlacement(), type, trans);
}

sc::Placement SCObject::currentPlacement() const {
  // In a scene the object moves with its group: read its current placement there.
  if (impl_->scene == nullptr) return impl_->placement;
  const auto placement = impl_->scene->impl_->scene.objectPlacement(impl_->id);
  return placement.hasValue() ? placement.value() : impl_->placement;
}
