// SPDX-License-Identifier: MIT
// Implicit spring-damper impulses of the potential model and the overlap push.
#include "contact_response.h"

#include <algorithm>
#include <cmath>

#include "smartcollision/bullet/plugin.h"

namespace sc::bullet::detail {

namespace {

constexpr double kTwoPi = 6.283185307179586;

btVector3 toBt(const Vec3& v) {
  return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
}

/// Impulse of the spring-damper m x'' = -k x - c x' over one substep, x the depth and
/// v its rate (approach speed), split into its spring part (dt k x: explicit, so a
/// resting contact carries exactly k x) and its velocity part (damping, implicit for
/// a body of mass m_damp, i.e. divided by 1 + dt c/m_damp + dt^2 k/m_damp; stable for
/// dt^2 k / m <= 1, where k is clamped). An impact (approach of more than `impact`
/// per substep) loses its approach speed at once (restitution 0), so nothing passes a
/// thin wall. The sum is >= 0: a contact never pulls.
struct SpringParts {
  double spring = 0.0;
  double velocity = 0.0;
  double total() const { return spring + velocity; }
};

SpringParts springImpulse(double m, double m_damp, double k, double c, double depth, double v,
                          double dt, double impact) {
  k = std::min(k, m / (dt * dt));
  SpringParts p;
  p.spring = dt * k * depth;
  p.velocity = dt * (c + k * dt) * v / (1.0 + dt * c / m_damp + dt * dt * k / m_damp);
  if (v * dt > impact && p.total() < m * v) p.velocity = m * v - p.spring;
  if (p.total() < 0.0) p.velocity = -p.spring;
  return p;
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

void deliver(Plugin& plugin, const BodySide& t, const BodySide& o, const Impulse& imp) {
  btRigidBody* body = t.body;
  if (body == nullptr || (imp.linear.isZero() && imp.velocity.isZero() && imp.angular.isZero() &&
                          imp.angular_velocity.isZero()))
    return;
  if (!body->isActive()) {
    // A sleeping body wakes when an active body presses on it.
    if (o.body == nullptr || !o.body->isActive()) return;
    body->activate();
  }
  // Impulses act at the placement centre (the body's centre of mass unless the shape
  // is a compound's child).
  const btVector3 lever = t.center - body->getCenterOfMassPosition();
  if (plugin.worldAttached()) {
    plugin.addImpulse(body, lever, imp.linear, imp.velocity, imp.angular, imp.angular_velocity);
  } else {
    body->applyCentralImpulse(imp.linear + imp.velocity);
    body->applyTorqueImpulse(imp.angular + imp.angular_velocity +
                             lever.cross(imp.linear + imp.velocity));
  }
}

void addTargetPoint(const Vec3& n, const Vec3& p_t, double depth, int dir,
                    btManifoldResult* result) {
  // In doubles, converted once: btVector3 arithmetic can be vectorized over its unset
  // fourth lane, which traps when floating-point exceptions are enabled.
  if (dir == 0) {
    result->addContactPoint(toBt(n), toBt(p_t - depth * n), btScalar(depth));
  } else {
    result->addContactPoint(toBt(-n), toBt(p_t), btScalar(depth));
  }
}

btVector3 BodySide::velocityAt(const btVector3& p) const {
  const auto* rb = btRigidBody::upcast(object);
  if (rb == nullptr) return btVector3(0, 0, 0);
  return rb->getVelocityInLocalPoint(p - rb->getCenterOfMassPosition());
}

btVector3 BodySide::angularVelocity() const {
  const auto* rb = btRigidBody::upcast(object);
  return rb == nullptr ? btVector3(0, 0, 0) : rb->getAngularVelocity();
}

double BodySide::inverseMomentAbout(const btVector3& e) const {
  if (body == nullptr) return 0.0;
  return std::max(0.0, double(e.dot(body->getInvInertiaTensorWorld() * e)));
}

Impulse potentialImpulse(const DirectedResult& r, const BodySide& t, const BodySide& o,
                         const ContactSettings& c, double dt, double friction, double impact) {
  Impulse out;
  const double inv_m = t.inv_mass + o.inv_mass;
  if (t.body == nullptr || !(inv_m > 0.0) || !(dt > 0.0)) return out;
  const double m = 1.0 / inv_m;
  const double omega = kTwoPi / (c.contact_period_steps * dt);
  // Clamped here, not only in springImpulse: the damping below must be critical for
  // the stiffness that acts, not for the one requested.
  const double k =
      std::min(c.force_stiffness > 0.0 ? c.force_stiffness : m * omega * omega, m / (dt * dt));
  // Damping: critical for the reduced mass, except that the heavier body of a pair
  // is damped as if its opponent were fixed (its own mass): with the reduced mass a
  // 100 kg box on a 1 kg one is damped at 7% of critical and keeps bouncing. The
  // lighter body's share stays as it was, so one step never reverses the pair's
  // relative velocity (the two shares add to less than 1).
  const double m_t = t.inv_mass < o.inv_mass ? 1.0 / t.inv_mass : m;
  const double damp = 2.0 * c.damping_ratio * std::sqrt(k * m_t);

  // Separation direction: back along TPDV, or the normal when T only touches.
  const double depth = r.tpdv.norm();
  out.depth = depth;
  const btVector3 u = toBt(depth > 1e-12 ? Vec3(-r.tpdv / depth) : r.normal);
  const btVector3 p = toBt(r.point_on_opponent);
  const btVector3 v_rel = t.velocityAt(p) - o.velocityAt(p);
  const double approach = -double(v_rel.dot(u));
  const SpringParts jn = springImpulse(m, m_t, k, damp, depth, approach, dt, impact);
  out.linear = btScalar(jn.spring) * u;
  out.velocity = btScalar(jn.velocity) * u;

  // Friction: remove the sliding velocity, at most mu * normal impulse.
  const btVector3 v_t = v_rel - v_rel.dot(u) * u;
  const double slide = v_t.length();
  if (slide > 1e-9 && friction > 0.0) {
    const double jt = std::min(m * slide, friction * c.friction_scale * jn.total());
    out.velocity -= btScalar(jt / slide) * v_t;
  }

  // Torque from the RPDV (zero in RotationMode::Input).
  const double angle = r.rpdv.norm();
  if (angle > 1e-12) {
    const btVector3 e = toBt(-r.rpdv / angle);
    const double inv_i = t.inverseMomentAbout(e) + o.inverseMomentAbout(e);
    if (inv_i > 0.0) {
      const double i = 1.0 / inv_i;
      const double kr = std::min(c.torque_stiffness > 0.0 ? c.torque_stiffness : i * omega * omega,
                                 i / (dt * dt));
      const double dr = 2.0 * c.damping_ratio * std::sqrt(kr * i);
      const double w_approach = -double((t.angularVelocity() - o.angularVelocity()).dot(e));
      // Parts kept apart: the velocity part is shared among the body's contacts
      // (Plugin::applyImpulses), as the linear one is; whole, a box held by four
      // neighbours lost 2.5x its angular velocity per substep and the pyramid blew up.
      const SpringParts jr = springImpulse(i, i, kr, dr, angle, w_approach, dt, kInfinity);
      out.angular = btScalar(jr.spring) * e;
      out.angular_velocity = btScalar(jr.velocity) * e;
    }
  }
  return out;
}

double springReach(const BodySide& t, const BodySide& o, const ContactSettings& c, double dt,
                   double speed) {
  const double inv_m = t.inv_mass + o.inv_mass;
  if (!(inv_m > 0.0) || !(dt > 0.0)) return 0.0;
  const double m = 1.0 / inv_m;
  const double omega = kTwoPi / (c.contact_period_steps * dt);
  const double k =
      std::min(c.force_stiffness > 0.0 ? c.force_stiffness : m * omega * omega, m / (dt * dt));
  return speed * std::sqrt(m / k);
}

Impulse recoveryImpulse(const BodySide& t, const BodySide& o, const btVector3& u, double depth,
                        double speed, double period) {
  Impulse out;
  const double inv_m = t.inv_mass + o.inv_mass;
  if (t.body == nullptr || !(inv_m > 0.0)) return out;
  out.depth = std::max(0.0, depth);
  // Out within one contact period, never faster than `speed`: a pair spawned touching
  // is barely pushed, a deep overlap leaves at `speed`.
  const double target = period > 0.0 ? std::min(speed, out.depth / period) : speed;
  const double separating = double((t.velocityAt(t.center) - o.velocityAt(t.center)).dot(u));
  out.velocity = btScalar(std::max(0.0, target - separating) / inv_m) * u;
  return out;
}

Impulse recoveryImpulse(const BodySide& t, const BodySide& o, const btVector3& t_min,
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

}  // namespace sc::bullet::detail
