// SPDX-License-Identifier: MIT
#include "smartcollision/model.h"

#include "preprocess/piece_data.h"

namespace sc {

Piece::Piece(std::unique_ptr<detail::PieceData> data) : data_(std::move(data)) {}
Piece::~Piece() = default;
ModelKind Piece::kind() const { return data_->kind; }
const MeshData& Piece::mesh() const { return data_->mesh; }
const PieceStats& Piece::stats() const { return data_->stats; }
const Aabb& Piece::bounds() const { return data_->bounds; }

Model::Model(ModelKind kind, std::vector<PiecePtr> pieces)
    : kind_(kind), pieces_(std::move(pieces)) {
  for (const PiecePtr& p : pieces_) bounds_.extend(p->bounds());
}

}  // namespace sc
