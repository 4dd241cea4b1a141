// SPDX-License-Identifier: MIT
// SCSceneManager: the manual's scene API over sc::Scene. Holds no logic of its
// own beyond argument checks and the translation of enums and result layouts.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <initializer_list>
#include <limits>
#include <memory>

#include "api/error_codes.h"
#include "api/facade_impl.h"
#include "api/transformation_io.h"
#include "sc.h"

namespace {

using sc::detail::toScCode;

/// One sc.h enum value and the modern API's value it stands for.
template <class E>
struct EnumRow {
  SCenum sc_value;
  E value;
};

constexpr EnumRow<sc::Activity> kActivities[] = {
    {SC_ACTIVITY_ACTIVE, sc::Activity::Active},
    {SC_ACTIVITY_SLEEPING, sc::Activity::Sleeping},
    {SC_ACTIVITY_PASSIVE, sc::Activity::Passive},
    {SC_ACTIVITY_INACTIVE, sc::Activity::Inactive},
};
constexpr EnumRow<sc::PairActivity> kPairActivities[] = {
    {SC_ACTIVITY_ACTIVE, sc::PairActivity::Active},
    {SC_ACTIVITY_INACTIVE, sc::PairActivity::Inactive},
    {SC_ACTIVITY_ONE_WAY_ACTIVE, sc::PairActivity::OneWayActive},
    {SC_ACTIVITY_ONE_WAY_INACTIVE, sc::PairActivity::OneWayInactive},
};
constexpr EnumRow<sc::RotationMode> kRotationModes[] = {
    {SC_ROTATION_MODE_NONE, sc::RotationMode::None},
    {SC_ROTATION_MODE_INPUT, sc::RotationMode::Input},
    {SC_ROTATION_MODE_FREE, sc::RotationMode::Free},
    {SC_ROTATION_MODE_MIX, sc::RotationMode::Mix},
};

/// The value of sc.h's `v` in `rows`; false (and `out` unchanged) when it has none.
template <class E, size_t N>
bool fromSc(const EnumRow<E> (&rows)[N], SCenum v, E& out) {
  for (const EnumRow<E>& row : rows) {
    if (row.sc_value != v) continue;
    out = row.value;
    return true;
  }
  return false;
}

SCenum fromRotationMode(sc::RotationMode m) {
  for (const EnumRow<sc::RotationMode>& row : kRotationModes)
    if (row.value == m) return row.sc_value;
  return SC_ROTATION_MODE_INPUT;
}

/// The double-valued attribute field, or null if `attribute` is not one.
double* doubleField(sc::SceneSettings& s, SCenum attribute) {
  switch (attribute) {
    case SC_SCENE_MANAGER_MAX_DISTANCE: return &s.max_distance;
    case SC_SCENE_MANAGER_TOLERANCE: return &s.tolerance;
    case SC_SCENE_MANAGER_SAFETY_COEFFICIENT: return &s.safety_coefficient;
    case SC_SCENE_MANAGER_FORCE_STIFFNESS: return &s.force_stiffness;
    case SC_SCENE_MANAGER_TORQUE_STIFFNESS: return &s.torque_stiffness;
    case SC_SCENE_MANAGER_TELEPORT_DISTANCE: return &s.teleport_distance;
    case SC_SCENE_MANAGER_PROXY_TRAVEL_RATIO:
      return &s.proxy_travel_ratio;
    default: return nullptr;
  }
}

/// The integer-valued attribute field, or null if `attribute` is not one.
int* intField(sc::SceneSettings& s, SCenum attribute) {
  switch (attribute) {
    case SC_SCENE_MANAGER_MAX_ITERATION: return &s.max_iterations;
    case SC_SCENE_MANAGER_THREADS: return &s.threads;
    default: return nullptr;
  }
}

/// The on/off attribute field (integer 0 or 1 in sc.h), or null if `attribute` is not one.
bool* boolField(sc::SceneSettings& s, SCenum attribute) {
  switch (attribute) {
    case SC_SCENE_MANAGER_RESOLVE_INITIAL_INTERSECTION: return &s.resolve_initial_intersection;
    case SC_SCENE_MANAGER_CONTACT_POINTS: return &s.contact_points;
    default: return nullptr;
  }
}

SCenum featureType(sc::FeatureType t) {
  switch (t) {
    case sc::FeatureType::Vertex: return SC_FEATURE_VERTEX;
    case sc::FeatureType::Edge: return SC_FEATURE_EDGE;
    case sc::FeatureType::Face: return SC_FEATURE_FACE;
  }
  return SC_FEATURE_VERTEX;
}

/// True when every value converts to Real without overflow. A double beyond float's
/// range is refused rather than written as inf (the conversion is undefined), as
/// GetTransformation does.
template <class Real>
bool fits(const double* v, int n) {
  for (int i = 0; i < n; ++i) {
    if (!(std::abs(v[i]) <= static_cast<double>(std::numeric_limits<Real>::max()))) return false;
  }
  return true;
}

/// Writes `n` values if all fit in Real; SC_ERROR_INVALID_ARGUMENT (nothing written)
/// otherwise.
template <class Real>
SCint writeChecked(const double* v, int n, Real* out) {
  if (!fits<Real>(v, n)) return SC_ERROR_INVALID_ARGUMENT;
  for (int i = 0; i < n; ++i) out[i] = static_cast<Real>(v[i]);
  return SC_NO_ERROR;
}

int put(const sc::Vec3& v, double* out) {
  for (int i = 0; i < 3; ++i) out[i] = v[i];
  return 3;
}

SCint directionStatus(sc::DirectionStatus s) {
  switch (s) {
    case sc::DirectionStatus::BeyondMaxDistance: return SC_DIRECTION_BEYOND_MAX_DISTANCE;
    case sc::DirectionStatus::FirstSeenIntersecting: return SC_DIRECTION_FIRST_SEEN_INTERSECTING;
    case sc::DirectionStatus::Separated: return SC_DIRECTION_SEPARATED;
    case sc::DirectionStatus::Touching: return SC_DIRECTION_TOUCHING;
    case sc::DirectionStatus::Penetrating: return SC_DIRECTION_PENETRATING;
    case sc::DirectionStatus::Lagging: return SC_DIRECTION_LAGGING;
    case sc::DirectionStatus::NotComputed: break;
  }
  return SC_DIRECTION_NOT_COMPUTED;
}

bool isOneOf(SCenum type, std::initializer_list<SCenum> types) {
  return std::find(types.begin(), types.end(), type) != types.end();
}

/// GetStatus for the integer-valued types.
SCint intStatus(const sc::PairStatus& pair, int d, SCenum type, SCint* out) {
  const sc::DirectedResult& r = pair.results[d];
  switch (type) {
    case SC_STATUS_RESULT:
      out[0] = toScCode(r.code);
      return SC_NO_ERROR;
    case SC_GROUP_ID:
      out[0] = pair.groups[d];
      out[1] = pair.groups[1 - d];
      return SC_NO_ERROR;
    case SC_CONTACT_POINT_COUNT:
      out[0] = static_cast<SCint>(pair.contacts[d].size());
      return SC_NO_ERROR;
    case SC_DIRECTION_STATUS:
      out[0] = directionStatus(r.status);
      return SC_NO_ERROR;
    default:
      if (!isOneOf(type, {SC_OBJECT_ID, SC_PIECE_ID, SC_FEATURE_TYPE, SC_FEATURE_ON_TARGET,
                          SC_FEATURE_ON_OPPONENT}))
        return SC_ERROR_INVALID_ARGUMENT;
  }
  if (r.code != sc::ErrorCode::Ok) return toScCode(r.code);
  switch (type) {
    case SC_OBJECT_ID:
      out[0] = r.target_object;
      out[1] = r.opponent_object;
      break;
    case SC_PIECE_ID:
      out[0] = r.target_piece;
      out[1] = r.opponent_piece;
      break;
    case SC_FEATURE_TYPE:
      out[0] = featureType(r.target_feature.type);
      out[1] = featureType(r.opponent_feature.type);
      break;
    default: {
      const sc::Feature& f = type == SC_FEATURE_ON_TARGET ? r.target_feature : r.opponent_feature;
      for (int i = 0; i < 3; ++i) out[i] = f.vertices[i];
    }
  }
  return SC_NO_ERROR;
}

/// The 10 reals of one contact of SC_CONTACT_POINTS.
void contactReals(const sc::ContactPoint& p, double* v) {
  put(p.point_on_target, v);
  put(p.point_on_opponent, v + 3);
  put(p.normal, v + 6);
  v[9] = p.separation;
}

/// SC_CONTACT_POINTS: 10 reals per contact; all checked before any is written.
template <class Real>
SCint contactPointsStatus(const std::vector<sc::ContactPoint>& points, Real* out) {
  double v[10];
  for (const sc::ContactPoint& p : points) {
    contactReals(p, v);
    if (!fits<Real>(v, 10)) return SC_ERROR_INVALID_ARGUMENT;
  }
  for (const sc::ContactPoint& p : points) {
    contactReals(p, v);
    writeChecked(v, 10, out);
    out += 10;
  }
  return SC_NO_ERROR;
}

/// GetStatus for the real-valued types.
template <class Real>
SCint realStatus(const sc::PairStatus& pair, int d, SCenum type, Real* out) {
  const sc::DirectedResult& r = pair.results[d];
  if (type == SC_CONTACT_POINTS) return contactPointsStatus(pair.contacts[d], out);
  if (!isOneOf(type, {SC_DISTANCE, SC_CONTACT_NORMAL, SC_POINT_ON_TARGET, SC_POINT_ON_OPPONENT,
                      SC_TPD_VECTOR, SC_RPD_VECTOR, SC_CONTACT_POSITION, SC_CONTACT_ORIENTATION}))
    return SC_ERROR_INVALID_ARGUMENT;
  if (r.code != sc::ErrorCode::Ok) return toScCode(r.code);
  double v[4];
  int n = 0;
  switch (type) {
    case SC_DISTANCE: v[n++] = r.distance; break;
    case SC_CONTACT_NORMAL: n = put(r.normal, v); break;
    case SC_POINT_ON_TARGET: n = put(r.point_on_target, v); break;
    case SC_POINT_ON_OPPONENT: n = put(r.point_on_opponent, v); break;
    case SC_TPD_VECTOR: n = put(r.tpdv, v); break;
    case SC_RPD_VECTOR: n = put(r.rpdv, v); break;
    case SC_CONTACT_POSITION: n = put(r.contact_position, v); break;
    default:
      v[0] = r.contact_orientation.w();
      v[1] = r.contact_orientation.x();
      v[2] = r.contact_orientation.y();
      v[3] = r.contact_orientation.z();
      n = 4;
  }
  return writeChecked(v, n, out);
}

}  // namespace

SCSceneManager::SCSceneManager(SCenum type)
    : impl_(std::make_unique<Impl>(type == SC_SCENE_MANAGER_TRIANGLE_SOUP
                                       ? sc::ModelKind::TriangleSoup
                                       : sc::ModelKind::ClosedPolyhedron,
                                   type == SC_SCENE_MANAGER_TRIANGLE_SOUP ||
                                       type == SC_SCENE_MANAGER_CLOSED_POLYHEDRA)) {}

SCSceneManager::~SCSceneManager() {
  for (auto& [id, object] : impl_->objects) {
    object->impl_->placement = object->currentPlacement();  // kept, as in DeleteObject
    object->impl_->scene = nullptr;
  }
}

SCint SCSceneManager::AddObject(SCint id, SCObject* object) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  if (object == nullptr) return SC_ERROR_INVALID_ARGUMENT;
  SCObject::Impl& o = *object->impl_;
  if (!o.known_type || o.kind != impl_->scene.kind()) return SC_ERROR_INVALID_OPERATION;
  if (o.scene != nullptr) return SC_ERROR_INVALID_OPERATION;
  if (impl_->objects.count(id)) return SC_ERROR_INVALID_ID;
  try {
    auto model = std::make_shared<const sc::Model>(o.kind, o.pieces);
    const SCint rc = toScCode(impl_->scene.addObject(id, std::move(model), o.placement));
    if (rc != SC_NO_ERROR) return rc;
    impl_->objects[id] = object;
  } catch (const std::exception&) {
    impl_->scene.deleteObject(id).ok();
    return SC_ERROR_INVALID_OPERATION;
  }
  o.scene = this;
  o.id = id;
  return SC_NO_ERROR;
}

SCint SCSceneManager::DeleteObject(SCint id) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  const auto it = impl_->objects.find(id);
  if (it == impl_->objects.end()) return SC_ERROR_INVALID_ID;
  SCObject::Impl& o = *it->second->impl_;
  // The object keeps the pose it had in the scene.
  const auto placement = impl_->scene.objectPlacement(id);
  if (placement.hasValue()) o.placement = placement.value();
  o.scene = nullptr;
  impl_->objects.erase(it);
  return toScCode(impl_->scene.deleteObject(id));
}

SCint SCSceneManager::AddObjectToGroup(SCint gid, SCint id) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  if (gid < 0) return SC_ERROR_INVALID_ARGUMENT;
  return toScCode(impl_->scene.addObjectToGroup(gid, id));
}

SCint SCSceneManager::DeleteObjectFromGroup(SCint gid, SCint id) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  return toScCode(impl_->scene.removeObjectFromGroup(gid, id));
}

SCint SCSceneManager::DeleteFromGroup(SCint gid, SCint id) { return DeleteObjectFromGroup(gid, id); }

template <class Real>
static SCint setGroupTransformation(sc::Scene& scene, SCint gid, SCenum type, const Real* v) {
  if (gid == sc::kStaticGroup) return SC_ERROR_INVALID_OPERATION;
  auto placement = scene.groupPlacement(gid);
  if (!placement.hasValue()) return toScCode(placement.status());
  sc::Placement p = placement.value();
  const SCint rc = sc::detail::setTransformation(p, type, v);
  if (rc != SC_NO_ERROR) return rc;
  return toScCode(scene.setGroupPlacement(gid, p));
}

template <class Real>
static SCint getGroupTransformation(const sc::Scene& scene, SCint gid, SCenum type, Real* v) {
  auto placement = scene.groupPlacement(gid);
  if (!placement.hasValue()) return toScCode(placement.status());
  return sc::detail::getTransformation(placement.value(), type, v);
}

SCint SCSceneManager::SetTransformation(SCint gid, SCenum type, const SCdouble* trans) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  return setGroupTransformation(impl_->scene, gid, type, trans);
}
SCint SCSceneManager::SetTransformation(SCint gid, SCenum type, const SCfloat* trans) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  return setGroupTransformation(impl_->scene, gid, type, trans);
}
SCint SCSceneManager::GetTransformation(SCint gid, SCenum type, SCdouble* trans) const {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  return getGroupTransformation(impl_->scene, gid, type, trans);
}
SCint SCSceneManager::GetTransformation(SCint gid, SCenum type, SCfloat* trans) const {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  return getGroupTransformation(impl_->scene, gid, type, trans);
}

SCint SCSceneManager::SetActivityObject(SCint id, SCenum activity) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  sc::Activity a;
  if (!fromSc(kActivities, activity, a)) return SC_ERROR_INVALID_ARGUMENT;
  return toScCode(impl_->scene.setObjectActivity(id, a));
}

SCint SCSceneManager::SetActivityGroup(SCint gid, SCenum activity) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  sc::Activity a;
  if (!fromSc(kActivities, activity, a)) return SC_ERROR_INVALID_ARGUMENT;
  return toScCode(impl_->scene.setGroupActivity(gid, a));
}

SCint SCSceneManager::SetActivityPair(SCint gid1, SCint gid2, SCenum activity) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  sc::PairActivity a;
  if (!fromSc(kPairActivities, activity, a)) return SC_ERROR_INVALID_ARGUMENT;
  return toScCode(impl_->scene.setPairActivity(gid1, gid2, a));
}

SCint SCSceneManager::SetAttributeDouble(SCenum attribute, SCdouble value) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  sc::SceneSettings s = impl_->scene.settings();
  double* field = doubleField(s, attribute);
  if (field == nullptr) return SC_ERROR_INVALID_ARGUMENT;
  *field = value;
  return toScCode(impl_->scene.setSettings(s));
}

SCint SCSceneManager::SetAttributeInteger(SCenum attribute, SCint value) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  sc::SceneSettings s = impl_->scene.settings();
  if (bool* flag = boolField(s, attribute)) {
    if (value != 0 && value != 1) return SC_ERROR_INVALID_ARGUMENT;
    *flag = value == 1;
    return toScCode(impl_->scene.setSettings(s));
  }
  int* field = intField(s, attribute);
  if (field == nullptr) return SC_ERROR_INVALID_ARGUMENT;
  *field = value;
  return toScCode(impl_->scene.setSettings(s));
}

SCint SCSceneManager::SetAttributeEnum(SCenum attribute, SCenum value) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  if (attribute != SC_SCENE_MANAGER_ROTATION_MODE) return SC_ERROR_INVALID_ARGUMENT;
  sc::SceneSettings s = impl_->scene.settings();
  if (!fromSc(kRotationModes, value, s.rotation_mode)) return SC_ERROR_INVALID_ARGUMENT;
  return toScCode(impl_->scene.setSettings(s));
}

SCint SCSceneManager::GetAttributeDouble(SCenum attribute, SCdouble* value) const {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  sc::SceneSettings s = impl_->scene.settings();
  const double* field = doubleField(s, attribute);
  if (field == nullptr || value == nullptr) return SC_ERROR_INVALID_ARGUMENT;
  *value = *field;
  return SC_NO_ERROR;
}

SCint SCSceneManager::GetAttributeInteger(SCenum attribute, SCint* value) const {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  sc::SceneSettings s = impl_->scene.settings();
  if (const bool* flag = boolField(s, attribute); flag != nullptr && value != nullptr) {
    *value = *flag ? 1 : 0;
    return SC_NO_ERROR;
  }
  const int* field = intField(s, attribute);
  if (field == nullptr || value == nullptr) return SC_ERROR_INVALID_ARGUMENT;
  *value = *field;
  return SC_NO_ERROR;
}

SCint SCSceneManager::GetAttributeEnum(SCenum attribute, SCenum* value) const {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  if (attribute != SC_SCENE_MANAGER_ROTATION_MODE || value == nullptr)
    return SC_ERROR_INVALID_ARGUMENT;
  *value = fromRotationMode(impl_->scene.settings().rotation_mode);
  return SC_NO_ERROR;
}

SCint SCSceneManager::UpdateStatus() {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  try {
    return toScCode(impl_->scene.update());
  } catch (const std::exception&) {
    return SC_ERROR_INVALID_OPERATION;  // out of memory
  }
}

SCint SCSceneManager::GetStatus(SCenum type, SCint* value) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  if (type != SC_STATUS_COUNT || value == nullptr) return SC_ERROR_INVALID_ARGUMENT;
  *value = static_cast<SCint>(impl_->scene.pairs().size());
  return SC_NO_ERROR;
}

SCint SCSceneManager::GetStatus(SCenum type, SCint* value, SCint index, SCbool reverseFlag) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  const auto& pairs = impl_->scene.pairs();
  if (value == nullptr || index < 0 || index >= static_cast<SCint>(pairs.size()))
    return SC_ERROR_INVALID_ARGUMENT;
  if (type == SC_STATUS_COUNT) return GetStatus(type, value);
  return intStatus(pairs[index], reverseFlag ? 1 : 0, type, value);
}

SCint SCSceneManager::GetStatus(SCenum type, SCfloat* value, SCint index, SCbool reverseFlag) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  const auto& pairs = impl_->scene.pairs();
  if (value == nullptr || index < 0 || index >= static_cast<SCint>(pairs.size()))
    return SC_ERROR_INVALID_ARGUMENT;
  return realStatus(pairs[index], reverseFlag ? 1 : 0, type, value);
}

SCint SCSceneManager::GetStatus(SCenum type, SCdouble* value, SCint index, SCbool reverseFlag) {
  if (!impl_->known_type) return SC_ERROR_INVALID_ARGUMENT;
  const auto& pairs = impl_->scene.pairs();
  if (value == nullptr || index < 0 || index >= static_cast<SCint>(pairs.size()))
    return SC_ERROR_INVALID_ARGUMENT;
  return realStatus(pairs[index], reverseFlag ? 1 : 0, type, value);
}
