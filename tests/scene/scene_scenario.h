// SPDX-License-Identifier: MIT
// Shared scene builders: convex and non-convex models, a random scenario of
// operations (motion, activities, deletions, group changes) applied alike to
// several scenes, and a bit-for-bit comparison of their pair lists.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene_reference.h"
#include "smartcollision/scene.h"
#include "support/test_support.h"

namespace sc::test {

/// Axis-aligned box centred at the origin, outward winding.
MeshData sceneBoxMesh(const Vec3& half_extents);
/// An L-shaped prism of about `size` (non-convex, closed, outward winding).
MeshData lPrismMesh(double size);
/// One-piece model of a mesh; fails the test if the mesh is rejected.
ModelPtr modelOf(ModelKind kind, const MeshData& mesh);

struct ScenarioOptions {
  std::uint64_t seed = 1;
  ModelKind kind = ModelKind::ClosedPolyhedron;
  int groups = 100;         ///< moving groups to start with (the count then drifts)
  int statics = 10;         ///< static objects to start with
  double max_distance = 0.5;
  double density = 0.08;    ///< groups per unit volume (objects are about 1 across)
  bool infinite_distance = false;  ///< sometimes switch to +inf (small scenes only)
};

/// One operation on a scene, valid or not.
struct Op {
  enum class Kind {
    AddObject, DeleteObject, AddToGroup, RemoveFromGroup, MoveGroup,
    ObjectActivity, GroupActivity, PairActivity, MaxDistance,
  };
  Kind kind = Kind::MoveGroup;
  int id = 0;     ///< object id, or target group of PairActivity
  int gid = 0;    ///< group id, or opponent group of PairActivity
  ModelPtr model;
  Placement placement;
  Activity activity = Activity::Active;
  PairActivity pair = PairActivity::Active;
  double value = 0.0;
};

/// Generates the operations; picks their targets from the reference's state.
class Scenario {
 public:
  explicit Scenario(const ScenarioOptions& options);

  /// The operations that build the initial scene (objects, groups, static world).
  std::vector<Op> populate();
  /// One frame: a random-walk step of every moving group, and a few changes of
  /// activities, membership, objects and pair settings (some of them invalid).
  std::vector<Op> frame(const ReferenceScene& state);

 private:
  Placement randomPlacement();
  void addGroup(std::vector<Op>& ops, int gid);
  void change(std::vector<Op>& ops, const ReferenceScene& state);
  int pick(const std::vector<int>& ids) { return ids[rng_() % ids.size()]; }
  ModelPtr randomModel();

  ScenarioOptions options_;
  Rng rng_;
  double half_world_;
  std::vector<ModelPtr> convex_;
  std::vector<ModelPtr> non_convex_;
  int next_object_ = 0;
};

/// Applies an operation; true when it succeeded.
bool apply(Scene& scene, const Op& op);
bool apply(ReferenceScene& scene, const Op& op);

/// Empty when the lists are equal bit for bit (every field of every result);
/// otherwise where they first differ.
std::string firstDifference(const std::vector<PairStatus>& a, const std::vector<PairStatus>& b);

/// Counts of a pair list, to check a scenario is representative.
struct PairCounts {
  long pairs = 0;
  long with_static = 0;
  long apart = 0;
  long penetrating = 0;
  long initial_intersection = 0;
  long one_way = 0;  ///< one direction computed, the other NoResult
};
void count(const std::vector<PairStatus>& pairs, PairCounts& counts);

/// True in sanitizer and debug builds, where scenarios run fewer frames.
bool slowBuild();

}  // namespace sc::test
