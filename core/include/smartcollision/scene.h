// SPDX-License-Identifier: MIT
// The scene manager of manual section 8: objects with ids, rigid groups, the
// static group, activities of objects, groups and group pairs (Table 8-1), and the
// per-pair results of UpdateStatus.
//
// Threads: distinct scenes may be used from distinct threads at once. One scene is
// used by one thread at a time, const calls included (pairs() reads what update()
// wrote); guard it with a mutex to share it. Models may be shared by any number of
// scenes and threads. update() may spread pairs over the scene's own workers
// (SceneSettings::threads) and returns when they are done; nothing runs on them
// after it returns. See docs/reliability.md, "Thread-safety contract".
//
// Bad input returns a non-Ok Status with a message and changes nothing.
#pragma once

#include <memory>
#include <vector>

#include "smartcollision/collision.h"

namespace sc {

/// The global static group: always passive, holds every object not in a group.
inline constexpr int kStaticGroup = -1;

/// One listed pair. results[i] has groups[i] as target. If one group is the static
/// group it is groups[1].
struct PairStatus {
  int groups[2] = {kStaticGroup, kStaticGroup};
  DirectedResult results[2];
  /// With SceneSettings::contact_points: PairTracker::contactPoints of each direction
  /// (threshold = the tolerance); empty otherwise.
  std::vector<ContactPoint> contacts[2];
};

class SC_API Scene {
 public:
  explicit Scene(ModelKind kind);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  ModelKind kind() const;

  // Objects. Ids are the caller's; an object starts in the static group, active.
  /// The placement's quaternion is normalised (InvalidArgument if zero or not finite),
  /// as by setGroupPlacement and sc.h's SetTransformation.
  Status addObject(int id, ModelPtr model, const Placement& placement);
  Status deleteObject(int id);
  bool hasObject(int id) const;
  /// The object's world placement (its r_LC kept; r_WC and q follow its group).
  Result<Placement> objectPlacement(int id) const;
  Result<int> groupOf(int id) const;

  // Groups. A group exists while it has objects; its frame is its first object's.
  /// An object in another group moves to `gid`: it stays where it is, its old group
  /// goes if it was its last object, and both groups' pairs lose their tracking
  /// state. Its own group again: nothing changes.
  Status addObjectToGroup(int gid, int id);
  /// The object stays where it is and returns to the static group.
  Status removeObjectFromGroup(int gid, int id);
  bool hasGroup(int gid) const;
  Result<Placement> groupPlacement(int gid) const;
  /// Moves the group along a path from its last placement: a pair the group passed
  /// through on the way keeps its penetration depth (the proxy stops at the first
  /// contact), however far the step. Quaternion normalised as by addObject.
  Status setGroupPlacement(int gid, const Placement& placement);
  /// Moves the group without a path: setGroupPlacement, then the tracking state of
  /// every pair of the group (both directions) is reset, so the next update measures
  /// each pair as first seen (apart: the distance; intersecting:
  /// InvalidInitialTransformation, or resolved if resolve_initial_intersection).
  /// In sc.h: SetActivityGroup(gid, INACTIVE), SetTransformation, then ACTIVE.
  Status teleportGroup(int gid, const Placement& placement);

  // Activities. Setting a group Passive drops the state of its directions as target,
  // Inactive that of every direction of its pairs.
  Status setObjectActivity(int id, Activity activity);  ///< Active or Inactive
  Status setGroupActivity(int gid, Activity activity);
  /// Overrides Table 8-1 for the pair; one-way values set only target_gid -> opponent_gid.
  Status setPairActivity(int target_gid, int opponent_gid, PairActivity activity);

  const SceneSettings& settings() const;
  /// InvalidArgument naming the field (settings kept) unless validate(settings) is Ok.
  Status setSettings(const SceneSettings& settings);

  /// Computes every listed pair for the current placements.
  Status update();
  /// The pairs of the last update, unchanged until the next one: a pair whose object
  /// or group was deleted since keeps its results (ids now unknown included).
  const std::vector<PairStatus>& pairs() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sc
