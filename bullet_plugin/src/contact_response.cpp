// SPDX-License-Identifier: MIT
// Soft rows of the potential model, impact projection and the overlap push.
#include "contact_response.h"

#include <algorithm>
#include <cmath>

#include "smartcollision/bullet/plugin.h"
#include "step_buffer.h"

namespace sc::bullet::detail {

namespace {

constexpr double kTwoPi = 2.0 * kPi;

btVector3 toBt(const Vec3& v) {
  return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
}

double reducedMass(const BodySide& a, const BodySide& b) {
  const double inv = a.inv_mass + b.inv_mass;
  return inv > 0.0 ? 1.0 / inv : 0.0;
}

}  // namespace

BodySide bodySide(const btCollisionObjectWrapper* w) {
  BodySide s;
  s.object = w->getCollisionObject();
  btRigidBody* rb = const_cast<btRigidBody*>(btRigidBody::upcast(s.object));
  const bool dynamic =
      rb != nullptr && !s.object->isStaticOrKinematicObject() && rb->getInvMass() > 0;
  s.body = dynamic ? rb : nullptr;
  s.inv_mass = dynamic ? double(rb->getInvMass()) : 0.0;
  s.center = w->getWorldTransform().getOrigin();
  return s;
}

btVector3 BodySide::velocityAt(const btVector3& p) const {
  const auto* rb = btRigidBody::upcast(object);
  if (rb == nullptr) return btVector3(0, 0, 0);
  return rb->getVelocityInLocalPoint(p - rb->getCenterOfMassPosition());
}

bool anyTouching(const std::vector<RowPoint>& points, const BodySide& t, const BodySide& o,
                 double dt) {
  for (const RowPoint& p : points) {
    const btVector3 at = toBt(p.point);
    const double approach = -double((t.velocityAt(at) - o.velocityAt(at)).dot(toBt(p.normal)));
    if (p.separation <= std::max(0.0, approach * dt)) return true;
  }
  return false;
}

void keepDeepest(std::vector<RowPoint>& points) {
  if (points.size() <= static_cast<std::size_t>(kMaxRowPoints)) return;
  std::nth_element(
      points.begin(), points.begin() + kMaxRowPoints, points.end(),
      [](const RowPoint& a, const RowPoint& b) { return a.separation < b.separation; });
  points.resize(static_cast<std::size_t>(kMaxRowPoints));
}

PairSpring pairSpring(const BodySide& a, const BodySide& b, const ContactSettings& c, double dt) {
  PairSpring s;
  s.mass = reducedMass(a, b);
  s.damping_ratio = c.damping_ratio;
  s.user_stiffness = c.contact_stiffness > 0.0;
  s.omega = kTwoPi / (c.contact_period_steps * (dt > 0.0 ? dt : 1.0 / 60.0));
  s.stiffness = s.user_stiffness ? c.contact_stiffness : s.mass * s.omega * s.omega;
  return s;
}

Vec3 impactProjection(const DirectedResult& r, const BodySide& t, const BodySide& o, double dt,
                      double tolerance, double held_depth) {
  if (t.body == nullptr || !r.penetrating() || !(dt > 0.0)) return Vec3::Zero();
  const double depth = r.tpdv.norm();
  const double excess = depth - std::max(0.0, held_depth);
  if (!(excess > tolerance)) return Vec3::Zero();
  const Vec3 u = -r.tpdv / depth;  // out of the opponent
  const btVector3 p = toBt(r.point_on_opponent);
  const double closing_t = -double(t.velocityAt(p).dot(toBt(u)));  // t towards o
  const double approach = closing_t + double(o.velocityAt(p).dot(toBt(u)));
  // Resting and slowly pressed contacts are the rows' to hold; only a body that came
  // in by more than the tolerance within this step is put back.
  if (!(approach * dt > tolerance)) return Vec3::Zero();
  // Each body undoes its own part of the approach: a body landing on a resting one is
  // put back whole, and the resting one is not pushed into its own supports.
  const double share = o.inv_mass > 0.0 ? std::clamp(closing_t / approach, 0.0, 1.0) : 1.0;
  return -share * (excess / depth) * r.tpdv;
}

double cascadeShare(const BodySide& t, const BodySide& o, const StepBuffer& step) {
  if (t.body == nullptr) return 0.0;
  const bool moved_t = step.projected(t.object), moved_o = step.projected(o.object);
  if (o.body == nullptr) return moved_t ? 1.0 : 0.0;
  if (!moved_o) return 0.0;
  return moved_t ? 0.5 : 1.0;
}

Vec3 projection(const DirectedResult& r, const BodySide& t, const BodySide& o, bool was_in_contact,
                double held_depth, const StepBuffer& step, double dt, double tolerance) {
  if (step.cascade()) {
    const double depth = r.tpdv.norm(), excess = depth - held_depth;
    if (!r.penetrating() || !(excess > tolerance)) return Vec3::Zero();
    return -cascadeShare(t, o, step) * (excess / depth) * r.tpdv;
  }
  if (step.rowsPass()) return Vec3::Zero();  // rows after the projections, none again
  if (step.impactPass()) return impactProjection(r, t, o, dt, tolerance, held_depth);
  return was_in_contact ? Vec3::Zero() : impactProjection(r, t, o, dt, tolerance);
}

btVector3 impactImpulse(const Vec3& shift, const BodySide& t, const BodySide& o) {
  if (t.body == nullptr || shift.isZero() || !(t.inv_mass > 0.0)) return btVector3(0, 0, 0);
  const btVector3 u = toBt(shift.normalized());  // out of the opponent
  const btVector3 vo =
      o.body != nullptr ? o.velocityAt(o.body->getCenterOfMassPosition()) : o.velocityAt(o.center);
  const double closing = -double((t.body->getLinearVelocity() - vo).dot(u));
  if (!(closing > 0.0)) return btVector3(0, 0, 0);
  const double reduced_mass = 1.0 / (t.inv_mass + o.inv_mass);
  return u * btScalar(reduced_mass * closing);
}

void shiftPoints(std::vector<RowPoint>& points, const Vec3& shift) {
  if (shift.isZero()) return;
  for (RowPoint& p : points) {
    p.point += shift;
    p.separation += p.normal.dot(shift);
  }
}

double rowThreshold(const PairSpring& spring, const PluginSettings& settings, double threshold) {
  return settings.model == ContactModel::Potential && spring.user_stiffness ? 0.0 : threshold;
}

void addRows(const std::vector<RowPoint>& points, int dir, double threshold,
             btManifoldResult* result) {
  // In doubles, converted once: btVector3 arithmetic can be vectorized over its unset
  // fourth lane, which traps when floating-point exceptions are enabled.
  for (const RowPoint& p : points) {
    if (!(p.separation < threshold)) continue;
    if (dir == 0) {
      result->addContactPoint(toBt(p.normal), toBt(p.point - p.separation * p.normal),
                              btScalar(p.separation));
    } else {
      result->addContactPoint(toBt(-p.normal), toBt(p.point), btScalar(p.separation));
    }
  }
}

void softenRows(btPersistentManifold* manifold, const PairSpring& spring, double dt,
                double friction_scale, int patch_rows) {
  const int rows = std::max(1, patch_rows);
  // Derived: rigid velocity rows (cfm 0) whose depth is pushed out at the rate of the
  // spring-damper of frequency omega relative to each row's own effective mass, the
  // mass-free form erp = h omega / (h omega + 2 zeta) (docs/bullet.md).
  const double hw = dt * spring.omega;
  const double erp = hw / (hw + 2.0 * spring.damping_ratio);
  // Set: the implicit spring-damper of kT spread over the rows, critical (times zeta)
  // for the row's share of the reduced mass; Bullet turns (k, c) into
  // erp = dt k / (dt k + c) and cfm = 1 / (dt k + c).
  const double k = spring.stiffness / rows;
  const double c = 2.0 * spring.damping_ratio * std::sqrt(k * spring.mass / rows);
  for (int i = 0; i < manifold->getNumContacts(); ++i) {
    btManifoldPoint& pt = manifold->getContactPoint(i);
    pt.m_combinedFriction *= btScalar(friction_scale);
    if (spring.user_stiffness) {
      pt.m_contactPointFlags |= BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING;
      pt.m_contactPointFlags &=
          ~(BT_CONTACT_FLAG_HAS_CONTACT_CFM | BT_CONTACT_FLAG_HAS_CONTACT_ERP);
      pt.m_combinedContactStiffness1 = btScalar(k);
      pt.m_combinedContactDamping1 = btScalar(c);
    } else {
      pt.m_contactPointFlags |= BT_CONTACT_FLAG_HAS_CONTACT_CFM | BT_CONTACT_FLAG_HAS_CONTACT_ERP;
      pt.m_contactPointFlags &= ~BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING;
      pt.m_contactCFM = 0;
      pt.m_contactERP = btScalar(erp);
    }
  }
}

double springReach(const PairSpring& s, double speed) {
  if (!(s.stiffness > 0.0)) return 0.0;
  return speed * std::sqrt(s.mass / s.stiffness);
}

btVector3 recoveryImpulse(const BodySide& t, const BodySide& o, const btVector3& u, double depth,
                          double speed, double period) {
  const double inv_m = t.inv_mass + o.inv_mass;
  if (t.body == nullptr || !(inv_m > 0.0)) return btVector3(0, 0, 0);
  // Out within one contact period, never faster than `speed`: a pair spawned touching
  // is barely pushed, a deep overlap leaves at `speed`.
  const double d = std::max(0.0, depth);
  const double target = period > 0.0 ? std::min(speed, d / period) : speed;
  const double separating = double((t.velocityAt(t.center) - o.velocityAt(t.center)).dot(u));
  return btScalar(std::max(0.0, target - separating) / inv_m) * u;
}

btVector3 recoveryImpulse(const BodySide& t, const BodySide& o, const btVector3& t_min,
                          const btVector3& t_max, const btVector3& o_min, const btVector3& o_max,
                          double speed, double period) {
  int axis = 0;
  double overlap = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double ov = std::min(t_max[k], o_max[k]) - std::max(t_min[k], o_min[k]);
    if (k == 0 || ov < overlap) {
      overlap = ov;
      axis = k;
    }
  }
  btVector3 u(0, 0, 0);
  const double side = (t_min[axis] + t_max[axis]) - (o_min[axis] + o_max[axis]);
  u[axis] = side < 0.0 ? btScalar(-1) : btScalar(1);
  return recoveryImpulse(t, o, u, overlap, speed, period);
}

void deliver(Plugin& plugin, const BodySide& t, const BodySide& o, const btVector3& impulse,
             const Vec3& projection) {
  btRigidBody* body = t.body;
  if (body == nullptr || (impulse.isZero() && projection.isZero())) return;
  if (!body->isActive()) {
    // A sleeping body wakes when an active body presses on it.
    if (o.body == nullptr || !o.body->isActive()) return;
    body->activate();
  }
  // Recovery impulses act at the placement centre (the body's centre of mass unless
  // the shape is a compound's child).
  const btVector3 lever = t.center - body->getCenterOfMassPosition();
  if (plugin.stepBuffer().worldAttached()) {
    plugin.stepBuffer().addImpulse(body, lever, impulse);
    plugin.stepBuffer().addProjection(body, toBt(projection));
    return;
  }
  body->applyImpulse(impulse, lever);
  if (!projection.isZero()) {
    btTransform x = body->getWorldTransform();
    x.setOrigin(x.getOrigin() + toBt(projection));
    body->setWorldTransform(x);
  }
}

}  // namespace sc::bullet::detail
