// SPDX-License-Identifier: MIT
// Scene builders: meshes, the random scenario and the bit-for-bit comparison.
#include "scene_scenario.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <sstream>

namespace sc::test {

MeshData sceneBoxMesh(const Vec3& h) {
  MeshData m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                            (i & 4) ? h.z() : -h.z());
  }
  m.triangles = {Tri(0, 2, 3), Tri(0, 3, 1), Tri(4, 5, 7), Tri(4, 7, 6),
                 Tri(0, 1, 5), Tri(0, 5, 4), Tri(2, 6, 7), Tri(2, 7, 3),
                 Tri(0, 4, 6), Tri(0, 6, 2), Tri(1, 3, 7), Tri(1, 7, 5)};
  return m;
}

MeshData lPrismMesh(double size) {
  // The L (counter-clockwise): a fan from corner 0 covers it, as it is star-shaped
  // about that corner.
  const double s = 0.5 * size;
  const double xy[6][2] = {{-s, -s}, {s, -s}, {s, 0}, {0, 0}, {0, s}, {-s, s}};
  const double hz = 0.25 * size;
  MeshData m;
  for (const auto& p : xy) m.vertices.emplace_back(p[0], p[1], -hz);
  for (const auto& p : xy) m.vertices.emplace_back(p[0], p[1], hz);
  for (int i = 1; i + 1 < 6; ++i) {
    m.triangles.emplace_back(0, i + 1, i);      // bottom, seen from below
    m.triangles.emplace_back(6, 6 + i, 7 + i);  // top
  }
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    m.triangles.emplace_back(i, j, 6 + j);
    m.triangles.emplace_back(i, 6 + j, 6 + i);
  }
  return m;
}

ModelPtr modelOf(ModelKind kind, const MeshData& mesh) {
  auto piece = buildPiece(kind, mesh);
  EXPECT_TRUE(piece.ok()) << piece.status().message();
  if (!piece.hasValue()) return nullptr;
  return std::make_shared<const Model>(kind, std::vector<PiecePtr>{piece.value()});
}

Scenario::Scenario(const ScenarioOptions& options)
    : options_(options),
      rng_(options.seed),
      half_world_(0.5 * std::cbrt(options.groups / options.density)) {
  for (int i = 0; i < 6; ++i) {
    const Vec3 h(uniform(rng_, 0.15, 0.5), uniform(rng_, 0.15, 0.5), uniform(rng_, 0.15, 0.5));
    convex_.push_back(modelOf(options.kind, sceneBoxMesh(h)));
  }
  non_convex_.push_back(modelOf(options.kind, lPrismMesh(1.0)));
  non_convex_.push_back(modelOf(options.kind, lPrismMesh(1.6)));
}

ModelPtr Scenario::randomModel() {
  if (uniform(rng_, 0, 1) < 0.05) return non_convex_[rng_() % non_convex_.size()];
  return convex_[rng_() % convex_.size()];
}

Placement Scenario::randomPlacement() {
  Placement p;
  const double w = half_world_;
  p.world_center = Vec3(uniform(rng_, -w, w), uniform(rng_, -w, w), uniform(rng_, -w, w));
  p.local_center = 0.2 * randomDirection(rng_);
  p.orientation = randomRotation(rng_);
  return p;
}

/// A new group `gid` of one to three objects close together.
void Scenario::addGroup(std::vector<Op>& ops, int gid) {
  const Placement at = randomPlacement();
  const int n = uniform(rng_, 0, 1) < 0.8 ? 1 : 2 + static_cast<int>(rng_() % 2);
  for (int k = 0; k < n; ++k) {
    Op add;
    add.kind = Op::Kind::AddObject;
    add.id = next_object_++;
    add.model = randomModel();
    add.placement = at;
    add.placement.world_center += 0.6 * k * randomDirection(rng_);
    add.placement.orientation = randomRotation(rng_);
    ops.push_back(add);
    Op join;
    join.kind = Op::Kind::AddToGroup;
    join.id = add.id;
    join.gid = gid;
    ops.push_back(join);
  }
}

std::vector<Op> Scenario::populate() {
  std::vector<Op> ops;
  for (int g = 0; g < options_.groups; ++g) addGroup(ops, 2 * g);  // odd ids come later
  for (int s = 0; s < options_.statics; ++s) {
    Op add;
    add.kind = Op::Kind::AddObject;
    add.id = next_object_++;
    add.model = randomModel();
    add.placement = randomPlacement();
    ops.push_back(add);
  }
  Op max_distance;
  max_distance.kind = Op::Kind::MaxDistance;
  max_distance.value = options_.max_distance;
  ops.push_back(max_distance);
  return ops;
}

std::vector<Op> Scenario::frame(const ReferenceScene& state) {
  std::vector<Op> ops;
  // Random walk; a group far out is pulled back towards the middle.
  for (int gid : state.groupIds()) {
    Op move;
    move.kind = Op::Kind::MoveGroup;
    move.gid = gid;
    move.placement = state.groupPlacement(gid);
    Vec3 step = 0.08 * randomDirection(rng_);
    if (move.placement.world_center.norm() > half_world_) step -= 0.05 * move.placement.world_center.normalized();
    move.placement.world_center += step;
    const Quat turn(Eigen::AngleAxisd(0.05, randomDirection(rng_)));
    move.placement.orientation = (turn * move.placement.orientation).normalized();
    ops.push_back(move);
  }
  const int changes = 1 + options_.groups / 40;
  for (int c = 0; c < changes; ++c) change(ops, state);
  return ops;
}

/// One random change. Targets are picked from the state before this frame's
/// changes, so some operations fail (deleted meanwhile), as do a few on purpose.
void Scenario::change(std::vector<Op>& ops, const ReferenceScene& state) {
  const std::vector<int> objects = state.objectIds();
  const std::vector<int> groups = state.groupIds();
  const double r = uniform(rng_, 0, 1);
  Op op;
  if (objects.empty() || groups.empty() || r < 0.14) {
    // A new group, or a new static object, or an object joining a group.
    if (uniform(rng_, 0, 1) < 0.5) {
      addGroup(ops, static_cast<int>(rng_() % (2 * options_.groups + 2)));
      return;
    }
    op.kind = Op::Kind::AddObject;
    op.id = next_object_++;
    op.model = randomModel();
    op.placement = randomPlacement();
  } else if (r < 0.28) {
    op.kind = Op::Kind::DeleteObject;
    op.id = pick(objects);
  } else if (r < 0.38) {
    op.kind = Op::Kind::AddToGroup;  // move to another group (merging) or a new one
    op.id = pick(objects);
    op.gid = uniform(rng_, 0, 1) < 0.7 ? pick(groups) : static_cast<int>(rng_() % (2 * options_.groups + 2));
  } else if (r < 0.46) {
    op.kind = Op::Kind::RemoveFromGroup;
    op.id = pick(objects);
    op.gid = state.groupOf(op.id);
    if (uniform(rng_, 0, 1) < 0.1) op.gid = pick(groups);  // mostly invalid
  } else if (r < 0.66) {
    op.kind = Op::Kind::GroupActivity;
    op.gid = uniform(rng_, 0, 1) < 0.05 ? kStaticGroup : pick(groups);
    const double a = uniform(rng_, 0, 1);
    op.activity = a < 0.45 ? Activity::Active
                  : a < 0.7 ? Activity::Sleeping
                  : a < 0.9 ? Activity::Passive
                            : Activity::Inactive;
  } else if (r < 0.78) {
    op.kind = Op::Kind::ObjectActivity;
    op.id = pick(objects);
    op.activity = uniform(rng_, 0, 1) < 0.6 ? Activity::Active : Activity::Inactive;
  } else if (r < 0.94) {
    op.kind = Op::Kind::PairActivity;
    op.id = uniform(rng_, 0, 1) < 0.1 ? kStaticGroup : pick(groups);
    op.gid = uniform(rng_, 0, 1) < 0.2 ? kStaticGroup : pick(groups);
    op.pair = static_cast<PairActivity>(rng_() % 4);
  } else if (r < 0.97) {
    op.kind = Op::Kind::MaxDistance;
    op.value = options_.infinite_distance && uniform(rng_, 0, 1) < 0.3
                   ? kInfinity
                   : options_.max_distance * uniform(rng_, 0.3, 2.0);
  } else {
    op.kind = Op::Kind::DeleteObject;  // unknown id: fails everywhere
    op.id = -1000 - static_cast<int>(rng_() % 100);
  }
  ops.push_back(op);
}

bool apply(Scene& scene, const Op& op) {
  switch (op.kind) {
    case Op::Kind::AddObject: return scene.addObject(op.id, op.model, op.placement).ok();
    case Op::Kind::DeleteObject: return scene.deleteObject(op.id).ok();
    case Op::Kind::AddToGroup: return scene.addObjectToGroup(op.gid, op.id).ok();
    case Op::Kind::RemoveFromGroup: return scene.removeObjectFromGroup(op.gid, op.id).ok();
    case Op::Kind::MoveGroup: return scene.setGroupPlacement(op.gid, op.placement).ok();
    case Op::Kind::ObjectActivity: return scene.setObjectActivity(op.id, op.activity).ok();
    case Op::Kind::GroupActivity: return scene.setGroupActivity(op.gid, op.activity).ok();
    case Op::Kind::PairActivity: return scene.setPairActivity(op.id, op.gid, op.pair).ok();
    case Op::Kind::MaxDistance: {
      SceneSettings s = scene.settings();
      s.max_distance = op.value;
      return scene.setSettings(s).ok();
    }
  }
  return false;
}

bool apply(ReferenceScene& scene, const Op& op) {
  switch (op.kind) {
    case Op::Kind::AddObject: return scene.addObject(op.id, op.model, op.placement);
    case Op::Kind::DeleteObject: return scene.deleteObject(op.id);
    case Op::Kind::AddToGroup: return scene.addObjectToGroup(op.gid, op.id);
    case Op::Kind::RemoveFromGroup: return scene.removeObjectFromGroup(op.gid, op.id);
    case Op::Kind::MoveGroup: return scene.setGroupPlacement(op.gid, op.placement);
    case Op::Kind::ObjectActivity: return scene.setObjectActivity(op.id, op.activity);
    case Op::Kind::GroupActivity: return scene.setGroupActivity(op.gid, op.activity);
    case Op::Kind::PairActivity: return scene.setPairActivity(op.id, op.gid, op.pair);
    case Op::Kind::MaxDistance: scene.setMaxDistance(op.value); return true;
  }
  return false;
}

namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool sameBits(const Vec3& a, const Vec3& b) {
  return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}

bool sameFeature(const Feature& a, const Feature& b) {
  return a.type == b.type && a.is_virtual == b.is_virtual && a.vertices[0] == b.vertices[0] &&
         a.vertices[1] == b.vertices[1] && a.vertices[2] == b.vertices[2];
}

/// Name of the first field that differs, or null.
const char* differingField(const DirectedResult& a, const DirectedResult& b) {
  if (a.code != b.code) return "code";
  if (a.target_object != b.target_object || a.opponent_object != b.opponent_object) return "object ids";
  if (a.target_piece != b.target_piece || a.opponent_piece != b.opponent_piece) return "piece ids";
  if (!sameBits(a.distance, b.distance)) return "distance";
  if (!sameBits(a.normal, b.normal)) return "normal";
  if (!sameBits(a.point_on_target, b.point_on_target)) return "point on target";
  if (!sameBits(a.point_on_opponent, b.point_on_opponent)) return "point on opponent";
  if (!sameFeature(a.target_feature, b.target_feature)) return "target feature";
  if (!sameFeature(a.opponent_feature, b.opponent_feature)) return "opponent feature";
  if (!sameBits(a.tpdv, b.tpdv)) return "tpdv";
  if (!sameBits(a.rpdv, b.rpdv)) return "rpdv";
  if (!sameBits(a.contact_position, b.contact_position)) return "contact position";
  if (!sameBits(a.contact_orientation.w(), b.contact_orientation.w()) ||
      !sameBits(a.contact_orientation.vec(), b.contact_orientation.vec()))
    return "contact orientation";
  return nullptr;
}

}  // namespace

std::string firstDifference(const std::vector<PairStatus>& a, const std::vector<PairStatus>& b) {
  std::ostringstream out;
  out.precision(17);
  for (size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
    if (a[k].groups[0] != b[k].groups[0] || a[k].groups[1] != b[k].groups[1]) {
      out << "pair " << k << ": groups (" << a[k].groups[0] << ", " << a[k].groups[1] << ") vs ("
          << b[k].groups[0] << ", " << b[k].groups[1] << ")";
      return out.str();
    }
    for (int d = 0; d < 2; ++d) {
      if (const char* field = differingField(a[k].results[d], b[k].results[d])) {
        out << "pair " << k << " (" << a[k].groups[0] << ", " << a[k].groups[1] << ") direction "
            << d << ": " << field << " (distance " << a[k].results[d].distance << " vs "
            << b[k].results[d].distance << ")";
        return out.str();
      }
    }
  }
  if (a.size() != b.size()) {
    out << "pair counts " << a.size() << " vs " << b.size();
    return out.str();
  }
  return {};
}

void count(const std::vector<PairStatus>& pairs, PairCounts& c) {
  for (const PairStatus& p : pairs) {
    ++c.pairs;
    if (p.groups[1] == kStaticGroup) ++c.with_static;
    const bool computed[2] = {p.results[0].code != ErrorCode::NoResult,
                              p.results[1].code != ErrorCode::NoResult};
    if (computed[0] != computed[1]) ++c.one_way;
    for (const DirectedResult& r : p.results) {
      if (r.code == ErrorCode::InvalidInitialTransformation) ++c.initial_intersection;
      if (r.code != ErrorCode::Ok) continue;
      ++(r.penetrating() ? c.penetrating : c.apart);
    }
  }
}

bool slowBuild() {
#if SC_TEST_SANITIZED || !defined(NDEBUG)
  return true;
#else
  return false;
#endif
}

}  // namespace sc::test
