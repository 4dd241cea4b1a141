// SPDX-License-Identifier: MIT
// Piece cache file: a valid file round-trips the decomposition and hierarchy
// exactly; anything truncated, corrupt, foreign or of another version is detected,
// rebuilt to the same result as a fresh build and rewritten; an unwritable file is
// a File warning with the piece; counts read are never trusted.
#include "preprocess/cache_file.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <future>
#include <iterator>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "query/gjk.h"
#include "sc.h"
#include "support/meshes.h"
#include "support/shapes.h"
#include "support/temp_files.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

using test::readBytes;
using test::TempFile;
using test::tempPath;
using test::writeBytes;

// Header: magic 8, version 4, endian 4, kind 4, reserved 4, hash 8, size 8, checksum 8.
constexpr std::size_t kHeaderBytes = 48;
constexpr std::size_t kVersionOffset = 8;
constexpr std::size_t kHashOffset = 24;

/// The fields a cache file stores, to compare as one.
auto storedFields(const ConvexPolytope& p) {
  return std::tie(p.vertices, p.original, p.faces, p.face_source, p.adjacency_start, p.adjacency,
                  p.vertex_face_start, p.vertex_faces, p.center, p.radius);
}
auto storedFields(const HullBvhNode& n) {
  return std::tie(n.left, n.right, n.polytope, n.center, n.radius);
}
/// The statistics a cache file keeps (not timing and origin).
auto storedFields(const PieceStats& s) {
  return std::tie(s.patches, s.virtual_faces, s.hull_vertices, s.tree_depth, s.convex, s.flipped);
}

void expectSamePolytope(const ConvexPolytope& a, const ConvexPolytope& b) {
  ASSERT_TRUE(storedFields(a) == storedFields(b));
}

/// Same leaves, hierarchy, statistics (except timing and origin) as `expected`.
void expectSamePiece(const PieceData& expected, const PieceData& actual) {
  ASSERT_EQ(expected.patches.size(), actual.patches.size());
  for (std::size_t i = 0; i < expected.patches.size(); ++i)
    ASSERT_NO_FATAL_FAILURE(expectSamePolytope(expected.patches[i], actual.patches[i])) << i;
  const HullBvh& a = expected.hierarchy;
  const HullBvh& b = actual.hierarchy;
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
    ASSERT_TRUE(storedFields(a.nodes[i]) == storedFields(b.nodes[i])) << "node " << i;
  ASSERT_EQ(a.hulls.size(), b.hulls.size());
  for (std::size_t i = 0; i < a.hulls.size(); ++i)
    ASSERT_NO_FATAL_FAILURE(expectSamePolytope(a.hulls[i], b.hulls[i])) << i;
  EXPECT_EQ(a.leaf_node, b.leaf_node);
  EXPECT_EQ(a.depth, b.depth);
  EXPECT_TRUE(storedFields(expected.stats) == storedFields(actual.stats));
}

/// A closed prism over a star with `points` tips: non-convex, 12 * points triangles.
MeshData starPrism(int points, double inner, double outer, double height) {
  MeshData m;
  const int n = 2 * points;
  for (int level = 0; level < 2; ++level) {
    for (int i = 0; i < n; ++i) {
      const double angle = kPi * i / points;
      const double r = i % 2 == 0 ? outer : inner;
      m.vertices.emplace_back(r * std::cos(angle), r * std::sin(angle), level * height);
    }
  }
  m.vertices.emplace_back(0.0, 0.0, 0.0);
  m.vertices.emplace_back(0.0, 0.0, height);
  const int bottom_centre = 2 * n, top_centre = 2 * n + 1;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.emplace_back(i, j, n + j);
    m.triangles.emplace_back(i, n + j, n + i);
    m.triangles.emplace_back(top_centre, n + i, n + j);
    m.triangles.emplace_back(bottom_centre, j, i);
  }
  return m;
}

class CacheFile : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    star_ = new MeshData(starPrism(12, 0.4, 1.0, 0.3));
    other_ = new MeshData(starPrism(7, 0.5, 1.0, 0.2));
    Result<PiecePtr> fresh = buildPiece(ModelKind::ClosedPolyhedron, *star_);
    if (fresh.ok()) fresh_star_ = new PiecePtr(fresh.value());
  }
  static void TearDownTestSuite() {
    delete star_;
    delete other_;
    delete fresh_star_;
  }
  void SetUp() override {
    if (fresh_star_ == nullptr) GTEST_FAIL() << "the star prism did not build";
    ASSERT_GT(fresh().patches.size(), 1u) << "the star prism should be non-convex";
  }

  /// Builds the star prism through `path`.
  static Result<PiecePtr> starThrough(const std::string& path) {
    BuildOptions options;
    options.cache_file = path;
    return buildPiece(ModelKind::ClosedPolyhedron, *star_, options);
  }
  static const PieceData& fresh() { return (*fresh_star_)->internals(); }
  static std::uint64_t starKey() { return pieceInputHash(ModelKind::ClosedPolyhedron, *star_); }
  /// What a decode of the star's file starts from: its kind and input mesh.
  static PieceData decodeTarget() {
    PieceData target;
    target.kind = ModelKind::ClosedPolyhedron;
    target.mesh = fresh().mesh;
    return target;
  }

  /// The damaged file is not trusted: the piece equals a fresh build and the file
  /// is rewritten with the valid bytes.
  static void expectRebuiltAndRewritten(const std::string& path,
                                        const std::vector<std::uint8_t>& valid) {
    const Result<PiecePtr> rebuilt = starThrough(path);
    ASSERT_TRUE(rebuilt.ok()) << rebuilt.status().message();
    EXPECT_FALSE(rebuilt.value()->stats().from_cache);
    ASSERT_NO_FATAL_FAILURE(expectSamePiece(fresh(), rebuilt.value()->internals()));
    EXPECT_EQ(readBytes(path), valid);
    const Result<PiecePtr> again = starThrough(path);
    ASSERT_TRUE(again.ok());
    EXPECT_TRUE(again.value()->stats().from_cache);
  }

  static MeshData* star_;
  static MeshData* other_;
  static PiecePtr* fresh_star_;
};

MeshData* CacheFile::star_ = nullptr;
MeshData* CacheFile::other_ = nullptr;
PiecePtr* CacheFile::fresh_star_ = nullptr;

TEST(CacheFileMesh, RealMeshRoundTripIsExactAndAnswersTheSame) {
  MeshData elephant;
  ASSERT_NO_FATAL_FAILURE(elephant = test::loadTestMesh("elephant"));
  const Result<PiecePtr> fresh_piece = buildPiece(ModelKind::ClosedPolyhedron, elephant);
  ASSERT_TRUE(fresh_piece.ok());
  TempFile file("sc_cache_test", "elephant.bvh");
  BuildOptions options;
  options.cache_file = file.path;
  const Result<PiecePtr> first = buildPiece(ModelKind::ClosedPolyhedron, elephant, options);
  ASSERT_TRUE(first.ok()) << first.status().message();
  EXPECT_FALSE(first.value()->stats().from_cache);
  const Result<PiecePtr> second = buildPiece(ModelKind::ClosedPolyhedron, elephant, options);
  ASSERT_TRUE(second.ok()) << second.status().message();
  EXPECT_TRUE(second.value()->stats().from_cache);
  const PieceData& a = fresh_piece.value()->internals();
  const PieceData& b = second.value()->internals();
  ASSERT_NO_FATAL_FAILURE(expectSamePiece(a, b));
  EXPECT_EQ(b.stats.virtual_faces, a.stats.virtual_faces);
  EXPECT_GT(a.stats.virtual_faces, 0);
  // Same queries: GJK between every 50th patch pair of the two copies, placed apart.
  const Rigid shift{Mat3(Eigen::AngleAxisd(0.3, Vec3::UnitZ())), Vec3(0.05, 0.02, 0.01)};
  for (std::size_t i = 0; i < a.patches.size(); i += 50) {
    for (std::size_t j = 0; j < a.patches.size(); j += 50) {
      SimplexCache ca, cb;
      const GjkResult ra = gjkDistance(a.patches[i], shift, a.patches[j], Rigid(), {}, ca);
      const GjkResult rb = gjkDistance(b.patches[i], shift, b.patches[j], Rigid(), {}, cb);
      ASSERT_EQ(ra.status, rb.status);
      ASSERT_EQ(ra.distance, rb.distance);
    }
  }
}

// The payload checksum changes with every single bit flipped and with two unequal
// words swapped, at any length (the partial last block included).
TEST(CacheFileChecksum, SeesEveryBitFlipAndWordSwap) {
  test::Rng rng(0x5EED);
  std::uniform_int_distribution<int> byte(0, 255);
  for (const std::size_t size : {1u, 7u, 31u, 32u, 33u, 200u}) {
    std::vector<std::uint8_t> bytes(size);
    for (std::uint8_t& b : bytes) b = static_cast<std::uint8_t>(byte(rng));
    const std::uint64_t sum = payloadChecksum(bytes.data(), size);
    for (std::size_t i = 0; i < size; ++i) {
      for (int bit = 0; bit < 8; ++bit) {
        bytes[i] ^= static_cast<std::uint8_t>(1u << bit);
        EXPECT_NE(payloadChecksum(bytes.data(), size), sum) << size << " " << i << " " << bit;
        bytes[i] ^= static_cast<std::uint8_t>(1u << bit);
      }
    }
    for (std::size_t i = 0; i + 16 <= size; i += 8) {
      std::swap_ranges(bytes.begin() + i, bytes.begin() + i + 8, bytes.begin() + i + 8);
      EXPECT_NE(payloadChecksum(bytes.data(), size), sum) << size << " " << i;
      std::swap_ranges(bytes.begin() + i, bytes.begin() + i + 8, bytes.begin() + i + 8);
    }
    // A zero byte appended is another payload, not the same padded block.
    bytes.push_back(0);
    EXPECT_NE(payloadChecksum(bytes.data(), size + 1), sum) << size;
  }
}

// A file of several write chunks (1 MiB each) holds exactly the bytes encoded in
// memory, checksum included, and loads.
TEST(CacheFileMesh, FileWrittenInChunksEqualsTheEncodedBytes) {
  const MeshData soup = test::torusMesh(1.0, 0.3, 100, 60);  // 12,000 triangles
  TempFile file("sc_cache_test", "chunks.bvh");
  BuildOptions options;
  options.cache_file = file.path;
  const Result<PiecePtr> built = buildPiece(ModelKind::TriangleSoup, soup, options);
  ASSERT_TRUE(built.ok()) << built.status().message();
  const std::vector<std::uint8_t> bytes = readBytes(file.path);
  EXPECT_GT(bytes.size(), std::size_t{2} << 20);
  const std::uint64_t key = pieceInputHash(ModelKind::TriangleSoup, soup);
  EXPECT_EQ(bytes, encodePieceCache(key, built.value()->internals()));
  const Result<PiecePtr> loaded = buildPiece(ModelKind::TriangleSoup, soup, options);
  ASSERT_TRUE(loaded.ok());
  EXPECT_TRUE(loaded.value()->stats().from_cache);
}

// Decoding derives every polytope's arrays on the threads it is given: one and two
// threads give the build's piece exactly (closed torus: patches and inner hulls).
TEST(CacheFileMesh, DecodedOnOneAndTwoThreadsEqualsTheBuild) {
  const MeshData torus = test::torusMesh(1.0, 0.3, 80, 40);
  const Result<PiecePtr> built = buildPiece(ModelKind::ClosedPolyhedron, torus);
  ASSERT_TRUE(built.ok()) << built.status().message();
  const PieceData& expected = built.value()->internals();
  ASSERT_GT(expected.patches.size() + expected.hierarchy.hulls.size(), 128u);
  const std::uint64_t key = pieceInputHash(ModelKind::ClosedPolyhedron, torus);
  const std::vector<std::uint8_t> bytes = encodePieceCache(key, expected);
  for (const int threads : {1, 2}) {
    PieceData loaded;
    loaded.kind = ModelKind::ClosedPolyhedron;
    loaded.mesh = expected.mesh;
    loaded.stats.flipped = expected.stats.flipped;
    ASSERT_TRUE(decodePieceCache(bytes, key, loaded, nullptr, threads)) << threads;
    ASSERT_NO_FATAL_FAILURE(expectSamePiece(expected, loaded)) << threads;
  }
}

// On two threads buildPiece reads the file's records beside the input's validation,
// which may turn the input outward: loads on one and two threads give the build's
// piece, for a torus given inside out as well.
TEST(CacheFileMesh, LoadedBesideTheValidationEqualsTheBuild) {
  for (const bool inside_out : {false, true}) {
    SCOPED_TRACE(inside_out ? "inside out" : "outward");
    MeshData torus = test::torusMesh(1.0, 0.3, 40, 20);
    if (inside_out) {
      for (Tri& t : torus.triangles) std::swap(t[1], t[2]);
    }
    TempFile file("sc_cache_test", "beside.bvh");
    BuildOptions options;
    options.cache_file = file.path;
    options.threads = 1;
    const Result<PiecePtr> built = buildPiece(ModelKind::ClosedPolyhedron, torus, options);
    ASSERT_TRUE(built.ok()) << built.status().message();
    ASSERT_FALSE(built.value()->stats().from_cache);
    EXPECT_EQ(built.value()->stats().flipped, inside_out);
    for (const int threads : {1, 2}) {
      options.threads = threads;
      const Result<PiecePtr> loaded = buildPiece(ModelKind::ClosedPolyhedron, torus, options);
      ASSERT_TRUE(loaded.ok()) << loaded.status().message();
      EXPECT_TRUE(loaded.value()->stats().from_cache) << threads;
      const PieceData& got = loaded.value()->internals();
      EXPECT_EQ(got.mesh.triangles, built.value()->internals().mesh.triangles) << threads;
      ASSERT_NO_FATAL_FAILURE(expectSamePiece(built.value()->internals(), got)) << threads;
    }
  }
}

// A file that matches the input does not vouch for it: an open mesh is refused with
// its validation error on one and two threads, though its file is read beside.
TEST(CacheFileMesh, InvalidInputIsRefusedWhateverItsFile) {
  const MeshData torus = test::torusMesh(1.0, 0.3, 40, 20);
  const Result<PiecePtr> built = buildPiece(ModelKind::ClosedPolyhedron, torus);
  ASSERT_TRUE(built.ok()) << built.status().message();
  MeshData open = torus;
  open.triangles.back() = open.triangles.front();  // same counts, one hole, one double
  TempFile file("sc_cache_test", "invalid.bvh");
  writeBytes(file.path, encodePieceCache(pieceInputHash(ModelKind::ClosedPolyhedron, open),
                                         built.value()->internals()));
  for (const int threads : {1, 2}) {
    BuildOptions options;
    options.cache_file = file.path;
    options.threads = threads;
    const Result<PiecePtr> refused = buildPiece(ModelKind::ClosedPolyhedron, open, options);
    ASSERT_FALSE(refused.ok()) << threads;
    EXPECT_EQ(refused.status().code(), ErrorCode::InvalidGeometry) << threads;
  }
}

TEST_F(CacheFile, RoundTripLoadsTheSamePreprocessing) {
  TempFile file("sc_cache_test", "roundtrip.bvh");
  const Result<PiecePtr> first = starThrough(file.path);
  ASSERT_TRUE(first.ok()) << first.status().message();
  EXPECT_FALSE(first.value()->stats().from_cache);
  ASSERT_NO_FATAL_FAILURE(expectSamePiece(fresh(), first.value()->internals()));
  const std::vector<std::uint8_t> bytes = readBytes(file.path);
  ASSERT_GT(bytes.size(), kHeaderBytes);

  const Result<PiecePtr> second = starThrough(file.path);
  ASSERT_TRUE(second.ok()) << second.status().message();
  EXPECT_TRUE(second.value()->stats().from_cache);
  ASSERT_NO_FATAL_FAILURE(expectSamePiece(fresh(), second.value()->internals()));
  EXPECT_EQ(readBytes(file.path), bytes) << "a valid file is not rewritten";
}

TEST_F(CacheFile, EncodeDecodeRoundTripIsExact) {
  const std::uint64_t key = starKey();
  const std::vector<std::uint8_t> bytes = encodePieceCache(key, fresh());
  PieceData loaded = decodeTarget();
  ASSERT_TRUE(decodePieceCache(bytes, key, loaded));
  loaded.stats.flipped = fresh().stats.flipped;
  ASSERT_NO_FATAL_FAILURE(expectSamePiece(fresh(), loaded));
  // Wrong key or kind: rejected.
  PieceData other = loaded;
  EXPECT_FALSE(decodePieceCache(bytes, key + 1, other));
  other.kind = ModelKind::TriangleSoup;
  EXPECT_FALSE(decodePieceCache(bytes, key, other));
}

TEST_F(CacheFile, TruncatedFilesAreRebuiltAndRewritten) {
  TempFile file("sc_cache_test", "truncated.bvh");
  ASSERT_TRUE(starThrough(file.path).ok());
  const std::vector<std::uint8_t> valid = readBytes(file.path);
  for (const std::size_t length :
       {std::size_t{0}, std::size_t{1}, kHeaderBytes - 1, kHeaderBytes, kHeaderBytes + 5,
        valid.size() / 3, valid.size() / 2, valid.size() - 8, valid.size() - 1}) {
    SCOPED_TRACE(::testing::Message() << "truncated to " << length << " of " << valid.size());
    writeBytes(file.path, std::vector<std::uint8_t>(valid.begin(), valid.begin() + length));
    ASSERT_NO_FATAL_FAILURE(expectRebuiltAndRewritten(file.path, valid));
  }
  // Longer than it says: rejected too.
  std::vector<std::uint8_t> longer = valid;
  longer.push_back(0);
  writeBytes(file.path, longer);
  ASSERT_NO_FATAL_FAILURE(expectRebuiltAndRewritten(file.path, valid));
}

TEST_F(CacheFile, FlippedBytesAreRebuiltAndRewritten) {
  TempFile file("sc_cache_test", "flipped.bvh");
  ASSERT_TRUE(starThrough(file.path).ok());
  const std::vector<std::uint8_t> valid = readBytes(file.path);
  for (const std::size_t at :
       {std::size_t{0}, kVersionOffset, std::size_t{20}, kHashOffset + 3, std::size_t{34},
        std::size_t{45}, kHeaderBytes, kHeaderBytes + 100, valid.size() / 2, valid.size() - 1}) {
    for (const std::uint8_t mask : {std::uint8_t{0x01}, std::uint8_t{0x80}}) {
      SCOPED_TRACE(::testing::Message() << "byte " << at << " xor " << int{mask});
      std::vector<std::uint8_t> bad = valid;
      bad[at] ^= mask;
      writeBytes(file.path, bad);
      ASSERT_NO_FATAL_FAILURE(expectRebuiltAndRewritten(file.path, valid));
    }
  }
}

TEST_F(CacheFile, AnotherMeshsCacheIsRebuiltForThisMesh) {
  TempFile file("sc_cache_test", "foreign.bvh");
  BuildOptions options;
  options.cache_file = file.path;
  const Result<PiecePtr> other = buildPiece(ModelKind::ClosedPolyhedron, *other_, options);
  ASSERT_TRUE(other.ok()) << other.status().message();
  ASSERT_FALSE(readBytes(file.path).empty());
  const std::vector<std::uint8_t> valid = encodePieceCache(starKey(), fresh());
  const std::vector<std::uint8_t> foreign = readBytes(file.path);
  ASSERT_NO_FATAL_FAILURE(expectRebuiltAndRewritten(file.path, valid));
  // Stale, not forged: read before the key is known (two threads) or after, it is
  // rebuilt without a warning.
  for (const int threads : {1, 2}) {
    writeBytes(file.path, foreign);
    options.threads = threads;
    const Result<PiecePtr> rebuilt = buildPiece(ModelKind::ClosedPolyhedron, *star_, options);
    ASSERT_TRUE(rebuilt.ok()) << rebuilt.status().message();
    EXPECT_FALSE(rebuilt.value()->stats().from_cache) << threads;
    EXPECT_EQ(rebuilt.status().code(), ErrorCode::Ok) << rebuilt.status().message();
  }
  options.threads = 0;
  // The same arrays as a soup are another input too.
  const Result<PiecePtr> soup = buildPiece(ModelKind::TriangleSoup, *star_, options);
  ASSERT_TRUE(soup.ok());
  EXPECT_FALSE(soup.value()->stats().from_cache);
  EXPECT_EQ(soup.value()->internals().patches.size(), star_->triangles.size());
}

TEST_F(CacheFile, OtherVersionIsRebuiltAndRewritten) {
  TempFile file("sc_cache_test", "version.bvh");
  ASSERT_TRUE(starThrough(file.path).ok());
  const std::vector<std::uint8_t> valid = readBytes(file.path);
  for (const std::uint32_t version : {kPieceCacheVersion - 1, kPieceCacheVersion + 1}) {
    std::vector<std::uint8_t> other = valid;
    std::memcpy(other.data() + kVersionOffset, &version, sizeof(version));
    writeBytes(file.path, other);
    ASSERT_NO_FATAL_FAILURE(expectRebuiltAndRewritten(file.path, valid));
  }
}

TEST_F(CacheFile, UnwritableFileGivesThePieceAndAFileWarning) {
  BuildOptions options;
  options.cache_file = tempPath("sc_cache_test", "no_such_dir") + "/piece.bvh";
  const Result<PiecePtr> piece = buildPiece(ModelKind::ClosedPolyhedron, *star_, options);
  ASSERT_TRUE(piece.hasValue());
  EXPECT_EQ(piece.status().code(), ErrorCode::File);
  EXPECT_FALSE(piece.value()->stats().from_cache);
  ASSERT_NO_FATAL_FAILURE(expectSamePiece(fresh(), piece.value()->internals()));

  // Through sc.h: SC_ERROR_FILE, and the piece is added.
  SCObject object(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  std::vector<double> xyz;
  for (const Vec3& v : star_->vertices) xyz.insert(xyz.end(), {v.x(), v.y(), v.z()});
  std::vector<int> ids;
  for (const Tri& t : star_->triangles) ids.insert(ids.end(), {t[0], t[1], t[2]});
  EXPECT_EQ(
      object.AddTriangles(xyz.data(), static_cast<int>(star_->vertices.size()), ids.data(),
                          static_cast<int>(star_->triangles.size()), options.cache_file.c_str()),
      SC_ERROR_FILE);
}

TEST_F(CacheFile, FifoIsNeitherReadNorReplaced) {
  TempFile fifo("sc_cache_test", "fifo.bvh");
  ASSERT_EQ(::mkfifo(fifo.path.c_str(), 0600), 0);
  std::future<Result<PiecePtr>> build =
      std::async(std::launch::async, [&fifo] { return starThrough(fifo.path); });
  if (build.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    // Blocked opening the FIFO: a writer that closes at once lets it finish.
    const int writer = ::open(fifo.path.c_str(), O_WRONLY | O_NONBLOCK);
    if (writer >= 0) ::close(writer);
    build.wait();
    FAIL() << "building through a FIFO cache file blocked";
  }
  const Result<PiecePtr> piece = build.get();
  ASSERT_TRUE(piece.hasValue());
  EXPECT_EQ(piece.status().code(), ErrorCode::File);
  EXPECT_NE(piece.status().message().find("not a regular file"), std::string::npos)
      << piece.status().message();
  EXPECT_FALSE(piece.value()->stats().from_cache);
  ASSERT_NO_FATAL_FAILURE(expectSamePiece(fresh(), piece.value()->internals()));
  struct stat st {};
  ASSERT_EQ(::stat(fifo.path.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
}

/// Re-signs a modified payload, so decoding gets past the checksum.
void resign(std::vector<std::uint8_t>& bytes) {
  const std::uint64_t size = bytes.size() - kHeaderBytes;
  const std::uint64_t sum = payloadChecksum(bytes.data() + kHeaderBytes, size);
  std::memcpy(bytes.data() + 32, &size, sizeof(size));
  std::memcpy(bytes.data() + 40, &sum, sizeof(sum));
}

TEST_F(CacheFile, CountsAndIndicesReadAreNeverTrusted) {
  const std::uint64_t key = starKey();
  const std::vector<std::uint8_t> valid = encodePieceCache(key, fresh());
  PieceData target = decodeTarget();
  // The patch count (after the convex flag and the virtual face count) made huge.
  std::vector<std::uint8_t> bad = valid;
  const std::uint64_t huge = std::uint64_t{1} << 60;
  std::memcpy(bad.data() + kHeaderBytes + 5, &huge, sizeof(huge));
  resign(bad);
  EXPECT_FALSE(decodePieceCache(bad, key, target));
  EXPECT_TRUE(target.patches.empty()) << "a rejected file leaves the piece unchanged";
  // Random corruption behind a valid checksum: rejected or, if it happens to keep
  // every count and index valid, accepted; never a crash (run under ASan).
  test::Rng rng(0xCAC4E);
  int rejected = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<std::uint8_t> fuzzed = valid;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < flips; ++k) {
      const std::size_t at = kHeaderBytes + rng() % (fuzzed.size() - kHeaderBytes);
      fuzzed[at] = static_cast<std::uint8_t>(rng());
    }
    resign(fuzzed);
    PieceData out = decodeTarget();
    if (!decodePieceCache(fuzzed, key, out)) ++rejected;
  }
  EXPECT_GT(rejected, 0);
  std::printf("[ cache file ] %d of 300 re-signed corrupt payloads rejected\n", rejected);
}

TEST(PieceInputHash, ChangesWithTheInput) {
  MeshData mesh = test::boxMesh(Vec3(1, 1, 1));
  const std::uint64_t h = pieceInputHash(ModelKind::ClosedPolyhedron, mesh);
  EXPECT_EQ(h, pieceInputHash(ModelKind::ClosedPolyhedron, mesh));
  EXPECT_NE(h, pieceInputHash(ModelKind::TriangleSoup, mesh));
  MeshData moved = mesh;
  moved.vertices[3].x() = std::nextafter(moved.vertices[3].x(), 2.0);
  EXPECT_NE(h, pieceInputHash(ModelKind::ClosedPolyhedron, moved));
  MeshData reordered = mesh;
  std::swap(reordered.triangles[0], reordered.triangles[1]);
  EXPECT_NE(h, pieceInputHash(ModelKind::ClosedPolyhedron, reordered));
}

}  // namespace
}  // namespace sc::detail
