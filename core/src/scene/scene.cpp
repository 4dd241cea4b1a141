// SPDX-License-Identifier: MIT
// Scene manager: objects, groups, activities, the broadphase over groups (a dynamic
// AABB tree, or brute force), the pair table kept across frames, and the parallel
// evaluation of the listed pairs into preassigned slots.
#include "smartcollision/scene.h"

#include <algorithm>
#include <map>
#include <thread>
#include <utility>
#include <vector>

#include "geometry/math_util.h"
#include "geometry/placement_check.h"
#include "scene/aabb_tree.h"
#include "scene/activity_table.h"
#include "scene/pair_table.h"
#include "scene/worker_pool.h"

namespace sc {

namespace {

using detail::PairKey;

/// Fewer listed pairs than this run on the calling thread: waking workers costs more.
constexpr int kMinParallelPairs = 16;

struct ObjectRec {
  int id = 0;
  ModelPtr model;
  Placement own;  ///< the object's placement while in the static group
  int group = kStaticGroup;
  Rigid group_from_model;  ///< constant while in a group
  bool active = true;
  Aabb static_box;  ///< world box while in the static group (it does not move there)
  int leaf = detail::DynamicAabbTree::kNull;  ///< its own tree leaf while static
};

struct GroupRec {
  int id = kStaticGroup;
  int slot = -1;  ///< index in Impl::slots, the tree leaves' user value
  Placement placement;  ///< identity for the static group
  Activity activity = Activity::Active;
  std::vector<ObjectRec*> members;  ///< in joining order
  std::vector<Part> parts;   ///< active members, rebuilt each update
  Aabb bounds;               ///< world frame, rebuilt each update (moving groups)
  bool seeker = false;  ///< may be a target of some pair (rebuilt each update)
  int leaf = detail::DynamicAabbTree::kNull;  ///< moving groups with parts only
};

bool takesPart(const ObjectRec& o) { return o.active && !o.model->pieces().empty(); }

Status invalidId(const char* what) { return Status(ErrorCode::InvalidId, what); }

/// A pair found by the broadphase: its key and its groups in listing roles.
struct Candidate {
  PairKey key;
  const GroupRec* first = nullptr;   ///< groups[0]
  const GroupRec* second = nullptr;  ///< groups[1]: the static group if in the pair
  bool operator<(const Candidate& o) const { return key < o.key; }
  bool operator==(const Candidate& o) const { return key == o.key; }
};

Candidate candidateOf(const GroupRec& a, const GroupRec& b) {
  Candidate c;
  c.key = detail::pairKeyOf(a.id, b.id);
  const bool a_first = b.id == kStaticGroup || (a.id != kStaticGroup && a.id < b.id);
  c.first = a_first ? &a : &b;
  c.second = a_first ? &b : &a;
  return c;
}

/// One listed pair to evaluate: its slot in the pair table and both groups.
struct Job {
  int entry = 0;
  const GroupRec* first = nullptr;
  const GroupRec* second = nullptr;
  Directions dirs;
};

GroupView viewOf(const GroupRec& g) {
  GroupView v;
  v.parts = g.parts.data();
  v.part_count = static_cast<int>(g.parts.size());
  v.placement = g.placement;
  return v;
}

}  // namespace

struct Scene::Impl {
  ModelKind kind;
  SceneSettings settings;
  std::map<int, ObjectRec> objects;
  std::map<int, GroupRec> groups;  ///< includes the static group
  std::vector<GroupRec*> slots;    ///< by GroupRec::slot; null when free
  std::vector<int> free_slots;
  detail::PairOverrides overrides;
  detail::DynamicAabbTree tree;  ///< group leaves and static object leaves (Tree mode)
  detail::PairTable table;
  detail::WorkerPool pool;
  std::vector<PairStatus> pairs;
  // Per-update buffers, capacity kept.
  std::vector<Candidate> candidates;
  std::vector<PairKey> listed;
  std::vector<int> entry_of;
  std::vector<Job> jobs;
  std::vector<const GroupRec*> moving;
  std::vector<const Aabb*> static_boxes;

  explicit Impl(ModelKind k) : kind(k) {
    GroupRec& s = groups[kStaticGroup];
    s.activity = Activity::Passive;
    takeSlot(s);
  }

  // ---- groups and objects ---------------------------------------------------

  void takeSlot(GroupRec& g) {
    if (free_slots.empty()) {
      g.slot = static_cast<int>(slots.size());
      slots.push_back(&g);
    } else {
      g.slot = free_slots.back();
      free_slots.pop_back();
      slots[g.slot] = &g;
    }
  }

  void eraseGroup(int gid) {
    GroupRec& g = groups.at(gid);
    if (g.leaf != detail::DynamicAabbTree::kNull) tree.remove(g.leaf);
    slots[g.slot] = nullptr;
    free_slots.push_back(g.slot);
    overrides.dropGroup(gid);
    table.dropGroup(gid);
    groups.erase(gid);
  }

  void dropStaticLeaf(ObjectRec& o) {
    if (o.leaf == detail::DynamicAabbTree::kNull) return;
    tree.remove(o.leaf);
    o.leaf = detail::DynamicAabbTree::kNull;
  }

  Rigid worldFromModel(const ObjectRec& o) const {
    if (o.group == kStaticGroup) return o.own.worldFromLocal();
    return groups.at(o.group).placement.worldFromLocal() * o.group_from_model;
  }

  /// Tracking state is about the shape of a moving group: drop it when that changes.
  /// The static world changes often (obstacles come and go) and does not move, so
  /// its changes keep every state; a target then meeting a new object is pushed out
  /// from its proxy.
  void forgetPairsOf(int gid) {
    if (gid != kStaticGroup) table.forgetGroup(gid);
  }

  void moveToGroup(ObjectRec& o, int gid) {
    const Rigid world_from_model = worldFromModel(o);
    const Placement world = placementOf(o);
    GroupRec& from = groups.at(o.group);
    from.members.erase(std::find(from.members.begin(), from.members.end(), &o));
    if (o.group == kStaticGroup) dropStaticLeaf(o);
    forgetPairsOf(o.group);
    if (o.group != kStaticGroup && from.members.empty()) eraseGroup(o.group);
    o.group = gid;
    if (gid == kStaticGroup) {
      o.own = world;
      o.group_from_model = Rigid();
      o.static_box = transformBox(o.model->bounds(), o.own.worldFromLocal());
    } else {
      auto [it, created] = groups.try_emplace(gid);
      if (created) {
        it->second.id = gid;
        it->second.placement = world;  // the first object gives the frame
        takeSlot(it->second);
      }
      o.group_from_model = it->second.placement.worldFromLocal().inverse() * world_from_model;
    }
    groups.at(gid).members.push_back(&o);
    forgetPairsOf(gid);
  }

  Placement placementOf(const ObjectRec& o) const {
    if (o.group == kStaticGroup) return o.own;
    return Placement::fromRigid(worldFromModel(o), o.own.local_center);
  }

  bool computes(const GroupRec& target, const GroupRec& opponent) const {
    if (target.parts.empty() || opponent.parts.empty()) return false;
    const int o = overrides.get(target.id, opponent.id);
    if (o >= 0) return o == 1;
    return detail::tableComputes(target.activity, opponent.activity);
  }

  // ---- per-update views and the tree ----------------------------------------

  bool useTree() const { return settings.broadphase == Broadphase::Tree; }

  /// Brute force keeps no tree; switching back rebuilds it leaf by leaf.
  void dropTree() {
    tree.clear();
    for (auto& [gid, g] : groups) {
      g.leaf = detail::DynamicAabbTree::kNull;
      for (ObjectRec* o : g.members) o->leaf = detail::DynamicAabbTree::kNull;
    }
  }

  void rebuildStatic(GroupRec& g) {
    const bool tree_on = useTree();
    for (ObjectRec* o : g.members) {
      const bool in = takesPart(*o);
      if (in) {
        Part part;
        part.model = o->model.get();
        part.group_from_model = o->own.worldFromLocal();
        part.id = o->id;
        g.parts.push_back(part);
        if (tree_on && o->leaf == detail::DynamicAabbTree::kNull)
          o->leaf = tree.insert(o->static_box, g.slot);
      } else {
        dropStaticLeaf(*o);
      }
    }
  }

  void rebuildMoving(GroupRec& g) {
    const Rigid world_from_group = g.placement.worldFromLocal();
    for (const ObjectRec* o : g.members) {
      if (!takesPart(*o)) continue;
      Part part;
      part.model = o->model.get();
      part.group_from_model = o->group_from_model;
      part.id = o->id;
      g.parts.push_back(part);
      g.bounds.extend(transformBox(o->model->bounds(), world_from_group * part.group_from_model));
    }
    if (!useTree()) return;
    if (g.parts.empty()) {
      if (g.leaf != detail::DynamicAabbTree::kNull) tree.remove(g.leaf);
      g.leaf = detail::DynamicAabbTree::kNull;
    } else if (g.leaf == detail::DynamicAabbTree::kNull) {
      g.leaf = tree.insert(g.bounds, g.slot);
    } else {
      tree.move(g.leaf, g.bounds);
    }
  }

  void rebuildGroupViews() {
    if (!useTree() && !tree.empty()) dropTree();
    for (auto& [gid, g] : groups) {
      g.parts.clear();
      g.bounds = Aabb();
      if (gid == kStaticGroup)
        rebuildStatic(g);
      else
        rebuildMoving(g);
      // A pair is listed only if one of its groups computes as target.
      g.seeker = !g.parts.empty() &&
                 (g.activity == Activity::Active || overrides.computesAsTarget(gid));
    }
  }

  // ---- broadphase -------------------------------------------------------------

  /// The leaf pairs of the tree within the maximum distance, as group pairs. Static
  /// objects are leaves of their own, so a large static world does not make every
  /// group a candidate; their pairs are all the pair (group, static).
  void treeCandidates() {
    const double max_distance = settings.max_distance;
    for (const detail::HandlePair& p : tree.pairs(max_distance)) {
      const GroupRec& a = *slots[tree.user(p.lo)];
      const GroupRec& b = *slots[tree.user(p.hi)];
      if (!a.seeker && !b.seeker) continue;
      if (boxDistance(tree.box(p.lo), tree.box(p.hi)) > max_distance) continue;
      candidates.push_back(candidateOf(a, b));
    }
  }

  /// The reference enumeration: every pair of groups, every static object.
  void bruteForceCandidates() {
    const double max_distance = settings.max_distance;
    moving.clear();
    static_boxes.clear();
    for (const auto& [gid, g] : groups) {
      if (g.parts.empty()) continue;
      if (gid != kStaticGroup) {
        moving.push_back(&g);
        continue;
      }
      for (const ObjectRec* o : g.members) {
        if (takesPart(*o)) static_boxes.push_back(&o->static_box);
      }
    }
    const GroupRec& world = groups.at(kStaticGroup);
    for (size_t i = 0; i < moving.size(); ++i) {
      const GroupRec& a = *moving[i];
      if (a.seeker || world.seeker) {
        for (const Aabb* s : static_boxes) {
          if (boxDistance(a.bounds, *s) <= max_distance) {
            candidates.push_back(candidateOf(a, world));
            break;
          }
        }
      }
      for (size_t j = i + 1; j < moving.size(); ++j) {
        const GroupRec& b = *moving[j];
        if ((a.seeker || b.seeker) && boxDistance(a.bounds, b.bounds) <= max_distance)
          candidates.push_back(candidateOf(a, b));
      }
    }
  }

  /// The listed pairs, sorted, and their jobs: candidates with at least one computed
  /// direction.
  void listPairs() {
    candidates.clear();
    if (useTree())
      treeCandidates();
    else
      bruteForceCandidates();
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    listed.clear();
    jobs.clear();
    for (const Candidate& c : candidates) {
      Job job;
      job.first = c.first;
      job.second = c.second;
      job.dirs = Directions{computes(*c.first, *c.second), computes(*c.second, *c.first)};
      if (!job.dirs.a_target && !job.dirs.b_target) continue;
      listed.push_back(c.key);
      jobs.push_back(job);
    }
  }

  // ---- evaluation -------------------------------------------------------------

  int threadCount() const {
    if (settings.threads > 0) return settings.threads;
    const int hardware = static_cast<int>(std::thread::hardware_concurrency());
    return std::clamp(hardware, 1, kMaxAutoThreads);
  }

  void evaluate(int k) {
    const Job& job = jobs[static_cast<size_t>(k)];
    PairTracker& tracker = table.entries()[static_cast<size_t>(job.entry)].tracker;
    PairStatus& status = pairs[static_cast<size_t>(k)];
    status.groups[0] = job.first->id;
    status.groups[1] = job.second->id;
    tracker.update(viewOf(*job.first), viewOf(*job.second), job.dirs, settings, status.results);
    for (int d = 0; d < 2; ++d) {
      if (settings.contact_points)
        tracker.contactPoints(d, settings.tolerance, status.contacts[d]);
      else
        status.contacts[d].clear();
    }
    // Directions not computed keep their state only if their target sleeps.
    if (!job.dirs.a_target && job.first->activity != Activity::Sleeping) tracker.forget(0);
    if (!job.dirs.b_target && job.second->activity != Activity::Sleeping) tracker.forget(1);
  }

  void update() {
    rebuildGroupViews();
    listPairs();
    table.sync(
        listed, [this](int gid) { return groups.at(gid).activity == Activity::Sleeping; },
        entry_of);
    for (size_t k = 0; k < jobs.size(); ++k) jobs[k].entry = entry_of[k];
    pairs.resize(jobs.size());
    const int n = static_cast<int>(jobs.size());
    const int threads = threadCount();
    if (threads > 1 && n >= kMinParallelPairs) {
      pool.resize(threads - 1);
      auto task = [this](int k) { evaluate(k); };
      pool.run(n, task);
    } else {
      for (int k = 0; k < n; ++k) evaluate(k);
    }
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
  const Result<Placement> unit = detail::usablePlacement(placement);
  if (!unit.ok()) return unit.status();
  ObjectRec o;
  o.id = id;
  o.model = std::move(model);
  o.own = unit.value();
  o.static_box = transformBox(o.model->bounds(), o.own.worldFromLocal());
  auto it = impl_->objects.emplace(id, std::move(o)).first;
  impl_->groups.at(kStaticGroup).members.push_back(&it->second);
  return {};
}

Status Scene::deleteObject(int id) {
  const auto it = impl_->objects.find(id);
  if (it == impl_->objects.end()) return invalidId("unknown object id");
  ObjectRec& o = it->second;
  if (o.group != kStaticGroup) impl_->moveToGroup(o, kStaticGroup);
  impl_->dropStaticLeaf(o);
  auto& members = impl_->groups.at(kStaticGroup).members;
  members.erase(std::find(members.begin(), members.end(), &o));
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
  impl_->moveToGroup(it->second, gid);
  return {};
}

Status Scene::removeObjectFromGroup(int gid, int id) {
  const auto it = impl_->objects.find(id);
  if (it == impl_->objects.end()) return invalidId("unknown object id");
  if (gid == kStaticGroup || it->second.group != gid) return invalidId("the object is not in that group");
  impl_->moveToGroup(it->second, kStaticGroup);
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
  const Result<Placement> unit = detail::usablePlacement(placement);
  if (!unit.ok()) return unit.status();
  it->second.placement = unit.value();
  return {};
}

Status Scene::teleportGroup(int gid, const Placement& placement) {
  if (Status s = setGroupPlacement(gid, placement); !s.ok()) return s;
  impl_->table.forgetGroup(gid);  // both directions of every pair: the path is cut
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
  if (activity != Activity::Active && activity != Activity::Sleeping &&
      activity != Activity::Passive && activity != Activity::Inactive)
    return Status(ErrorCode::InvalidArgument, "unknown group activity");
  it->second.activity = activity;
  // A passive or inactive group keeps no collision status (manual 8.4): drop it now,
  // so that re-activating before the next update cannot resume it. An inactive group
  // takes part in no pair (Table 8-1), as opponent either: its pairs are dropped both
  // ways, which makes INACTIVE then ACTIVE sc.h's teleport (Scene::teleportGroup).
  if (activity == Activity::Inactive)
    impl_->table.forgetGroup(gid);
  else if (activity == Activity::Passive)
    impl_->table.forgetTarget(gid);
  return {};
}

Status Scene::setPairActivity(int target_gid, int opponent_gid, PairActivity activity) {
  if (!hasGroup(target_gid) || !hasGroup(opponent_gid)) return invalidId("unknown group id");
  if (target_gid == opponent_gid)
    return Status(ErrorCode::InvalidArgument, "a pair needs two different groups");
  if (activity != PairActivity::Active && activity != PairActivity::Inactive &&
      activity != PairActivity::OneWayActive && activity != PairActivity::OneWayInactive)
    return Status(ErrorCode::InvalidArgument, "unknown pair activity");
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
