// SPDX-License-Identifier: MIT
#include "penetration/initial_resolution.h"

#include <algorithm>
#include <cmath>

#include "geometry/math_util.h"
#include "penetration/contact_qp.h"
#include "query/convex_pair.h"
#include "query/epa.h"

namespace sc::detail {
namespace {

/// Half-space rounds: a bounded call (touching) or one that gives way to the sweeps.
constexpr int kMaxRounds = 32;
constexpr int kUnboundedRounds = 8;
/// Rows (leaf pairs' exits) an unbounded call gathers before it gives way: shallow
/// overlaps of two 75k-triangle bunnies (0 to 2% deep) gather more than 256 and
/// resolve in some 3 ms, where the sweeps take some 30.
constexpr std::size_t kUnboundedRows = 2048;
constexpr std::size_t kNoRowLimit = ~std::size_t{0};
/// The sweeps' directions: a lattice, then tilts about the best down to this.
constexpr int kSweptDirections = 64;
constexpr double kFinestTilt = 0.01;
constexpr int kMaxTilts = 16;

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

/// Half-space rounds from `goal` (see the header). Free: `t` frees the target;
/// TooDeep: an exit deeper than `max_depth`; else no free pose within `rounds`.
enum class Rounds { Free, TooDeep, Unresolved };

Rounds halfSpaceRounds(GroupPairQuery& query, const Rigid& goal, double skin, double max_depth,
                       int rounds, std::size_t max_rows, ResolutionScratch& scratch, Vec3& t) {
  t = Vec3::Zero();
  for (int round = 0; round < rounds; ++round) {
    const Rigid pose{goal.rotation, goal.translation + t};
    query.contacts(pose, 0.0, scratch.contacts);
    const auto crossing = std::count_if(scratch.contacts.begin(), scratch.contacts.end(),
                                        [](const LeafContact& c) { return c.intersecting; });
    // A deep overlap of large meshes: thousands of exits per round, and rows that
    // conflict; the sweeps answer it for less.
    if (scratch.normals.size() + static_cast<std::size_t>(crossing) > max_rows)
      return Rounds::Unresolved;
    bool any = false;
    for (const LeafContact& c : scratch.contacts) {
      if (!c.intersecting) continue;
      any = true;
      const EpaResult e = leafExit(query, c, pose, scratch.depth);
      if (e.depth + e.normal.dot(t) > max_depth) return Rounds::TooDeep;  // its overlap at the goal
      // Row in the total translation: n . (t' - t) >= depth + skin.
      scratch.normals.push_back(e.normal);
      scratch.offsets.push_back(e.depth + skin + e.normal.dot(t));
    }
    if (!any) return Rounds::Free;
    t = smallestExit(scratch);
  }
  return Rounds::Unresolved;
}

/// Direction i of n about evenly spread on the unit sphere (a Fibonacci lattice).
Vec3 latticeDirection(int i, int n) {
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - (2.0 * i + 1.0) / n;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vec3(r * std::cos(golden * i), r * std::sin(golden * i), z);
}

/// Length of the free exit along unit u: the target swept in from beyond the opponent
/// along -u stops at its first contact, a gap within [skin/2, skin], so the pose there
/// is free whatever the shapes (the last exit along u; inf when none is found).
double exitAlong(GroupPairQuery& query, const Rigid& goal, const Vec3& u, double skin) {
  static const std::vector<LeafPair> none;
  const double far = query.clearingLength(goal, u, 2.0 * skin);
  const Rigid start{goal.rotation, goal.translation + far * u};
  const double s = query.translationToi(start, -far * u, skin, none);
  return s < 1.0 ? far * (1.0 - s) : kInfinity;
}

/// The shortest exit over `hint` and a lattice of directions, then refined
/// about the best by tilts that halve while they find nothing shorter.
Vec3 shortestSweptExit(GroupPairQuery& query, const Rigid& goal, double skin, const Vec3& hint) {
  double best = kInfinity;
  Vec3 best_u = Vec3::UnitZ();
  const auto consider = [&](const Vec3& v) {
    const double norm = v.norm();
    if (!(norm > 0.0)) return false;
    const Vec3 u = v / norm;
    const double length = exitAlong(query, goal, u, skin);
    if (!(length < best)) return false;
    best = length;
    best_u = u;
    return true;
  };
  consider(hint);
  for (int i = 0; i < kSweptDirections; ++i) consider(latticeDirection(i, kSweptDirections));
  int tilts = 0;
  for (double tilt = 0.25; tilt > kFinestTilt && tilts < kMaxTilts; tilt *= 0.5, ++tilts) {
    const Vec3 u = best_u, a = u.unitOrthogonal(), b = u.cross(a);
    const Vec3 sides[4] = {a, -a, b, -b};
    bool moved = false;
    for (const Vec3& side : sides) moved = consider(u + tilt * side) || moved;
    if (moved) tilt *= 2.0;  // same tilt again from the new best
  }
  return std::isfinite(best) ? Vec3(best * best_u) : Vec3(Vec3::Constant(kInfinity));
}

}  // namespace

bool resolveInitialIntersection(GroupPairQuery& query, const Rigid& goal,
                                const PairSettings& settings, Rigid& free_pose,
                                ResolutionScratch& scratch, double max_depth,
                                const LeafContact* first) {
  // The exit keeps a gap of half the tolerance, so the proxy starts clearly free.
  const double skin = 0.5 * settings.tolerance;
  scratch.normals.clear();
  scratch.offsets.clear();
  // Bounded: one intersecting pair deeper than the bound settles it before every
  // intersecting pair is gathered (thousands in a deep overlap of two large meshes).
  if (first != nullptr && leafExit(query, *first, goal, scratch.depth).depth > max_depth)
    return false;
  const bool bounded = std::isfinite(max_depth);
  Vec3 t;
  const Rounds r =
      halfSpaceRounds(query, goal, skin, max_depth, bounded ? kMaxRounds : kUnboundedRounds,
                      bounded ? kNoRowLimit : kUnboundedRows, scratch, t);
  if (r == Rounds::TooDeep || (r == Rounds::Unresolved && bounded)) return false;
  // Unresolved: the last round's t, which met the rows, hints at a way out.
  if (r == Rounds::Unresolved) t = shortestSweptExit(query, goal, skin, t);
  if (!allFinite(t)) return false;
  free_pose = {goal.rotation, goal.translation + t};
  return true;
}

}  // namespace sc::detail
