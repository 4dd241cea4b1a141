// SPDX-License-Identifier: MIT
// The plugin object: registered create functions, shape models, per-body
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

namespace detail {
class StepBuffer;
}

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
  void setContactModel(ContactModel model);

  /// Per-body override of the world's ContactSettings. A pair with two overridden
  /// bodies takes the larger stiffnesses and damping ratio and the shorter period.
  /// Every valid setting is honoured as given (the rows are implicit: no stiffness is
  /// clamped); InvalidArgument (nothing kept) otherwise. Kept by the body's address:
  /// ScDynamicsWorld clears it when the body is removed; with another world, call
  /// clearBodySettings before deleting the body.
  Status setBodySettings(const btCollisionObject* body, const ContactSettings& settings);
  void clearBodySettings(const btCollisionObject* body);
  /// The settings of the pair (a, b) after the overrides.
  ContactSettings pairSettings(const btCollisionObject* a, const btCollisionObject* b) const;

  /// SmartCollision model of a shape, as the algorithms take it: an ScBulletShape's
  /// own; btBoxShape and btConvexHullShape as a convex polytope (corners / points,
  /// hulled); btSphereShape and btCapsuleShape as their core, a point or the axis
  /// segment, whose results the algorithm widens by the radius (nothing is
  /// tessellated); btBvhTriangleMeshShape (any btTriangleMeshShape) and
  /// btScaledBvhTriangleMeshShape as a triangle soup of all their subparts, scaled.
  /// Built once per shape and cached (rebuilt when the shape changes: see
  /// docs/bullet.md); the first pair of a shape builds it, or call this ahead (a large
  /// mesh takes a while). Without a model (a flat hull, a mesh without triangles or
  /// with a NaN) the shape's pairs are ignored; the status says why.
  Result<ModelPtr> shapeModel(const btCollisionShape* shape);

  /// What the last collision detection saw.
  const StepStats& stats() const;
  /// The state of the current step (internal: ScDynamicsWorld and the algorithms).
  detail::StepBuffer& stepBuffer() { return *step_; }

  /// Create functions owned here; the dispatcher keeps raw pointers to them.
  btCollisionAlgorithmCreateFunc* contactCreateFunc() const;
  btCollisionAlgorithmCreateFunc* closestPointsCreateFunc() const;
  /// ScBulletShape against btStaticPlaneShape (ScPlaneAlgorithm).
  btCollisionAlgorithmCreateFunc* planeCreateFunc(bool closest_points) const;

 private:
  struct CachedModel {
    ModelPtr model;
    Status status;            ///< why there is no model
    std::vector<double> key;  ///< everything the model depends on (see shapeKey)
  };
  struct CreateFuncs;

  PluginSettings settings_;
  std::unordered_map<const btCollisionObject*, ContactSettings> body_settings_;
  std::unordered_map<const btCollisionShape*, CachedModel> models_;
  std::unique_ptr<detail::StepBuffer> step_;
  std::unique_ptr<CreateFuncs> create_funcs_;
};

/// Construction info whose algorithm pool fits ScCollisionAlgorithm (release builds
/// of Bullet's pool allocator do not check the size). Pass it to
/// btDefaultCollisionConfiguration.
btDefaultCollisionConstructionInfo collisionConstructionInfo();

/// Registers the SmartCollision algorithms for ScBulletShape against ScBulletShape,
/// btBoxShape, btConvexHullShape, btSphereShape, btCapsuleShape, btTriangleMeshShape
/// (btBvhTriangleMeshShape) and btScaledBvhTriangleMeshShape (ScCollisionAlgorithm)
/// and btStaticPlaneShape (ScPlaneAlgorithm), both orders, in the contact and the
/// closest-points tables. Pairs of Bullet shapes keep Bullet's algorithms.
/// @return the plugin (keep it alive as long as the dispatcher); InvalidArgument for
///   a null dispatcher or bad settings; InvalidOperation when the dispatcher's
///   algorithm pool is too small (use collisionConstructionInfo()) or a live plugin is
///   already registered on it (the dispatcher is left as it was).
Result<std::shared_ptr<Plugin>> registerSmartCollision(btCollisionDispatcher* dispatcher,
                                                       const PluginSettings& settings = {});

}  // namespace sc::bullet
