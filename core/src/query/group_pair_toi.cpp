// SPDX-License-Identifier: MIT
// GroupPairQuery::translationToi: how far the target translates before a leaf pair
// blocks it, by conservative advancement on the pairs the hull hierarchies cannot
// rule out along the motion.
//
// The node pairs are taken earliest first: each carries a fraction of the motion
// before which its hulls stay more than skin apart (its entry), pushed on by the
// separating planes of GJK runs at it, one per turn. A pair is split, or its leaves
// advanced, only once no plane is open at its entry, and none is looked at whose
// entry is past the limit found so far: what lies along the motion beyond the first
// contact costs nothing. Planes found at one rotation serve the next sweeps at it
// (PlaneMemo): a slide's sweeps all run at its rotation.
#include <algorithm>
#include <utility>

#include "geometry/math_util.h"
#include "geometry/triangle_distance.h"
#include "query/group_pair_traversal.h"

namespace sc::detail {

namespace {

constexpr int kMaxAdvanceSteps = 64;
/// GJK runs that push a node pair's entry on before it is split regardless: a
/// pair creeping up on the skin (Zeno) goes to its children instead.
constexpr int kMaxNodeSteps = 8;

Rigid translated(const Rigid& x, const Vec3& delta) { return {x.rotation, x.translation + delta}; }

}  // namespace

struct GroupPairQuery::ToiPolicy {
  GroupPairQuery& q;
  const Vec3& delta;
  double reach_length;  ///< |delta|
  double skin;
  const std::vector<LeafPair>& skip;
  double limit = 1.0;

  // The pair's gap shrinks by at most limit * |delta| along the way; a pair that
  // starts within skin would block at once.
  bool prunes(double bound) const {
    return bound > skin && bound - limit * reach_length > 0.5 * skin;
  }
  /// The entry of a pair whose start distance is at least `bound`: its gap shrinks by
  /// at most |delta| per unit of the motion.
  double entryByBound(double bound) const {
    if (bound <= skin) return 0.0;
    return reach_length > 0.0 ? (bound - skin) / reach_length : kInfinity;
  }
  /// False when the pair's bounding spheres stay more than skin / 2 apart up to the
  /// limit: the target sphere's centre runs along a segment.
  bool sphereReaches(const NodePair& p) const {
    const HullBvhNode& t = q.t_slots_[p.t_slot].data->hierarchy.nodes[p.t_node];
    const Slot& os = q.o_slots_[p.o_slot];
    const HullBvhNode& o = os.data->hierarchy.nodes[p.o_node];
    const Vec3 c0 = q.o_from_piece_[p.t_slot] * t.center;
    const double swept =
        pointSegmentDistance(os.group_from_piece * o.center, c0, c0 + limit * delta) - t.radius -
        o.radius;
    return swept <= 0.5 * skin;
  }
  /// Pushes p's entry s on by its known planes, then by up to `steps` GJK runs at it.
  /// `closed` when no plane is open at the entry returned (p within skin there, or no
  /// hulls to run GJK on); kInfinity when p never comes within skin / 2 before the limit.
  double advance(NodePair& p, double s, int steps, bool& closed) {
    closed = false;
    if (!q.hullsOf(p)) {  // no hull, no plane: its children may have one
      closed = true;
      return s;
    }
    for (int k = 0; k < steps && s < limit; ++k) {
      s = knownPlanesReach(p, s);
      if (s >= limit) break;
      GjkSettings settings;  // beyond this it cannot come within skin / 2 in time
      settings.max_distance = (limit - s) * reach_length + 0.5 * skin;
      // Nor along a plane that keeps it beyond the skin, where no leaf pair's advance
      // (visit) would stop, while it moves by what is left of the motion.
      settings.motion = (limit - s) * delta;
      settings.motion_clearance = skin;
      const Rigid at = translated(q.o_from_piece_[p.t_slot], s * delta);
      const GjkResult r = q.nodeGjkAt(p, at, settings, q.cacheOf(p));
      if (r.status == GjkStatus::BeyondMaxDistance) return kInfinity;
      if (s == 0.0) {  // a bound at the start: the children's entries start from it
        p.bound = std::max(p.bound, r.status == GjkStatus::Intersecting ? 0.0 : r.lower_bound);
        p.refined = true;
      }
      const std::pair<double, double> open = openInterval(r, s);
      if (open.first > s) {
        closed = true;
        return s;
      }
      q.planes_.record(q.keyOf(p), at, r.normal, std::min(r.lower_bound, r.distance));
      s = open.second;
    }
    return s;
  }
  /// s pushed on by the planes found earlier at this rotation (PlaneMemo) open at it.
  double knownPlanesReach(const NodePair& p, double s) const {
    const Rigid& start = q.o_from_piece_[p.t_slot];
    const PlaneMemo::Plane* planes = nullptr;
    const int n = q.planes_.find(q.keyOf(p), start.rotation, planes);
    // n passes take the planes in any order.
    for (int pass = 0; pass < n && s < limit; ++pass) {
      for (int i = 0; i < n && s < limit; ++i) {
        const double gap = planes[i].offset + planes[i].normal.dot(start.translation);
        const double closing = -planes[i].normal.dot(delta);  // per unit of s, forwards
        const double at_s = gap - closing * s;
        if (at_s <= skin) continue;
        s = closing <= 0.0 ? kInfinity : s + (at_s - skin) / closing;
      }
    }
    return s;
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
  /// True for a leaf pair the caller skips (a contact it already holds).
  bool skipped(const NodePair& p) const {
    const Slot& ts = q.t_slots_[p.t_slot];
    const Slot& os = q.o_slots_[p.o_slot];
    const HullBvhNode& t = ts.data->hierarchy.nodes[p.t_node];
    const HullBvhNode& o = os.data->hierarchy.nodes[p.o_node];
    if (skip.empty() || !t.leaf() || !o.leaf()) return false;
    const LeafPair leaves{ts.first_leaf + t.polytope, os.first_leaf + o.polytope};
    return std::binary_search(skip.begin(), skip.end(), leaves);
  }
  /// Conservative advancement of a leaf pair, from the start (its stops, and so the
  /// answer, are those of every leaf pair's advancement); false when the limit
  /// reached 0.
  bool visit(const NodePair& p) {
    // The separating plane of the current closest points stays separating while the
    // target moves towards it by less than the gap.
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

void GroupPairQuery::sweep(ToiPolicy& policy) {
  std::vector<Timed>& heap = sweep_heap_;
  heap.clear();
  const auto later = [](const Timed& a, const Timed& b) { return a.when > b.when; };
  const auto push = [&](double when, int steps, const NodePair& pair) {
    heap.push_back({when, steps, pair});
    std::push_heap(heap.begin(), heap.end(), later);
  };
  // A child's hulls lie within its parent's: it enters no earlier.
  const auto offer = [&](double parent_when, const NodePair& pair) {
    if (policy.skipped(pair) || !policy.sphereReaches(pair)) return;
    const double when = std::max(parent_when, policy.entryByBound(pair.bound));
    if (when < policy.limit) push(when, 0, pair);
  };
  forEachRoot([&](const NodePair& root) { offer(0.0, root); });
  // Once the limit is at or before the earliest entry left, no pair left can lower it.
  while (!heap.empty() && heap.front().when < policy.limit) {
    std::pop_heap(heap.begin(), heap.end(), later);
    const Timed e = heap.back();
    heap.pop_back();
    NodePair p = e.pair;
    bool closed = false;
    const double when = policy.advance(p, e.when, 1, closed);
    if (!closed && e.steps + 1 < kMaxNodeSteps) {
      if (when < policy.limit) push(when, e.steps + 1, p);  // its turn comes later
      continue;
    }
    ++counters_.node_pairs;
    if (leavesOf(p)) {
      if (!policy.visit(p)) break;
      continue;
    }
    for (const NodePair& c : childrenOf(p)) offer(when, c);
  }
  heap.clear();
}

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
  ToiPolicy policy{*this, delta, reach_length, skin, skip, 1.0};
  // A pair that can block starts within this reach. When contactsNear()'s pairs hold
  // every pair within it, advance only those, nearest first; a pair whose gap (less
  // the translation since) rules it out is pruned as the traversal would.
  const double reach = std::max(skin, reach_length + 0.5 * skin);
  if (!near_.covers(o_from_t, reach)) {
    sweep(policy);
    return policy.limit;
  }
  near_.prepareBounds(o_from_t);
  for (std::size_t i = 0; i < near_.pairs().size(); ++i) {
    if (policy.prunes(near_.gapBound(i))) continue;
    const LeafContact& candidate = near_.pairs()[i];
    NodePair p = leafPair(candidate.t_leaf, candidate.o_leaf);
    if (policy.skipped(p) || !policy.sphereReaches(p)) continue;
    bool closed = false;
    if (policy.advance(p, 0.0, kMaxNodeSteps, closed) >= policy.limit) continue;
    if (!policy.visit(p)) break;
  }
  return policy.limit;
}

}  // namespace sc::detail
