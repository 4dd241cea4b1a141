// SPDX-License-Identifier: MIT
// PairTable: forgetting and dropping the pair state of one group.
#include "scene/pair_table.h"

#include <algorithm>

namespace sc::detail {

void PairTable::forgetGroup(int gid) {
  for (Entry& e : entries_) {
    if (e.key.lo == gid || e.key.hi == gid) {
      e.tracker.forget(0);
      e.tracker.forget(1);
    }
  }
}

void PairTable::forgetTarget(int gid) {
  for (Entry& e : entries_) {
    for (int d = 0; d < 2; ++d) {
      if (targetOf(e.key, d) == gid) e.tracker.forget(d);
    }
  }
}

void PairTable::dropGroup(int gid) {
  entries_.erase(std::remove_if(entries_.begin(), entries_.end(),
                                [gid](const Entry& e) { return e.key.lo == gid || e.key.hi == gid; }),
                 entries_.end());
}

}  // namespace sc::detail
