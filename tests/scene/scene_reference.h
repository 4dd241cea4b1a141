// SPDX-License-Identifier: MIT
// The scene manager's behaviour as a plain brute-force model over the public
// PairTracker: every group pair, every static object, maps keyed by ids. The
// differential tests hold sc::Scene to it, result for result.
#pragma once

#include <map>
#include <utility>
#include <vector>

#include "smartcollision/scene.h"

namespace sc::test {

/// Same operations as sc::Scene (returning only whether they succeeded) and the
/// same documented rules: Table 8-1 and pair overrides, tracking state kept while
/// computed or while the target sleeps, the static group second, pairs in id order.
/// A moving group is bounded by one box; the static group by its objects' boxes.
class ReferenceScene {
 public:
  explicit ReferenceScene(ModelKind kind) : kind_(kind) {
    groups_[kStaticGroup].activity = Activity::Passive;
  }

  bool addObject(int id, ModelPtr model, const Placement& placement);
  bool deleteObject(int id);
  bool addObjectToGroup(int gid, int id);
  bool removeObjectFromGroup(int gid, int id);
  bool setGroupPlacement(int gid, const Placement& placement);
  bool setObjectActivity(int id, Activity activity);
  bool setGroupActivity(int gid, Activity activity);
  bool setPairActivity(int target_gid, int opponent_gid, PairActivity activity);
  void setMaxDistance(double d) { settings_.max_distance = d; }
  void update();
  const std::vector<PairStatus>& pairs() const { return pairs_; }

  // What a scenario needs to pick valid operations.
  std::vector<int> objectIds() const;
  std::vector<int> groupIds() const;  ///< moving groups only
  bool hasObject(int id) const { return objects_.count(id) != 0; }
  bool hasGroup(int gid) const { return groups_.count(gid) != 0; }
  int groupOf(int id) const { return objects_.at(id).group; }
  Placement groupPlacement(int gid) const { return groups_.at(gid).placement; }
  int trackerCount() const { return static_cast<int>(trackers_.size()); }

 private:
  struct Object {
    ModelPtr model;
    Placement own;
    int group = kStaticGroup;
    Rigid group_from_model;
    bool active = true;
  };
  struct Group {
    Placement placement;
    Activity activity = Activity::Active;
    std::vector<int> members;
    std::vector<Part> parts;
    Aabb bounds;
    std::vector<Aabb> object_boxes;  ///< static group: one per taking part object
  };
  using Key = std::pair<int, int>;  ///< (groups[0], groups[1]) of the pair

  Rigid worldFromModel(const Object& o) const;
  Placement placementOf(const Object& o) const;
  void moveToGroup(int id, Object& o, int gid);
  void forgetPairsOf(int gid);
  void dropGroup(int gid);
  bool computes(int target, int opponent) const;
  bool withinRange(int g0, int g1) const;
  void rebuildGroups();

  ModelKind kind_;
  SceneSettings settings_;
  std::map<int, Object> objects_;
  std::map<int, Group> groups_;
  std::map<Key, bool> overrides_;
  std::map<Key, PairTracker> trackers_;
  std::vector<PairStatus> pairs_;
};

}  // namespace sc::test
