// SPDX-License-Identifier: MIT
// The scene's pair state across frames: one PairTracker per group pair that is
// listed, or whose sleeping target still tracks it, kept sorted in listing order.
#pragma once

#include <vector>

#include "scene/ordered_pair.h"
#include "smartcollision/pair_tracker.h"
#include "smartcollision/scene.h"

namespace sc::detail {

/// An unordered group pair in listing order: lo < hi, so the static group (the
/// smallest id) is always lo.
using PairKey = OrderedPair;

inline PairKey pairKeyOf(int a, int b) { return a < b ? PairKey{a, b} : PairKey{b, a}; }

/// groups[0] and groups[1] of the listed pair: the static group is second.
inline int firstGroup(const PairKey& k) { return k.lo == kStaticGroup ? k.hi : k.lo; }
inline int secondGroup(const PairKey& k) { return k.lo == kStaticGroup ? k.lo : k.hi; }
/// The target of direction d (0: first group, 1: second group).
inline int targetOf(const PairKey& k, int d) { return d == 0 ? firstGroup(k) : secondGroup(k); }

class PairTable {
 public:
  struct Entry {
    PairKey key;
    PairTracker tracker;
  };

  /// Makes `listed` (sorted, unique) the listed pairs: each keeps its tracker or
  /// gets a new one, and slots[k] is the index in entries() of listed[k]. Every other
  /// entry forgets the directions whose target is not sleeping (`sleeping(gid)`), and
  /// is dropped when it tracks nothing. Allocates only for new pairs and growth.
  template <class Sleeping>
  void sync(const std::vector<PairKey>& listed, Sleeping&& sleeping, std::vector<int>& slots);

  std::vector<Entry>& entries() { return entries_; }
  const std::vector<Entry>& entries() const { return entries_; }

  /// Forgets both directions of every pair naming `gid` (its shape changed).
  void forgetGroup(int gid);
  /// Forgets the directions with `gid` as target.
  void forgetTarget(int gid);
  /// Drops every pair naming `gid` (the group is gone).
  void dropGroup(int gid);

 private:
  std::vector<Entry> entries_;
  std::vector<Entry> next_;  ///< double buffer of sync, capacity kept
};

template <class Sleeping>
void PairTable::sync(const std::vector<PairKey>& listed, Sleeping&& sleeping,
                     std::vector<int>& slots) {
  next_.clear();
  slots.clear();
  auto keepUnlisted = [&](Entry& e) {
    for (int d = 0; d < 2; ++d) {
      if (!sleeping(targetOf(e.key, d))) e.tracker.forget(d);
    }
    if (e.tracker.tracking(0) || e.tracker.tracking(1)) next_.push_back(std::move(e));
  };
  size_t i = 0;
  for (const PairKey& key : listed) {
    while (i < entries_.size() && entries_[i].key < key) keepUnlisted(entries_[i++]);
    slots.push_back(static_cast<int>(next_.size()));
    if (i < entries_.size() && entries_[i].key == key) {
      next_.push_back(std::move(entries_[i++]));
    } else {
      next_.push_back(Entry{key, PairTracker()});
    }
  }
  while (i < entries_.size()) keepUnlisted(entries_[i++]);
  entries_.swap(next_);
}

}  // namespace sc::detail
