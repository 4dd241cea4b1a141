// SPDX-License-Identifier: MIT
// The preprocessing cache file of a piece (manual List 6-5, AddTriangles' bvhFile):
// the convex patches and the hull hierarchy, keyed by a hash of the input.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "preprocess/piece_data.h"

namespace sc::detail {

/// Format version; bump it whenever the layout or the preprocessing changes, so
/// files written by other versions are rebuilt.
inline constexpr std::uint32_t kPieceCacheVersion = 3;

/// FNV-1a 64 of `size` bytes, continuing from `hash` (start: kFnvOffset).
inline constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;
std::uint64_t fnv1a64(const void* bytes, std::size_t size, std::uint64_t hash = kFnvOffset);

/// Checksum of a cache file's payload: four interleaved 64-bit multiply-rotate lanes
/// over little-endian words, about 15x faster to take than FNV-1a's byte steps.
std::uint64_t payloadChecksum(const void* bytes, std::size_t size);

/// Key of a piece's cache: FNV-1a 64 of the kind and the input arrays as given
/// (before any orientation fix).
std::uint64_t pieceInputHash(ModelKind kind, const MeshData& mesh);

/// The file's bytes for `data` (its patches, hierarchy and the statistics they
/// imply). Layout, little-endian: header {magic "SCPIECE\0", u32 version,
/// u32 0x01020304, u32 kind, u32 0, u64 input hash, u64 payload size, u64
/// payloadChecksum}, then the payload.
std::vector<std::uint8_t> encodePieceCache(std::uint64_t input_hash, const PieceData& data);

/// Fills data.patches, data.hierarchy and the statistics they carry from `bytes`.
/// `data.kind` and `data.mesh` (as stored) must be set: every index read is checked
/// against them. False, leaving `data` unchanged, unless the bytes are a complete
/// file of this version and kind for this input with a matching checksum and valid
/// contents. Never trusts a count: each is bounded by the bytes that remain.
/// The checksum finds damage, not forgery; past it the contents are checked against
/// the input: every hull vertex is the input vertex it names (bit for bit), real
/// faces are the input triangles and cover them all, the hierarchy is a tree over
/// the leaves and every inner hull's box contains its children's. A file failing
/// those (forged, or written by a bug) sets `*rejected` (if given) to the reason;
/// a damaged, stale or foreign file leaves it unchanged. The polytopes' derived
/// arrays (ConvexPolytope::build) are computed on up to `threads` threads; same result
/// for any count.
bool decodePieceCache(const std::vector<std::uint8_t>& bytes, std::uint64_t input_hash,
                      PieceData& data, std::string* rejected = nullptr, int threads = 1);

/// A file's records as read, before the polytopes are built and checked against
/// the input's contents: each polytope as where its checked record starts in the
/// file's bytes (`bytes`, or the caller's for decodePieceCache).
struct PieceCacheRecords {
  bool convex = false;
  int virtual_faces = 0;
  std::vector<const std::uint8_t*> patch_at;
  std::vector<const std::uint8_t*> hull_at;
  HullBvh hierarchy;  ///< nodes only: hulls and finishHullBvh come with the polytopes
  std::unique_ptr<std::uint8_t[]> bytes;
};

/// The first half of loadPieceCache: the file's header, checksum and records, every
/// index checked against the input's counts only. It reads nothing of the input's
/// contents, so it may run while another thread hashes, validates and orients them:
/// `input_hash` is called once, after the file is read (it may wait for that
/// thread), and a file written for another input is then dropped. False when the
/// file is missing, unreadable, stale, foreign or damaged, or (then setting
/// `*rejected`) its records are malformed.
bool readPieceCacheRecords(const std::string& path,
                           const std::function<std::uint64_t()>& input_hash, ModelKind kind,
                           std::size_t vertex_count, std::size_t triangle_count,
                           PieceCacheRecords& out, std::string* rejected = nullptr);

/// The second half: builds the polytopes on up to `threads` threads, checks them
/// against `data.mesh` as decodePieceCache does, and moves them into `data`; false
/// (setting `*rejected`, `data` unchanged) when they are not its preprocessing.
bool acceptPieceCacheRecords(PieceCacheRecords&& records, PieceData& data,
                             std::string* rejected = nullptr, int threads = 1);

/// decodePieceCache on the file at `path` (readPieceCacheRecords, then
/// acceptPieceCacheRecords); false when it is missing or unreadable.
bool loadPieceCache(const std::string& path, std::uint64_t input_hash, PieceData& data,
                    std::string* rejected = nullptr, int threads = 1);

/// Writes the file, a chunk at a time (no buffer of its size), through a temporary
/// file renamed over `path`, so readers never see a partial file. File status when
/// it cannot be written.
Status savePieceCache(const std::string& path, std::uint64_t input_hash, const PieceData& data);

}  // namespace sc::detail
