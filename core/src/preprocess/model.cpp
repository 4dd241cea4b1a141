// SPDX-License-Identifier: MIT
#include "smartcollision/model.h"

#include <stdexcept>

#include "preprocess/piece_data.h"

namespace sc {

bool knownKind(ModelKind kind) {
  return kind == ModelKind::ClosedPolyhedron || kind == ModelKind::TriangleSoup;
}

Piece::Piece(std::unique_ptr<detail::PieceData> data) : data_(std::move(data)) {}
Piece::~Piece() = default;
ModelKind Piece::kind() const { return data_->kind; }
const MeshData& Piece::mesh() const { return data_->mesh; }
const PieceStats& Piece::stats() const { return data_->stats; }
const Aabb& Piece::bounds() const { return data_->bounds; }

Model::Model(ModelKind kind, std::vector<PiecePtr> pieces)
    : kind_(kind), pieces_(std::move(pieces)) {
  // A constructor has no code to return: bad arguments throw, and no model exists.
  if (!knownKind(kind_)) throw std::invalid_argument("sc::Model: unknown ModelKind");
  for (const PiecePtr& p : pieces_) {
    if (!p) throw std::invalid_argument("sc::Model: null piece");
    if (p->kind() != kind_)
      throw std::invalid_argument("sc::Model: a piece's kind differs from the model's");
    bounds_.extend(p->bounds());
  }
}

}  // namespace sc
