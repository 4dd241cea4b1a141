// SPDX-License-Identifier: MIT
// A convex polytope given by its vertices and triangulated boundary: the leaf of
// every closed-polyhedron query (a convex piece, or one patch hull of a
// non-convex piece). Support mapping by hill climbing over vertex adjacency.
//
// Storage: a piece holds about two polytopes per input triangle (its leaves and
// hierarchy), so each keeps all its arrays in one heap block and each array is
// a single pointer, its count stored just before its data. The arrays of a
// two-sided triangle (faces, adjacency, vertex-face lists) are shared constants.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "smartcollision/types.h"

namespace sc::detail {

/// One array of a ConvexPolytope: a pointer to its data inside the polytope's block
/// (or to a shared constant), the count in the 8 bytes before the data. Null: empty.
/// Elements are writable through a non-const polytope (shared constants never are).
template <class T>
class PolytopeArray {
 public:
  std::size_t size() const {
    if (data_ == nullptr) return 0;
    std::uint32_t n;
    std::memcpy(&n, reinterpret_cast<const char*>(data_) - kHeaderBytes, sizeof(n));
    return n;
  }
  bool empty() const { return data_ == nullptr; }
  const T* data() const { return data_; }
  T* data() { return data_; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size(); }
  T* begin() { return data_; }
  T* end() { return data_ + size(); }

  friend bool operator==(const PolytopeArray& a, const PolytopeArray& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
  }
  friend bool operator!=(const PolytopeArray& a, const PolytopeArray& b) { return !(a == b); }

  /// Bytes before each array's data holding its count (keeps the data 8-aligned).
  static constexpr std::size_t kHeaderBytes = 8;

 private:
  friend struct PolytopePacking;
  T* data_ = nullptr;
};

/// What a polytope is built from: its vertices and faces with their input indices.
struct PolytopeParts {
  std::vector<Vec3> vertices;  ///< in the model's local frame
  std::vector<int> original;   ///< per vertex: its index in the input piece
  std::vector<Tri> faces;      ///< outward counter-clockwise, indices into `vertices`
  std::vector<int> face_source;
};

/// Which derived arrays a built polytope keeps.
enum class PolytopeKeep {
  Everything,   ///< adjacency and vertex-face lists (a closed piece's leaves)
  NoFaceLists,  ///< no vertex-face lists: readers scan the faces (a soup's leaves)
  Support,      ///< vertices, original indices, faces, adjacency: an inner hull
};

/// Working arrays of ConvexPolytope::build, reusable from one polytope to the next.
struct FinalizeScratch {
  std::vector<int> fill, mark, entries;
  std::vector<int> adjacency_start, adjacency, vertex_face_start, vertex_faces;
};

class ConvexPolytope {
 public:
  PolytopeArray<Vec3> vertices;  ///< in the model's local frame
  PolytopeArray<int> original;   ///< per vertex: its index in the input piece
  PolytopeArray<Tri> faces;      ///< outward counter-clockwise, indices into `vertices`
  /// Per face: the index of the input triangle it equals, or -1 for a virtual face
  /// (all faces virtual when empty).
  PolytopeArray<int> face_source;
  /// Vertex adjacency in CSR form: neighbours of v are
  /// adjacency[adjacency_start[v] .. adjacency_start[v + 1]).
  PolytopeArray<int> adjacency_start;
  PolytopeArray<int> adjacency;
  /// Faces around each vertex, CSR like adjacency: where a closest point is found
  /// from GJK's simplex without scanning every face.
  PolytopeArray<int> vertex_face_start;
  PolytopeArray<int> vertex_faces;
  Vec3 center = Vec3::Zero();  ///< centre of the bounding sphere (centre of the box)
  double radius = 0.0;         ///< bounding sphere radius about `center`

  ConvexPolytope() = default;
  ConvexPolytope(const ConvexPolytope& other);
  ConvexPolytope(ConvexPolytope&& other) noexcept;
  ConvexPolytope& operator=(const ConvexPolytope& other);
  ConvexPolytope& operator=(ConvexPolytope&& other) noexcept;
  ~ConvexPolytope();

  /// Packs `parts` into one block with the adjacency (and, per `keep`, the
  /// vertex-face lists) derived from the faces. Without faces (a bare point set)
  /// the adjacency and vertex-face arrays stay empty; with `Support`, face sources
  /// are dropped. The scratch form allocates nothing but the block.
  static ConvexPolytope build(const PolytopeParts& parts,
                              PolytopeKeep keep = PolytopeKeep::Everything);
  static ConvexPolytope build(const PolytopeParts& parts, FinalizeScratch& scratch,
                              PolytopeKeep keep = PolytopeKeep::Everything);
  /// build() in two steps, for a caller that reads the derived lists first: derive()
  /// puts the adjacency and vertex-face lists of `parts` (faces needed) into
  /// `scratch`; pack() makes the polytope from `parts` and those lists.
  static void derive(const PolytopeParts& parts, FinalizeScratch& scratch);
  static ConvexPolytope pack(const PolytopeParts& parts, const FinalizeScratch& derived,
                             PolytopeKeep keep = PolytopeKeep::Everything);

  /// This polytope repacked without what `keep` leaves out.
  ConvexPolytope reduced(PolytopeKeep keep) const;

  /// Copies of the arrays it was built from (face sources as kept).
  PolytopeParts parts() const;

  /// The box of the vertices (computed: queries cull by the bounding sphere).
  Aabb bounds() const;

  /// Index of a vertex maximising dot(direction, vertex). `hint` (in/out) is the
  /// vertex to start hill climbing from; any value in range is valid.
  int support(const Vec3& direction, int& hint) const;

 private:
  friend struct PolytopePacking;
  void release();

  char* block_ = nullptr;  ///< owns every array that is not a shared constant
};

}  // namespace sc::detail
