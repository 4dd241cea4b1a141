// SPDX-License-Identifier: MIT
// StepBuffer: the plugin's state within one step of the world, shared by
// ScDynamicsWorld and the algorithms (not installed): the direct corrections
// gathered during a detection and applied after it, which detection pass is running,
// and the step's statistics.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "smartcollision/bullet/step_stats.h"

namespace sc::bullet::detail {

class StepBuffer {
 public:
  /// Set by ScDynamicsWorld; without a world the algorithms apply corrections at once.
  void attachWorld(bool attached) { world_attached_ = attached; }
  bool worldAttached() const { return world_attached_; }

  /// Recovery push or impact impulse: an impulse on `body` at `lever` from its centre
  /// of mass. Each is the whole change of velocity its pair needs, so several on one
  /// body combine as the largest along each one's direction (the children of a
  /// compound landing together, or two supports, do not each stop it) and add where
  /// they oppose; they act at their levers' mean, weighted by their sizes.
  void addImpulse(btRigidBody* body, const btVector3& lever, const btVector3& impulse);
  /// Projection of an impact: `body` is moved by `shift` back to the entry side.
  /// Several projections of one body combine as the largest along each one's
  /// direction (two supports under a landing body do not lift it twice).
  void addProjection(btRigidBody* body, const btVector3& shift);
  /// Starts a detection: nothing buffered, nothing projected, statistics zero.
  void begin();
  /// Applies and clears the buffered impulses and projections.
  void apply();

  /// The detection after the integration: only pairs that may have a fresh impact
  /// (apart at their last query, by less than the bodies could have moved since) are
  /// queried; pairs in contact keep their rows.
  void setImpactPass(bool on) { impact_pass_ = on; }
  bool impactPass() const { return impact_pass_; }
  /// The dispatch after projections: only pairs with a projected body measure their
  /// rows again (at its new pose). Nothing is pushed or projected, except in a cascade.
  void setRowsPass(bool on) { rows_pass_ = on; }
  bool rowsPass() const { return rows_pass_; }
  /// A rows pass after the integration: a body that a projected one was put back into
  /// is moved out of it in turn (a landing body put back onto the one that fell
  /// behind it), and so on down the chain.
  bool cascade() const { return impact_pass_ && rows_pass_; }
  /// Bodies moved by projections since begin().
  bool anyProjected() const { return !projected_.empty(); }
  bool projected(const btCollisionObject* body) const;
  /// True when the last apply() moved a body (false after begin()).
  bool movedByLastApply() const { return moved_by_last_; }

  /// Changes with every change of the plugin's settings or of a body's: a pair's kept
  /// rows are only valid under the settings they were made with.
  int settingsVersion() const { return settings_version_; }
  void settingsChanged() { ++settings_version_; }

  StepStats& stats() { return stats_; }
  const StepStats& stats() const { return stats_; }

 private:
  struct Impulse {
    btVector3 impulse;
    btVector3 weighted_lever;  ///< sum of lever * |impulse| over the combined ones
    btScalar weight;           ///< sum of |impulse|
  };
  std::unordered_map<btRigidBody*, Impulse> impulses_;       ///< reused every detection
  std::unordered_map<btRigidBody*, btVector3> projections_;  ///< reused every detection
  std::unordered_set<const btCollisionObject*> projected_;   ///< each body once
  StepStats stats_;
  bool world_attached_ = false;
  bool impact_pass_ = false;
  bool rows_pass_ = false;
  bool moved_by_last_ = false;
  int settings_version_ = 0;
};

}  // namespace sc::bullet::detail
