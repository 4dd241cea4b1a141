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
#include "smartcollision/model.h"

namespace sc::bullet {

/// What the last collision detection saw (for metrics and tests).
struct StepStats {
  int pairs = 0;              ///< pairs the algorithm ran on
  int penetrating = 0;        ///< directions with a penetration depth
  int recovering = 0;         ///< directions first seen intersecting (AABB push)
  double max_depth = 0.0;     ///< largest |TPDV| [m]
  double max_rotation = 0.0;  ///< largest |RPDV| [rad]
  int projected = 0;          ///< directions whose impact was projected to the entry side
  int rows = 0;               ///< contact rows handed to Bullet's solver
  int dropped_rows = 0;       ///< row candidates beyond the patches a pair keeps
  /// directions in contact this step: a row touching, or whose gap closes within the
  /// step at the current approach speed (the rows stop a body at the surface, so an
  /// impact shows here before any penetration does)
  int touching = 0;
  /// pairs not queried: apart at their last query by more than the bodies could have
  /// moved towards each other since (a conservative bound), so nothing can respond
  int skipped = 0;
};

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
  void setContactModel(ContactModel model) { settings_.model = model; }

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
