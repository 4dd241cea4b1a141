// SPDX-License-Identifier: MIT
#include "penetration/convex_resolution.h"

namespace sc::detail {
namespace {

bool convexPiece(const GroupView& group, const Leaf& leaf) {
  if (leaf.part < 0 || leaf.part >= group.part_count) return false;
  const Model* model = group.parts[leaf.part].model;
  if (!model || leaf.piece < 0 || leaf.piece >= static_cast<int>(model->pieces().size()))
    return false;
  const Piece& piece = *model->pieces()[leaf.piece];
  return piece.kind() == ModelKind::ClosedPolyhedron && piece.stats().convex;
}

/// The outcome of a convex pair at `goal` penetrating by e (opponent frame).
void fillOutcome(const EpaResult& e, const Rigid& goal, ProxyOutcome& out) {
  out = ProxyOutcome();
  out.code = ErrorCode::Ok;
  out.penetrating = true;
  out.contact_pose = {goal.rotation, goal.translation + e.depth * e.normal};
  // The pose moved by a translation only: TPDV is that translation reversed, free of
  // the rounding of the two placed centres (which a tiny depth would not survive).
  out.tpdv = -e.depth * e.normal;
  out.distance = -out.tpdv.norm();
  out.iterations = e.iterations;
  LeafContact& c = out.contact;
  c.t_leaf = 0;
  c.o_leaf = 0;
  c.normal = e.normal;
  c.point_t = e.point_a + e.depth * e.normal;  // at the contact pose
  c.point_o = e.point_b;
  c.simplex_count = e.face_count;  // seeds the feature search at the contact
  for (int m = 0; m < e.face_count; ++m) {
    c.simplex_t[m] = e.face_a[m];
    c.simplex_o[m] = e.face_b[m];
  }
}

}  // namespace

bool isConvexPair(const GroupPairQuery& query, const GroupView& target, const GroupView& opponent) {
  return query.targetLeafCount() == 1 && query.opponentLeafCount() == 1 &&
         convexPiece(target, query.targetLeaf(0)) && convexPiece(opponent, query.opponentLeaf(0));
}

bool resolveConvexPair(const GroupPairQuery& query, const GroupView& target,
                       const GroupView& opponent, const Rigid& goal, const PairSettings& settings,
                       ConvexPairCache& cache, ProxyOutcome& out, Rigid& free_pose) {
  const RotationMode mode = settings.rotation_mode;
  if (mode != RotationMode::Input && mode != RotationMode::None) return false;
  if (!isConvexPair(query, target, opponent)) return false;
  const Leaf lt = query.targetLeaf(0);
  const Leaf lo = query.opponentLeaf(0);
  EpaResult e;
  if (convexDepth(*lt.poly, goal * lt.group_from_leaf, *lo.poly, lo.group_from_leaf, cache, e) !=
      ConvexDepthStatus::Penetrating)
    return false;
  fillOutcome(e, goal, out);
  // As the general path: the proxy starts half a tolerance clear of the contact.
  free_pose = {goal.rotation, goal.translation + (e.depth + 0.5 * settings.tolerance) * e.normal};
  return true;
}

}  // namespace sc::detail
