// SPDX-License-Identifier: MIT
// GroupPairQuery::translationToi: how far the target translates before a leaf pair
// blocks it, by conservative advancement on the pairs the hull hierarchies cannot
// rule out along the motion.
#include <algorithm>
#include <utility>

#include "geometry/math_util.h"
#include "geometry/triangle_distance.h"
#include "query/group_pair_traversal.h"

namespace sc::detail {

namespace {

constexpr int kMaxAdvanceSteps = 64;

Rigid translated(const Rigid& x, const Vec3& delta) { return {x.rotation, x.translation + delta}; }

}  // namespace

struct GroupPairQuery::ToiPolicy {
  GroupPairQuery& q;
  const Vec3& delta;
  double reach_length;  ///< |delta|
  double skin;
  const std::vector<LeafPair>& skip;
  double limit = 1.0;
  SimplexCache scratch_;                ///< warm start of the planes sampled along the motion
  static constexpr int kMaxPlanes = 6;  ///< sampled per node pair, past the two ends

  // The pair's gap shrinks by at most limit * |delta| along the way; a pair that
  // starts within skin would block at once.
  bool prunes(double bound) const {
    return bound > skin && bound - limit * reach_length > 0.5 * skin;
  }
  double reach() const { return limit * reach_length + 0.5 * skin; }
  double splitWithin() const { return -1.0; }
  bool full() const { return false; }
  void pruned(const NodePair&) const {}
  /// May tighten p's bound with the GJK it runs (then marked refined, so the
  /// traversal does not run it again).
  bool admits(NodePair& p) {
    // Swept bounding spheres: the target sphere's centre runs along a segment.
    const HullBvhNode& t = q.t_slots_[p.t_slot].data->hierarchy.nodes[p.t_node];
    const Slot& os = q.o_slots_[p.o_slot];
    const HullBvhNode& o = os.data->hierarchy.nodes[p.o_node];
    const Vec3 c0 = q.o_from_piece_[p.t_slot] * t.center;
    const double swept =
        pointSegmentDistance(os.group_from_piece * o.center, c0, c0 + limit * delta) - t.radius -
        o.radius;
    if (swept > 0.5 * skin) return false;
    return !planesKeepApart(p);
  }
  /// True when the hulls stay more than skin apart up to `limit`, by separating
  /// planes: along the normal n of the plane at some point s of the motion they part
  /// at the rate n.delta, whatever the distance does, so that plane keeps them apart
  /// over an interval around s. The planes at the start and at `limit` go first, then
  /// planes in the middle of what is left uncovered, a few per pair. A motion along
  /// the contact (a jump sideways) prunes what the distance bound alone, assuming the
  /// worst direction, would keep.
  bool planesKeepApart(NodePair& p) {
    if (!q.hullsOf(p)) return false;  // no hull, no plane: its children may have one
    const GjkResult r = q.nodeGjk(p, reach(), -1.0);
    if (r.status == GjkStatus::BeyondMaxDistance) return true;
    p.bound = std::max(p.bound, r.status == GjkStatus::Intersecting ? 0.0 : r.lower_bound);
    p.refined = true;
    if (prunes(p.bound)) return true;
    const double s1 = openInterval(r, 0.0).second;
    if (s1 >= limit) return true;
    if (s1 < 0.0) return false;
    // Later planes start from the start's simplex; the pair's cache keeps that one.
    scratch_ = q.cacheOf(p);
    const double s0 = openInterval(sampleAt(p, limit), limit).first;
    return s0 <= limit && coverGap(p, s1, s0, kMaxPlanes);
  }
  /// True when planes sampled in (lo, hi) cover it, at most `planes` of them.
  bool coverGap(const NodePair& p, double lo, double hi, int planes) {
    if (lo >= hi) return true;
    if (planes <= 0) return false;
    const double mid = 0.5 * (lo + hi);
    const std::pair<double, double> open = openInterval(sampleAt(p, mid), mid);
    if (open.first > mid) return false;  // not open at mid
    const int left = (planes - 1) / 2;
    return coverGap(p, lo, open.first, left) && coverGap(p, open.second, hi, planes - 1 - left);
  }
  GjkResult sampleAt(const NodePair& p, double s) {
    const Rigid at = translated(q.o_from_piece_[p.t_slot], s * delta);
    return q.nodeGjkAt(p, at, GjkSettings(), scratch_);
  }
  /// Where along the motion the separating plane of `r`, found at s, stays more than
  /// skin open; an empty interval (first > s) when it is not open at s.
  std::pair<double, double> openInterval(const GjkResult& r, double s) const {
    if (r.status != GjkStatus::Separated || r.distance <= skin) return {kInfinity, -1.0};
    const double room = r.distance - skin;
    const double closing = -r.normal.dot(delta);  // per unit of s, forwards
    const double ahead = closing <= 0.0 ? kInfinity : room / closing;
    const double behind = closing >= 0.0 ? kInfinity : room / -closing;
    return {s - behind, s + ahead};
  }
  bool visit(const NodePair& p) {
    const Slot& ts = q.t_slots_[p.t_slot];
    const Slot& os = q.o_slots_[p.o_slot];
    const LeafPair leaves{ts.first_leaf + ts.data->hierarchy.nodes[p.t_node].polytope,
                          os.first_leaf + os.data->hierarchy.nodes[p.o_node].polytope};
    if (std::binary_search(skip.begin(), skip.end(), leaves)) return true;
    NodePair again = p;  // the limit may have shrunk since p was admitted
    if (!admits(again)) return true;
    // Conservative advancement: the separating plane of the current closest points
    // stays separating while the target moves towards it by less than the gap.
    const Rigid& start = q.o_from_piece_[p.t_slot];
    double s = 0.0;
    for (int step = 0; step < kMaxAdvanceSteps && s < limit; ++step) {
      bool beyond = false;
      const LeafContact c = q.evaluate(p, translated(start, s * delta), kInfinity, beyond);
      const double rate = -c.normal.dot(delta);
      // A pair starting within the skin blocks, unless it starts at skin / 2 or more
      // and the motion opens it: its separation along the normal then only grows.
      if (step == 0 && !c.intersecting && c.gap >= 0.5 * skin && rate <= 0.0) {
        s = limit;
        break;
      }
      if (c.intersecting || c.gap <= skin) break;
      if (rate <= 0.0) {
        s = limit;
        break;
      }
      s = std::min(limit, s + (c.gap - 0.5 * skin) / rate);
    }
    limit = std::min(limit, s);
    return limit > 0.0;
  }
};

double GroupPairQuery::translationToi(const Rigid& o_from_t, const Vec3& delta, double skin,
                                      const std::vector<LeafPair>& skip) {
  counters_ = TraversalCounters();
  const double reach_length = delta.norm();
  const double known = knownLowerBound(o_from_t);
  if (known > skin && known - reach_length > 0.5 * skin) {
    counters_.shortcut = true;
    return 1.0;
  }
  placeTargets(o_from_t);
  ToiPolicy policy{*this, delta, reach_length, skin, skip, 1.0, SimplexCache()};
  // A pair that can block starts within this reach. When contactsNear()'s pairs hold
  // every pair within it, advance only those, nearest first; a pair whose gap (less
  // the translation since) rules it out is pruned as the traversal would.
  const double reach = std::max(skin, reach_length + 0.5 * skin);
  if (!near_.covers(o_from_t, reach)) {
    traverse(policy);
    return policy.limit;
  }
  near_.prepareBounds(o_from_t);
  for (std::size_t i = 0; i < near_.pairs().size(); ++i) {
    if (policy.prunes(near_.gapBound(i))) continue;
    const LeafContact& candidate = near_.pairs()[i];
    if (!policy.visit(leafPair(candidate.t_leaf, candidate.o_leaf))) break;
  }
  return policy.limit;
}

}  // namespace sc::detail
