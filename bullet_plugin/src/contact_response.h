// SPDX-License-Identifier: MIT
// The one contact responder of every SmartCollision algorithm: a direction's contact
// points (the support polygon of its result) become rows of Bullet's solver, soft in
// the potential model (an implicit spring-damper, manual 5.9), rigid in the manifold
// model; an impact is projected back to the entry side first; pairs first seen deep
// get a bounded push.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <vector>

#include "smartcollision/bullet/settings.h"
#include "smartcollision/collision.h"

namespace sc::bullet {
class Plugin;
}

namespace sc::bullet::detail {

class StepBuffer;

/// A side of a pair as the response sees it. `body` is null for a static or
/// kinematic object (infinite mass: it gets no impulse).
struct BodySide {
  const btCollisionObject* object = nullptr;
  btRigidBody* body = nullptr;
  btVector3 center;  ///< world centre of the placement (the shape's origin)
  double inv_mass = 0.0;
  /// Velocity of the material point at `p` (world); kinematic bodies included.
  btVector3 velocityAt(const btVector3& p) const;
};

/// The side of a Bullet object: its rigid body when dynamic, the world origin of its
/// shape as the centre.
BodySide bodySide(const btCollisionObjectWrapper* w);

/// One row candidate of a direction: a point of the target at its current pose, the
/// unit normal from the opponent towards the target, and the signed separation along
/// it (< 0 penetrating). World coordinates.
struct RowPoint {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  double separation = 0.0;
  bool exact = false;   ///< a corner of a convex piece, measured on a convex opponent
  bool corner = false;  ///< a corner of a convex piece (exact or on a face's plane)
};

/// A plane in world coordinates: outward unit normal and offset.
struct WorldPlane {
  Vec3 normal = Vec3::UnitY();
  double offset = 0.0;
  double distance(const Vec3& p) const { return normal.dot(p) - offset; }
};

/// Candidates kept per direction, deepest first (Bullet's manifold keeps 4 per pair:
/// the deepest and the widest polygon among what it is given).
constexpr int kMaxRowPoints = 16;

/// True when a row of `points` touches, or its gap closes within `dt` at the
/// approach speed of T (side `t`) towards O (side `o`) at the row's point.
bool anyTouching(const std::vector<RowPoint>& points, const BodySide& t, const BodySide& o,
                 double dt);

/// Keeps the `kMaxRowPoints` deepest of `points` (in place).
void keepDeepest(std::vector<RowPoint>& points);

/// The pair's spring of the potential model, before it is spread over the rows.
struct PairSpring {
  double stiffness = 0.0;  ///< kT [N/m]: the user's, or m omega^2
  bool user_stiffness = false;
  double mass = 0.0;  ///< reduced mass of the pair [kg]
  double damping_ratio = 1.0;
  double omega = 0.0;  ///< 2 pi / contact period [rad/s]
};

/// The spring of a pair: kT = contact_stiffness when set, else m omega^2 with
/// omega = 2 pi / (contact_period_steps dt).
PairSpring pairSpring(const BodySide& a, const BodySide& b, const ContactSettings& c, double dt);

/// Projection of an impact: when the target approached the opponent by more than
/// `tolerance` in this step and the result is deeper than `held_depth` (the depth the
/// rows already held, 0 for a fresh impact) by more than `tolerance`, the target's
/// share of that excess along -TPDV brings it back at once; zero otherwise. The share
/// is the target's part of the approach speed at the contact (all of it against a
/// static opponent); its approach speed is impactImpulse's and the rows'.
Vec3 impactProjection(const DirectedResult& r, const BodySide& t, const BodySide& o, double dt,
                      double tolerance, double held_depth = 0.0);

/// The projection of target `t` for result `r`, one rule for every algorithm: at the
/// step's detection a fresh impact's (impactProjection; a pair that was in contact is
/// its rows' to hold); after the integration the depth beyond `held_depth` (the
/// detection's: a second region of a pair in contact struck where no row stood); in a
/// cascade the excess over `held_depth` of a pair with a projected side, taken by the
/// side that may move (cascadeShare); in any other rows pass none.
Vec3 projection(const DirectedResult& r, const BodySide& t, const BodySide& o, bool was_in_contact,
                double held_depth, const StepBuffer& step, double dt, double tolerance);

/// The target's share of a cascade's excess: a body a projected one was put back into
/// moves out of it whole, a projected body out of a static one whole, two projected
/// bodies half each; a projected body does not move for one that was not.
double cascadeShare(const BodySide& t, const BodySide& o, const StepBuffer& step);

/// The plastic impulse on the target of a projected impact (`shift` from
/// impactProjection): cancels its share of the centres of mass' approach along the
/// shift, as a restitution-0 collision through the centres would. The rows alone would
/// absorb a fast approach in one sequential solve, unevenly across their points, and
/// send the body off spinning; this leaves them only the residual.
btVector3 impactImpulse(const Vec3& shift, const BodySide& t, const BodySide& o);

/// Moves the points with the target by `shift`: separations grow by normal . shift.
void shiftPoints(std::vector<RowPoint>& points, const Vec3& shift);

/// The separation below which a point becomes a row: the manifold's threshold
/// (speculative rows: a gap closing within the step is stopped at the surface), but
/// 0 for a set stiffness of the potential model, a spring that acts on depth only
/// (a speculative row would stop the body rigidly, whatever its spring).
double rowThreshold(const PairSpring& spring, const PluginSettings& settings, double threshold);

/// Adds the points below `threshold` to the manifold result; `dir` is the result's
/// body (0 or 1) that is the target.
void addRows(const std::vector<RowPoint>& points, int dir, double threshold,
             btManifoldResult* result);

/// Potential model: every point of `manifold` becomes a row of the spring-damper.
/// Derived stiffness: a rigid velocity row whose depth recovers at the spring's rate
/// (erp = h omega / (h omega + 2 zeta), cfm 0). Set stiffness: the implicit spring
/// kT / rows (Bullet's erp = dt k / (dt k + c), cfm = 1 / (dt k + c)). Friction scaled.
/// `rows`: the rows a set kT is spread over (a patch's).
void softenRows(btPersistentManifold* manifold, const PairSpring& spring, double dt,
                double friction_scale, int rows);

/// The depth whose spring energy 1/2 k d^2 equals the recovery bound 1/2 m_red
/// speed^2: a pair first seen within it can take the rows at once (speed / omega).
double springReach(const PairSpring& s, double speed);

/// Velocity change pushing T away from O along unit `u` so that they separate at
/// depth / period, at most `speed`: relative kinetic energy at most 1/2 m_red speed^2.
btVector3 recoveryImpulse(const BodySide& t, const BodySide& o, const btVector3& u, double depth,
                          double speed, double period);

/// The same along the smallest overlap axis of their (tight) AABBs, the overlap as
/// depth (pairs first seen intersecting, no depth from the core yet).
btVector3 recoveryImpulse(const BodySide& t, const BodySide& o, const btVector3& t_min,
                          const btVector3& t_max, const btVector3& o_min, const btVector3& o_max,
                          double speed, double period);

/// Buffers in the plugin (or, without an ScDynamicsWorld, applies) the central
/// impulse of a recovery and the projection of an impact of target `t`; wakes a
/// sleeping `t` pressed by an active `o`.
void deliver(Plugin& plugin, const BodySide& t, const BodySide& o, const btVector3& impulse,
             const Vec3& projection);

}  // namespace sc::bullet::detail
