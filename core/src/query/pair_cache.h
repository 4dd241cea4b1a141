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
    if (sets_.empty()) resize(kInitialEntries);
    ++clock_;
    Set& set = sets_[setOf(key)];
    int victim = 0;
    for (int w = 0; w < kWays; ++w) {
      if (set.key[w] == key) {
        set.stamp[w] = clock_;
        return set.cache[w];
      }
      if (set.stamp[w] < set.stamp[victim]) victim = w;
    }
    if (set.key[victim] == kEmpty) {
      ++used_;
      if (4 * used_ > 3 * capacity() && capacity() < kMaxEntries) {
        resize(2 * capacity());
        return at(key);
      }
    }
    set.key[victim] = key;
    set.stamp[victim] = clock_;
    set.cache[victim] = SimplexCache();
    return set.cache[victim];
  }

  /// Starts loading the set of `key` (its keys and its warm starts) into the cache,
  /// ahead of at(key): the tables of many pairs outgrow the caches, and a lookup and
  /// the GJK it starts otherwise wait on memory.
  void prefetch(std::uint64_t key) const {
    if (sets_.empty()) return;
    const char* set = reinterpret_cast<const char*>(&sets_[setOf(key)]);
    for (std::size_t line = 0; line < sizeof(Set); line += 64) __builtin_prefetch(set + line);
  }

  void clear() {
    std::fill(sets_.begin(), sets_.end(), Set());
    used_ = 0;
  }

  std::size_t capacity() const { return sets_.size() * kWays; }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  static constexpr int kWays = 4;
  static constexpr std::size_t kInitialEntries = 64;

  /// One set, its keys and stamps in one cache line: a lookup reads that line and
  /// the warm start it returns (with an entry per line, a miss read four lines).
  struct alignas(64) Set {
    std::uint64_t key[kWays] = {kEmpty, kEmpty, kEmpty, kEmpty};
    std::uint64_t stamp[kWays] = {0, 0, 0, 0};  ///< last use; 0 = never (evicted first)
    SimplexCache cache[kWays];
  };

  std::size_t setOf(std::uint64_t key) const {
    // Fibonacci hashing: the high bits of key * 2^64 / phi.
    const std::uint64_t mixed = key * 0x9E3779B97F4A7C15ull;
    return static_cast<std::size_t>(mixed >> 32) & (sets_.size() - 1);
  }

  /// Re-inserts the held entries into a table of `size` entries (a power of two), in
  /// their old order, each over the least recently used way of its new set.
  void resize(std::size_t size) {
    std::vector<Set> old(size / kWays);
    old.swap(sets_);
    used_ = 0;
    for (const Set& from : old) {
      for (int w = 0; w < kWays; ++w) {
        if (from.key[w] == kEmpty) continue;
        Set& to = sets_[setOf(from.key[w])];
        int victim = 0;
        for (int v = 1; v < kWays; ++v)
          if (to.stamp[v] < to.stamp[victim]) victim = v;
        if (to.key[victim] == kEmpty) ++used_;
        to.key[victim] = from.key[w];
        to.stamp[victim] = from.stamp[w];
        to.cache[victim] = from.cache[w];
      }
    }
  }

  std::vector<Set> sets_;
  std::uint64_t clock_ = 0;
  std::size_t used_ = 0;
};

}  // namespace sc::detail
