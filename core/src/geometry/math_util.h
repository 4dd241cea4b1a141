// SPDX-License-Identifier: MIT
// Small numeric helpers that never produce NaN from finite input.
#pragma once

#include <algorithm>
#include <cmath>

#include "smartcollision/types.h"

namespace sc::detail {

/// v / |v|, or `fallback` when |v| is too small to normalise reliably.
inline Vec3 normalizedOr(const Vec3& v, const Vec3& fallback) {
  const double n = v.norm();
  return n > 1e-300 && std::isfinite(n) ? Vec3(v / n) : fallback;
}

/// Any unit vector orthogonal to the unit vector n.
inline Vec3 anyOrthogonal(const Vec3& n) {
  const Vec3 a = std::abs(n.x()) < 0.57 ? Vec3::UnitX() : Vec3::UnitY();
  return n.cross(a).normalized();
}

/// Rotation vector (axis * angle, angle in [0, pi]) of a rotation matrix.
inline Vec3 rotationVector(const Mat3& r) {
  const Eigen::AngleAxisd aa(r);
  const double angle = aa.angle();
  return std::isfinite(angle) ? Vec3(aa.axis() * angle) : Vec3::Zero();
}

/// Rotation matrix of a rotation vector (axis * angle).
inline Mat3 rotationFromVector(const Vec3& w) {
  const double angle = w.norm();
  if (angle < 1e-300) return Mat3::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

/// Element-wise std::isfinite. Eigen's allFinite() computes x - x, which raises
/// FE_INVALID on an infinite input: a trap in tests, a false alarm in user code.
template <class Derived>
bool allFinite(const Eigen::DenseBase<Derived>& m) {
  for (Eigen::Index i = 0; i < m.size(); ++i)
    if (!std::isfinite(m.derived().coeff(i))) return false;
  return true;
}

/// Largest accepted vertex coordinate and placement position magnitude: squares and
/// cross products of coordinates, and of differences between them, stay far from
/// overflow.
inline constexpr double kMaxCoordinate = 1e100;

/// Finite and within kMaxCoordinate in every component.
template <class Derived>
bool withinCoordinateLimit(const Eigen::DenseBase<Derived>& m) {
  for (Eigen::Index i = 0; i < m.size(); ++i)
    if (!(std::abs(m.derived().coeff(i)) <= kMaxCoordinate)) return false;
  return true;
}

}  // namespace sc::detail
