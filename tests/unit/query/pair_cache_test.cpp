// SPDX-License-Identifier: MIT
// The GJK warm-start table: an entry written is read back, a full set evicts its
// least recently used entry, growth keeps what it held and stops at the cap.
#include "query/pair_cache.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace sc::detail {
namespace {

/// Marks the warm start of `key` with `key` itself (a count of 1, hint_a = key).
void mark(PairCache& cache, std::uint64_t key) {
  SimplexCache& c = cache.at(key);
  c.count = 1;
  c.hint_a = static_cast<int>(key);
}

bool held(PairCache& cache, std::uint64_t key) {
  const SimplexCache& c = cache.at(key);
  return c.count == 1 && c.hint_a == static_cast<int>(key);
}

TEST(PairCache, KeepsEntriesAndStaysBounded) {
  PairCache cache;
  cache.at(7).count = 3;
  EXPECT_EQ(cache.at(7).count, 3);
  EXPECT_EQ(cache.at(8).count, 0);
  for (std::uint64_t k = 0; k < 100000; ++k) cache.at(k * 7919).hint_a = static_cast<int>(k);
  EXPECT_LE(cache.capacity(), PairCache::kMaxEntries);
  // The most recent keys are still held.
  for (std::uint64_t k = 99990; k < 100000; ++k)
    EXPECT_EQ(cache.at(k * 7919).hint_a, static_cast<int>(k));
  cache.clear();
  EXPECT_EQ(cache.at(99999 * 7919).hint_a, 0);
}

TEST(PairCache, GrowsKeepingItsEntriesUpToTheCap) {
  PairCache cache;
  const std::uint64_t n = 3000;  // grows 64 -> 4096 entries on the way
  for (std::uint64_t k = 0; k < n; ++k) mark(cache, k);
  EXPECT_GE(cache.capacity(), 4 * n / 3);
  int kept = 0;
  for (std::uint64_t k = 0; k < n; ++k) kept += held(cache, k) ? 1 : 0;
  // Below three quarters of the capacity, a set overflows only by hashing's chance.
  EXPECT_GE(kept, static_cast<int>(0.95 * n));
  for (std::uint64_t k = n; k < 10 * PairCache::kMaxEntries; ++k) mark(cache, k);
  EXPECT_EQ(cache.capacity(), PairCache::kMaxEntries);
}

/// The set a key falls in at `capacity` entries (pair_cache.h: Fibonacci hashing over
/// sets of four).
std::uint64_t setOf(std::uint64_t key, std::size_t capacity) {
  return ((key * 0x9E3779B97F4A7C15ull) >> 32) & (capacity / 4 - 1);
}

TEST(PairCache, AFullSetEvictsItsLeastRecentlyUsedEntry) {
  PairCache cache;
  for (std::uint64_t k = 0; k < 4 * PairCache::kMaxEntries; ++k) mark(cache, k);
  ASSERT_EQ(cache.capacity(), PairCache::kMaxEntries);
  // Five new keys of one set: the four first take its ways (every older entry there
  // was used before them), the first is used again, and the fifth takes the place of
  // the one used least recently, the second.
  std::uint64_t keys[5];
  int found = 0;
  const std::uint64_t set = setOf(std::uint64_t{1} << 40, cache.capacity());
  for (std::uint64_t k = std::uint64_t{1} << 40; found < 5; ++k)
    if (setOf(k, cache.capacity()) == set) keys[found++] = k;
  for (int i = 0; i < 4; ++i) mark(cache, keys[i]);
  EXPECT_TRUE(held(cache, keys[0]));
  mark(cache, keys[4]);
  EXPECT_TRUE(held(cache, keys[4]));
  EXPECT_TRUE(held(cache, keys[3]));
  EXPECT_TRUE(held(cache, keys[2]));
  EXPECT_TRUE(held(cache, keys[0]));
  EXPECT_FALSE(held(cache, keys[1]));  // last: reading it inserts it again
}

}  // namespace
}  // namespace sc::detail
