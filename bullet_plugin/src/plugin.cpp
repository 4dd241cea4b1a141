// SPDX-License-Identifier: MIT
// Plugin: settings, per-body overrides, the shape-model cache, the impulse
// buffer and the registration of the create functions on a dispatcher.
#include "smartcollision/bullet/plugin.h"

#include <LinearMath/btConvexHullComputer.h>
#include <LinearMath/btPoolAllocator.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <new>
#include <string>
#include <vector>

#include "sc_collision_algorithm.h"
#include "sc_plane_algorithm.h"
#include "smartcollision/bullet/sc_bullet_shape.h"
#include "step_buffer.h"
#include "triangle_mesh_model.h"

namespace sc::bullet {

namespace {

/// Both algorithms come from the dispatcher's pool.
constexpr int kAlgorithmSize =
    static_cast<int>(std::max(sizeof(ScCollisionAlgorithm), sizeof(ScPlaneAlgorithm)));

bool finiteAtLeast(double v, double lo) { return std::isfinite(v) && v >= lo; }

Vec3 toVec(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }

/// Triangles of a convex polygon fan, each turned to face away from `inside`.
void addFan(const std::vector<int>& loop, const std::vector<Vec3>& vertices, const Vec3& inside,
            std::vector<Tri>& triangles) {
  for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
    Tri t(loop[0], loop[k], loop[k + 1]);
    const Vec3& a = vertices[static_cast<std::size_t>(t[0])];
    const Vec3 n = (vertices[static_cast<std::size_t>(t[1])] - a)
                       .cross(vertices[static_cast<std::size_t>(t[2])] - a);
    if (n.dot(a - inside) < 0.0) std::swap(t[1], t[2]);
    triangles.push_back(t);
  }
}

Result<ModelPtr> convexModel(MeshData mesh) {
  Result<PiecePtr> piece = buildPiece(ModelKind::ClosedPolyhedron, std::move(mesh));
  if (!piece.hasValue()) return piece.status();
  return ModelPtr(std::make_shared<const Model>(ModelKind::ClosedPolyhedron,
                                                std::vector<PiecePtr>{piece.value()}));
}

Result<ModelPtr> boxModel(const btVector3& half) {
  MeshData m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                            (i & 4) ? half.z() : -half.z());
  // Faces as corner loops (bit patterns of the index), then fans facing outwards.
  const int faces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
  for (const auto& f : faces)
    addFan({f[0], f[1], f[2], f[3]}, m.vertices, Vec3::Zero(), m.triangles);
  return convexModel(std::move(m));
}

Result<ModelPtr> hullModel(const btConvexHullShape& hull) {
  const int n = hull.getNumPoints();
  std::vector<btScalar> coords;
  coords.reserve(static_cast<std::size_t>(3 * n));
  for (int i = 0; i < n; ++i) {
    const btVector3 p = hull.getScaledPoint(i);
    coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  }
  btConvexHullComputer computer;
  if (computer.compute(coords.data(), 3 * static_cast<int>(sizeof(btScalar)), n, 0, 0) < 0 ||
      computer.faces.size() < 4)
    return Status(ErrorCode::InvalidGeometry, "the hull's points span no volume");
  MeshData m;
  Vec3 inside = Vec3::Zero();
  for (int i = 0; i < computer.vertices.size(); ++i) {
    m.vertices.push_back(toVec(computer.vertices[i]));
    inside += m.vertices.back();
  }
  inside /= static_cast<double>(m.vertices.size());
  std::vector<int> loop;
  for (int f = 0; f < computer.faces.size(); ++f) {
    loop.clear();
    const btConvexHullComputer::Edge* first = &computer.edges[computer.faces[f]];
    const btConvexHullComputer::Edge* e = first;
    do {
      loop.push_back(e->getSourceVertex());
      e = e->getNextEdgeOfFace();
    } while (e != first && loop.size() <= static_cast<std::size_t>(computer.vertices.size()));
    addFan(loop, m.vertices, inside, m.triangles);
  }
  return convexModel(std::move(m));
}

/// The core of a rounded primitive: a point (sphere) or the axis segment (capsule) as
/// a one-triangle soup whose corners repeat, so its support is exactly the point or
/// the segment; the radius is added to the results (no tessellated surface).
Result<ModelPtr> coreModel(const Vec3& a, const Vec3& b) {
  MeshData m;
  m.vertices = {a, b};
  m.triangles = {Tri(0, 1, 1)};
  Result<PiecePtr> piece = buildPiece(ModelKind::TriangleSoup, std::move(m));
  if (!piece.hasValue()) return piece.status();
  return ModelPtr(
      std::make_shared<const Model>(ModelKind::TriangleSoup, std::vector<PiecePtr>{piece.value()}));
}

Result<ModelPtr> capsuleModel(const btCapsuleShape& capsule) {
  Vec3 half = Vec3::Zero();
  half[capsule.getUpAxis()] = double(capsule.getHalfHeight());
  return coreModel(-half, half);
}

/// Everything a shape's model depends on, exactly: a shape changed in place (an
/// edited hull, a resized box, a rescaled or regrown mesh) or a new shape at a freed
/// address gets a new model (sums of the coordinates, the key before, let a
/// reordered or edited hull of the same sums keep a stale one). A triangle mesh's
/// key is read without walking its triangles (detail::appendTriangleMeshKey). Empty
/// for shapes without a model.
std::vector<double> shapeKey(const btCollisionShape* shape) {
  std::vector<double> key{double(shape->getShapeType())};
  auto add = [&key](const btVector3& v) { key.insert(key.end(), {v.x(), v.y(), v.z()}); };
  switch (shape->getShapeType()) {
    case BOX_SHAPE_PROXYTYPE:
      add(static_cast<const btBoxShape*>(shape)->getHalfExtentsWithMargin());
      return key;
    case CONVEX_HULL_SHAPE_PROXYTYPE: {
      const auto* hull = static_cast<const btConvexHullShape*>(shape);
      for (int i = 0; i < hull->getNumPoints(); ++i) add(hull->getScaledPoint(i));
      return key;
    }
    case SPHERE_SHAPE_PROXYTYPE:
      return key;  // the point does not depend on the radius
    case CAPSULE_SHAPE_PROXYTYPE: {
      const auto* capsule = static_cast<const btCapsuleShape*>(shape);
      key.insert(key.end(), {capsule->getHalfHeight(), double(capsule->getUpAxis())});
      return key;
    }
    case TRIANGLE_MESH_SHAPE_PROXYTYPE:
    case SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE:
      detail::appendTriangleMeshKey(shape, key);
      return key;
    default:
      return {};
  }
}

/// Bit for bit, so that a key holding a NaN (a broken shape) still finds its
/// cached failure instead of building again at every pair.
bool sameKey(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

Result<ModelPtr> buildShapeModel(const btCollisionShape* shape) {
  switch (shape->getShapeType()) {
    case BOX_SHAPE_PROXYTYPE:
      return boxModel(static_cast<const btBoxShape*>(shape)->getHalfExtentsWithMargin());
    case CONVEX_HULL_SHAPE_PROXYTYPE:
      return hullModel(*static_cast<const btConvexHullShape*>(shape));
    case SPHERE_SHAPE_PROXYTYPE:
      return coreModel(Vec3::Zero(), Vec3::Zero());
    case CAPSULE_SHAPE_PROXYTYPE:
      return capsuleModel(*static_cast<const btCapsuleShape*>(shape));
    default:
      return detail::triangleMeshModel(shape);  // shapeKey admits no other type
  }
}

/// Reads the create function a dispatcher holds for a pair of shape types (Bullet
/// keeps its tables protected and offers no getter).
struct DispatcherTable : btCollisionDispatcher {
  static const btCollisionAlgorithmCreateFunc* contact(const btCollisionDispatcher& d, int a,
                                                       int b) {
    return (d.*(&DispatcherTable::m_doubleDispatchContactPoints))[a][b];
  }
};

/// The live plugins' registrations: a dispatcher holds one plugin at a time (a second
/// one would replace the first's create functions, which the dispatcher then keeps
/// using after that second plugin is gone).
struct Registration {
  const btCollisionAlgorithmCreateFunc* func;
  const btCollisionDispatcher* dispatcher;
  const Plugin* plugin;
};
std::mutex g_registrations_mutex;
std::vector<Registration> g_registrations;

/// True when a live plugin's algorithms are registered on `dispatcher`: its table
/// holds a function a live plugin registered there (a stale entry, from a dispatcher
/// or a plugin since destroyed at the same address, does not count).
bool pluginRegisteredOn(const btCollisionDispatcher& dispatcher) {
  const btCollisionAlgorithmCreateFunc* f =
      DispatcherTable::contact(dispatcher, kShapeType, kShapeType);
  return std::any_of(g_registrations.begin(), g_registrations.end(), [&](const Registration& r) {
    return r.func == f && r.dispatcher == &dispatcher;
  });
}

}  // namespace

SceneSettings defaultQuerySettings() {
  // Input, although the core accepts Mix: measured at 240 Hz, Mix topples the 15-box
  // pyramid and costs 10x per step on the tower (docs/bullet.md); revisit when the
  // core's Mix settles.
  SceneSettings s;
  s.rotation_mode = RotationMode::Input;
  // Bodies spawned touching or overlapping get a depth (and a contact) at once,
  // rather than no result until they are pushed apart.
  s.resolve_initial_intersection = true;
  return s;
}

Status validate(const ContactSettings& c) {
  auto bad = [](const char* what) { return Status(ErrorCode::InvalidArgument, what); };
  if (!finiteAtLeast(c.contact_period_steps, 1.0)) return bad("contact_period_steps must be >= 1");
  if (!finiteAtLeast(c.damping_ratio, 0.0)) return bad("damping_ratio must be >= 0");
  if (!finiteAtLeast(c.contact_stiffness, 0.0)) return bad("contact_stiffness must be >= 0");
  if (!finiteAtLeast(c.contact_torque_stiffness, 0.0))
    return bad("contact_torque_stiffness must be >= 0");
  if (!finiteAtLeast(c.friction_scale, 0.0)) return bad("friction_scale must be >= 0");
  // Bullet's solver works in single precision: dt k must stay a float.
  if (c.contact_stiffness > 1e30 || c.contact_torque_stiffness > 1e30)
    return bad("stiffness beyond single precision (> 1e30)");
  return Status();
}

Status validate(const PluginSettings& s) {
  if (s.model != ContactModel::Potential && s.model != ContactModel::Manifold)
    return Status(ErrorCode::InvalidArgument, "unknown contact model");
  Status c = validate(s.contact);
  if (!c.ok()) return c;
  if (!(std::isfinite(s.recovery_speed) && s.recovery_speed > 0.0))
    return Status(ErrorCode::InvalidArgument, "recovery_speed must be finite and > 0");
  if (!finiteAtLeast(s.relative_tolerance, 0.0))
    return Status(ErrorCode::InvalidArgument, "relative_tolerance must be finite and >= 0");
  return validate(s.query);
}

struct Plugin::CreateFuncs {
  template <class Algorithm>
  struct Func : btCollisionAlgorithmCreateFunc {
    Func(Plugin* p, bool closest) : plugin(p), closest_points(closest) {}
    btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                   const btCollisionObjectWrapper* body0,
                                                   const btCollisionObjectWrapper* body1) override {
      void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(Algorithm));
      return new (mem) Algorithm(ci, body0, body1, plugin, closest_points);
    }
    Plugin* plugin;
    bool closest_points;
  };
  explicit CreateFuncs(Plugin* p)
      : contact(p, false), closest(p, true), plane(p, false), plane_closest(p, true) {}
  Func<ScCollisionAlgorithm> contact;
  Func<ScCollisionAlgorithm> closest;
  Func<ScPlaneAlgorithm> plane;
  Func<ScPlaneAlgorithm> plane_closest;
};

Plugin::Plugin(const PluginSettings& settings)
    : settings_(settings),
      step_(std::make_unique<detail::StepBuffer>()),
      create_funcs_(std::make_unique<CreateFuncs>(this)) {}

Plugin::~Plugin() {
  std::lock_guard<std::mutex> lock(g_registrations_mutex);
  g_registrations.erase(std::remove_if(g_registrations.begin(), g_registrations.end(),
                                       [this](const Registration& r) { return r.plugin == this; }),
                        g_registrations.end());
}

Status Plugin::setSettings(const PluginSettings& settings) {
  Status s = validate(settings);
  if (s.ok()) settings_ = settings, step_->settingsChanged();
  return s;
}

void Plugin::setContactModel(ContactModel model) {
  settings_.model = model;
  step_->settingsChanged();
}

Status Plugin::setBodySettings(const btCollisionObject* body, const ContactSettings& settings) {
  if (body == nullptr) return Status(ErrorCode::InvalidArgument, "null body");
  Status s = validate(settings);
  if (s.ok()) body_settings_[body] = settings, step_->settingsChanged();
  return s;
}

void Plugin::clearBodySettings(const btCollisionObject* body) {
  if (body_settings_.erase(body) > 0) step_->settingsChanged();
}

void accumulate(StepStats& into, const StepStats& pair) {
  into.pairs += pair.pairs;
  into.penetrating += pair.penetrating;
  into.recovering += pair.recovering;
  into.max_depth = std::max(into.max_depth, pair.max_depth);
  into.max_rotation = std::max(into.max_rotation, pair.max_rotation);
  into.projected += pair.projected;
  into.rows += pair.rows;
  into.dropped_rows += pair.dropped_rows;
  into.touching += pair.touching;
  into.skipped += pair.skipped;
  into.reused += pair.reused;
}

ContactSettings Plugin::pairSettings(const btCollisionObject* a, const btCollisionObject* b) const {
  if (body_settings_.empty()) return settings_.contact;
  const auto ia = body_settings_.find(a);
  const auto ib = body_settings_.find(b);
  const bool has_a = ia != body_settings_.end();
  const bool has_b = ib != body_settings_.end();
  if (!has_a && !has_b) return settings_.contact;
  if (has_a != has_b) return has_a ? ia->second : ib->second;
  ContactSettings c = ia->second;
  const ContactSettings& d = ib->second;
  c.contact_period_steps = std::min(c.contact_period_steps, d.contact_period_steps);
  c.damping_ratio = std::max(c.damping_ratio, d.damping_ratio);
  c.contact_stiffness = std::max(c.contact_stiffness, d.contact_stiffness);
  c.contact_torque_stiffness = std::max(c.contact_torque_stiffness, d.contact_torque_stiffness);
  c.friction_scale = std::max(c.friction_scale, d.friction_scale);
  return c;
}

Result<ModelPtr> Plugin::shapeModel(const btCollisionShape* shape) {
  if (shape == nullptr) return Status(ErrorCode::InvalidArgument, "null shape");
  if (shape->getShapeType() == kShapeType)
    return static_cast<const ScBulletShape*>(shape)->modelPtr();
  std::vector<double> key = shapeKey(shape);
  if (key.empty())
    return Status(ErrorCode::InvalidArgument,
                  std::string("no SmartCollision model for a ") + shape->getName() + " shape");
  auto it = models_.find(shape);
  if (it == models_.end() || !sameKey(it->second.key, key)) {
    Result<ModelPtr> built = buildShapeModel(shape);
    Status status = built.hasValue()
                        ? Status()
                        : Status(built.status().code(),
                                 std::string(shape->getName()) + ": " + built.status().message());
    it = models_.insert_or_assign(shape, CachedModel{built.value(), status, std::move(key)}).first;
  }
  if (!it->second.model) return it->second.status;
  return it->second.model;
}

const StepStats& Plugin::stats() const { return step_->stats(); }

btCollisionAlgorithmCreateFunc* Plugin::contactCreateFunc() const {
  return &create_funcs_->contact;
}

btCollisionAlgorithmCreateFunc* Plugin::closestPointsCreateFunc() const {
  return &create_funcs_->closest;
}

btCollisionAlgorithmCreateFunc* Plugin::planeCreateFunc(bool closest_points) const {
  return closest_points
             ? static_cast<btCollisionAlgorithmCreateFunc*>(&create_funcs_->plane_closest)
             : &create_funcs_->plane;
}

btDefaultCollisionConstructionInfo collisionConstructionInfo() {
  btDefaultCollisionConstructionInfo info;
  info.m_customCollisionAlgorithmMaxElementSize = kAlgorithmSize;
  return info;
}

Result<std::shared_ptr<Plugin>> registerSmartCollision(btCollisionDispatcher* dispatcher,
                                                       const PluginSettings& settings) {
  if (dispatcher == nullptr) return Status(ErrorCode::InvalidArgument, "null dispatcher");
  Status s = validate(settings);
  if (!s.ok()) return s;
  btCollisionConfiguration* config = dispatcher->getCollisionConfiguration();
  if (config == nullptr || config->getCollisionAlgorithmPool() == nullptr ||
      config->getCollisionAlgorithmPool()->getElementSize() < kAlgorithmSize)
    return Status(ErrorCode::InvalidOperation,
                  "the dispatcher's algorithm pool is too small: build the collision "
                  "configuration from sc::bullet::collisionConstructionInfo()");
  std::lock_guard<std::mutex> lock(g_registrations_mutex);
  if (pluginRegisteredOn(*dispatcher))
    return Status(ErrorCode::InvalidOperation,
                  "a SmartCollision plugin is already registered on this dispatcher (one per "
                  "dispatcher: keep and share the first)");
  auto plugin = std::make_shared<Plugin>(settings);
  g_registrations.push_back({plugin->contactCreateFunc(), dispatcher, plugin.get()});
  const int others[] = {kShapeType,
                        BOX_SHAPE_PROXYTYPE,
                        CONVEX_HULL_SHAPE_PROXYTYPE,
                        SPHERE_SHAPE_PROXYTYPE,
                        CAPSULE_SHAPE_PROXYTYPE,
                        STATIC_PLANE_PROXYTYPE,
                        TRIANGLE_MESH_SHAPE_PROXYTYPE,
                        SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE};
  for (int other : others) {
    const bool plane = other == STATIC_PLANE_PROXYTYPE;
    for (int order = 0; order < 2; ++order) {
      const int t0 = order == 0 ? kShapeType : other;
      const int t1 = order == 0 ? other : kShapeType;
      dispatcher->registerCollisionCreateFunc(
          t0, t1, plane ? plugin->planeCreateFunc(false) : plugin->contactCreateFunc());
      dispatcher->registerClosestPointsCreateFunc(
          t0, t1, plane ? plugin->planeCreateFunc(true) : plugin->closestPointsCreateFunc());
    }
  }
  return plugin;
}

}  // namespace sc::bullet
