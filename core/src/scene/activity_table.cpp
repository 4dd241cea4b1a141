// SPDX-License-Identifier: MIT
#include "scene/activity_table.h"

namespace sc::detail {

bool tableComputes(Activity target, Activity opponent) {
  return target == Activity::Active && opponent != Activity::Inactive;
}

void PairOverrides::set(int g1, int g2, PairActivity activity) {
  switch (activity) {
    case PairActivity::Active:
    case PairActivity::Inactive: {
      const bool on = activity == PairActivity::Active;
      directions_[{g1, g2}] = on;
      directions_[{g2, g1}] = on;
      break;
    }
    case PairActivity::OneWayActive:
      directions_[{g1, g2}] = true;
      break;
    case PairActivity::OneWayInactive:
      directions_[{g1, g2}] = false;
      break;
  }
}

int PairOverrides::get(int target, int opponent) const {
  const auto it = directions_.find({target, opponent});
  return it == directions_.end() ? -1 : (it->second ? 1 : 0);
}

bool PairOverrides::computesAsTarget(int gid) const {
  for (auto it = directions_.lower_bound({gid, INT_MIN}); it != directions_.end() && it->first.first == gid;
       ++it) {
    if (it->second) return true;
  }
  return false;
}

void PairOverrides::dropGroup(int gid) {
  for (auto it = directions_.begin(); it != directions_.end();) {
    if (it->first.first == gid || it->first.second == gid)
      it = directions_.erase(it);
    else
      ++it;
  }
}

}  // namespace sc::detail
