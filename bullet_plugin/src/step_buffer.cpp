// SPDX-License-Identifier: MIT
#include "step_buffer.h"

#include <algorithm>

namespace sc::bullet::detail {

void StepBuffer::addImpulse(btRigidBody* body, const btVector3& lever, const btVector3& impulse) {
  if (!impulse.isZero() && (!rows_pass_ || cascade()))
    impulses_.push_back(Impulse{body, lever, impulse});
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
  for (const Impulse& i : impulses_) i.body->applyImpulse(i.impulse, i.lever);
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
