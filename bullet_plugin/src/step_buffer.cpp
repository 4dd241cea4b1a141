// SPDX-License-Identifier: MIT
#include "step_buffer.h"

#include <algorithm>

namespace sc::bullet::detail {

void StepBuffer::addImpulse(btRigidBody* body, const btVector3& lever, const btVector3& impulse) {
  if (impulse.isZero() || (rows_pass_ && !cascade())) return;
  const btScalar size = impulse.length();
  auto [it, fresh] = impulses_.try_emplace(body, Impulse{impulse, lever * size, size});
  if (fresh) return;
  Impulse& total = it->second;
  total.weighted_lever += lever * size;
  total.weight += size;
  if (total.impulse.fuzzyZero()) {  // opposite ones cancelled
    total.impulse += impulse;
    return;
  }
  const btVector3 along = total.impulse.normalized();
  const btScalar reach = impulse.dot(along);
  if (reach > 0)
    total.impulse = along * std::max(total.impulse.length(), reach) + (impulse - along * reach);
  else
    total.impulse += impulse;
}

void StepBuffer::addProjection(btRigidBody* body, const btVector3& shift) {
  if (shift.isZero() || (rows_pass_ && !cascade())) return;
  auto [it, fresh] = projections_.try_emplace(body, shift);
  if (fresh) return;
  btVector3& total = it->second;
  const btVector3 along = total.normalized();
  const btScalar reach = shift.dot(along);
  total = along * std::max(total.length(), reach) + (shift - along * reach);
}

void StepBuffer::begin() {
  impulses_.clear();
  projections_.clear();
  projected_.clear();
  moved_by_last_ = false;
  stats_ = StepStats();
}

void StepBuffer::apply() {
  for (const auto& [body, i] : impulses_)
    body->applyImpulse(i.impulse, i.weighted_lever / i.weight);
  impulses_.clear();
  moved_by_last_ = !projections_.empty();
  for (auto& [body, shift] : projections_) {
    btTransform x = body->getWorldTransform();
    x.setOrigin(x.getOrigin() + shift);
    body->setWorldTransform(x);
    projected_.insert(body);
  }
  projections_.clear();
}

bool StepBuffer::projected(const btCollisionObject* body) const {
  return projected_.count(body) != 0;
}

}  // namespace sc::bullet::detail
