// SPDX-License-Identifier: MIT
// buildPiece: validates one piece and preprocesses it: a convex closed piece becomes
// one patch, a non-convex one is decomposed, a soup is kept as its triangles; then
// the hull hierarchy over those leaves. A valid cache file replaces both steps.
#include "smartcollision/model.h"

#include "geometry/convex_polytope.h"
#include "geometry/mesh_validation.h"
#include "preprocess/cache_file.h"
#include "preprocess/convex_decomposition.h"
#include "preprocess/hull_bvh.h"
#include "preprocess/piece_data.h"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <future>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace sc {
namespace {

using detail::ConvexPolytope;
using detail::PieceData;

// Overall progress: validation, then decomposition, then the hierarchy.
constexpr double kDecompositionStart = 0.05;
constexpr double kHierarchyStart = 0.85;
constexpr double kHierarchyEnd = 0.99;

/// `progress` with the stage's fractions mapped into [from, to]; empty if it is.
ProgressCallback subRange(const ProgressCallback& progress, double from, double to) {
  if (!progress) return {};
  return [&progress, from, to](double fraction, const char* stage) {
    progress(from + (to - from) * std::clamp(fraction, 0.0, 1.0), stage);
  };
}

/// Box of the vertices some triangle uses; unused vertices do not count.
Aabb referencedBounds(const MeshData& mesh) {
  Aabb box;
  for (const Tri& f : mesh.triangles) {
    for (int k = 0; k < 3; ++k) box.extend(mesh.vertices[static_cast<std::size_t>(f[k])]);
  }
  return box;
}

/// A convex piece as its single patch: the referenced vertices in input order
/// (`original` = input index), the triangles as faces (`face_source` = index).
ConvexPolytope convexPatch(const MeshData& mesh) {
  std::vector<int> compact(mesh.vertices.size(), -1);
  for (const Tri& f : mesh.triangles) {
    for (int k = 0; k < 3; ++k) compact[static_cast<std::size_t>(f[k])] = 0;
  }
  detail::PolytopeParts patch;
  for (std::size_t i = 0; i < compact.size(); ++i) {
    if (compact[i] < 0) continue;
    compact[i] = static_cast<int>(patch.vertices.size());
    patch.vertices.push_back(mesh.vertices[i]);
    patch.original.push_back(static_cast<int>(i));
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Tri& f = mesh.triangles[t];
    patch.faces.emplace_back(compact[f[0]], compact[f[1]], compact[f[2]]);
    patch.face_source.push_back(static_cast<int>(t));
  }
  return ConvexPolytope::build(patch);
}

/// A soup's leaves are its triangles, each a two-sided wall: a polytope of three
/// vertices (coincident ones for a degenerate triangle) with both windings as faces.
/// Without vertex-face lists: its two faces hold all three vertices, so the readers'
/// scan of the faces finds the same faces in the same order. Its faces and
/// adjacency are the shared constants of a two-sided triangle.
void buildSoupLeaves(PieceData& data) {
  data.patches.reserve(data.mesh.triangles.size());
  detail::FinalizeScratch scratch;
  detail::PolytopeParts leaf;
  leaf.vertices.resize(3);
  leaf.original.resize(3);
  leaf.faces = {Tri(0, 1, 2), Tri(0, 2, 1)};
  leaf.face_source.resize(2);
  for (std::size_t t = 0; t < data.mesh.triangles.size(); ++t) {
    const Tri& f = data.mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      leaf.vertices[k] = data.mesh.vertices[static_cast<std::size_t>(f[k])];
      leaf.original[k] = f[k];
    }
    leaf.face_source[0] = leaf.face_source[1] = static_cast<int>(t);
    data.patches.push_back(ConvexPolytope::build(leaf, scratch, detail::PolytopeKeep::NoFaceLists));
  }
  data.stats.patches = static_cast<int>(data.patches.size());
  data.stats.hull_vertices = 3 * data.stats.patches;
}

/// Threads to build with: BuildOptions::threads, or for 0 one per hardware thread.
int threadCount(const BuildOptions& options) {
  if (options.threads > 0) return options.threads;
  const int hardware = static_cast<int>(std::thread::hardware_concurrency());
  return std::clamp(hardware, 1, kMaxBuildThreads);
}

bool cancelled(const BuildOptions& options) { return options.cancel && options.cancel(); }

Status cancelledStatus() { return {ErrorCode::InvalidOperation, "build cancelled"}; }

/// Closed piece, already validated and oriented: its convex patches.
Status buildPatches(PieceData& data, const ProgressCallback& progress, const CancelCallback& cancel,
                    int threads) {
  if (progress) progress(0.0, "decompose");
  if (detail::isConvex(data.mesh)) {
    data.patches.push_back(convexPatch(data.mesh));
    data.stats.convex = true;
  } else {
    Result<detail::Decomposition> decomposition =
        detail::decomposeConvexSurface(data.mesh, progress, cancel, threads);
    if (!decomposition.ok()) return decomposition.status();
    data.patches = std::move(decomposition.value().patches);
    data.stats.virtual_faces = decomposition.value().virtual_faces;
  }
  data.stats.patches = static_cast<int>(data.patches.size());
  for (const ConvexPolytope& patch : data.patches) {
    data.stats.hull_vertices += static_cast<int>(patch.vertices.size());
  }
  return Status::success();
}

/// Leaves (patches or soup triangles), then the hierarchy over them.
Status preprocess(PieceData& data, const BuildOptions& options) {
  const ProgressCallback& progress = options.progress;
  const int threads = threadCount(options);
  if (data.kind == ModelKind::ClosedPolyhedron) {
    const ProgressCallback stage = subRange(progress, kDecompositionStart, kHierarchyStart);
    if (Status s = buildPatches(data, stage, options.cancel, threads); !s.ok()) return s;
  } else {
    buildSoupLeaves(data);
  }
  if (cancelled(options)) return cancelledStatus();
  const double from =
      data.kind == ModelKind::ClosedPolyhedron ? kHierarchyStart : kDecompositionStart;
  const detail::HullLevels levels = data.kind == ModelKind::TriangleSoup
                                        ? detail::HullLevels::Alternate
                                        : detail::HullLevels::Every;
  data.hierarchy =
      detail::buildHullBvh(data.patches, subRange(progress, from, kHierarchyEnd), threads, levels);
  data.stats.tree_depth = data.hierarchy.depth;
  // Last chance before the cache file: a cancelled build writes nothing.
  return cancelled(options) ? cancelledStatus() : Status::success();
}

/// The warning for a cache file that passed its checksum but not the content checks.
Status refusedCache(const std::string& path, const std::string& reason, const Status& saved) {
  std::string message = "cache file '" + path + "' passed its checksum but " + reason +
                        ": not trusted; the piece was rebuilt";
  message += saved.ok() ? " and the file rewritten" : "; " + saved.message();
  return Status(ErrorCode::File, std::move(message));
}

/// A closed piece's cache key (the hash of the input as given) and validation on this
/// thread, the cache file read on a second one beside them: reading the records
/// needs only the input's counts, and the key only at the end. An exception on
/// either side (an allocation a file's size asks for) is thrown again after the
/// join: none escapes the thread, leaves it running or leaves it waiting.
Status hashAndValidateBesideRead(MeshData& mesh, const std::string& path, std::uint64_t& key,
                                 bool& flipped, detail::PieceCacheRecords& records,
                                 bool& have_records, std::string& rejected) {
  constexpr ModelKind kind = ModelKind::ClosedPolyhedron;
  const std::size_t vertex_count = mesh.vertices.size();
  const std::size_t triangle_count = mesh.triangles.size();
  std::promise<std::uint64_t> hashed;
  std::future<std::uint64_t> hash = hashed.get_future();
  std::exception_ptr read_failure, failure;
  std::thread reader([&] {
    try {
      have_records = detail::readPieceCacheRecords(
          path, [&hash] { return hash.get(); }, kind, vertex_count, triangle_count, records,
          &rejected);
    } catch (...) {
      read_failure = std::current_exception();
    }
  });
  Status valid;
  try {
    key = detail::pieceInputHash(kind, mesh);
    hashed.set_value(key);
    valid = detail::validateClosed(mesh, flipped);
  } catch (...) {
    failure = std::current_exception();
    try {
      hashed.set_exception(failure);  // the reader stops waiting for the key
    } catch (const std::future_error&) {
    }
  }
  reader.join();
  if (failure) std::rethrow_exception(failure);
  if (read_failure) std::rethrow_exception(read_failure);
  return valid;
}

/// Computes the cache key (`key`, with a cache file), validates a closed piece
/// (orienting it outward) and reads the cache file's records (`have_records`). On
/// two or more threads the read runs beside the rest: on a cache hit the
/// validation is most of what is left besides the file.
Status validateAndReadCache(ModelKind kind, MeshData& mesh, const BuildOptions& options,
                            std::uint64_t& key, bool& flipped, detail::PieceCacheRecords& records,
                            bool& have_records, std::string& rejected) {
  const std::string& path = options.cache_file;
  const bool closed = kind == ModelKind::ClosedPolyhedron;
  if (!path.empty() && closed && threadCount(options) >= 2)
    return hashAndValidateBesideRead(mesh, path, key, flipped, records, have_records, rejected);
  // The key is the input as given, before any orientation fix.
  key = path.empty() ? 0 : detail::pieceInputHash(kind, mesh);
  if (closed) {
    if (Status s = detail::validateClosed(mesh, flipped); !s.ok()) return s;
  }
  if (!path.empty()) {
    have_records = detail::readPieceCacheRecords(
        path, [key] { return key; }, kind, mesh.vertices.size(), mesh.triangles.size(), records,
        &rejected);
  }
  return Status::success();
}

}  // namespace

Result<PiecePtr> buildPiece(ModelKind kind, MeshData mesh, const BuildOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!knownKind(kind)) return Status(ErrorCode::InvalidArgument, "unknown ModelKind");
  if (options.threads < 0 || options.threads > kMaxBuildThreads) {
    return Status(ErrorCode::InvalidArgument, "BuildOptions::threads outside [0, 256]");
  }
  if (options.progress) options.progress(0.0, "validating piece");
  if (Status s = detail::validateArrays(mesh); !s.ok()) return s;

  const bool use_cache = !options.cache_file.empty();
  std::uint64_t key = 0;
  auto data = std::make_unique<PieceData>();
  data->kind = kind;
  data->stats.vertices = static_cast<int>(mesh.vertices.size());
  data->stats.triangles = static_cast<int>(mesh.triangles.size());
  std::string rejected;
  detail::PieceCacheRecords records;
  bool have_records = false;
  if (Status s = validateAndReadCache(kind, mesh, options, key, data->stats.flipped, records,
                                      have_records, rejected);
      !s.ok())
    return s;
  data->mesh = std::move(mesh);
  data->bounds = referencedBounds(data->mesh);
  Status file_status;
  if (have_records &&
      detail::acceptPieceCacheRecords(std::move(records), *data, &rejected, threadCount(options))) {
    data->stats.from_cache = true;
  } else {
    if (cancelled(options)) return cancelledStatus();
    if (Status s = preprocess(*data, options); !s.ok()) return s;
    if (use_cache) file_status = detail::savePieceCache(options.cache_file, key, *data);
    if (!rejected.empty()) file_status = refusedCache(options.cache_file, rejected, file_status);
  }
  data->stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.progress) options.progress(1.0, "piece built");
  return Result<PiecePtr>(PiecePtr(std::make_shared<const Piece>(std::move(data))),
                          std::move(file_status));
}

}  // namespace sc
