// SPDX-License-Identifier: MIT
// Which directions of a group pair are computed: manual Table 8-1 and the explicit
// pair settings of 8.4.
#pragma once

#include <climits>
#include <map>
#include <utility>

#include "smartcollision/types.h"

namespace sc::detail {

/// Table 8-1: is the direction "target -> opponent" computed for these activities?
/// Only an active target is computed, against an active, sleeping or passive opponent.
bool tableComputes(Activity target, Activity opponent);

/// Explicit per-direction settings that override Table 8-1.
class PairOverrides {
 public:
  /// Applies SetActivityPair(g1, g2, activity): two-way values set both directions,
  /// one-way values only g1 -> g2.
  void set(int g1, int g2, PairActivity activity);
  /// The override of target -> opponent, if any: 1 computed, 0 not, -1 none.
  int get(int target, int opponent) const;
  /// True when some override computes a direction with `gid` as target.
  bool computesAsTarget(int gid) const;
  /// Drops every setting that names `gid`.
  void dropGroup(int gid);

 private:
  std::map<std::pair<int, int>, bool> directions_;
};

}  // namespace sc::detail
