// SPDX-License-Identifier: MIT
// Geometry input and preprocessing: a piece is one indexed triangle set (one
// AddTriangles call), validated and preprocessed once, then immutable and shared.
// A model is the pieces of one object.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "smartcollision/mesh.h"
#include "smartcollision/types.h"

namespace sc {

namespace detail {
struct PieceData;
}

/// What preprocessing made of a piece.
struct PieceStats {
  int vertices = 0;         ///< input vertices
  int triangles = 0;        ///< input triangles
  bool flipped = false;     ///< closed piece given inside out, stored flipped
  bool convex = false;      ///< closed piece that is one convex patch
  int patches = 0;          ///< convex patches (closed) or triangle leaves (soup)
  int virtual_faces = 0;    ///< hull faces that are not input triangles
  int hull_vertices = 0;    ///< vertices summed over patch hulls
  int tree_depth = 0;       ///< depth of the hull (or triangle) hierarchy
  bool from_cache = false;  ///< loaded from the cache file
  double seconds = 0.0;     ///< wall time of preprocessing
};

/// Called during preprocessing with a fraction in [0, 1] and the stage's name.
using ProgressCallback = std::function<void(double fraction, const char* stage)>;

/// Asked between steps of a build (between patches while decomposing); returning
/// true cancels it. Usually reads a flag the progress callback or another thread sets.
using CancelCallback = std::function<bool()>;

struct BuildOptions {
  std::string cache_file;     ///< empty: no cache; else load if valid, else build and write
  ProgressCallback progress;  ///< optional
  /// Optional. A cancelled build returns InvalidOperation without a piece and writes
  /// no cache file (an existing one is left as it was).
  CancelCallback cancel;
  /// Threads for the independent parts of the build (regions of the decomposition,
  /// levels of the hull hierarchy); 0 = one per hardware thread. The piece and its
  /// cache file are the same for every count. Callbacks run on the calling thread.
  int threads = 0;
};
/// Largest BuildOptions::threads accepted.
inline constexpr int kMaxBuildThreads = 256;

class SC_API Piece {
 public:
  explicit Piece(std::unique_ptr<detail::PieceData> data);
  ~Piece();
  Piece(const Piece&) = delete;
  Piece& operator=(const Piece&) = delete;

  ModelKind kind() const;
  /// The triangles as stored: closed pieces given inside out are flipped.
  const MeshData& mesh() const;
  const PieceStats& stats() const;
  const Aabb& bounds() const;  ///< in the object's local frame
  /// Preprocessed data; its type is private to the library.
  const detail::PieceData& internals() const { return *data_; }

 private:
  std::unique_ptr<detail::PieceData> data_;
};
using PiecePtr = std::shared_ptr<const Piece>;

/// True for the values ModelKind names (a cast integer may name none).
SC_API bool knownKind(ModelKind kind);

/// Validates and preprocesses one piece.
/// Closed polyhedron: every edge shared by exactly two triangles with opposite
/// winding, no degenerate triangle, one connected shell; inside-out is flipped.
/// Triangle soup: anything finite with valid indices.
/// @return the piece; InvalidArgument (unknown kind, threads outside [0,
///   kMaxBuildThreads], non-finite, bad index, extent outside [kMinPieceExtent,
///   kMaxPieceExtent]) or InvalidGeometry (closed rules)
///   without a piece; or the piece with a File warning when the cache file could not
///   be written, or passed its checksum but does not describe this input (then it is
///   rebuilt and rewritten; see docs/api.md).
SC_API Result<PiecePtr> buildPiece(ModelKind kind, MeshData mesh, const BuildOptions& options = {});

/// The pieces of one object, all of one kind. May be empty (takes part in nothing).
class SC_API Model {
 public:
  /// Throws std::invalid_argument (and no model exists) for an unknown kind, a null
  /// piece, or a piece of another kind.
  Model(ModelKind kind, std::vector<PiecePtr> pieces);

  ModelKind kind() const { return kind_; }
  const std::vector<PiecePtr>& pieces() const { return pieces_; }
  const Aabb& bounds() const { return bounds_; }  ///< local frame; empty if no piece

 private:
  ModelKind kind_;
  std::vector<PiecePtr> pieces_;
  Aabb bounds_;
};
using ModelPtr = std::shared_ptr<const Model>;

}  // namespace sc
