// SPDX-License-Identifier: MIT
// Two ids of the scene layer with lo < hi, in lexicographic order: the broadphase
// tree's leaf pairs (HandlePair) and the scene's group pairs (PairKey).
#pragma once

namespace sc::detail {

struct OrderedPair {
  int lo = 0;
  int hi = 0;
  bool operator<(const OrderedPair& o) const { return lo < o.lo || (lo == o.lo && hi < o.hi); }
  bool operator==(const OrderedPair& o) const { return lo == o.lo && hi == o.hi; }
};

}  // namespace sc::detail
