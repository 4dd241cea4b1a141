// SPDX-License-Identifier: MIT
#include "geometry/convex_polytope.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <new>
#include <utility>

namespace sc::detail {

namespace {

/// Sorts a vertex's few neighbours (insertion sort: a hull vertex has about six).
void sortSmall(int* first, int* last) {
  for (int* i = first + 1; i < last; ++i) {
    const int value = *i;
    int* j = i;
    for (; j > first && *(j - 1) > value; --j) *j = *(j - 1);
    *j = value;
  }
}

/// The derived arrays of a two-sided triangle (vertices 0, 1, 2; faces (0, 1, 2)
/// and (0, 2, 1)), each after its count as a polytope block lays arrays out: every
/// soup leaf points here instead of holding copies.
struct alignas(8) TwoSidedArrays {
  std::uint32_t faces_count = 2, pad0 = 0;
  int faces[6] = {0, 1, 2, 0, 2, 1};
  std::uint32_t adjacency_start_count = 4, pad1 = 0;
  int adjacency_start[4] = {0, 2, 4, 6};
  std::uint32_t adjacency_count = 6, pad2 = 0;
  int adjacency[6] = {1, 2, 0, 2, 0, 1};
  std::uint32_t vertex_face_start_count = 4, pad3 = 0;
  int vertex_face_start[4] = {0, 2, 4, 6};
  std::uint32_t vertex_faces_count = 6, pad4 = 0;
  int vertex_faces[6] = {0, 1, 0, 1, 0, 1};
};
static_assert(sizeof(TwoSidedArrays) == 5 * 8 + 4 * (6 + 4 + 6 + 4 + 6));
static_assert(sizeof(Tri) == 3 * sizeof(int) && alignof(Tri) <= alignof(int));

const TwoSidedArrays kTwoSided;

bool isShared(const void* p) {
  const char* c = static_cast<const char*>(p);
  const char* first = reinterpret_cast<const char*>(&kTwoSided);
  const std::less<const char*> before;
  return !before(c, first) && before(c, first + sizeof(kTwoSided));
}

bool isTwoSided(const Tri* faces, std::size_t face_count, std::size_t vertex_count) {
  return vertex_count == 3 && face_count == 2 && faces[0] == Tri(0, 1, 2) &&
         faces[1] == Tri(0, 2, 1);
}

constexpr std::size_t kHeader = PolytopeArray<int>::kHeaderBytes;

std::size_t roundUp8(std::size_t n) { return (n + 7) & ~std::size_t{7}; }

}  // namespace

/// Lays arrays out in one block: each gets its count, then its data, 8-aligned.
/// Arrays marked shared point at their constant instead.
struct PolytopePacking {
  struct Source {
    const void* data = nullptr;
    std::size_t count = 0;
    bool shared = false;
  };
  enum Slot { kVertices, kOriginal, kFaces, kFaceSource, kAdjStart, kAdj, kVfStart, kVf, kSlots };
  static constexpr std::size_t kItem[kSlots] = {sizeof(Vec3), sizeof(int), sizeof(Tri),
                                                sizeof(int),  sizeof(int), sizeof(int),
                                                sizeof(int),  sizeof(int)};

  Source sources[kSlots];

  void set(Slot slot, const void* data, std::size_t count) {
    sources[slot] = {count > 0 ? data : nullptr, count, count > 0 && isShared(data)};
  }

  static void** pointerOf(ConvexPolytope& p, Slot slot) {
    switch (slot) {
      case kVertices:
        return reinterpret_cast<void**>(&p.vertices.data_);
      case kOriginal:
        return reinterpret_cast<void**>(&p.original.data_);
      case kFaces:
        return reinterpret_cast<void**>(&p.faces.data_);
      case kFaceSource:
        return reinterpret_cast<void**>(&p.face_source.data_);
      case kAdjStart:
        return reinterpret_cast<void**>(&p.adjacency_start.data_);
      case kAdj:
        return reinterpret_cast<void**>(&p.adjacency.data_);
      case kVfStart:
        return reinterpret_cast<void**>(&p.vertex_face_start.data_);
      default:
        return reinterpret_cast<void**>(&p.vertex_faces.data_);
    }
  }

  /// The sources as `out`'s arrays (out is empty): one block for the owned ones.
  void into(ConvexPolytope& out) const {
    std::size_t bytes = 0;
    for (int s = 0; s < kSlots; ++s) {
      if (sources[s].count > 0 && !sources[s].shared)
        bytes += kHeader + roundUp8(sources[s].count * kItem[s]);
    }
    char* block = bytes > 0 ? static_cast<char*>(::operator new(bytes)) : nullptr;
    std::size_t at = 0;
    for (int s = 0; s < kSlots; ++s) {
      const Source& source = sources[s];
      void** pointer = pointerOf(out, static_cast<Slot>(s));
      if (source.count == 0) continue;
      if (source.shared) {
        *pointer = const_cast<void*>(source.data);
        continue;
      }
      const std::uint32_t header[2] = {static_cast<std::uint32_t>(source.count), 0};
      std::memcpy(block + at, &header, sizeof(header));
      std::memcpy(block + at + kHeader, source.data, source.count * kItem[s]);
      *pointer = block + at + kHeader;
      at += kHeader + roundUp8(source.count * kItem[s]);
    }
    out.block_ = block;
  }

  /// The sources of `p`'s arrays (its own, shared or not).
  static PolytopePacking of(const ConvexPolytope& p) {
    PolytopePacking packing;
    packing.set(kVertices, p.vertices.data(), p.vertices.size());
    packing.set(kOriginal, p.original.data(), p.original.size());
    packing.set(kFaces, p.faces.data(), p.faces.size());
    packing.set(kFaceSource, p.face_source.data(), p.face_source.size());
    packing.set(kAdjStart, p.adjacency_start.data(), p.adjacency_start.size());
    packing.set(kAdj, p.adjacency.data(), p.adjacency.size());
    packing.set(kVfStart, p.vertex_face_start.data(), p.vertex_face_start.size());
    packing.set(kVf, p.vertex_faces.data(), p.vertex_faces.size());
    return packing;
  }

  static void moveArrays(ConvexPolytope& to, ConvexPolytope& from) {
    for (int s = 0; s < kSlots; ++s) {
      void** target = pointerOf(to, static_cast<Slot>(s));
      void** source = pointerOf(from, static_cast<Slot>(s));
      *target = *source;
      *source = nullptr;
    }
    to.block_ = std::exchange(from.block_, nullptr);
  }
};

namespace {

/// Vertex-face lists and adjacency of `parts` into the scratch's arrays. One pass
/// over the faces files each corner under its vertex: the face (CSR) and the
/// corner's two other vertices, its candidate neighbours. Each vertex's candidates
/// then lose their repeats (a mark per vertex; on a closed surface each neighbour
/// comes twice) and are sorted in place. Walking each vertex's faces instead visits
/// every face three times; a cache load builds tens of thousands of polytopes with
/// the same scratch. Raw pointers: every array here holds ints, so through the
/// vectors each store would reload every bound.
void buildAdjacency(const PolytopeParts& parts, FinalizeScratch& scratch) {
  const int n = static_cast<int>(parts.vertices.size());
  const int face_count = static_cast<int>(parts.faces.size());
  scratch.vertex_face_start.assign(static_cast<std::size_t>(n) + 1, 0);
  int* const start = scratch.vertex_face_start.data();
  for (const Tri& f : parts.faces)
    for (int k = 0; k < 3; ++k) ++start[f[k] + 1];
  for (int v = 0; v < n; ++v) start[v + 1] += start[v];
  const int corners = start[n];
  scratch.fill.assign(start, start + n);
  scratch.entries.resize(2 * static_cast<std::size_t>(corners));
  scratch.vertex_faces.resize(static_cast<std::size_t>(corners));
  int* const fill = scratch.fill.data();
  int* const entries = scratch.entries.data();
  int* const around = scratch.vertex_faces.data();
  for (int f = 0; f < face_count; ++f) {
    const Tri& face = parts.faces[f];
    const int a = face[0], b = face[1], c = face[2];
    const int sa = fill[a]++, sb = fill[b]++, sc = fill[c]++;
    around[sa] = around[sb] = around[sc] = f;
    entries[2 * sa] = b, entries[2 * sa + 1] = c;
    entries[2 * sb] = c, entries[2 * sb + 1] = a;
    entries[2 * sc] = a, entries[2 * sc + 1] = b;
  }
  scratch.mark.assign(static_cast<std::size_t>(n), -1);
  int* const mark = scratch.mark.data();
  scratch.adjacency_start.resize(static_cast<std::size_t>(n) + 1);
  int* const adjacency_start = scratch.adjacency_start.data();
  adjacency_start[0] = 0;
  int kept = 0;  // candidates kept so far, compacted to the front of `entries`
  for (int v = 0; v < n; ++v) {
    const int first = kept;
    const int end = 2 * start[v + 1];
    mark[v] = v;  // v is no neighbour of its own
    for (int k = 2 * start[v]; k < end; ++k) {
      const int w = entries[k];
      if (mark[w] == v) continue;
      mark[w] = v;
      entries[kept++] = w;
    }
    sortSmall(entries + first, entries + kept);
    adjacency_start[v + 1] = kept;
  }
  scratch.adjacency.assign(entries, entries + kept);
}

/// Box centre and the radius about it of `count` points.
void boundingSphere(const Vec3* points, std::size_t count, Vec3& center, double& radius) {
  Aabb box;
  for (std::size_t i = 0; i < count; ++i) box.extend(points[i]);
  center = count > 0 ? Vec3(0.5 * (box.min + box.max)) : Vec3::Zero();
  radius = 0.0;
  for (std::size_t i = 0; i < count; ++i)
    radius = std::max(radius, (points[i] - center).squaredNorm());
  radius = std::sqrt(radius);
}

}  // namespace

ConvexPolytope::ConvexPolytope(const ConvexPolytope& other)
    : center(other.center), radius(other.radius) {
  PolytopePacking::of(other).into(*this);
}

ConvexPolytope::ConvexPolytope(ConvexPolytope&& other) noexcept
    : center(other.center), radius(other.radius) {
  PolytopePacking::moveArrays(*this, other);
}

ConvexPolytope& ConvexPolytope::operator=(const ConvexPolytope& other) {
  if (this != &other) *this = ConvexPolytope(other);
  return *this;
}

ConvexPolytope& ConvexPolytope::operator=(ConvexPolytope&& other) noexcept {
  if (this != &other) {
    release();
    PolytopePacking::moveArrays(*this, other);
    center = other.center;
    radius = other.radius;
  }
  return *this;
}

ConvexPolytope::~ConvexPolytope() { release(); }

void ConvexPolytope::release() {
  ::operator delete(block_);
  block_ = nullptr;
}

ConvexPolytope ConvexPolytope::build(const PolytopeParts& parts, PolytopeKeep keep) {
  FinalizeScratch scratch;
  return build(parts, scratch, keep);
}

ConvexPolytope ConvexPolytope::build(const PolytopeParts& parts, FinalizeScratch& scratch,
                                     PolytopeKeep keep) {
  // A two-sided triangle's lists are constants; a bare point set (an inner node of
  // a hierarchy) has no faces to walk: its arrays stay empty, which every reader
  // takes as "scan the vertices".
  const bool shared = isTwoSided(parts.faces.data(), parts.faces.size(), parts.vertices.size());
  if (!shared && !parts.faces.empty()) derive(parts, scratch);
  return pack(parts, scratch, keep);
}

void ConvexPolytope::derive(const PolytopeParts& parts, FinalizeScratch& scratch) {
  buildAdjacency(parts, scratch);
}

ConvexPolytope ConvexPolytope::pack(const PolytopeParts& parts, const FinalizeScratch& scratch,
                                    PolytopeKeep keep) {
  using P = PolytopePacking;
  const std::size_t n = parts.vertices.size(), nf = parts.faces.size();
  P packing;
  packing.set(P::kVertices, parts.vertices.data(), n);
  packing.set(P::kOriginal, parts.original.data(), parts.original.size());
  if (keep != PolytopeKeep::Support)
    packing.set(P::kFaceSource, parts.face_source.data(), parts.face_source.size());
  const bool face_lists = keep == PolytopeKeep::Everything;
  if (isTwoSided(parts.faces.data(), nf, n)) {
    packing.set(P::kFaces, kTwoSided.faces, 2);
    packing.set(P::kAdjStart, kTwoSided.adjacency_start, 4);
    packing.set(P::kAdj, kTwoSided.adjacency, 6);
    if (face_lists) {
      packing.set(P::kVfStart, kTwoSided.vertex_face_start, 4);
      packing.set(P::kVf, kTwoSided.vertex_faces, 6);
    }
  } else if (nf > 0) {
    packing.set(P::kFaces, parts.faces.data(), nf);
    packing.set(P::kAdjStart, scratch.adjacency_start.data(), scratch.adjacency_start.size());
    packing.set(P::kAdj, scratch.adjacency.data(), scratch.adjacency.size());
    if (face_lists) {
      packing.set(P::kVfStart, scratch.vertex_face_start.data(), scratch.vertex_face_start.size());
      packing.set(P::kVf, scratch.vertex_faces.data(), scratch.vertex_faces.size());
    }
  }
  ConvexPolytope out;
  packing.into(out);
  boundingSphere(parts.vertices.data(), n, out.center, out.radius);
  return out;
}

ConvexPolytope ConvexPolytope::reduced(PolytopeKeep keep) const {
  using P = PolytopePacking;
  P packing = P::of(*this);
  if (keep != PolytopeKeep::Everything) packing.sources[P::kVfStart] = packing.sources[P::kVf] = {};
  if (keep == PolytopeKeep::Support) packing.sources[P::kFaceSource] = {};
  ConvexPolytope out;
  packing.into(out);
  out.center = center;
  out.radius = radius;
  return out;
}

PolytopeParts ConvexPolytope::parts() const {
  PolytopeParts parts;
  parts.vertices.assign(vertices.begin(), vertices.end());
  parts.original.assign(original.begin(), original.end());
  parts.faces.assign(faces.begin(), faces.end());
  parts.face_source.assign(face_source.begin(), face_source.end());
  return parts;
}

Aabb ConvexPolytope::bounds() const {
  Aabb box;
  for (const Vec3& p : vertices) box.extend(p);
  return box;
}

int ConvexPolytope::support(const Vec3& direction, int& hint) const {
  const int n = static_cast<int>(vertices.size());
  // Small polytopes: a linear scan beats pointer chasing.
  if (n <= 32 || adjacency.empty()) {
    int best = 0;
    double best_dot = vertices[0].dot(direction);
    for (int i = 1; i < n; ++i) {
      const double d = vertices[i].dot(direction);
      if (d > best_dot) {
        best_dot = d;
        best = i;
      }
    }
    hint = best;
    return best;
  }
  // Hill climbing: on a convex surface a vertex no neighbour improves on is a
  // maximum (flat regions are triangulated, so ties lie on the maximal face).
  int v = (hint >= 0 && hint < n) ? hint : 0;
  double v_dot = vertices[v].dot(direction);
  for (bool improved = true; improved;) {
    improved = false;
    int best = v;
    for (int k = adjacency_start[v]; k < adjacency_start[v + 1]; ++k) {
      const int w = adjacency[k];
      const double d = vertices[w].dot(direction);
      if (d > v_dot) {
        best = w;
        v_dot = d;
        improved = true;
      }
    }
    v = best;
  }
  hint = v;
  return v;
}

}  // namespace sc::detail
