// SPDX-License-Identifier: MIT
// GroupPairQuery::contactsNear: contacts at poses that differ by small motions, from
// the pairs kept by one traversal with a margin (their state and the rule that drops
// it: near_pairs.h), rebuilt ahead of need a little per call.
#include <algorithm>
#include <cmath>

#include "query/group_pair_traversal.h"

namespace sc::detail {

namespace {
/// Kept pairs gathered for more than this many times the reach a call needs are
/// rebuilt, ahead of need, at that reach.
constexpr double kOversizedReach = 4.0;
/// A rebuild starts from the last one's front unless the target moved more than this
/// many times the rebuild's reach since: then the front's fine trail lies far from the
/// new contact, and the roots' GJK bounds prune more at once (a jump's first free
/// pose: 42 node pairs from the roots, 152 from the front).
constexpr double kFrontMoves = 8.0;
}  // namespace

double GroupPairQuery::nearCoveredReach(const Rigid& o_from_t) const {
  // The last distance bounds every pair from below: an answer is complete up to that
  // too (an empty one from contactsNear's shortcut, in particular).
  return std::max(near_.coveredReach(o_from_t), knownLowerBound(o_from_t));
}

void GroupPairQuery::contactsNear(const Rigid& o_from_t, double threshold, double margin,
                                  std::vector<LeafContact>& out) {
  // Every pair is farther than the threshold by the last distance, less the motion
  // since (a free proxy): nothing to gather, and no near pairs to keep or rebuild.
  if (knownLowerBound(o_from_t) > threshold) {
    out.clear();
    counters_ = TraversalCounters();
    counters_.shortcut = true;
    return;
  }
  // The same pose and threshold as the last call (a slide that did not move, then the
  // depth's projection at the same proxy): its answer, without the GJK calls.
  if (const std::vector<LeafContact>* memo = near_.memo(o_from_t, threshold)) {
    counters_ = TraversalCounters();
    out = *memo;
    return;
  }
  contactsNearUncached(o_from_t, threshold, margin, out);
  // The nearest pair seeds the next distance(): a proxy leaving contact measures its
  // distance next to where it touched, not where it was last seen apart.
  if (!out.empty()) seed_ = {out.front().t_leaf, out.front().o_leaf};
  near_.remember(o_from_t, threshold, out);
}

void GroupPairQuery::contactsNearUncached(const Rigid& o_from_t, double threshold, double margin,
                                          std::vector<LeafContact>& out) {
  out.clear();
  // The kept pairs no longer cover this pose: what is left of a rebuild started
  // ahead is cheaper than a new one, when that still covers it.
  const bool due = !near_.covers(o_from_t, threshold);
  near_.pending().approach = 0.0;  // paced by the kept pairs' cover from here
  near_.pending().receding = false;
  const TraversalCounters ahead = advancePendingNear(o_from_t, threshold, due);
  if (!near_.covers(o_from_t, threshold)) {
    // Nothing gathered ahead covers it: a rebuild here, run as far as this pose needs
    // and then on, a little per call, as one started ahead.
    startPendingNear(o_from_t, threshold + margin);
    counters_ = advancePendingNear(o_from_t, threshold, true);
    for (const LeafContact& c : near_.pairs())  // already sorted
      if (c.gap <= threshold) out.push_back(c);
    measureKept(o_from_t, threshold, out);
  } else {
    evaluateNear(o_from_t, threshold, out);
    // A third of the slack used: the next rebuild starts here, spread over the calls
    // while the rest lasts. So does one for a set gathered for a far larger reach than
    // the calls now ask (a long advancement's), whose every pair each call would scan.
    // A rebuild run ahead for such a reach (one that hit the cap, kMaxContacts, never
    // finishes) gives way to one at the reach needed.
    const double slack = near_.reach() - threshold;
    const double oversized = kOversizedReach * (threshold + margin);
    const NearPairs::Pending& pending = near_.pending();
    if ((!pending.active || pending.reach > oversized) &&
        (near_.reach() > oversized || displacementBound(near_.pose(), o_from_t) > slack / 3.0))
      startPendingNear(o_from_t, threshold + margin);
  }
  counters_.ahead_node_pairs = ahead.node_pairs;
  counters_.ahead_gjk = ahead.node_gjk + ahead.leaf_gjk;
  counters_.ahead_installed = ahead.ahead_installed;
}

void GroupPairQuery::rebuildNearAhead(const Rigid& o_from_t, double threshold, double margin,
                                      double gap) {
  if (near_.covers(o_from_t, threshold)) return;
  if (!near_.pendingCovers(o_from_t, threshold)) startPendingNear(o_from_t, threshold + margin);
  // Paced by the gap left: done by the first contact, not left to it.
  NearPairs::Pending& pending = near_.pending();
  pending.receding = pending.approach > 0.0 && gap > pending.approach;
  pending.approach = std::max(gap, 0.0);
  advancePendingNear(o_from_t, threshold, false);
}

bool GroupPairQuery::distanceNear(const Rigid& o_from_t, double max_distance, LeafContact& best,
                                  bool& found) {
  // The kept pairs hold every leaf pair within `covered` here, and a leaf's hull is
  // never farther than its triangles: the nearest kept pair, when within that, is the
  // distance (a proxy just out of contact), with no traversal.
  const double covered = near_.coveredReach(o_from_t);
  if (!(covered > 0.0)) return false;
  near_.prepareBounds(o_from_t);
  double bound = found ? std::min(best.gap, max_distance) : max_distance;
  // A pair whose hulls are closest on a virtual feature is not refined here, where
  // the bound may still be loose (refine()'s cost grows with it): its hulls' gap
  // bounds its faces' from below, and one nearer than the answer leaves it to the
  // traversal, which measures it in order.
  double deferred = kInfinity;
  for (std::size_t i = 0; i < near_.pairs().size(); ++i) {
    if (near_.gapBound(i) >= std::min(bound, covered)) continue;
    const LeafContact& kept = near_.pairs()[i];
    bool beyond = false;
    const LeafContact c =
        exactLeafDistance(leafPair(kept.t_leaf, kept.o_leaf), bound, beyond, true);
    if (beyond && !c.intersecting && c.gap < bound) deferred = std::min(deferred, c.gap);
    if (beyond || (found && c.gap >= best.gap)) continue;
    best = c;
    found = true;
    bound = std::min(c.gap, max_distance);
    if (c.intersecting) break;
  }
  return found && best.gap <= std::min(covered, deferred);
}

void GroupPairQuery::evaluateNear(const Rigid& o_from_t, double threshold,
                                  std::vector<LeafContact>& out) {
  counters_ = TraversalCounters();
  placeTargets(o_from_t);
  const int pose = near_.prepareBounds(o_from_t);
  for (std::size_t i = 0; i < near_.pairs().size(); ++i) {
    if (near_.gapBound(i) > threshold) continue;
    const LeafContact& candidate = near_.pairs()[i];
    const NodePair p = leafPair(candidate.t_leaf, candidate.o_leaf);
    bool beyond = false;
    // Evaluated up to the set's reach: an exact gap there keeps the pair pruned for
    // longer than the lower bound an early exit at the threshold would give.
    const LeafContact c =
        evaluate(p, o_from_piece_[p.t_slot], near_.reach(), beyond, &near_.cache(i));
    near_.measured(i, c.gap, pose);
    if (!beyond && c.gap <= threshold) out.push_back(c);
  }
  sortContacts(out);
}

void GroupPairQuery::measureKept(const Rigid& o_from_t, double threshold,
                                 std::vector<LeafContact>& out) {
  const auto unmeasured = [](const LeafContact& c) { return !c.measured; };
  if (std::none_of(out.begin(), out.end(), unmeasured)) return;
  placeTargets(o_from_t);
  const int pose = near_.prepareBounds(o_from_t);
  std::size_t kept = 0;
  for (const LeafContact& c : out) {
    LeafContact exact = c;
    if (!c.measured) {
      const int i = near_.find({c.t_leaf, c.o_leaf});  // out holds near_'s pairs
      const NodePair p = leafPair(c.t_leaf, c.o_leaf);
      bool beyond = false;
      exact = evaluate(p, o_from_piece_[p.t_slot], near_.reach(), beyond,
                       i >= 0 ? &near_.cache(static_cast<std::size_t>(i)) : nullptr);
      if (i >= 0) near_.measured(static_cast<std::size_t>(i), exact.gap, pose);
      if (beyond || exact.gap > threshold) continue;
    }
    out[kept++] = exact;
  }
  out.resize(kept);
  sortContacts(out);
}

bool GroupPairQuery::visitKept(const NodePair& p, const Rigid& pose, double reach,
                               std::vector<LeafContact>& out, NearFront* front) {
  const Slot& ts = t_slots_[p.t_slot];
  const Slot& os = o_slots_[p.o_slot];
  const int t_leaf = ts.first_leaf + ts.data->hierarchy.nodes[p.t_node].polytope;
  const int o_leaf = os.first_leaf + os.data->hierarchy.nodes[p.o_node].polytope;
  const int i = near_.find({t_leaf, o_leaf});
  if (i < 0) return false;
  // Its last gap less the motion since bounds it here: a pair beyond the reach by
  // that is pruned, one within it is kept with the bound, and measured only once a
  // call's threshold needs it (most stay farther than that while kept).
  const double bound = std::max(0.0, near_.gapBoundAt(static_cast<std::size_t>(i), pose));
  if (bound > reach) {
    NodePair far = p;
    far.bound = bound;
    if (front) front->record(far);
    return true;
  }
  LeafContact c = near_.pairs()[static_cast<std::size_t>(i)];
  c.gap = bound;
  c.measured = false;
  out.push_back(c);
  return true;
}

void GroupPairQuery::saveNearCaches() {
  // The kept pairs' warm starts are fresher than the rebuild's, which now measures
  // few of them: the next set starts from them.
  if (!near_.reuseInRebuilds()) return;
  for (std::size_t i = 0; i < near_.pairs().size(); ++i) {
    const LeafContact& c = near_.pairs()[i];
    cacheOf(leafPair(c.t_leaf, c.o_leaf)) = near_.cache(i);
  }
}

void GroupPairQuery::installNear(const Rigid& pose, double reach) {
  near_.install(pose, reach);
  for (const LeafContact& c : near_.pairs()) {
    const NodePair p = leafPair(c.t_leaf, c.o_leaf);
    const Slot& ts = t_slots_[p.t_slot];
    const HullBvhNode& node = ts.data->hierarchy.nodes[p.t_node];
    near_.keep(cacheOf(p), ts.group_from_piece * node.center, node.radius, c.gap);
  }
  near_.indexPairs();
}

void GroupPairQuery::startPendingNear(const Rigid& o_from_t, double reach) {
  frontFromPending();
  NearPairs::Pending& pending = near_.pending();
  pending.active = true;
  pending.pose = o_from_t;
  pending.reach = reach;
  pending.found.clear();
  pending.work = 0;
  pending.last_pose = o_from_t;
  // The traversal reads the placements from o_from_piece_: the pending ones are placed
  // there and lent back to it on every call.
  o_from_piece_.swap(pending.o_from_piece);
  placeTargets(o_from_t);
  ContactsPolicy policy{*this, reach, pending.found, &front_, keptAt(pending.pose)};
  seedPendingNear(policy, o_from_t, pending.heap);
  o_from_piece_.swap(pending.o_from_piece);
}

void GroupPairQuery::seedPendingNear(ContactsPolicy& policy, const Rigid& o_from_t,
                                     std::vector<NodePair>& heap) {
  const double moved = displacementBound(front_.pose(), o_from_t);
  if (!front_.serves() || moved > kFrontMoves * policy.threshold) {
    front_.begin(true);
    seedTraversal(policy, heap);
    return;
  }
  // Every entry's bound drops by the motion since the front's pose, and its spheres
  // at this pose bound it too: after a long move (a slide iteration, a jump) the
  // spheres prune the entries far from the new contact, which the motion alone would
  // all let through. Those that may now be within reach are taken again (node pairs
  // with a fresh GJK bound), the others stay in the front with the better bound.
  front_.begin(false);
  heap.clear();
  for (NodePair p : front_.pairs()) {
    p.bound = std::max(0.0, p.bound - moved);
    if (!policy.prunes(p.bound)) p.bound = std::max(p.bound, sphereBound(p));
    if (policy.prunes(p.bound)) {
      front_.record(p);
      continue;
    }
    p.refined = false;
    heap.push_back(p);
  }
  std::make_heap(heap.begin(), heap.end(), Farther());
}

void GroupPairQuery::frontFromPending() {
  // A rebuild given up or replaced before its end still partitions every leaf pair at
  // its pose: what it pruned (recorded), what is left in its queue and what it found.
  NearPairs::Pending& pending = near_.pending();
  if (!pending.active) return;
  for (const NodePair& p : pending.heap) front_.record(p);
  for (const LeafContact& c : pending.found) {
    NodePair p = leafPair(c.t_leaf, c.o_leaf);
    p.bound = c.gap;
    front_.record(p);
  }
  front_.finish(pending.pose);
}

TraversalCounters GroupPairQuery::advancePendingNear(const Rigid& o_from_t, double threshold,
                                                     bool finish) {
  NearPairs::Pending& pending = near_.pending();
  if (!pending.active) return {};
  if (!near_.pendingCovers(o_from_t, threshold)) {  // and never will again
    frontFromPending();
    near_.dropPending();
    return {};
  }
  const double need = displacementBound(pending.pose, o_from_t) + threshold;
  const int budget = finish ? -1 : near_.pendingBudget(o_from_t, threshold);
  // Due, it runs only as far as this pose and a few calls more need: the traversal
  // takes node pairs nearest first, so every leaf pair nearer than its queue's front
  // is among the pairs found (the pairs of a rebuild of that reach).
  const double until = finish ? need + 0.5 * (pending.reach - need) : kInfinity;
  pending.last_pose = o_from_t;
  const TraversalCounters saved = counters_;
  counters_ = TraversalCounters();
  o_from_piece_.swap(pending.o_from_piece);
  ContactsPolicy policy{*this, pending.reach, pending.found, &front_, keptAt(pending.pose)};
  const bool done = runTraversal(policy, pending.heap, budget, until);
  o_from_piece_.swap(pending.o_from_piece);
  const TraversalCounters work = counters_;
  counters_ = saved;
  pending.work += work.node_pairs;
  if (!done && !finish) return work;
  TraversalCounters installed = work;
  installed.ahead_installed = true;
  saveNearCaches();
  if (!done) {  // installed as far as it got; it goes on
    near_.mutablePairs() = pending.found;
    sortContacts(near_.mutablePairs());
    // A pair exactly at the front's bound may be still in the queue.
    installNear(pending.pose, std::nextafter(pending.heap.front().bound, 0.0));
    return installed;
  }
  sortContacts(pending.found);
  const Rigid pose = pending.pose;
  const double reach = pending.reach;
  for (const LeafContact& c : pending.found) {  // the rest of the front
    NodePair p = leafPair(c.t_leaf, c.o_leaf);
    p.bound = c.gap;
    front_.record(p);
  }
  front_.finish(pose);
  near_.finishPending();
  installNear(pose, reach);
  return installed;
}

}  // namespace sc::detail
