// SPDX-License-Identifier: MIT
// What the mesh benches share around a query: a one-piece closed model of a mesh,
// and the target's direction of a pair of one-part groups.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "smartcollision/smartcollision.h"

namespace sc_bench {

/// A one-piece closed-polyhedron model of `mesh`; null, with a message naming `name`
/// on stderr, when the mesh is rejected.
inline sc::ModelPtr closedModel(const sc::MeshData& mesh, const std::string& name = "mesh") {
  auto piece = sc::buildPiece(sc::ModelKind::ClosedPolyhedron, mesh);
  if (!piece.hasValue()) {
    std::fprintf(stderr, "bench: %s rejected: %s\n", name.c_str(),
                 piece.status().message().c_str());
    return nullptr;
  }
  return std::make_shared<const sc::Model>(sc::ModelKind::ClosedPolyhedron,
                                           std::vector<sc::PiecePtr>{piece.value()});
}

/// The target's direction only, of one part placed at `target` against one at
/// `opponent`.
inline sc::DirectedResult updateOneWay(sc::PairTracker& tracker, const sc::Part& target_part,
                                       const sc::Placement& target, const sc::Part& opponent_part,
                                       const sc::Placement& opponent,
                                       const sc::SceneSettings& settings) {
  const sc::GroupView a{&target_part, 1, target};
  const sc::GroupView b{&opponent_part, 1, opponent};
  sc::DirectedResult out[2];
  tracker.update(a, b, sc::Directions{true, false}, settings, out);
  return out[0];
}

}  // namespace sc_bench
