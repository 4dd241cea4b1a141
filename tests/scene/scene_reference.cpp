// SPDX-License-Identifier: MIT
// ReferenceScene: the scene manager written the obvious way (brute force over all
// pairs, maps everywhere), as the ground truth of the differential tests.
#include "scene_reference.h"

#include <algorithm>

namespace sc::test {

std::vector<int> ReferenceScene::objectIds() const {
  std::vector<int> ids;
  for (const auto& [id, o] : objects_) ids.push_back(id);
  return ids;
}

std::vector<int> ReferenceScene::groupIds() const {
  std::vector<int> ids;
  for (const auto& [gid, g] : groups_) {
    if (gid != kStaticGroup) ids.push_back(gid);
  }
  return ids;
}

Rigid ReferenceScene::worldFromModel(const Object& o) const {
  if (o.group == kStaticGroup) return o.own.worldFromLocal();
  return groups_.at(o.group).placement.worldFromLocal() * o.group_from_model;
}

Placement ReferenceScene::placementOf(const Object& o) const {
  if (o.group == kStaticGroup) return o.own;
  return Placement::fromRigid(worldFromModel(o), o.own.local_center);
}

void ReferenceScene::forgetPairsOf(int gid) {
  if (gid == kStaticGroup) return;
  for (auto& [key, tracker] : trackers_) {
    if (key.first == gid || key.second == gid) {
      tracker.forget(0);
      tracker.forget(1);
    }
  }
}

void ReferenceScene::dropGroup(int gid) {
  for (auto it = overrides_.begin(); it != overrides_.end();) {
    it = it->first.first == gid || it->first.second == gid ? overrides_.erase(it) : std::next(it);
  }
  for (auto it = trackers_.begin(); it != trackers_.end();) {
    it = it->first.first == gid || it->first.second == gid ? trackers_.erase(it) : std::next(it);
  }
  groups_.erase(gid);
}

void ReferenceScene::moveToGroup(int id, Object& o, int gid) {
  const Rigid world_from_model = worldFromModel(o);
  const Placement world = placementOf(o);
  Group& from = groups_.at(o.group);
  from.members.erase(std::find(from.members.begin(), from.members.end(), id));
  forgetPairsOf(o.group);
  if (o.group != kStaticGroup && from.members.empty()) dropGroup(o.group);
  o.group = gid;
  if (gid == kStaticGroup) {
    o.own = world;
    o.group_from_model = Rigid();
  } else {
    auto [it, created] = groups_.try_emplace(gid);
    if (created) it->second.placement = world;
    o.group_from_model = it->second.placement.worldFromLocal().inverse() * world_from_model;
  }
  groups_.at(gid).members.push_back(id);
  forgetPairsOf(gid);
}

bool ReferenceScene::addObject(int id, ModelPtr model, const Placement& placement) {
  if (!model || model->kind() != kind_ || objects_.count(id)) return false;
  Object o;
  o.model = std::move(model);
  o.own = placement;
  o.own.orientation.normalize();  // as setGroupPlacement
  objects_.emplace(id, std::move(o));
  groups_.at(kStaticGroup).members.push_back(id);
  return true;
}

bool ReferenceScene::deleteObject(int id) {
  const auto it = objects_.find(id);
  if (it == objects_.end()) return false;
  if (it->second.group != kStaticGroup) moveToGroup(id, it->second, kStaticGroup);
  auto& members = groups_.at(kStaticGroup).members;
  members.erase(std::find(members.begin(), members.end(), id));
  objects_.erase(it);
  return true;
}

bool ReferenceScene::addObjectToGroup(int gid, int id) {
  const auto it = objects_.find(id);
  if (gid < 0 || it == objects_.end()) return false;
  if (it->second.group != gid) moveToGroup(id, it->second, gid);
  return true;
}

bool ReferenceScene::removeObjectFromGroup(int gid, int id) {
  const auto it = objects_.find(id);
  if (it == objects_.end() || gid == kStaticGroup || it->second.group != gid) return false;
  moveToGroup(id, it->second, kStaticGroup);
  return true;
}

bool ReferenceScene::setGroupPlacement(int gid, const Placement& placement) {
  if (gid == kStaticGroup || !groups_.count(gid)) return false;
  Group& g = groups_.at(gid);
  g.placement = placement;
  g.placement.orientation.normalize();
  return true;
}

bool ReferenceScene::setObjectActivity(int id, Activity activity) {
  const auto it = objects_.find(id);
  if (it == objects_.end()) return false;
  if (activity != Activity::Active && activity != Activity::Inactive) return false;
  const bool active = activity == Activity::Active;
  if (it->second.active != active) {
    it->second.active = active;
    forgetPairsOf(it->second.group);
  }
  return true;
}

bool ReferenceScene::setGroupActivity(int gid, Activity activity) {
  if (gid == kStaticGroup || !groups_.count(gid)) return false;
  groups_.at(gid).activity = activity;
  // Passive: the directions with the group as target; Inactive: its pairs both ways.
  const bool inactive = activity == Activity::Inactive;
  if (activity == Activity::Passive || inactive) {
    for (auto& [key, tracker] : trackers_) {
      if (key.first == gid || (inactive && key.second == gid)) tracker.forget(0);
      if (key.second == gid || (inactive && key.first == gid)) tracker.forget(1);
    }
  }
  return true;
}

bool ReferenceScene::setPairActivity(int target, int opponent, PairActivity activity) {
  if (!groups_.count(target) || !groups_.count(opponent) || target == opponent) return false;
  const bool on = activity == PairActivity::Active || activity == PairActivity::OneWayActive;
  overrides_[{target, opponent}] = on;
  if (activity == PairActivity::Active || activity == PairActivity::Inactive)
    overrides_[{opponent, target}] = on;
  return true;
}

bool ReferenceScene::computes(int target, int opponent) const {
  const Group& t = groups_.at(target);
  const Group& o = groups_.at(opponent);
  if (t.parts.empty() || o.parts.empty()) return false;
  const auto it = overrides_.find({target, opponent});
  if (it != overrides_.end()) return it->second;
  return t.activity == Activity::Active && o.activity != Activity::Inactive;
}

bool ReferenceScene::withinRange(int g0, int g1) const {
  const Group& a = groups_.at(g0);
  if (g1 != kStaticGroup)
    return boxDistance(a.bounds, groups_.at(g1).bounds) <= settings_.max_distance;
  for (const Aabb& box : groups_.at(kStaticGroup).object_boxes) {
    if (boxDistance(a.bounds, box) <= settings_.max_distance) return true;
  }
  return false;
}

void ReferenceScene::rebuildGroups() {
  for (auto& [gid, g] : groups_) {
    g.parts.clear();
    g.bounds = Aabb();
    g.object_boxes.clear();
    const Rigid world_from_group = g.placement.worldFromLocal();
    for (int id : g.members) {
      const Object& o = objects_.at(id);
      if (!o.active || o.model->pieces().empty()) continue;
      Part part;
      part.model = o.model.get();
      part.group_from_model = gid == kStaticGroup ? o.own.worldFromLocal() : o.group_from_model;
      part.id = id;
      g.parts.push_back(part);
      if (gid == kStaticGroup)
        g.object_boxes.push_back(transformBox(o.model->bounds(), part.group_from_model));
      else
        g.bounds.extend(transformBox(o.model->bounds(), world_from_group * part.group_from_model));
    }
  }
}

void ReferenceScene::update() {
  rebuildGroups();
  pairs_.clear();
  std::vector<Key> seen;
  auto view = [this](int gid) {
    const Group& g = groups_.at(gid);
    GroupView v;
    v.parts = g.parts.data();
    v.part_count = static_cast<int>(g.parts.size());
    v.placement = g.placement;
    return v;
  };
  for (auto a = groups_.begin(); a != groups_.end(); ++a) {
    for (auto b = std::next(a); b != groups_.end(); ++b) {
      // Ids ascending; the static group (-1) comes first but is groups[1].
      const Key key = a->first == kStaticGroup ? Key(b->first, a->first) : Key(a->first, b->first);
      const Directions dirs{computes(key.first, key.second), computes(key.second, key.first)};
      if (!dirs.a_target && !dirs.b_target) continue;
      if (!withinRange(key.first, key.second)) continue;
      seen.push_back(key);
      PairTracker& tracker = trackers_[key];
      PairStatus status;
      status.groups[0] = key.first;
      status.groups[1] = key.second;
      tracker.update(view(key.first), view(key.second), dirs, settings_, status.results);
      if (!dirs.a_target && groups_.at(key.first).activity != Activity::Sleeping) tracker.forget(0);
      if (!dirs.b_target && groups_.at(key.second).activity != Activity::Sleeping) tracker.forget(1);
      pairs_.push_back(status);
    }
  }
  std::sort(seen.begin(), seen.end());
  for (auto it = trackers_.begin(); it != trackers_.end();) {
    if (!std::binary_search(seen.begin(), seen.end(), it->first)) {
      if (groups_.at(it->first.first).activity != Activity::Sleeping) it->second.forget(0);
      if (groups_.at(it->first.second).activity != Activity::Sleeping) it->second.forget(1);
      if (!it->second.tracking(0) && !it->second.tracking(1)) {
        it = trackers_.erase(it);
        continue;
      }
    }
    ++it;
  }
}

}  // namespace sc::test
