// SPDX-License-Identifier: MIT
// Piece cache file: encode, decode with every count and index checked, and atomic
// write. Adjacency, bounds and bounding spheres are not stored: ConvexPolytope::build and
// finishHullBvh() recompute them on load, so a file cannot make them inconsistent.
#include "preprocess/cache_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <thread>
#include <type_traits>
#include <utility>

namespace sc::detail {
namespace {

constexpr char kMagic[8] = {'S', 'C', 'P', 'I', 'E', 'C', 'E', '\0'};
constexpr std::uint32_t kEndianMarker = 0x01020304u;
constexpr std::size_t kHeaderSize = 8 + 4 + 4 + 4 + 4 + 8 + 8 + 8;
// Per stored vertex: x, y, z, original; per face: three indices and the source.
constexpr std::size_t kVertexBytes = 3 * sizeof(double) + sizeof(std::int32_t);
constexpr std::size_t kFaceBytes = 4 * sizeof(std::int32_t);
constexpr std::size_t kNodeBytes = 3 * sizeof(std::int32_t);

/// payloadChecksum taken a piece at a time: whole 32-byte blocks go through the four
/// lanes, a partial one waits for the next piece, so the result does not depend on
/// how the bytes are split.
class PayloadHash {
 public:
  void update(const std::uint8_t* p, std::size_t n) {
    total_ += n;
    if (pending_ > 0) {
      const std::size_t take = std::min(n, kBlock - pending_);
      std::memcpy(block_ + pending_, p, take);
      pending_ += take;
      p += take;
      n -= take;
      if (pending_ < kBlock) return;
      mixBlock(block_);
      pending_ = 0;
    }
    for (; n >= kBlock; p += kBlock, n -= kBlock) mixBlock(p);
    std::memcpy(block_, p, n);
    pending_ = n;
  }
  /// The checksum of everything so far: the last partial block zero-padded, then
  /// the lanes and the length folded together.
  std::uint64_t value() const {
    PayloadHash last = *this;
    if (last.pending_ > 0) {
      std::memset(last.block_ + last.pending_, 0, kBlock - last.pending_);
      last.mixBlock(last.block_);
    }
    std::uint64_t h = total_ * kPrime1;
    for (const std::uint64_t lane : last.lanes_) h = round(h, lane);
    h ^= h >> 29;
    h *= kPrime2;
    return h ^ (h >> 32);
  }

 private:
  static constexpr std::size_t kBlock = 32;
  static constexpr std::uint64_t kPrime1 = 0x9E3779B185EBCA87ull;
  static constexpr std::uint64_t kPrime2 = 0xC2B2AE3D27D4EB4Full;
  static std::uint64_t round(std::uint64_t lane, std::uint64_t word) {
    lane += word * kPrime2;
    lane = (lane << 31) | (lane >> 33);
    return lane * kPrime1;
  }
  void mixBlock(const std::uint8_t* p) {
    for (int k = 0; k < 4; ++k) {
      std::uint64_t word = 0;
      std::memcpy(&word, p + 8 * k, sizeof(word));
      lanes_[k] = round(lanes_[k], word);
    }
  }
  std::uint64_t lanes_[4] = {kPrime1 + kPrime2, kPrime2, 0, 0 - kPrime1};
  std::uint8_t block_[kBlock] = {};
  std::size_t pending_ = 0;
  std::uint64_t total_ = 0;
};

/// Appends values to a buffer at a write position (no resize per value). With a
/// file, the buffer is written out whenever it holds kFlushBytes, and the payload's
/// checksum is taken on the way, so a file never needs a buffer of its whole size;
/// in memory the buffer ends at the last value written (finish()).
class Writer {
 public:
  Writer(std::vector<std::uint8_t>& out, std::FILE* file) : out_(out), file_(file) {
    if (file_ != nullptr) out_.resize(kFlushBytes + 64);  // a value never passes it
  }
  template <class T>
  void put(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (at_ + sizeof(T) > out_.size()) out_.resize(std::max(2 * out_.size(), at_ + sizeof(T)));
    std::memcpy(out_.data() + at_, &value, sizeof(T));
    at_ += sizeof(T);
    if (file_ != nullptr && at_ >= kFlushBytes) flush();
  }
  void putCount(std::size_t n) { put(static_cast<std::uint64_t>(n)); }
  void putPolytope(const ConvexPolytope& p) {
    putCount(p.vertices.size());
    for (std::size_t i = 0; i < p.vertices.size(); ++i) {
      for (int k = 0; k < 3; ++k) put(p.vertices[i][k]);
      put(static_cast<std::int32_t>(i < p.original.size() ? p.original[i] : -1));
    }
    putCount(p.faces.size());
    for (std::size_t f = 0; f < p.faces.size(); ++f) {
      for (int k = 0; k < 3; ++k) put(static_cast<std::int32_t>(p.faces[f][k]));
      put(static_cast<std::int32_t>(f < p.face_source.size() ? p.face_source[f] : -1));
    }
  }
  /// Checksums and writes what the buffer holds (file only); false on a write error.
  bool flush() {
    const std::size_t skip = written_ < kHeaderSize ? kHeaderSize - written_ : 0;
    if (at_ > skip) hash_.update(out_.data() + skip, at_ - skip);
    ok_ = ok_ && std::fwrite(out_.data(), 1, at_, file_) == at_;
    written_ += at_;
    at_ = 0;
    return ok_;
  }
  /// The payload's checksum; with a file, after the last flush().
  std::uint64_t checksum() const {
    if (file_ != nullptr) return hash_.value();
    return payloadChecksum(out_.data() + kHeaderSize, at_ - kHeaderSize);
  }
  /// In memory: the buffer cut to the bytes written.
  void finish() { out_.resize(at_); }

 private:
  static constexpr std::size_t kFlushBytes = std::size_t{1} << 20;
  std::vector<std::uint8_t>& out_;
  std::FILE* file_;
  std::size_t at_ = 0;       ///< bytes in the buffer
  std::size_t written_ = 0;  ///< bytes already in the file
  PayloadHash hash_;
  bool ok_ = true;
};

/// Reads from a byte range; every read is bounds-checked and sticky on failure.
class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  template <class T>
  bool get(T& value) {
    if (!ok_ || size_ - at_ < sizeof(T)) return ok_ = false;
    std::memcpy(&value, data_ + at_, sizeof(T));
    at_ += sizeof(T);
    return true;
  }
  /// A count of items of `item_bytes` each that must fit in the remaining bytes.
  bool getCount(std::size_t item_bytes, std::size_t& n) {
    std::uint64_t raw = 0;
    if (!get(raw) || raw > (size_ - at_) / item_bytes) return ok_ = false;
    n = static_cast<std::size_t>(raw);
    return true;
  }
  /// The next `n` bytes, which a getCount() of them has shown to be there.
  const std::uint8_t* take(std::size_t n) {
    const std::uint8_t* p = data_ + at_;
    at_ += n;
    return p;
  }
  bool done() const { return ok_ && at_ == size_; }
  std::size_t position() const { return at_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
  bool ok_ = true;
};

/// The input's counts, all that reading the records needs of it.
struct InputCounts {
  std::int64_t vertices = 0;
  std::int64_t triangles = 0;
};

/// Checks one polytope record and steps over it: vertex `original` must index the
/// input's vertices and face sources its triangles (or be -1), coordinates be
/// finite. readPolytope decodes it once every record has passed.
bool checkPolytope(Reader& r, const InputCounts& input) {
  std::size_t nv = 0, nf = 0;
  if (!r.getCount(kVertexBytes, nv) || nv == 0) return false;
  const std::int64_t vertex_limit = input.vertices;
  const std::uint8_t* at = r.take(nv * kVertexBytes);
  for (std::size_t i = 0; i < nv; ++i, at += kVertexBytes) {
    double xyz[3];
    std::int32_t original = -1;
    std::memcpy(xyz, at, sizeof(xyz));
    std::memcpy(&original, at + sizeof(xyz), sizeof(original));
    if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]) ||
        original < 0 || original >= vertex_limit)
      return false;
  }
  if (!r.getCount(kFaceBytes, nf)) return false;
  const std::int64_t triangle_limit = input.triangles;
  at = r.take(nf * kFaceBytes);
  for (std::size_t f = 0; f < nf; ++f, at += kFaceBytes) {
    std::int32_t record[4];
    std::memcpy(record, at, sizeof(record));
    for (int k = 0; k < 3; ++k) {
      if (record[k] < 0 || static_cast<std::size_t>(record[k]) >= nv) return false;
    }
    if (record[3] < -1 || record[3] >= triangle_limit) return false;
  }
  return true;
}

/// The 8-byte count at `at`, which it then passes.
std::size_t takeCount(const std::uint8_t*& at) {
  std::uint64_t count = 0;
  std::memcpy(&count, at, sizeof(count));
  at += sizeof(count);
  return static_cast<std::size_t>(count);
}

/// Decodes the polytope record at `at`, which checkPolytope passed.
void readPolytope(const std::uint8_t* at, PolytopeParts& p) {
  const std::size_t nv = takeCount(at);
  p.vertices.resize(nv);
  p.original.resize(nv);
  for (std::size_t i = 0; i < nv; ++i, at += kVertexBytes) {
    double xyz[3];
    std::int32_t original = -1;
    std::memcpy(xyz, at, sizeof(xyz));
    std::memcpy(&original, at + sizeof(xyz), sizeof(original));
    p.vertices[i] = Vec3(xyz[0], xyz[1], xyz[2]);
    p.original[i] = original;
  }
  const std::size_t nf = takeCount(at);
  p.faces.resize(nf);
  p.face_source.resize(nf);
  for (std::size_t f = 0; f < nf; ++f, at += kFaceBytes) {
    std::int32_t record[4];
    std::memcpy(record, at, sizeof(record));
    p.faces[f] = Tri(record[0], record[1], record[2]);
    p.face_source[f] = record[3];
  }
}

/// Checks a list of polytope records, noting where each starts (from `base`).
bool getPolytopes(Reader& r, const InputCounts& input, const std::uint8_t* base,
                  std::vector<const std::uint8_t*>& at) {
  std::size_t n = 0;
  // Every polytope takes at least its two counts and one vertex.
  if (!r.getCount(2 * sizeof(std::uint64_t) + kVertexBytes, n)) return false;
  at.resize(n);
  for (const std::uint8_t*& record : at) {
    record = base + r.position();
    if (!checkPolytope(r, input)) return false;
  }
  return true;
}

struct Header {
  char magic[8] = {};
  std::uint32_t version = 0;
  std::uint32_t endian = 0;
  std::uint32_t kind = 0;
  std::uint32_t reserved = 0;
  std::uint64_t input_hash = 0;
  std::uint64_t payload_size = 0;
  std::uint64_t checksum = 0;
};

bool readHeader(Reader& r, Header& h) {
  for (char& c : h.magic) {
    if (!r.get(c)) return false;
  }
  return r.get(h.version) && r.get(h.endian) && r.get(h.kind) && r.get(h.reserved) &&
         r.get(h.input_hash) && r.get(h.payload_size) && r.get(h.checksum);
}

/// The statistics the stored preprocessing implies.
void fillStats(PieceData& data, bool convex, int virtual_faces) {
  data.stats.convex = convex;
  data.stats.virtual_faces = virtual_faces;
  data.stats.patches = static_cast<int>(data.patches.size());
  data.stats.hull_vertices = 0;
  for (const ConvexPolytope& p : data.patches)
    data.stats.hull_vertices += static_cast<int>(p.vertices.size());
  data.stats.tree_depth = data.hierarchy.depth;
}

/// This version, kind and input, and a payload filling the rest of the file.
bool headerMatches(const Header& h, std::uint64_t input_hash, ModelKind kind,
                   std::size_t file_size) {
  return std::memcmp(h.magic, kMagic, sizeof(kMagic)) == 0 && h.version == kPieceCacheVersion &&
         h.endian == kEndianMarker && h.kind == static_cast<std::uint32_t>(kind) &&
         h.reserved == 0 && h.input_hash == input_hash && file_size >= kHeaderSize &&
         h.payload_size == file_size - kHeaderSize;
}

/// Every vertex is the input vertex it names, bit for bit: hulls are made of input
/// vertices, never of computed points.
bool verticesAreInput(const MeshData& mesh, const ConvexPolytope& p) {
  for (std::size_t i = 0; i < p.vertices.size(); ++i) {
    if (p.vertices[i] != mesh.vertices[static_cast<std::size_t>(p.original[i])]) return false;
  }
  return true;
}

/// Every real face is the input triangle it names (same vertices).
bool realFacesAreInput(const MeshData& mesh, const ConvexPolytope& p) {
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    const int source = p.face_source[f];
    if (source < 0) continue;
    Tri face(p.original[p.faces[f][0]], p.original[p.faces[f][1]], p.original[p.faces[f][2]]);
    Tri input = mesh.triangles[static_cast<std::size_t>(source)];
    std::sort(face.data(), face.data() + 3);
    std::sort(input.data(), input.data() + 3);
    if (face != input) return false;
  }
  return true;
}

/// Every input triangle is a real face of some leaf: the leaves cover the surface.
bool leavesCoverInput(const MeshData& mesh, const std::vector<ConvexPolytope>& leaves) {
  std::vector<char> covered(mesh.triangles.size(), 0);
  for (const ConvexPolytope& p : leaves) {
    for (const int source : p.face_source) {
      if (source >= 0) covered[static_cast<std::size_t>(source)] = 1;
    }
  }
  return std::find(covered.begin(), covered.end(), 0) == covered.end();
}

/// What the per-polytope checks found, a flag per kind: the problem reported then
/// does not depend on which thread saw which polytope.
struct PolytopeProblems {
  std::atomic<bool> leaf_vertex{false};
  std::atomic<bool> hull_vertex{false};
  std::atomic<bool> real_face{false};
};

/// Builds every leaf then every hull from its record, with the per-polytope checks
/// against `mesh`, on up to `threads` threads taking blocks of polytopes in turn;
/// each polytope's result depends on it alone. A soup's leaves keep no vertex-face
/// lists and hulls only what queries read, as a build leaves them.
void buildAndCheck(const PieceCacheRecords& records, ModelKind kind, const MeshData& mesh,
                   std::vector<ConvexPolytope>& leaves, std::vector<ConvexPolytope>& hulls,
                   PolytopeProblems& problems, int threads) {
  constexpr std::size_t kBlock = 64;
  leaves.resize(records.patch_at.size());
  hulls.resize(records.hull_at.size());
  const std::size_t total = leaves.size() + hulls.size();
  const PolytopeKeep leaf_keep =
      kind == ModelKind::TriangleSoup ? PolytopeKeep::NoFaceLists : PolytopeKeep::Everything;
  std::atomic<std::size_t> next{0};
  auto one = [&](std::size_t i, PolytopeParts& parts, FinalizeScratch& scratch) {
    const bool leaf = i < leaves.size();
    const std::size_t j = leaf ? i : i - leaves.size();
    readPolytope(leaf ? records.patch_at[j] : records.hull_at[j], parts);
    ConvexPolytope& p = leaf ? leaves[j] : hulls[j];
    p = ConvexPolytope::build(parts, scratch, leaf ? leaf_keep : PolytopeKeep::Support);
    if (!verticesAreInput(mesh, p))
      (leaf ? problems.leaf_vertex : problems.hull_vertex).store(true, std::memory_order_relaxed);
    if (leaf && !realFacesAreInput(mesh, p))
      problems.real_face.store(true, std::memory_order_relaxed);
  };
  auto work = [&] {
    PolytopeParts parts;
    FinalizeScratch scratch;
    for (std::size_t from = next.fetch_add(kBlock); from < total; from = next.fetch_add(kBlock)) {
      for (std::size_t i = from; i < std::min(total, from + kBlock); ++i) one(i, parts, scratch);
    }
  };
  const std::size_t helpers =
      std::min(static_cast<std::size_t>(std::max(threads, 1) - 1), total / kBlock);
  std::vector<std::thread> pool;
  pool.reserve(helpers);
  for (std::size_t t = 0; t < helpers; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
}

/// Every inner hull's box contains the boxes of the polytopes nearest below it (to
/// rounding of the hull build): a hierarchy that culls by a smaller hull would miss
/// contacts. A node without hull is bounded by a sphere of those polytopes' points.
bool innerHullsContainChildren(const std::vector<ConvexPolytope>& leaves, const HullBvh& bvh,
                               double slack) {
  std::vector<int> stack;
  for (const HullBvhNode& node : bvh.nodes) {
    if (node.leaf() || !node.hasPolytope()) continue;
    const Aabb box = bvh.hulls[static_cast<std::size_t>(node.polytope)].bounds();
    stack.assign({node.left, node.right});
    while (!stack.empty()) {
      const HullBvhNode& child = bvh.nodes[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
      if (!child.hasPolytope()) {
        stack.insert(stack.end(), {child.left, child.right});
        continue;
      }
      const Aabb inner = bvh.polytope(leaves, static_cast<int>(&child - bvh.nodes.data())).bounds();
      if ((inner.min.array() < box.min.array() - slack).any() ||
          (inner.max.array() > box.max.array() + slack).any())
        return false;
    }
  }
  return true;
}

/// What makes built leaves and hierarchy (structurally valid) not a
/// preprocessing of `mesh`, or null. Linear in the decoded size.
const char* contentProblem(const MeshData& mesh, const std::vector<ConvexPolytope>& leaves,
                           const HullBvh& bvh, const PolytopeProblems& problems) {
  if (problems.leaf_vertex) return "a leaf vertex is not the input vertex it names";
  if (problems.hull_vertex) return "a hull vertex is not the input vertex it names";
  if (problems.real_face || !leavesCoverInput(mesh, leaves))
    return "its real faces are not the input triangles, or do not cover them";
  Aabb box;
  for (const Vec3& v : mesh.vertices) box.extend(v);
  const double slack = box.empty() ? 0.0 : 1e-9 * (box.max - box.min).norm();
  if (!innerHullsContainChildren(leaves, bvh, slack))
    return "an inner hull of its hierarchy does not contain its children";
  return nullptr;
}

/// Reads the records of a payload whose header and checksum passed; null on
/// success, else why it is refused.
const char* readPayload(const std::uint8_t* payload, std::size_t size, const InputCounts& input,
                        PieceCacheRecords& out) {
  const char* const malformed = "its payload is malformed";
  Reader r(payload, size);
  std::uint8_t convex = 0;
  std::int32_t virtual_faces = 0;
  if (!r.get(convex) || convex > 1 || !r.get(virtual_faces) || virtual_faces < 0) return malformed;
  out.convex = convex != 0;
  out.virtual_faces = virtual_faces;
  if (!getPolytopes(r, input, payload, out.patch_at)) return malformed;
  std::size_t node_count = 0;
  if (!r.getCount(kNodeBytes, node_count)) return malformed;
  out.hierarchy.nodes.resize(node_count);
  for (HullBvhNode& n : out.hierarchy.nodes) {
    std::int32_t left = -1, right = -1, polytope = -1;
    if (!r.get(left) || !r.get(right) || !r.get(polytope)) return malformed;
    n.left = left;
    n.right = right;
    n.polytope = polytope;
  }
  if (!getPolytopes(r, input, payload, out.hull_at) || !r.done()) return malformed;
  return nullptr;
}

/// The records of a complete file of this version and kind for this input with a
/// matching checksum into `out`; false otherwise, with `*rejected` set (if given)
/// when the checksum passed but the records are malformed.
bool readBytes(const std::uint8_t* bytes, std::size_t size, std::uint64_t input_hash,
               ModelKind kind, const InputCounts& input, PieceCacheRecords& out,
               std::string* rejected) {
  Reader head(bytes, size);
  Header h;
  if (!readHeader(head, h) || !headerMatches(h, input_hash, kind, size)) return false;
  const std::uint8_t* payload = bytes + kHeaderSize;
  if (payloadChecksum(payload, size - kHeaderSize) != h.checksum) return false;
  // Past the checksum the file is intact: what follows finds a file that was not
  // written by this library for this input (forged, or written by a bug).
  PieceCacheRecords records;
  if (const char* problem = readPayload(payload, size - kHeaderSize, input, records)) {
    if (rejected != nullptr) *rejected = problem;
    return false;
  }
  out = std::move(records);
  return true;
}

InputCounts countsOf(const MeshData& mesh) {
  return {static_cast<std::int64_t>(mesh.vertices.size()),
          static_cast<std::int64_t>(mesh.triangles.size())};
}

}  // namespace

std::uint64_t fnv1a64(const void* bytes, std::size_t size, std::uint64_t hash) {
  const auto* p = static_cast<const std::uint8_t*>(bytes);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= p[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

std::uint64_t payloadChecksum(const void* bytes, std::size_t size) {
  PayloadHash hash;
  hash.update(static_cast<const std::uint8_t*>(bytes), size);
  return hash.value();
}

std::uint64_t pieceInputHash(ModelKind kind, const MeshData& mesh) {
  const std::uint64_t header[3] = {static_cast<std::uint64_t>(kind), mesh.vertices.size(),
                                   mesh.triangles.size()};
  std::uint64_t h = fnv1a64(header, sizeof(header));
  for (const Vec3& v : mesh.vertices) {
    const double xyz[3] = {v.x(), v.y(), v.z()};
    h = fnv1a64(xyz, sizeof(xyz), h);
  }
  for (const Tri& t : mesh.triangles) {
    const std::int32_t ids[3] = {t[0], t[1], t[2]};
    h = fnv1a64(ids, sizeof(ids), h);
  }
  return h;
}

namespace {

/// Bytes Writer::putPolytope writes for `p`.
std::size_t polytopeBytes(const ConvexPolytope& p) {
  return 2 * sizeof(std::uint64_t) + p.vertices.size() * (3 * sizeof(double) + 4) +
         p.faces.size() * 16;
}

/// Bytes of the payload encodePieceCache writes, for the header and so that the
/// bytes in memory take one buffer of their final size.
std::size_t payloadBytes(const PieceData& data) {
  std::size_t n = 1 + 4 + 3 * sizeof(std::uint64_t) + data.hierarchy.nodes.size() * 12;
  for (const ConvexPolytope& p : data.patches) n += polytopeBytes(p);
  for (const ConvexPolytope& p : data.hierarchy.hulls) n += polytopeBytes(p);
  return n;
}

/// Writes the header (checksum 0: the caller fills it in) and the payload.
void encodeInto(Writer& w, std::uint64_t input_hash, const PieceData& data) {
  for (const char c : kMagic) w.put(c);
  w.put(kPieceCacheVersion);
  w.put(kEndianMarker);
  w.put(static_cast<std::uint32_t>(data.kind));
  w.put(std::uint32_t{0});
  w.put(input_hash);
  w.put(static_cast<std::uint64_t>(payloadBytes(data)));
  w.put(std::uint64_t{0});  // the checksum, once the payload is written
  w.put(static_cast<std::uint8_t>(data.stats.convex ? 1 : 0));
  w.put(static_cast<std::int32_t>(data.stats.virtual_faces));
  w.putCount(data.patches.size());
  for (const ConvexPolytope& p : data.patches) w.putPolytope(p);
  w.putCount(data.hierarchy.nodes.size());
  for (const HullBvhNode& n : data.hierarchy.nodes) {
    w.put(static_cast<std::int32_t>(n.left));
    w.put(static_cast<std::int32_t>(n.right));
    w.put(static_cast<std::int32_t>(n.polytope));
  }
  w.putCount(data.hierarchy.hulls.size());
  for (const ConvexPolytope& p : data.hierarchy.hulls) w.putPolytope(p);
}

/// The file's bytes into `file`, a chunk at a time; false on a write error.
bool writePieceCache(std::FILE* file, std::uint64_t input_hash, const PieceData& data) {
  std::vector<std::uint8_t> chunk;
  Writer w(chunk, file);
  encodeInto(w, input_hash, data);
  if (!w.flush()) return false;
  const std::uint64_t checksum = w.checksum();
  return std::fseek(file, static_cast<long>(kHeaderSize - sizeof(checksum)), SEEK_SET) == 0 &&
         std::fwrite(&checksum, sizeof(checksum), 1, file) == 1;
}

}  // namespace

std::vector<std::uint8_t> encodePieceCache(std::uint64_t input_hash, const PieceData& data) {
  std::vector<std::uint8_t> bytes;
  bytes.resize(kHeaderSize + payloadBytes(data));
  Writer w(bytes, nullptr);
  encodeInto(w, input_hash, data);
  w.finish();
  const std::uint64_t checksum = w.checksum();
  std::memcpy(bytes.data() + kHeaderSize - sizeof(checksum), &checksum, sizeof(checksum));
  return bytes;
}

bool acceptPieceCacheRecords(PieceCacheRecords&& records, PieceData& data, std::string* rejected,
                             int threads) {
  PolytopeProblems problems;
  std::vector<ConvexPolytope> leaves;
  buildAndCheck(records, data.kind, data.mesh, leaves, records.hierarchy.hulls, problems, threads);
  const char* problem = finishHullBvh(leaves, records.hierarchy)
                            ? contentProblem(data.mesh, leaves, records.hierarchy, problems)
                            : "its hierarchy is not a tree over its leaves";
  if (problem != nullptr) {
    if (rejected != nullptr) *rejected = problem;
    return false;
  }
  data.patches = std::move(leaves);
  data.hierarchy = std::move(records.hierarchy);
  fillStats(data, records.convex, records.virtual_faces);
  return true;
}

bool decodePieceCache(const std::vector<std::uint8_t>& bytes, std::uint64_t input_hash,
                      PieceData& data, std::string* rejected, int threads) {
  PieceCacheRecords records;
  return readBytes(bytes.data(), bytes.size(), input_hash, data.kind, countsOf(data.mesh), records,
                   rejected) &&
         acceptPieceCacheRecords(std::move(records), data, rejected, threads);
}

namespace {

/// The file at `path` opened for reading, or null when it is missing or not a
/// regular file: opening a FIFO or a device without O_NONBLOCK can block forever.
std::FILE* openRegularFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return nullptr;
  struct stat st {};
  std::FILE* file = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) ? ::fdopen(fd, "rb") : nullptr;
  if (file == nullptr) ::close(fd);
  return file;
}

/// True when `path` names something other than a regular file (a FIFO, a device,
/// a directory): the cache never replaces it.
bool existsAsNonRegular(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
}

}  // namespace

bool readPieceCacheRecords(const std::string& path,
                           const std::function<std::uint64_t()>& input_hash, ModelKind kind,
                           std::size_t vertex_count, std::size_t triangle_count,
                           PieceCacheRecords& out, std::string* rejected) {
  std::FILE* file = openRegularFile(path);
  if (file == nullptr) return false;
  // The header first: a file of another version or kind is rejected unread. The
  // input's hash is asked for last, so that its computation can overlap the read.
  std::uint8_t header[kHeaderSize];
  bool ok = std::fseek(file, 0, SEEK_END) == 0;
  const long size = ok ? std::ftell(file) : -1;
  ok = ok && size >= static_cast<long>(kHeaderSize) && std::fseek(file, 0, SEEK_SET) == 0 &&
       std::fread(header, 1, kHeaderSize, file) == kHeaderSize;
  Header h;
  Reader head(header, kHeaderSize);
  ok = ok && readHeader(head, h) &&
       headerMatches(h, h.input_hash, kind, static_cast<std::size_t>(size));
  // Not zero-filled first: every byte is read over at once (a vector would clear
  // them all, a pass as long as the read).
  std::unique_ptr<std::uint8_t[]> bytes;
  if (ok) {
    const auto total = static_cast<std::size_t>(size);
    bytes.reset(new std::uint8_t[total]);
    std::memcpy(bytes.get(), header, kHeaderSize);
    ok = std::fread(bytes.get() + kHeaderSize, 1, total - kHeaderSize, file) == total - kHeaderSize;
  }
  std::fclose(file);
  const InputCounts input{static_cast<std::int64_t>(vertex_count),
                          static_cast<std::int64_t>(triangle_count)};
  PieceCacheRecords records;
  std::string problem;
  ok = ok && readBytes(bytes.get(), static_cast<std::size_t>(size), h.input_hash, kind, input,
                       records, &problem);
  // Another input's file (stale, foreign) is rebuilt without a word, however it reads.
  if (input_hash() != h.input_hash) return false;
  if (!ok) {
    if (rejected != nullptr && !problem.empty()) *rejected = problem;
    return false;
  }
  out = std::move(records);
  out.bytes = std::move(bytes);  // the records point into them
  return true;
}

bool loadPieceCache(const std::string& path, std::uint64_t input_hash, PieceData& data,
                    std::string* rejected, int threads) {
  PieceCacheRecords records;
  return readPieceCacheRecords(
             path, [input_hash] { return input_hash; }, data.kind, data.mesh.vertices.size(),
             data.mesh.triangles.size(), records, rejected) &&
         acceptPieceCacheRecords(std::move(records), data, rejected, threads);
}

Status savePieceCache(const std::string& path, std::uint64_t input_hash, const PieceData& data) {
  if (existsAsNonRegular(path))
    return Status(ErrorCode::File, "the cache file '" + path + "' is not a regular file");
  // A name of our own beside the target, so rename() replaces it in one step.
  const auto tick = std::chrono::steady_clock::now().time_since_epoch().count();
  const std::string temporary = path + ".tmp" + std::to_string(tick);
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  bool ok = file != nullptr;
  if (ok) {
    ok = writePieceCache(file, input_hash, data);
    ok = std::fclose(file) == 0 && ok;
  }
  ok = ok && std::rename(temporary.c_str(), path.c_str()) == 0;
  if (!ok) {
    if (file != nullptr) std::remove(temporary.c_str());
    return Status(ErrorCode::File, "cannot write the cache file '" + path + "'");
  }
  return Status::success();
}

}  // namespace sc::detail
