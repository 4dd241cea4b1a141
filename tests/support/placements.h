// SPDX-License-Identifier: MIT
// What the placement and transformation tests share: the start state of their
// hand-computed rows, the sign-blind quaternion distance, and the float and double
// variants with the tolerance of a value read back in each.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "smartcollision/placement.h"

namespace sc::test {

/// r_WC = (1,2,3), r_LC = (4,5,6), 90 degrees about z: R(x,y,z) = (-y,x,z).
/// Hence r_O = r_WC - R r_LC = (1,2,3) - (-5,4,6) = (6,-2,-3).
inline Placement startState() {
  const double h = std::sqrt(0.5);
  Placement p;
  p.world_center = Vec3(1, 2, 3);
  p.local_center = Vec3(4, 5, 6);
  p.orientation = Quat(h, 0, 0, h);
  return p;
}

/// Orientation `q` about the local origin, placed with that origin at `center`.
inline Placement placementOf(const Quat& q, const Vec3& center) {
  Placement p;
  p.orientation = q;
  p.world_center = center;
  return p;
}

/// The same with the orientation as a rotation matrix.
inline Placement placementOf(const Mat3& r, const Vec3& center) {
  return placementOf(Quat(r), center);
}

/// q and -q are the same rotation.
inline double quatDistance(const Quat& a, const Quat& b) {
  return std::min((a.coeffs() - b.coeffs()).norm(), (a.coeffs() + b.coeffs()).norm());
}

/// Relative tolerance of a value that went through `Real`.
template <class Real>
inline constexpr double kRelTol = 1e-12;
template <>
inline constexpr double kRelTol<float> = 1e-6;  // ~8 float ulps

/// Tolerance on a value of `magnitude` that went through `Real`.
template <class Real>
double realTol(double magnitude) {
  return kRelTol<Real> * (1.0 + std::abs(magnitude));
}

/// `values` as `To` (the arrays the float and double API variants take and give).
template <class To, class From>
std::vector<To> convert(const std::vector<From>& values) {
  return std::vector<To>(values.begin(), values.end());
}

/// NaN, +inf and -inf: the values every transformation input must reject.
template <class Real>
std::vector<Real> nonFinite() {
  return {std::numeric_limits<Real>::quiet_NaN(), std::numeric_limits<Real>::infinity(),
          -std::numeric_limits<Real>::infinity()};
}

/// The typed tests' two precisions, named Float and Double.
using Reals = ::testing::Types<float, double>;
struct RealNames {
  template <class T>
  static std::string GetName(int) {
    return std::is_same_v<T, float> ? "Float" : "Double";
  }
};

}  // namespace sc::test
