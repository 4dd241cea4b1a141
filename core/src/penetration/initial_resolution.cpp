// SPDX-License-Identifier: MIT
#include "penetration/initial_resolution.h"

#include <algorithm>

#include "geometry/math_util.h"
#include "penetration/contact_qp.h"
#include "query/convex_pair.h"
#include "query/epa.h"

namespace sc::detail {
namespace {

/// Global exit of one intersecting leaf pair: translating the target by depth * n
/// (opponent frame) makes the two leaves touch. A flat Minkowski difference (two
/// coplanar triangles of soups) touches at depth 0 along its plane normal.
EpaResult leafExit(const GroupPairQuery& query, const LeafContact& c, const Rigid& pose,
                   ConvexPairCache& cache) {
  const Leaf lt = query.targetLeaf(c.t_leaf);
  const Leaf lo = query.opponentLeaf(c.o_leaf);
  const Rigid fa = pose * lt.group_from_leaf;
  cache.gjk = SimplexCache();  // another leaf pair: the last one's vertex indices mean nothing
  EpaResult e;
  if (convexDepth(*lt.poly, fa, *lo.poly, lo.group_from_leaf, cache, e) !=
      ConvexDepthStatus::Separated)
    return e;
  // The traversal found them intersecting, this GJK apart: touching within rounding.
  return penetrationDepth(*lt.poly, fa, *lo.poly, lo.group_from_leaf);
}

/// Least-norm t with every row kept; falls back to the deepest row alone when the
/// rows admit no common solution (a target wedged between opposite walls).
Vec3 smallestExit(const ResolutionScratch& s) {
  const int m = static_cast<int>(s.normals.size());
  MatX a(m, 3);
  VecX b(m);
  int deepest = 0;
  for (int i = 0; i < m; ++i) {
    a.row(i) = s.normals[i].transpose();
    b[i] = s.offsets[i];
    if (s.offsets[i] > s.offsets[deepest]) deepest = i;
  }
  const QpResult qp = solveContactQp(VecX::Zero(3), VecX::Ones(3), a, b);
  if (qp.feasible && allFinite(qp.z)) return qp.z;
  return s.normals[deepest] * s.offsets[deepest];
}

}  // namespace

bool resolveInitialIntersection(GroupPairQuery& query, const Rigid& goal,
                                const PairSettings& settings, Rigid& free_pose,
                                ResolutionScratch& scratch, double max_depth,
                                const LeafContact* first) {
  constexpr int max_rounds = 32;
  // The exit keeps a gap of half the tolerance, so the proxy starts clearly free.
  const double skin = 0.5 * settings.tolerance;
  scratch.normals.clear();
  scratch.offsets.clear();
  // Bounded: one intersecting pair deeper than the bound settles it before every
  // intersecting pair is gathered (thousands in a deep overlap of two large meshes).
  if (first != nullptr && leafExit(query, *first, goal, scratch.depth).depth > max_depth)
    return false;
  Vec3 t = Vec3::Zero();
  for (int round = 0; round < max_rounds; ++round) {
    const Rigid pose{goal.rotation, goal.translation + t};
    query.contacts(pose, 0.0, scratch.contacts);
    bool any = false;
    for (const LeafContact& c : scratch.contacts) {
      if (!c.intersecting) continue;
      any = true;
      const EpaResult e = leafExit(query, c, pose, scratch.depth);
      if (e.depth + e.normal.dot(t) > max_depth) return false;  // its overlap at the goal
      // Row in the total translation: n . (t' - t) >= depth + skin.
      scratch.normals.push_back(e.normal);
      scratch.offsets.push_back(e.depth + skin + e.normal.dot(t));
    }
    if (!any) {
      free_pose = pose;
      return true;
    }
    t = smallestExit(scratch);
  }
  return false;
}

}  // namespace sc::detail
