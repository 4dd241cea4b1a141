// SPDX-License-Identifier: MIT
// Fuzzes the preprocessing cache file (BuildOptions::cache_file): arbitrary bytes
// stand as the cache of a fixed small mesh. A rejected file means a fresh build,
// which must equal the reference piece; an accepted one must be usable.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "fuzz_common.h"
#include "preprocess/cache_file.h"
#include "preprocess/piece_data.h"
#include "sc_support/off_mesh.h"
#include "smartcollision/model.h"
#include "smartcollision/scene.h"

namespace {

/// Header of the cache layout (cache_file.h): magic, version, byte order, kind,
/// zero, input hash, then the payload size at 32 and its checksum at 40.
constexpr std::size_t kHeaderSize = 48;
constexpr std::size_t kPayloadSizeAt = 32;
constexpr std::size_t kChecksumAt = 40;

struct Fixture {
  sc::MeshData mesh;
  std::uint64_t input_hash = 0;
  std::vector<std::uint8_t> reference;  ///< encoding of a fresh build
  sc::ModelPtr box;
  std::string path;

  Fixture() {
    auto m = sc::support::readOff(std::string(SC_TEST_DATA_DIR) + "/l_prism.off");
    if (!m.hasValue()) sc::fuzz::fail("cannot read tests/data/l_prism.off");
    mesh = m.value();
    auto fresh = sc::buildPiece(sc::ModelKind::ClosedPolyhedron, mesh);
    if (!fresh.hasValue()) sc::fuzz::fail("l_prism rejected");
    input_hash = sc::detail::pieceInputHash(sc::ModelKind::ClosedPolyhedron, mesh);
    reference = sc::detail::encodePieceCache(input_hash, fresh.value()->internals());
    std::uint64_t payload_size = 0;
    std::memcpy(&payload_size, reference.data() + kPayloadSizeAt, sizeof payload_size);
    if (reference.size() < kHeaderSize || payload_size != reference.size() - kHeaderSize)
      sc::fuzz::fail("cache header layout changed; update fuzz_cache_file.cpp");

    sc::MeshData box_mesh;
    box_mesh.vertices = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                         {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    box_mesh.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                          {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    auto box_piece = sc::buildPiece(sc::ModelKind::ClosedPolyhedron, box_mesh);
    if (!box_piece.hasValue()) sc::fuzz::fail("box rejected");
    box = std::make_shared<const sc::Model>(sc::ModelKind::ClosedPolyhedron,
                                            std::vector<sc::PiecePtr>{box_piece.value()});

    // make_seeds.sh takes the reference file from here.
    if (const char* out = std::getenv("SC_FUZZ_WRITE_REFERENCE")) {
      std::ofstream(out, std::ios::binary)
          .write(reinterpret_cast<const char*>(reference.data()),
                 static_cast<std::streamsize>(reference.size()));
    }

    char dir[] = "/tmp/sc_fuzz_cache_XXXXXX";
    if (mkdtemp(dir) == nullptr) sc::fuzz::fail("mkdtemp failed");
    directory = dir;
    path = directory + "/piece.scc";
  }
  ~Fixture() {
    std::remove(path.c_str());
    rmdir(directory.c_str());
  }
  Fixture(const Fixture&) = delete;
  Fixture& operator=(const Fixture&) = delete;

  std::string directory;
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

/// The bytes wrapped in a header that matches this mesh, with the right size and
/// checksum, so mutations reach the payload decoder instead of the checksum test.
std::vector<std::uint8_t> withValidHeader(const Fixture& f, const std::uint8_t* data,
                                          std::size_t size) {
  std::vector<std::uint8_t> file(f.reference.begin(), f.reference.begin() + kHeaderSize);
  file.insert(file.end(), data, data + size);
  const std::uint64_t payload_size = size;
  const std::uint64_t checksum = sc::detail::payloadChecksum(data, size);
  std::memcpy(file.data() + kPayloadSizeAt, &payload_size, sizeof payload_size);
  std::memcpy(file.data() + kChecksumAt, &checksum, sizeof checksum);
  return file;
}

/// A piece loaded from a cache the decoder accepted: its queries must behave.
void exercise(const Fixture& f, const sc::PiecePtr& piece) {
  auto model = std::make_shared<const sc::Model>(sc::ModelKind::ClosedPolyhedron,
                                                 std::vector<sc::PiecePtr>{piece});
  sc::Scene scene(sc::ModelKind::ClosedPolyhedron);
  if (!scene.addObject(1, model, sc::Placement{}).ok() ||
      !scene.addObject(2, f.box, sc::Placement{}).ok() || !scene.addObjectToGroup(2, 2).ok())
    sc::fuzz::fail("scene refused the cached piece");
  for (double x : {4.0, 2.5, 1.5, 0.5}) {
    sc::Placement p;
    p.world_center = sc::Vec3(x, 0.3, 0.2);
    if (!scene.setGroupPlacement(2, p).ok()) sc::fuzz::fail("setGroupPlacement");
    if (!scene.update().ok()) sc::fuzz::fail("update failed on a cached piece");
    for (const sc::PairStatus& pair : scene.pairs())
      for (const sc::DirectedResult& r : pair.results)
        if (sc::Status s = sc::detail::checkResult(r); !s.ok()) {
          std::fprintf(stderr, "%s\n", s.message().c_str());
          sc::fuzz::fail("checkResult on a cached piece");
        }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Fixture& f = fixture();
  if (size == 0) return 0;
  const bool fix_header = (data[0] & 1) != 0;
  const std::vector<std::uint8_t> file =
      fix_header ? withValidHeader(f, data + 1, size - 1)
                 : std::vector<std::uint8_t>(data + 1, data + size);
  {
    std::ofstream out(f.path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(file.data()), static_cast<std::streamsize>(file.size()));
    if (!out) sc::fuzz::fail("cannot write the temporary cache file");
  }
  sc::BuildOptions options;
  options.cache_file = f.path;
  auto piece = sc::buildPiece(sc::ModelKind::ClosedPolyhedron, f.mesh, options);
  if (!piece.hasValue()) sc::fuzz::fail("buildPiece failed with a cache file");
  const sc::Piece& p = *piece.value();
  if (p.mesh().vertices != f.mesh.vertices || p.mesh().triangles != f.mesh.triangles)
    sc::fuzz::fail("cached piece changed the mesh");
  const std::vector<std::uint8_t> got = sc::detail::encodePieceCache(f.input_hash, p.internals());
  // Raw bytes pass the checksum only if they are the reference file itself; a
  // rebuilt piece is the fresh build. Either way the piece equals the reference.
  if (!p.stats().from_cache || !fix_header) {
    if (got != f.reference) sc::fuzz::fail("piece differs from a fresh build");
  } else if (got != f.reference) {
    exercise(f, piece.value());
  }
  std::remove(f.path.c_str());
  return 0;
}
