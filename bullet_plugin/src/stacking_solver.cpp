// SPDX-License-Identifier: MIT
// StackingSolver: spring rows unsplit; Bullet's iterations, then bottom-up
// shock-propagation sweeps.
#include "smartcollision/bullet/stacking_solver.h"

#include <algorithm>

namespace sc::bullet {
namespace {

// A contact within 45 degrees of gravity takes part in the sweeps.
constexpr btScalar kVerticalCos = btScalar(0.7071);

btScalar inverseMass(const btSolverBody& b) {
  return b.m_originalBody ? b.m_originalBody->getInvMass() : btScalar(0);
}

/// One row solved for the upper body alone (the lower one immovable), clamped to
/// [lo, hi] in its accumulated impulse. The row's target velocity, softness (cfm)
/// and relaxation are Bullet's own, recovered from its scaled form.
void solveUpperOnly(btSolverBody& a, btSolverBody& b, btSolverConstraint& c, bool upper_is_a,
                    btScalar lo, btScalar hi, btScalar relaxation) {
  if (c.m_jacDiagABInv == btScalar(0)) return;
  btSolverBody& u = upper_is_a ? a : b;
  const btVector3& n = upper_is_a ? c.m_contactNormal1 : c.m_contactNormal2;
  const btVector3& rxn = upper_is_a ? c.m_relpos1CrossNormal : c.m_relpos2CrossNormal;
  const btVector3& ang = upper_is_a ? c.m_angularComponentA : c.m_angularComponentB;
  const btScalar denom = n.dot(n * u.internalGetInvMass()) + rxn.dot(ang);
  if (!(denom > btScalar(0))) return;
  // Bullet stores rhs = target * jac, cfm = cfm' * jac with jac = relaxation / (dA + dB + cfm').
  const btScalar full = btScalar(1) / c.m_jacDiagABInv;
  const btScalar cfm = c.m_cfm * full;
  const btScalar jac = relaxation / (denom + cfm);
  const btScalar dv = c.m_contactNormal1.dot(a.internalGetDeltaLinearVelocity()) +
                      c.m_relpos1CrossNormal.dot(a.internalGetDeltaAngularVelocity()) +
                      c.m_contactNormal2.dot(b.internalGetDeltaLinearVelocity()) +
                      c.m_relpos2CrossNormal.dot(b.internalGetDeltaAngularVelocity());
  const btScalar applied = c.m_appliedImpulse;
  btScalar delta = jac * (c.m_rhs * full - applied * cfm - dv);
  const btScalar sum = std::clamp(applied + delta, lo, hi);
  delta = sum - applied;
  c.m_appliedImpulse = sum;
  u.internalApplyImpulse(n * u.internalGetInvMass(), ang, delta);
}

/// True when Bullet set the row up from the point's stiffness and damping (its own
/// cfm/erp flags take precedence in setupContactConstraint).
bool isSpringRow(const btSolverConstraint& c) {
  const auto* point = static_cast<const btManifoldPoint*>(c.m_originalContactPoint);
  if (point == nullptr) return false;
  const int flags = point->m_contactPointFlags;
  return (flags & BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING) != 0 &&
         (flags & (BT_CONTACT_FLAG_HAS_CONTACT_CFM | BT_CONTACT_FLAG_HAS_CONTACT_ERP)) == 0;
}

}  // namespace

void StackingSolver::convertContacts(btPersistentManifold** manifolds, int numManifolds,
                                     const btContactSolverInfo& info) {
  btSequentialImpulseConstraintSolver::convertContacts(manifolds, numManifolds, info);
  // A split row's depth impulse is m_rhsPenetration and its velocity one m_rhs; unsplit,
  // Bullet's rhs is their sum: a spring's force acts through the velocities again.
  for (int i = 0; i < m_tmpSolverContactConstraintPool.size(); ++i) {
    btSolverConstraint& c = m_tmpSolverContactConstraintPool[i];
    if (c.m_rhsPenetration == btScalar(0) || !isSpringRow(c)) continue;
    c.m_rhs += c.m_rhsPenetration;
    c.m_rhsPenetration = btScalar(0);
  }
}

btScalar StackingSolver::solveGroupCacheFriendlyIterations(
    btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
    btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& info,
    btIDebugDraw* debugDrawer) {
  const btScalar residual = btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyIterations(
      bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
  if (collectShockRows()) sweep(info);
  return residual;
}

bool StackingSolver::collectShockRows() {
  rows_.clear();
  bool ratio = false;
  for (int i = 0; i < m_tmpSolverContactConstraintPool.size(); ++i) {
    const btSolverConstraint& c = m_tmpSolverContactConstraintPool[i];
    const btSolverBody& a = m_tmpSolverBodyPool[c.m_solverBodyIdA];
    const btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdB];
    const btRigidBody* dynamic = a.m_originalBody ? a.m_originalBody : b.m_originalBody;
    if (dynamic == nullptr || c.m_originalContactPoint == nullptr) continue;
    const btVector3 g = dynamic->getGravity();
    if (g.length2() <= btScalar(0)) continue;
    const btVector3 up = -g.normalized();
    // The point's normal: a row keeps it only on the side of a dynamic body.
    const auto* point = static_cast<const btManifoldPoint*>(c.m_originalContactPoint);
    const btScalar along = point->m_normalWorldOnB.dot(up);  // > 0: A above B
    if (std::abs(along) < kVerticalCos) continue;
    const bool upper_is_a = along > 0;
    const btScalar upper_inv = inverseMass(upper_is_a ? a : b);
    const btScalar lower_inv = inverseMass(upper_is_a ? b : a);
    if (upper_inv <= btScalar(0)) continue;
    ratio = ratio || lower_inv >= btScalar(kShockMassRatio) * upper_inv;
    rows_.push_back({point->getPositionWorldOnB().dot(up), i, upper_is_a});
  }
  if (!ratio) return false;
  std::sort(rows_.begin(), rows_.end(),
            [](const ShockRow& l, const ShockRow& r) { return l.height < r.height; });
  return true;
}

void StackingSolver::sweep(const btContactSolverInfo& info) {
  const btScalar huge = btScalar(BT_LARGE_FLOAT);
  for (int s = 0; s < kShockSweeps; ++s) {
    for (const ShockRow& r : rows_) {
      btSolverConstraint& c = m_tmpSolverContactConstraintPool[r.row];
      btSolverBody& a = m_tmpSolverBodyPool[c.m_solverBodyIdA];
      btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdB];
      solveUpperOnly(a, b, c, r.upper_is_a, c.m_lowerLimit, huge, info.m_sor);
      // Its friction rows follow it in the friction pool and name it.
      for (int f = c.m_frictionIndex; f < m_tmpSolverContactFrictionConstraintPool.size(); ++f) {
        btSolverConstraint& fr = m_tmpSolverContactFrictionConstraintPool[f];
        if (fr.m_frictionIndex != r.row) break;
        const btScalar limit = btFabs(fr.m_friction * c.m_appliedImpulse);
        solveUpperOnly(a, b, fr, r.upper_is_a, -limit, limit, info.m_sor);
      }
    }
  }
}

}  // namespace sc::bullet
