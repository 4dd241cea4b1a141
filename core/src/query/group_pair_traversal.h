// SPDX-License-Identifier: MIT
// The best-first traversal of two groups' hull hierarchies (group_pair_query.cpp's
// outline), shared by the group pair query's files, with the contacts policy.
#pragma once

#include <algorithm>
#include <vector>

#include "query/group_pair_query.h"

namespace sc::detail {

/// Heap order: the smallest bound on top.
struct Farther {
  template <class P>
  bool operator()(const P& a, const P& b) const {
    return a.bound > b.bound;
  }
};

/// Queues a node pair unless its bound prunes it (the policy is told) or the policy
/// vetoes it (`admits` may adjust the copy it queues).
template <class Policy, class Pair>
void offer(Policy& policy, std::vector<Pair>& heap, Pair pair) {
  if (policy.prunes(pair.bound)) {
    policy.pruned(pair);
    return;
  }
  if (!policy.admits(pair)) return;
  heap.push_back(pair);
  std::push_heap(heap.begin(), heap.end(), Farther());
}

// A policy says which bounds are pruned (`prunes`, monotone in the bound), how far
// GJK on a node pair needs to look (`reach`), may veto a child pair (`admits`),
// takes leaf pairs (`visit`, false to stop) and is told of each pair pruned by its
// bound (`pruned`: the front a rebuild of the near pairs leaves, near_front.h).
template <class Policy>
void GroupPairQuery::traverse(Policy& policy) {
  seedTraversal(policy, heap_);
  runTraversal(policy, heap_, -1);
}

template <class Policy>
void GroupPairQuery::seedTraversal(Policy& policy, std::vector<NodePair>& heap) {
  heap.clear();
  forEachRoot([&](const NodePair& root) { offer(policy, heap, root); });
}

template <class Policy>
bool GroupPairQuery::runTraversal(Policy& policy, std::vector<NodePair>& heap, int budget,
                                  double until) {
  for (int taken = 0; !heap.empty(); ++taken) {
    if (budget >= 0 && taken >= budget) return false;
    if (policy.full()) return false;  // the queue kept: its front bounds what is missing
    const double front = heap.front().bound;
    if (front >= until && !policy.prunes(front)) return false;
    std::pop_heap(heap.begin(), heap.end(), Farther());
    NodePair p = heap.back();
    heap.pop_back();
    if (policy.prunes(p.bound)) {  // every pair left is at least as far
      policy.pruned(p);
      for (const NodePair& left : heap) policy.pruned(left);
      break;
    }
    ++counters_.node_pairs;
    if (leavesOf(p)) {
      if (!policy.visit(p)) break;
      continue;
    }
    if (!p.refined) {
      p.bound = std::max(p.bound, nodeLowerBound(p, policy.reach(), policy.splitWithin()));
      p.refined = true;
      if (policy.prunes(p.bound)) {
        policy.pruned(p);
        continue;
      }
      if (!heap.empty() && p.bound > heap.front().bound) {
        heap.push_back(p);
        std::push_heap(heap.begin(), heap.end(), Farther());
        continue;
      }
    }
    for (const NodePair& c : childrenOf(p)) {
      caches_.prefetch(keyOf(c));  // its GJK's warm start, read when it is taken
      offer(policy, heap, c);
    }
  }
  heap.clear();
  return true;
}

struct GroupPairQuery::ContactsPolicy {
  GroupPairQuery& q;
  double threshold;
  std::vector<LeafContact>& out;
  NearFront* front = nullptr;  ///< a rebuild of the near pairs records its front here
  /// A rebuild of the near pairs at this pose: a leaf pair it already keeps is taken
  /// with its bound there, unmeasured (visitKept).
  const Rigid* kept_at = nullptr;

  bool prunes(double bound) const { return bound > threshold; }
  double reach() const { return threshold; }
  /// Every pair within the threshold is visited, in any order: a node pair known to
  /// be within it is split without its exact distance.
  double splitWithin() const { return threshold; }
  /// At kMaxContacts the traversal stops with its queue kept: what it found includes
  /// every pair nearer than the queue front's lower bound.
  bool full() const { return out.size() >= kMaxContacts; }
  bool admits(const NodePair&) const { return true; }
  void pruned(const NodePair& p) {
    if (front) front->record(p);
  }
  bool visit(const NodePair& p) {
    if (kept_at != nullptr && q.visitKept(p, *kept_at, threshold, out, front)) return true;
    bool beyond = false;
    const LeafContact c = q.evaluate(p, q.o_from_piece_[p.t_slot], threshold, beyond);
    if (!beyond && c.gap <= threshold) {
      out.push_back(c);
    } else if (front) {
      NodePair far = p;
      far.bound = c.gap;  // a lower bound when beyond
      front->record(far);
    }
    return true;
  }
};

/// Nearest first, ties by leaf indices: one order whatever found the contacts.
inline void sortContacts(std::vector<LeafContact>& contacts) {
  std::sort(contacts.begin(), contacts.end(), [](const LeafContact& a, const LeafContact& b) {
    if (a.gap != b.gap) return a.gap < b.gap;
    return LeafPair{a.t_leaf, a.o_leaf} < LeafPair{b.t_leaf, b.o_leaf};
  });
}

}  // namespace sc::detail
