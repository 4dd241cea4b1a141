// SPDX-License-Identifier: MIT
// StackingSolver: Bullet's sequential-impulse solver plus a shock-propagation pass
// that lets stacks of very different masses (a 1000 kg box on a 1 kg box) stand, and
// contact springs that hold at any depth under split impulse.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <vector>

namespace sc::bullet {

/// btSequentialImpulseConstraintSolver whose iterations are followed, in a solve group
/// where a body rests on one at least `kShockMassRatio` times lighter, by a few
/// bottom-up sweeps over the contacts whose normal is within 45 degrees of gravity,
/// in which the lower body counts as immovable (shock propagation, Erleben 2004).
///
/// Why: with a 1:1000 mass ratio the sequential impulses do not converge within
/// hundreds of iterations (each iteration passes a light body a small part of the
/// heavy one's weight), the heavy body sinks into the light one and squeezes it out
/// sideways. The sweep removes the remaining approach of each upper body layer by
/// layer, from the ground up; its impulses act on the upper body only, so they are
/// not momentum-conserving, and are kept in the rows' applied impulses, which warm
/// start the next step with a closer estimate of the load. Groups without such a
/// mass ratio (towers, piles of like bodies) are solved exactly as by Bullet.
///
/// Contact rows that are springs (BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING: a set
/// ContactSettings::contact_stiffness) keep their depth term in the velocity solve at
/// any depth. Why: with split impulse on, Bullet moves the depth term of a row deeper
/// than m_splitImpulsePenetrationThreshold (-4 cm by default) to its position-only
/// pass. The velocities then meet only the row's damper (c + dt k), the spring pushes
/// positions alone, scaled down by the row's softness, and a body whose sag load / kT
/// exceeds the threshold sinks (1 kg on 100 N/m: 471 mm after 12 s instead of 98 mm;
/// through a 2 m ground at 240 Hz). Other rows (the derived stiffness, Bullet's rigid
/// contacts) keep Bullet's split, which their deep overlaps rely on.
class StackingSolver : public btSequentialImpulseConstraintSolver {
 public:
  /// A contact whose upper body is at least this many times heavier than its
  /// (dynamic) lower body turns the sweeps on for its solve group.
  static constexpr double kShockMassRatio = 10.0;
  /// Bottom-up sweeps per step (each settles one more row layer within a body's
  /// support polygon).
  static constexpr int kShockSweeps = 8;

 protected:
  void convertContacts(btPersistentManifold** manifolds, int numManifolds,
                       const btContactSolverInfo& info) override;
  btScalar solveGroupCacheFriendlyIterations(btCollisionObject** bodies, int numBodies,
                                             btPersistentManifold** manifolds, int numManifolds,
                                             btTypedConstraint** constraints, int numConstraints,
                                             const btContactSolverInfo& info,
                                             btIDebugDraw* debugDrawer) override;

 private:
  struct ShockRow {
    btScalar height;  ///< contact point along -gravity
    int row;          ///< index in the contact pool
    bool upper_is_a;  ///< body A of the row is the upper one
  };
  /// Collects the near-vertical contact rows, sorted bottom-up; false when no row
  /// has the mass ratio that needs the sweeps.
  bool collectShockRows();
  void sweep(const btContactSolverInfo& info);
  std::vector<ShockRow> rows_;  ///< reused from step to step
};

}  // namespace sc::bullet
