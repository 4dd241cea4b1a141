// SPDX-License-Identifier: MIT
// ScPlaneAlgorithm: an ScBulletShape against a btStaticPlaneShape, exactly. A
// half-space needs no model: the translational depth of any body in it is its deepest
// point's, along the plane's normal, and only the shape's hull corners can be deepest.
#pragma once

#include <vector>

#include "algorithm_base.h"
#include "contact_response.h"

namespace sc::bullet {

class ScPlaneAlgorithm : public AlgorithmBase {
 public:
  using AlgorithmBase::AlgorithmBase;

  void processCollision(const btCollisionObjectWrapper* body0,
                        const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                        btManifoldResult* result) override;

 private:
  /// The response acts (seen out of the plane, or first seen within
  /// detail::springReach); before that a body deep in the plane is pushed out at a
  /// bounded speed.
  bool spring_on_ = false;
  bool in_contact_ = false;               ///< penetrating in the last step (detail::projection)
  double held_depth_ = 0.0;               ///< depth at the step's detection (0: apart)
  std::vector<detail::RowPoint> points_;  ///< row points of the step (reused)
};

}  // namespace sc::bullet
