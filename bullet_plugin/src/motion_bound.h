// SPDX-License-Identifier: MIT
// How far a body's surface can have moved between two poses: one bound for the
// world's impact pass and the algorithms' pair skipping.
#pragma once

#include <LinearMath/btTransform.h>

#include <algorithm>

namespace sc::bullet::detail {

/// Bound on the motion of any point within `reach` of the origin from pose `a` to
/// pose `b`: the origin's displacement plus the chord a rotation sweeps at `reach`,
/// 2 r sin(angle / 2) <= 2 r |q - q'| (the nearer sign of q'). Unlike the angle from
/// the quaternions' dot product, the difference has no rounding floor: a float dot
/// product one ulp below 1 reads as 3.5e-4 rad.
inline double motionBound(const btTransform& a, const btTransform& b, double reach) {
  const btQuaternion q = a.getRotation(), p = b.getRotation();
  const double minus = double((q - p).length()), plus = double((q + p).length());
  return double((a.getOrigin() - b.getOrigin()).length()) + 2.0 * reach * std::min(minus, plus);
}

}  // namespace sc::bullet::detail
