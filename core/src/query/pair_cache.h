// SPDX-License-Identifier: MIT
// GJK warm starts keyed by node pair, in bounded memory: a 4-way set-associative
// table that evicts the least recently used entry of a set, grown by doubling up to
// a cap while the working set grows, so steady-state queries allocate nothing.
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "query/gjk.h"

namespace sc::detail {

class PairCache {
 public:
  /// Most entries ever held (64 bytes each).
  static constexpr std::size_t kMaxEntries = 8192;

  /// The warm start of `key` (default-constructed, i.e. cold, if not held); the
  /// reference is valid until the next call.
  SimplexCache& at(std::uint64_t key) {
    if (entries_.empty()) resize(kInitialEntries);
    ++clock_;
    Entry* set = &entries_[setOf(key) * kWays];
    Entry* victim = set;
    for (int w = 0; w < kWays; ++w) {
      if (set[w].key == key) {
        set[w].stamp = clock_;
        return set[w].cache;
      }
      if (set[w].stamp < victim->stamp) victim = &set[w];
    }
    if (victim->key == kEmpty) {
      ++used_;
      if (4 * used_ > 3 * entries_.size() && entries_.size() < kMaxEntries) {
        resize(2 * entries_.size());
        return at(key);
      }
    }
    *victim = Entry{key, clock_, SimplexCache()};
    return victim->cache;
  }

  void clear() {
    std::fill(entries_.begin(), entries_.end(), Entry());
    used_ = 0;
  }

  std::size_t capacity() const { return entries_.size(); }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  static constexpr int kWays = 4;
  static constexpr std::size_t kInitialEntries = 64;

  struct Entry {
    std::uint64_t key = kEmpty;
    std::uint64_t stamp = 0;  ///< last use; 0 = never (evicted first)
    SimplexCache cache;
  };

  std::size_t setOf(std::uint64_t key) const {
    // Fibonacci hashing: the high bits of key * 2^64 / phi.
    const std::uint64_t mixed = key * 0x9E3779B97F4A7C15ull;
    return static_cast<std::size_t>(mixed >> 32) & (entries_.size() / kWays - 1);
  }

  /// Re-inserts the held entries into a table of `size` (a power of two).
  void resize(std::size_t size) {
    std::vector<Entry> old(size);
    old.swap(entries_);
    used_ = 0;
    for (const Entry& e : old) {
      if (e.key == kEmpty) continue;
      Entry* set = &entries_[setOf(e.key) * kWays];
      Entry* victim = std::min_element(
          set, set + kWays, [](const Entry& a, const Entry& b) { return a.stamp < b.stamp; });
      if (victim->key == kEmpty) ++used_;
      *victim = e;
    }
  }

  std::vector<Entry> entries_;
  std::uint64_t clock_ = 0;
  std::size_t used_ = 0;
};

}  // namespace sc::detail
