// SPDX-License-Identifier: MIT
// Manual Tables 7-1 and 7-2 over raw arrays, for SCObject and SCSceneManager:
// validates the type and the numbers, then applies or reads a Placement.
#pragma once

#include "sc.h"
#include "smartcollision/placement.h"

namespace sc::detail {

/// Number of values an array of this transformation type holds (3, 4, 9 or 16), or 0
/// for an unknown type.
int transformationArraySize(SCenum type);

/// Table 7-1: applies `values` of `type` to `placement`. SC_ERROR_INVALID_ARGUMENT
/// for an unknown type, a null pointer, non-finite values, a zero quaternion, or a
/// matrix that is not a rotation (or, for SC_TRANSFORMATION_MATRIX, whose last row
/// is not 0 0 0 1); `placement` is then unchanged.
template <class Real>
SCint setTransformation(Placement& placement, SCenum type, const Real* values);

/// Table 7-2: writes `type` of `placement` into `values`. SC_POSITION_NEW_* are not
/// readable (SC_ERROR_INVALID_ARGUMENT), nor is an unknown type or a null pointer.
template <class Real>
SCint getTransformation(const Placement& placement, SCenum type, Real* values);

}  // namespace sc::detail
