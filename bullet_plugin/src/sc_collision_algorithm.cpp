// SPDX-License-Identifier: MIT
// ScCollisionAlgorithm: builds the two group views from the Bullet objects, runs
// the pair tracker, and hands the results to the potential model (impulses), to a
// persistent manifold (Bullet's solver), or to a closest-points query.
#include "smartcollision/bullet/sc_collision_algorithm.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "contact_response.h"
#include "smartcollision/bullet/plugin.h"
#include "smartcollision/bullet/sc_bullet_shape.h"

namespace sc::bullet {

namespace {

constexpr double kTwoPi = 6.283185307179586;

btVector3 toBt(const Vec3& v) {
  return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
}

ModelPtr modelOf(Plugin& plugin, const btCollisionShape* shape) {
  if (shape->getShapeType() == kShapeType)
    return static_cast<const ScBulletShape*>(shape)->modelPtr();
  return plugin.primitiveModel(shape);
}

/// One side of the pair: what the tracker and the response need.
struct Side {
  detail::BodySide body;
  Part part;
  GroupView view;
  btVector3 aabb_min, aabb_max;
  bool dynamic = false;
  double radius = 0.0;  ///< rounded primitives: the model is the core, this the radius
};

/// Radius of a rounded primitive (a sphere is a point, a capsule a segment, plus
/// this radius); 0 for every other shape. Read each step, like Bullet does.
double roundingRadius(const btCollisionShape* shape) {
  switch (shape->getShapeType()) {
    case SPHERE_SHAPE_PROXYTYPE:
      return double(static_cast<const btSphereShape*>(shape)->getRadius());
    case CAPSULE_SHAPE_PROXYTYPE:
      return double(static_cast<const btCapsuleShape*>(shape)->getRadius());
    default:
      return 0.0;
  }
}

void makeSide(const btCollisionObjectWrapper* w, const Model* model, Side& s) {
  const btTransform& t = w->getWorldTransform();
  s.body = detail::bodySide(w);
  s.dynamic = s.body.body != nullptr;
  s.radius = roundingRadius(w->getCollisionShape());
  s.part.model = model;
  s.part.id = 0;
  s.view.parts = &s.part;
  s.view.part_count = 1;
  const btQuaternion q = t.getRotation();
  s.view.placement.world_center = Vec3(t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z());
  s.view.placement.local_center = Vec3::Zero();
  s.view.placement.orientation = Quat(q.w(), q.x(), q.y(), q.z()).normalized();
  // Tight AABB of the model (the shape's own AABB carries margins).
  const Aabb& b = model->bounds();
  const btVector3 lo(btScalar(b.min.x()), btScalar(b.min.y()), btScalar(b.min.z()));
  const btVector3 hi(btScalar(b.max.x()), btScalar(b.max.y()), btScalar(b.max.z()));
  const btVector3 half = 0.5 * (hi - lo);
  const btVector3 center = t(0.5 * (hi + lo));
  const btMatrix3x3 abs_basis = t.getBasis().absolute();
  const btVector3 extent =
      btVector3(abs_basis[0].dot(half), abs_basis[1].dot(half), abs_basis[2].dot(half)) +
      btVector3(1, 1, 1) * btScalar(s.radius);
  s.aabb_min = center - extent;
  s.aabb_max = center + extent;
}

/// A direction's result for the rounded shapes: the core measured the core point or
/// segment (target radius rt, opponent ro); the surfaces are R = rt + ro closer along
/// the normal. Apart within R becomes a depth R - d along the normal; a depth of the
/// cores grows by R, its contact centre moves out by R.
void inflate(DirectedResult& r, double rt, double ro) {
  const double rr = rt + ro;
  if (r.code != ErrorCode::Ok || rr <= 0.0) return;
  r.point_on_target -= rt * r.normal;
  r.point_on_opponent += ro * r.normal;
  if (r.distance > rr) {
    r.distance -= rr;
    return;
  }
  const Vec3 current = r.contact_position + r.tpdv;
  r.tpdv = r.distance > 0.0 ? Vec3((r.distance - rr) * r.normal) : Vec3(r.tpdv - rr * r.normal);
  r.distance = -r.tpdv.norm();
  r.contact_position = current - r.tpdv;
}

/// Scalar moment of a side's body (trace / 3 of the world inertia), 0 when static.
double meanMoment(const Side& s) {
  if (s.body.body == nullptr) return 0.0;
  const btVector3 inv = s.body.body->getInvInertiaDiagLocal();
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) sum += inv[k] > 0 ? 1.0 / double(inv[k]) : 0.0;
  return sum / 3.0;
}

double reduced(double a, double b) {
  if (a > 0.0 && b > 0.0) return a * b / (a + b);
  return std::max(a, b);
}

/// Bullet's contact point of a direction whose target is the result's body `dir`:
/// the point on body 1 and the normal from body 1 towards body 0, as
/// btManifoldResult expects.
void addPoint(const DirectedResult& r, int dir, double depth, btManifoldResult* result) {
  detail::addTargetPoint(r.normal, r.point_on_opponent + depth * r.normal, depth, dir, result);
}

/// The target's contact face (or edge) corners as extra manifold points: one closest
/// pair per direction would leave a resting box on one corner. A convex piece gives
/// every vertex within the threshold (its whole contact face, not just the reported
/// triangle, so a box rests on four corners); a non-convex one its contact triangle's
/// or edge's corners. Their depth is taken against the opponent's contact plane
/// (through its contact point, normal n), which is the opponent's surface only when
/// its contact feature is a face: otherwise (a tilted box's corner on a face below)
/// the corners of the face would all read touching and hold the tilt, so only the
/// direction whose opponent shows a face adds corners. A corner beyond the edge of
/// that face is counted as supported (an approximation).
void addFeaturePoints(const DirectedResult& r, const Side& target, int dir, double threshold,
                      btManifoldResult* result) {
  if (r.opponent_feature.type != FeatureType::Face) return;
  const Feature& f = r.target_feature;
  const Model* model = target.part.model;
  if (r.target_piece < 0 || r.target_piece >= static_cast<int>(model->pieces().size())) return;
  const Piece& piece = *model->pieces()[static_cast<std::size_t>(r.target_piece)];
  const MeshData& mesh = piece.mesh();
  const Rigid world_from_t = target.view.placement.worldFromLocal();
  auto add = [&](int vi) {
    // On the surface of a rounded target: its core corner, radius towards O.
    const Vec3 p =
        world_from_t * mesh.vertices[static_cast<std::size_t>(vi)] - target.radius * r.normal;
    const double depth = r.normal.dot(p - r.point_on_opponent);
    if (depth < threshold) detail::addTargetPoint(r.normal, p, depth, dir, result);
  };
  if (piece.stats().convex) {
    for (int vi = 0; vi < static_cast<int>(mesh.vertices.size()); ++vi) add(vi);
    return;
  }
  if (f.type == FeatureType::Vertex) return;
  for (int k = 0; k < f.count(); ++k)
    if (f.vertices[k] >= 0 && f.vertices[k] < static_cast<int>(mesh.vertices.size()))
      add(f.vertices[k]);
}

/// Smallest-overlap axis of two AABBs as a manifold point (first-seen intersections).
void addOverlapPoint(const Side& a, const Side& b, btManifoldResult* result) {
  int axis = 0;
  double overlap = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double ov =
        std::min(a.aabb_max[k], b.aabb_max[k]) - std::max(a.aabb_min[k], b.aabb_min[k]);
    if (k == 0 || ov < overlap) {
      overlap = ov;
      axis = k;
    }
  }
  if (overlap <= 0.0) return;
  btVector3 n(0, 0, 0);  // from body 1 towards body 0
  n[axis] = (a.aabb_min[axis] + a.aabb_max[axis]) < (b.aabb_min[axis] + b.aabb_max[axis]) ? -1 : 1;
  btVector3 lo = a.aabb_min;
  lo.setMax(b.aabb_min);
  btVector3 hi = a.aabb_max;
  hi.setMin(b.aabb_max);
  btVector3 p = 0.5 * (lo + hi);
  p[axis] = n[axis] > 0 ? hi[axis] : lo[axis];  // on body 1's surface side
  result->addContactPoint(n, p, btScalar(-overlap));
}

/// The core's settings for this pair. Mix weighs translation against rotation by
/// kT / kR; with derived stiffnesses that ratio is m / I of the pair (omega^2 cancels).
SceneSettings pairQuerySettings(const SceneSettings& base, const ContactSettings& contact,
                                const Side sides[2], double dt) {
  SceneSettings query = base;
  const double m = reduced(sides[0].body.inv_mass > 0 ? 1.0 / sides[0].body.inv_mass : 0.0,
                           sides[1].body.inv_mass > 0 ? 1.0 / sides[1].body.inv_mass : 0.0);
  const double inertia = reduced(meanMoment(sides[0]), meanMoment(sides[1]));
  if (!(m > 0.0 && inertia > 0.0)) return query;
  const double omega = kTwoPi / (contact.contact_period_steps * (dt > 0.0 ? dt : 1.0 / 60.0));
  const bool set_t = contact.force_stiffness > 0.0, set_r = contact.torque_stiffness > 0.0;
  query.force_stiffness = set_t ? contact.force_stiffness : set_r ? m * omega * omega : m;
  query.torque_stiffness = set_r   ? contact.torque_stiffness
                           : set_t ? inertia * omega * omega
                                   : inertia;
  return query;
}

/// Closest-points query (contactTest): one point within the threshold, or the AABB
/// overlap of a pair first seen intersecting.
void reportClosestPoints(const DirectedResult out[2], const Side sides[2], bool swapped,
                         btManifoldResult* result) {
  const double threshold = double(result->m_closestPointDistanceThreshold);
  for (int dir = 0; dir < 2; ++dir) {
    if (out[dir].code == ErrorCode::Ok && out[dir].distance <= threshold) {
      addPoint(out[dir], swapped ? 1 - dir : dir, out[dir].distance, result);
      return;  // one point per query, as Bullet's convex algorithms report
    }
  }
  if (out[0].code == ErrorCode::InvalidInitialTransformation ||
      out[1].code == ErrorCode::InvalidInitialTransformation)
    addOverlapPoint(sides[swapped ? 1 : 0], sides[swapped ? 0 : 1], result);
}

}  // namespace

ScCollisionAlgorithm::ScCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                                           const btCollisionObjectWrapper* body0,
                                           const btCollisionObjectWrapper* body1, Plugin* plugin,
                                           bool closest_points)
    : btActivatingCollisionAlgorithm(ci, body0, body1),
      plugin_(plugin),
      objects_{body0->getCollisionObject(), body1->getCollisionObject()},
      models_{modelOf(*plugin, body0->getCollisionShape()),
              modelOf(*plugin, body1->getCollisionShape())},
      closest_points_(closest_points) {
  if (closest_points_) manifold_ = m_dispatcher->getNewManifold(objects_[0], objects_[1]);
}

ScCollisionAlgorithm::~ScCollisionAlgorithm() {
  if (manifold_ != nullptr) m_dispatcher->releaseManifold(manifold_);
}

void ScCollisionAlgorithm::getAllContactManifolds(btManifoldArray& manifolds) {
  if (manifold_ != nullptr && !closest_points_) manifolds.push_back(manifold_);
}

void ScCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                            const btCollisionObjectWrapper* body1,
                                            const btDispatcherInfo& info,
                                            btManifoldResult* result) {
  // The pair keeps its order for its life; side i is objects_[i] in any case, so
  // the tracker's directions stay attached to the same bodies.
  if (!models_[0] || !models_[1]) return;
  const bool swapped = body0->getCollisionObject() != objects_[0];
  const btCollisionObjectWrapper* wraps[2] = {swapped ? body1 : body0, swapped ? body0 : body1};
  Side sides[2];
  for (int i = 0; i < 2; ++i) makeSide(wraps[i], models_[i].get(), sides[i]);

  const PluginSettings& ps = plugin_->settings();
  const ContactSettings contact = plugin_->pairSettings(objects_[0], objects_[1]);
  const SceneSettings query = pairQuerySettings(ps.query, contact, sides, double(info.m_timeStep));
  Directions dirs;
  dirs.a_target = sides[0].dynamic || !sides[1].dynamic || closest_points_;
  dirs.b_target = sides[1].dynamic || closest_points_;
  DirectedResult out[2];
  tracker_.update(sides[0].view, sides[1].view, dirs, query, out);
  for (int dir = 0; dir < 2; ++dir) inflate(out[dir], sides[dir].radius, sides[1 - dir].radius);

  if (closest_points_) {
    result->setPersistentManifold(manifold_);
    reportClosestPoints(out, sides, swapped, result);
    return;
  }

  StepStats& stats = plugin_->stats();
  ++stats.pairs;
  const double dt = double(info.m_timeStep);
  const double period = contact.contact_period_steps * dt;  // recovery time scale
  const bool potential = ps.model == ContactModel::Potential;
  const double friction = double(objects_[0]->getFriction() * objects_[1]->getFriction());
  bool any_point = false;
  if (!potential) {
    if (manifold_ == nullptr) manifold_ = m_dispatcher->getNewManifold(objects_[0], objects_[1]);
    result->setPersistentManifold(manifold_);
  } else if (manifold_ != nullptr) {
    manifold_->clearManifold();  // switched from the manifold model: no double response
  }
  for (int dir = 0; dir < 2; ++dir) {
    const DirectedResult& r = out[dir];
    const Side& t = sides[dir];
    const Side& o = sides[1 - dir];
    detail::Impulse imp;
    if (r.code == ErrorCode::InvalidInitialTransformation) {
      ++stats.recovering;
      imp = detail::recoveryImpulse(t.body, o.body, t.aabb_min, t.aabb_max, o.aabb_min, o.aabb_max,
                                    ps.recovery_speed, period);
    } else if (r.code == ErrorCode::Ok) {
      if (r.penetrating() && r.tpdv.dot(r.normal) > 0.0) {
        // A depth whose TPDV points out of the opponent is not one (seen from the
        // core when tracking starts within the tolerance of touching): start over.
        tracker_.forget(dir);
        continue;
      }
      // The spring takes over once the pair was seen apart, or at once when the first
      // depth is small enough that its spring energy fits the recovery bound.
      if (!r.penetrating() || r.tpdv.norm() <= detail::springReach(t.body, o.body, contact, dt,
                                                                   ps.recovery_speed))
        spring_on_[dir] = true;
      if (r.penetrating()) {
        ++stats.penetrating;
        stats.max_depth = std::max(stats.max_depth, r.tpdv.norm());
        stats.max_rotation = std::max(stats.max_rotation, r.rpdv.norm());
      }
      const double threshold = potential ? 0.0 : double(manifold_->getContactBreakingThreshold());
      if (r.penetrating() && !spring_on_[dir]) {
        ++stats.recovering;
        imp = detail::recoveryImpulse(t.body, o.body, toBt(r.normal), r.tpdv.norm(),
                                      ps.recovery_speed, period);
      } else if (!potential && r.distance < threshold) {
        addPoint(r, swapped ? 1 - dir : dir, r.distance, result);
        addFeaturePoints(r, t, swapped ? 1 - dir : dir, threshold, result);
        any_point = true;
      } else if (potential && r.penetrating()) {
        imp = detail::potentialImpulse(r, t.body, o.body, contact, dt, friction, query.tolerance);
      }
    }
    detail::deliver(*plugin_, t.body, o.body, imp);
  }
  if (!potential) {
    if (any_point)
      result->refreshContactPoints();
    else
      manifold_->clearManifold();
  }
}

}  // namespace sc::bullet
