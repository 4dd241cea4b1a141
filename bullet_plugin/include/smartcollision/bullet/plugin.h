// SPDX-License-Identifier: MIT
// The plugin object: registered create functions, primitive models, per-body
// settings and the impulse buffer of the potential model. One per dispatcher.
#pragma once

#include <btBulletCollisionCommon.h>
#include <btBulletDynamicsCommon.h>

#include <memory>
#include <unordered_map>
#include <vector>

#include "smartcollision/bullet/settings.h"
#include "smartcollision/bullet/step_stats.h"
#include "smartcollision/model.h"

namespace sc::bullet {

class Plugin {
 public:
  explicit Plugin(const PluginSettings& settings = {});
  ~Plugin();
  Plugin(const Plugin&) = delete;
  Plugin& operator=(const Plugin&) = delete;

  const PluginSettings& settings() const { return settings_; }
  /// InvalidArgument (settings kept) when validate(settings) fails.
  Status setSettings(const PluginSettings& settings);
  ContactModel contactModel() const { return settings_.model; }
  void setContactModel(ContactModel model) {
    settings_.model = model;
    ++settings_version_;
  }
  /// Changes with every change of the settings or of a body's: a pair's kept rows
  /// are only valid under the settings they were made with.
  int settingsVersion() const { return settings_version_; }

  /// Per-body override of the world's ContactSettings. A pair with two overridden
  /// bodies takes the larger stiffnesses and damping ratio and the shorter period.
  /// Every valid setting is honoured as given (the rows are implicit: no stiffness is
  /// clamped); InvalidArgument (nothing kept) otherwise.
  Status setBodySettings(const btCollisionObject* body, const ContactSettings& settings);
  void clearBodySettings(const btCollisionObject* body);
  /// The settings of the pair (a, b) after the overrides.
  ContactSettings pairSettings(const btCollisionObject* a, const btCollisionObject* b) const;

  /// SmartCollision model of a Bullet primitive, built once per shape and cached:
  /// btBoxShape and btConvexHullShape as a convex polytope (corners / points, hulled);
  /// btSphereShape and btCapsuleShape as their core, a point or the axis segment, whose
  /// results the algorithm widens by the radius (nothing is tessellated). Null for any
  /// other shape.
  ModelPtr primitiveModel(const btCollisionShape* shape);

  // Buffer of the direct corrections, filled during collision detection and applied
  // after it (the rows go to Bullet's solver through the pairs' manifolds).
  /// Called by ScDynamicsWorld; without a world the algorithm applies them at once.
  void attachWorld(bool attached) { world_attached_ = attached; }
  bool worldAttached() const { return world_attached_; }
  /// Recovery push of a pair first seen deep: an impulse on `body` at `lever` from
  /// its centre of mass.
  void addImpulse(btRigidBody* body, const btVector3& lever, const btVector3& impulse);
  /// Projection of an impact: `body` is moved by `shift` back to the entry side.
  /// Several projections of one body combine as the largest along each one's
  /// direction (two supports under a landing body do not lift it twice).
  void addProjection(btRigidBody* body, const btVector3& shift);
  void beginStep();
  /// Applies and clears the buffered impulses and projections.
  void applyImpulses();
  /// Set by ScDynamicsWorld around its detection after the integration: only pairs
  /// that may have a fresh impact (apart at their last query, by less than the bodies
  /// could have moved since) are queried then; pairs in contact keep their rows.
  void setImpactPass(bool on) { impact_pass_ = on; }
  bool impactPass() const { return impact_pass_; }
  /// Set by ScDynamicsWorld around a dispatch after projections were applied: only
  /// pairs with a projected body measure their rows again (at the bodies' new poses),
  /// and nothing is pushed or projected.
  void setRowsPass(bool on) { rows_pass_ = on; }
  bool rowsPass() const { return rows_pass_; }
  /// Bodies moved by the last applyImpulses() (none after beginStep()).
  bool anyProjected() const { return !projected_.empty(); }
  bool projected(const btCollisionObject* body) const;

  StepStats& stats() { return stats_; }
  const StepStats& stats() const { return stats_; }

  /// Create functions owned here; the dispatcher keeps raw pointers to them.
  btCollisionAlgorithmCreateFunc* contactCreateFunc() const;
  btCollisionAlgorithmCreateFunc* closestPointsCreateFunc() const;
  /// ScBulletShape against btStaticPlaneShape (ScPlaneAlgorithm).
  btCollisionAlgorithmCreateFunc* planeCreateFunc(bool closest_points) const;

 private:
  struct Impulse {
    btRigidBody* body;
    btVector3 lever;
    btVector3 impulse;
  };
  struct CachedModel {
    ModelPtr model;
    btVector3 signature;  ///< what the model depends on (see primitiveSignature)
  };
  struct CreateFuncs;

  PluginSettings settings_;
  std::unordered_map<const btCollisionObject*, ContactSettings> body_settings_;
  std::unordered_map<const btCollisionShape*, CachedModel> models_;
  std::vector<Impulse> impulses_;
  std::unordered_map<btRigidBody*, btVector3> projections_;  ///< reused every substep
  StepStats stats_;
  bool world_attached_ = false;
  bool impact_pass_ = false;
  bool rows_pass_ = false;
  std::vector<const btCollisionObject*> projected_;
  int settings_version_ = 0;
  std::unique_ptr<CreateFuncs> create_funcs_;
};

/// Construction info whose algorithm pool fits ScCollisionAlgorithm (release builds
/// of Bullet's pool allocator do not check the size). Pass it to
/// btDefaultCollisionConfiguration.
btDefaultCollisionConstructionInfo collisionConstructionInfo();

/// Registers the SmartCollision algorithms for ScBulletShape against ScBulletShape,
/// btBoxShape, btConvexHullShape, btSphereShape, btCapsuleShape (ScCollisionAlgorithm)
/// and btStaticPlaneShape (ScPlaneAlgorithm), both orders, in the contact and the
/// closest-points tables. Pairs of Bullet shapes keep Bullet's algorithms.
/// @return the plugin (keep it alive as long as the dispatcher); InvalidArgument for
///   a null dispatcher or bad settings; InvalidOperation when the dispatcher's
///   algorithm pool is too small (use collisionConstructionInfo()).
Result<std::shared_ptr<Plugin>> registerSmartCollision(btCollisionDispatcher* dispatcher,
                                                       const PluginSettings& settings = {});

}  // namespace sc::bullet
