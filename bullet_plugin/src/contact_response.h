// SPDX-License-Identifier: MIT
// The potential model's impulses for one direction of a pair (manual 5.9 with
// damping and friction over one substep: explicit spring, implicit damping).
#pragma once

#include <btBulletDynamicsCommon.h>

#include "smartcollision/bullet/settings.h"
#include "smartcollision/collision.h"

namespace sc::bullet {
class Plugin;
}

namespace sc::bullet::detail {

/// A side of a pair as the response sees it. `body` is null for a static or
/// kinematic object (infinite mass: it gets no impulse).
struct BodySide {
  const btCollisionObject* object = nullptr;
  btRigidBody* body = nullptr;
  btVector3 center;  ///< world centre of the placement (the shape's origin)
  double inv_mass = 0.0;
  /// Velocity of the material point at `p` (world); kinematic bodies included.
  btVector3 velocityAt(const btVector3& p) const;
  btVector3 angularVelocity() const;
  /// 1 / (e . I^-1 e), or 0 for an infinite moment.
  double inverseMomentAbout(const btVector3& e) const;
};

/// The side of a Bullet object: its rigid body when dynamic, the world origin of its
/// shape as the centre.
BodySide bodySide(const btCollisionObjectWrapper* w);

/// Linear parts act at the target's placement centre. The velocity part (damping,
/// friction, impact, recovery) is shared among the body's contacts of the substep
/// (Plugin::applyImpulses), the spring part is not.
struct Impulse {
  btVector3 linear = btVector3(0, 0, 0);            ///< spring part
  btVector3 velocity = btVector3(0, 0, 0);          ///< velocity part
  btVector3 angular = btVector3(0, 0, 0);           ///< torque impulse, spring part
  btVector3 angular_velocity = btVector3(0, 0, 0);  ///< torque impulse, velocity part
  double depth = 0.0;
};

/// Impulse on the target T of `r` (penetrating) against the opponent O.
/// F = -kT TPDV and tau = -kR RPDV plus damping of the approach speed, over one
/// substep (never pulls; see springImpulse), plus Coulomb-capped viscous friction at
/// the centre (`friction` = combined coefficient). An approach of more than `impact`
/// per substep is stopped at once.
Impulse potentialImpulse(const DirectedResult& r, const BodySide& t, const BodySide& o,
                         const ContactSettings& c, double dt, double friction, double impact);

/// The depth whose spring energy 1/2 k d^2 equals the recovery bound 1/2 m_red
/// speed^2: a pair first seen within it can take the spring at once (speed / omega).
double springReach(const BodySide& t, const BodySide& o, const ContactSettings& c, double dt,
                   double speed);

/// Pushes T away from O along unit `u` so that they separate at depth / period, at
/// most `speed`: relative kinetic energy at most 1/2 m_red speed^2.
Impulse recoveryImpulse(const BodySide& t, const BodySide& o, const btVector3& u, double depth,
                        double speed, double period);

/// The same along the smallest overlap axis of their (tight) AABBs, the overlap as
/// depth (pairs first seen intersecting, no depth from the core yet).
Impulse recoveryImpulse(const BodySide& t, const BodySide& o, const btVector3& t_min,
                        const btVector3& t_max, const btVector3& o_min, const btVector3& o_max,
                        double speed, double period);

/// Bullet's contact point for a point `p_t` of a target with signed distance `depth`
/// along `n` (from the opponent towards the target); `dir` is the btManifoldResult's
/// body (0 or 1) that is the target.
void addTargetPoint(const Vec3& n, const Vec3& p_t, double depth, int dir,
                    btManifoldResult* result);

/// Buffers in the plugin (or, without an ScDynamicsWorld, applies) the impulse of
/// target `t` at its centre; wakes a sleeping `t` pressed by an active `o`.
void deliver(Plugin& plugin, const BodySide& t, const BodySide& o, const Impulse& imp);

}  // namespace sc::bullet::detail
