// SPDX-License-Identifier: MIT
// Scene manager: objects, groups, activities, and the per-pair trackers.
// Pairs are enumerated by brute force over groups with an AABB test against the
// maximum distance; each listed pair runs its PairTracker.
#include "smartcollision/scene.h"

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include "geometry/math_util.h"
#include "scene/activity_table.h"

namespace sc {

namespace {

struct ObjectRec {
  ModelPtr model;
  Placement own;  ///< the object's placement while in the static group
  int group = kStaticGroup;
  Rigid group_from_model;  ///< constant while in a group
  bool active = true;
};

struct GroupRec {
  Placement placement;  ///< identity for the static group
  Activity activity = Activity::Active;
  std::vector<int> members;  ///< object ids in joining order
  std::vector<Part> parts;   ///< active members, rebuilt each update
  Aabb bounds;               ///< world frame, rebuilt each update
};

/// World AABB of a local AABB under a rigid transform.
Aabb transformBox(const Aabb& box, const Rigid& world_from_local) {
  if (box.empty()) return box;
  const Vec3 c = world_from_local * Vec3(0.5 * (box.min + box.max));
  const Vec3 e = world_from_local.rotation.cwiseAbs() * Vec3(0.5 * (box.max - box.min));
  Aabb out;
  out.min = c - e;
  out.max = c + e;
  return out;
}

double boxDistance(const Aabb& a, const Aabb& b) {
  const Vec3 gap = (a.min - b.max).cwiseMax(b.min - a.max).cwiseMax(Vec3::Zero());
  return gap.norm();
}

Status invalidId(const char* what) { return Status(ErrorCode::InvalidId, what); }

}  // namespace

struct Scene::Impl {
  ModelKind kind;
  SceneSettings settings;
  std::map<int, ObjectRec> objects;
  std::map<int, GroupRec> groups;  ///< includes the static group
  detail::PairOverrides overrides;
  std::map<std::pair<int, int>, PairTracker> trackers;  ///< key: (groups[0], groups[1])
  std::vector<PairStatus> pairs;

  explicit Impl(ModelKind k) : kind(k) { groups[kStaticGroup].activity = Activity::Passive; }

  Rigid worldFromModel(const ObjectRec& o) const {
    if (o.group == kStaticGroup) return o.own.worldFromLocal();
    return groups.at(o.group).placement.worldFromLocal() * o.group_from_model;
  }

  /// Tracking state is about the shape of a moving group: drop it when that changes.
  /// The static world changes often (obstacles come and go) and does not move, so
  /// its changes keep every state; a target then meeting a new object is pushed out
  /// from its proxy.
  void forgetPairsOf(int gid) {
    if (gid == kStaticGroup) return;
    for (auto& [key, tracker] : trackers) {
      if (key.first == gid || key.second == gid) {
        tracker.forget(0);
        tracker.forget(1);
      }
    }
  }

  void forgetAsTarget(int gid) {
    for (auto& [key, tracker] : trackers) {
      if (key.first == gid) tracker.forget(0);
      if (key.second == gid) tracker.forget(1);
    }
  }

  void moveToGroup(int id, ObjectRec& o, int gid) {
    const Rigid world_from_model = worldFromModel(o);
    const Placement world = placementOf(o);
    GroupRec& from = groups.at(o.group);
    from.members.erase(std::find(from.members.begin(), from.members.end(), id));
    forgetPairsOf(o.group);
    if (o.group != kStaticGroup && from.members.empty()) {
      overrides.dropGroup(o.group);
      dropTrackersOf(o.group);
      groups.erase(o.group);
    }
    o.group = gid;
    if (gid == kStaticGroup) {
      o.own = world;
      o.group_from_model = Rigid();
    } else {
      auto [it, created] = groups.try_emplace(gid);
      if (created) it->second.placement = world;  // the first object gives the frame
      o.group_from_model = it->second.placement.worldFromLocal().inverse() * world_from_model;
    }
    groups.at(gid).members.push_back(id);
    forgetPairsOf(gid);
  }

  void dropTrackersOf(int gid) {
    for (auto it = trackers.begin(); it != trackers.end();) {
      if (it->first.first == gid || it->first.second == gid)
        it = trackers.erase(it);
      else
        ++it;
    }
  }

  Placement placementOf(const ObjectRec& o) const {
    if (o.group == kStaticGroup) return o.own;
    const Rigid w = worldFromModel(o);
    Placement p;
    p.local_center = o.own.local_center;
    p.orientation = Quat(w.rotation).normalized();
    p.world_center = w * p.local_center;
    return p;
  }

  Activity activityOf(int gid) const { return groups.at(gid).activity; }

  bool computes(int target, int opponent) const {
    if (groups.at(target).parts.empty() || groups.at(opponent).parts.empty()) return false;
    const int o = overrides.get(target, opponent);
    if (o >= 0) return o == 1;
    return detail::tableComputes(activityOf(target), activityOf(opponent));
  }

  void rebuildGroupViews() {
    for (auto& [gid, g] : groups) {
      g.parts.clear();
      g.bounds = Aabb();
      const Rigid world_from_group = g.placement.worldFromLocal();
      for (int id : g.members) {
        const ObjectRec& o = objects.at(id);
        if (!o.active || o.model->pieces().empty()) continue;
        Part part;
        part.model = o.model.get();
        part.group_from_model = gid == kStaticGroup ? o.own.worldFromLocal() : o.group_from_model;
        part.id = id;
        g.parts.push_back(part);
        g.bounds.extend(transformBox(o.model->bounds(), world_from_group * part.group_from_model));
      }
    }
  }

  GroupView viewOf(int gid) const {
    const GroupRec& g = groups.at(gid);
    GroupView v;
    v.parts = g.parts.data();
    v.part_count = static_cast<int>(g.parts.size());
    v.placement = g.placement;
    return v;
  }

  void update() {
    rebuildGroupViews();
    pairs.clear();
    std::vector<std::pair<int, int>> seen;
    for (auto a = groups.begin(); a != groups.end(); ++a) {
      for (auto b = std::next(a); b != groups.end(); ++b) {
        // The static group (the smallest id) is never groups[0].
        const int g0 = b->first, g1 = a->first;
        const std::pair<int, int> key =
            g1 == kStaticGroup ? std::make_pair(g0, g1) : std::make_pair(g1, g0);
        updatePair(key, seen);
      }
    }
    std::sort(seen.begin(), seen.end());
    // Directions not computed keep their state only if their target sleeps.
    for (auto it = trackers.begin(); it != trackers.end();) {
      const bool listed = std::binary_search(seen.begin(), seen.end(), it->first);
      if (!listed) {
        for (int d = 0; d < 2; ++d) {
          const int target = d == 0 ? it->first.first : it->first.second;
          if (activityOf(target) != Activity::Sleeping) it->second.forget(d);
        }
        if (!it->second.tracking(0) && !it->second.tracking(1)) {
          it = trackers.erase(it);
          continue;
        }
      }
      ++it;
    }
  }

  void updatePair(const std::pair<int, int>& key, std::vector<std::pair<int, int>>& seen) {
    const auto [g0, g1] = key;
    Directions dirs{computes(g0, g1), computes(g1, g0)};
    if (!dirs.a_target && !dirs.b_target) return;
    if (boxDistance(groups.at(g0).bounds, groups.at(g1).bounds) > settings.max_distance) return;
    seen.push_back(key);
    PairTracker& tracker = trackers[key];
    PairStatus status;
    status.groups[0] = g0;
    status.groups[1] = g1;
    tracker.update(viewOf(g0), viewOf(g1), dirs, settings, status.results);
    for (int d = 0; d < 2; ++d) {
      const bool computed = d == 0 ? dirs.a_target : dirs.b_target;
      const int target = d == 0 ? g0 : g1;
      if (!computed && activityOf(target) != Activity::Sleeping) tracker.forget(d);
    }
    pairs.push_back(status);
  }
};

Scene::Scene(ModelKind kind) : impl_(std::make_unique<Impl>(kind)) {}
Scene::~Scene() = default;
ModelKind Scene::kind() const { return impl_->kind; }

Status Scene::addObject(int id, ModelPtr model, const Placement& placement) {
  if (!model) return Status(ErrorCode::InvalidArgument, "null model");
  if (model->kind() != impl_->kind)
    return Status(ErrorCode::InvalidOperation, "object type differs from the scene type");
  if (impl_->objects.count(id)) return invalidId("object id already in the scene");
  ObjectRec o;
  o.model = std::move(model);
  o.own = placement;
  impl_->objects.emplace(id, std::move(o));
  impl_->groups.at(kStaticGroup).members.push_back(id);
  return {};
}

Status Scene::deleteObject(int id) {
  const auto it = impl_->objects.find(id);
  if (it == impl_->objects.end()) return invalidId("unknown object id");
  if (it->second.group != kStaticGroup) impl_->moveToGroup(id, it->second, kStaticGroup);
  auto& members = impl_->groups.at(kStaticGroup).members;
  members.erase(std::find(members.begin(), members.end(), id));
  impl_->objects.erase(it);
  return {};
}

bool Scene::hasObject(int id) const { return impl_->objects.count(id) != 0; }

Result<Placement> Scene::objectPlacement(int id) const {
  const auto it = impl_->objects.find(id);
  if (it == impl_->objects.end()) return Status(invalidId("unknown object id"));
  return impl_->placementOf(it->second);
}

Result<int> Scene::groupOf(int id) const {
  const auto it = impl_->objects.find(id);
  if (it == impl_->objects.end()) return Status(invalidId("unknown object id"));
  return it->second.group;
}

Status Scene::addObjectToGroup(int gid, int id) {
  if (gid < 0) return Status(ErrorCode::InvalidArgument, "group ids are >= 0; the static group is implicit");
  const auto it = impl_->objects.find(id);
  if (it == impl_->objects.end()) return invalidId("unknown object id");
  if (it->second.group == gid) return {};
  impl_->moveToGroup(id, it->second, gid);
  return {};
}

Status Scene::removeObjectFromGroup(int gid, int id) {
  const auto it = impl_->objects.find(id);
  if (it == impl_->objects.end()) return invalidId("unknown object id");
  if (gid == kStaticGroup || it->second.group != gid) return invalidId("the object is not in that group");
  impl_->moveToGroup(id, it->second, kStaticGroup);
  return {};
}

bool Scene::hasGroup(int gid) const { return impl_->groups.count(gid) != 0; }

Result<Placement> Scene::groupPlacement(int gid) const {
  const auto it = impl_->groups.find(gid);
  if (it == impl_->groups.end()) return Status(invalidId("unknown group id"));
  return it->second.placement;
}

Status Scene::setGroupPlacement(int gid, const Placement& placement) {
  if (gid == kStaticGroup)
    return Status(ErrorCode::InvalidOperation, "the static group does not move");
  const auto it = impl_->groups.find(gid);
  if (it == impl_->groups.end()) return invalidId("unknown group id");
  if (!detail::allFinite(placement.world_center) || !detail::allFinite(placement.local_center) ||
      !detail::allFinite(placement.orientation.coeffs()) || placement.orientation.norm() < 0.5)
    return Status(ErrorCode::InvalidArgument, "non-finite placement");
  it->second.placement = placement;
  it->second.placement.orientation.normalize();
  return {};
}

Status Scene::setObjectActivity(int id, Activity activity) {
  const auto it = impl_->objects.find(id);
  if (it == impl_->objects.end()) return invalidId("unknown object id");
  if (activity != Activity::Active && activity != Activity::Inactive)
    return Status(ErrorCode::InvalidArgument, "an object is only active or inactive");
  const bool active = activity == Activity::Active;
  if (it->second.active != active) {
    it->second.active = active;
    impl_->forgetPairsOf(it->second.group);
  }
  return {};
}

Status Scene::setGroupActivity(int gid, Activity activity) {
  if (gid == kStaticGroup)
    return Status(ErrorCode::InvalidOperation, "the static group is always passive");
  const auto it = impl_->groups.find(gid);
  if (it == impl_->groups.end()) return invalidId("unknown group id");
  it->second.activity = activity;
  // A passive or inactive group keeps no collision status (manual 8.4): drop it now,
  // so that re-activating before the next update cannot resume it.
  if (activity == Activity::Passive || activity == Activity::Inactive) impl_->forgetAsTarget(gid);
  return {};
}

Status Scene::setPairActivity(int target_gid, int opponent_gid, PairActivity activity) {
  if (!hasGroup(target_gid) || !hasGroup(opponent_gid)) return invalidId("unknown group id");
  if (target_gid == opponent_gid)
    return Status(ErrorCode::InvalidArgument, "a pair needs two different groups");
  impl_->overrides.set(target_gid, opponent_gid, activity);
  return {};
}

const SceneSettings& Scene::settings() const { return impl_->settings; }

Status Scene::setSettings(const SceneSettings& settings) {
  Status s = validate(settings);
  if (s.ok()) impl_->settings = settings;
  return s;
}

Status Scene::update() {
  impl_->update();
  return {};
}

const std::vector<PairStatus>& Scene::pairs() const { return impl_->pairs; }

}  // namespace sc
