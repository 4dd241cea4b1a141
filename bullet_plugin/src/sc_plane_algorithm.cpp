// SPDX-License-Identifier: MIT
// ScPlaneAlgorithm: the deepest hull corner gives distance and depth; the potential
// model takes it as the pair's result, the manifold model takes every corner within
// the breaking threshold.
#include "sc_plane_algorithm.h"

#include <algorithm>
#include <limits>

#include "contact_response.h"
#include "smartcollision/bullet/plugin.h"
#include "smartcollision/bullet/sc_bullet_shape.h"
#include "step_buffer.h"

namespace sc::bullet {

namespace {

Vec3 toVec(const btVector3& v) { return Vec3(double(v.x()), double(v.y()), double(v.z())); }

/// The plane in world coordinates: unit normal n and offset c (points x with n.x = c).
struct WorldPlane {
  btVector3 normal;
  double offset;
  double signedDistance(const btVector3& p) const { return double(normal.dot(p)) - offset; }
};

WorldPlane worldPlane(const btCollisionObjectWrapper* w) {
  const auto* plane = static_cast<const btStaticPlaneShape*>(w->getCollisionShape());
  const btTransform& t = w->getWorldTransform();
  WorldPlane p;
  p.normal = (t.getBasis() * plane->getPlaneNormal()).normalized();
  p.offset = double(p.normal.dot(t(plane->getPlaneNormal() * plane->getPlaneConstant())));
  return p;
}

/// Result of the shape (target) against the plane (opponent), as the core would report
/// it: exact, since a half-space's depth is the deepest point's.
DirectedResult planeResult(const WorldPlane& plane, const btTransform& t,
                           const std::vector<btVector3>& hull) {
  double deepest = std::numeric_limits<double>::infinity();
  btVector3 point(0, 0, 0);
  for (const btVector3& v : hull) {
    const btVector3 w = t(v);
    const double s = plane.signedDistance(w);
    if (s < deepest) {
      deepest = s;
      point = w;
    }
  }
  DirectedResult r;
  if (hull.empty()) return r;
  const Vec3 n = toVec(plane.normal);
  r.code = ErrorCode::Ok;
  r.distance = deepest;
  r.normal = n;
  r.point_on_target = toVec(point);
  r.point_on_opponent = r.point_on_target - deepest * n;
  r.tpdv = deepest < 0.0 ? Vec3(deepest * n) : Vec3::Zero();
  r.contact_position = toVec(t.getOrigin()) - r.tpdv;
  const btQuaternion q = t.getRotation();
  r.contact_orientation = Quat(double(q.w()), double(q.x()), double(q.y()), double(q.z()));
  return r;
}

/// Every hull corner (moved by `shift`) closer to the plane than `threshold`.
void cornerPoints(const WorldPlane& plane, const btTransform& t, const std::vector<btVector3>& hull,
                  const Vec3& shift, double threshold, std::vector<detail::RowPoint>& points) {
  const Vec3 n = toVec(plane.normal);
  for (const btVector3& v : hull) {
    const Vec3 w = toVec(t(v)) + shift;
    const double s = double(plane.normal.dot(t(v))) - plane.offset + n.dot(shift);
    if (s < threshold) points.push_back({w, n, s});
  }
}

}  // namespace

void ScPlaneAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                        const btCollisionObjectWrapper* body1,
                                        const btDispatcherInfo& info, btManifoldResult* result) {
  // The result's body of the shape (the other is the plane).
  const int dir = body0->getCollisionShape()->getShapeType() == kShapeType ? 0 : 1;
  const btCollisionObjectWrapper* shape_w = dir == 0 ? body0 : body1;
  const btCollisionObjectWrapper* plane_w = dir == 0 ? body1 : body0;
  const auto* shape = static_cast<const ScBulletShape*>(shape_w->getCollisionShape());
  const std::vector<btVector3>& hull = shape->hullVertices();
  const WorldPlane plane = worldPlane(plane_w);
  const btTransform& t = shape_w->getWorldTransform();
  const DirectedResult r = planeResult(plane, t, hull);
  if (r.code != ErrorCode::Ok) return;

  if (closest_points_) {
    result->setPersistentManifold(manifold_);
    if (r.distance <= double(result->m_closestPointDistanceThreshold))
      detail::addRows({{r.point_on_target, r.normal, r.distance}}, dir, kInfinity, result);
    return;
  }
  const PluginSettings& ps = plugin_->settings();
  StepStats& stats = plugin_->stepBuffer().stats();
  ++stats.pairs;
  const detail::BodySide target = detail::bodySide(shape_w);
  const detail::BodySide plane_side = detail::bodySide(plane_w);
  const ContactSettings contact =
      plugin_->pairSettings(body0->getCollisionObject(), body1->getCollisionObject());
  const double dt = double(info.m_timeStep);
  const detail::PairSpring spring = detail::pairSpring(target, plane_side, contact, dt);
  // As ScCollisionAlgorithm: the rows start once the body was seen out of the plane
  // or within the depth whose spring energy fits the recovery bound.
  if (!r.penetrating() || r.tpdv.norm() <= detail::springReach(spring, ps.recovery_speed))
    spring_on_ = true;
  if (r.penetrating()) {
    ++stats.penetrating;
    stats.max_depth = std::max(stats.max_depth, r.tpdv.norm());
  }
  if (manifold_ == nullptr)
    manifold_ =
        m_dispatcher->getNewManifold(body0->getCollisionObject(), body1->getCollisionObject());
  result->setPersistentManifold(manifold_);
  if (r.penetrating() && !spring_on_) {
    ++stats.recovering;
    manifold_->clearManifold();
    detail::deliver(*plugin_, target, plane_side,
                    detail::recoveryImpulse(target, plane_side, plane.normal, r.tpdv.norm(),
                                            ps.recovery_speed, contact.contact_period_steps * dt),
                    Vec3::Zero());
    return;
  }
  const double threshold = double(manifold_->getContactBreakingThreshold());
  const bool was_in_contact = in_contact_;
  in_contact_ = r.penetrating();
  const detail::StepBuffer& step = plugin_->stepBuffer();
  if (!step.impactPass()) held_depth_ = r.penetrating() ? r.tpdv.norm() : 0.0;
  const Vec3 shift = detail::projection(r, target, plane_side, was_in_contact, held_depth_, step,
                                        dt, ps.query.tolerance);
  if (!shift.isZero()) {
    ++stats.projected;
    detail::deliver(*plugin_, target, plane_side, detail::impactImpulse(shift, target, plane_side),
                    shift);
  }
  points_.clear();
  cornerPoints(plane, t, hull, shift, threshold, points_);
  detail::keepDeepest(points_);
  if (detail::anyTouching(points_, target, plane_side, dt)) ++stats.touching;
  detail::addRows(points_, dir, detail::rowThreshold(spring, ps, threshold), result);
  if (points_.empty() || manifold_->getNumContacts() == 0) {
    manifold_->clearManifold();
    return;
  }
  result->refreshContactPoints();
  if (ps.model == ContactModel::Potential && shift.isZero())  // an impact's rows stay rigid
    detail::softenRows(manifold_, spring, dt, contact.friction_scale, manifold_->getNumContacts());
  stats.rows += manifold_->getNumContacts();
}

}  // namespace sc::bullet
