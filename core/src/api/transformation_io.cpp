// SPDX-License-Identifier: MIT
// Tables 7-1 and 7-2 over raw float/double arrays: validate everything first, apply
// to a copy, and commit only on success, so a rejected call changes nothing.
#include "api/transformation_io.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "geometry/math_util.h"

namespace sc::detail {
namespace {

/// Frobenius norm of R^T R - I accepted for an input rotation. A rotation rounded
/// to float is about 1e-7 off, one typed with six digits (0.707107) about 1e-6.
constexpr double kRotationTolerance = 1e-4;
/// Absolute tolerance on the last row 0 0 0 1 of SC_TRANSFORMATION_MATRIX.
constexpr double kLastRowTolerance = 1e-4;
/// Largest accepted input value: no table operation (a few sums of rotated
/// differences) can overflow, so a placement never holds inf or NaN. The stored
/// centres are then held to the tighter kMaxCoordinate, as vertices are, so that
/// distances and motions between placed models cannot overflow either.
constexpr double kMaxMagnitude = 1e300;
constexpr int kMaxArraySize = 16;

/// Copies `n` values to doubles; false if any is non-finite or beyond kMaxMagnitude.
template <class Real>
bool readValues(const Real* values, int n, double* out) {
  for (int i = 0; i < n; ++i) {
    // std::isfinite before any arithmetic: inf - inf would raise FE_INVALID.
    if (!std::isfinite(values[i])) return false;
    out[i] = static_cast<double>(values[i]);
    if (!(std::abs(out[i]) <= kMaxMagnitude)) return false;
  }
  return true;
}

bool lastRowIsAffine(const Eigen::Matrix4d& m) {
  return std::abs(m(3, 0)) <= kLastRowTolerance && std::abs(m(3, 1)) <= kLastRowTolerance &&
         std::abs(m(3, 2)) <= kLastRowTolerance && std::abs(m(3, 3) - 1.0) <= kLastRowTolerance;
}

/// Rows 1-5 of Table 7-1: a position of three values and the Placement setter it calls.
struct PositionRow {
  SCenum type;
  void (Placement::*set)(const Vec3&);
};
constexpr PositionRow kPositionRows[] = {
    {SC_POSITION_ORIGIN, &Placement::setOrigin},
    {SC_POSITION_WORLD_CENTER, &Placement::setWorldCenter},
    {SC_POSITION_LOCAL_CENTER, &Placement::setLocalCenter},
    {SC_POSITION_NEW_WORLD_CENTER, &Placement::setNewWorldCenter},
    {SC_POSITION_NEW_LOCAL_CENTER, &Placement::setNewLocalCenter},
};

const PositionRow* positionRow(SCenum type) {
  for (const PositionRow& row : kPositionRows)
    if (row.type == type) return &row;
  return nullptr;
}

/// One row of Table 7-1 on finite, bounded values; false for an invalid argument.
bool apply(Placement& p, SCenum type, const double* v) {
  if (const PositionRow* row = positionRow(type)) {
    (p.*row->set)(Vec3(v[0], v[1], v[2]));
    return true;
  }
  switch (type) {
    case SC_ORIENTATION_QUATERNION: {
      const Quat q(v[0], v[1], v[2], v[3]);  // {s, vx, vy, vz}: Eigen takes w first too
      if (q.coeffs().cwiseAbs().maxCoeff() == 0.0) return false;
      p.setOrientation(q);
      return true;
    }
    case SC_ORIENTATION_MATRIX: {
      const Result<Quat> q = rotationToQuaternion(Eigen::Map<const Mat3>(v), kRotationTolerance);
      if (!q.ok()) return false;
      p.setOrientation(q.value());
      return true;
    }
    case SC_TRANSFORMATION_MATRIX: {
      const Eigen::Map<const Eigen::Matrix4d> m(v);  // column-major, as OpenGL
      if (!lastRowIsAffine(m)) return false;
      const Mat3 r = m.topLeftCorner<3, 3>();
      if (!rotationToQuaternion(r, kRotationTolerance).ok()) return false;
      p.setMatrix(r, m.topRightCorner<3, 1>());
      return true;
    }
    default:
      return false;
  }
}

/// Copies a plain Eigen vector or matrix in its storage order (column-major, as
/// OpenGL); returns the number of values.
template <class Matrix>
int store(const Matrix& m, double* out) {
  std::copy(m.data(), m.data() + m.size(), out);
  return static_cast<int>(m.size());
}

}  // namespace

int transformationArraySize(SCenum type) {
  if (positionRow(type) != nullptr) return 3;
  // The rotations: a quaternion, a 3x3 matrix, a 4x4 matrix.
  const std::pair<SCenum, int> kRotationSizes[] = {
      {SC_ORIENTATION_QUATERNION, 4}, {SC_ORIENTATION_MATRIX, 9}, {SC_TRANSFORMATION_MATRIX, 16}};
  for (const auto& [rotation, size] : kRotationSizes)
    if (rotation == type) return size;
  return 0;
}

template <class Real>
SCint setTransformation(Placement& placement, SCenum type, const Real* values) {
  const int n = transformationArraySize(type);
  if (n == 0 || values == nullptr) return SC_ERROR_INVALID_ARGUMENT;
  double v[kMaxArraySize];
  if (!readValues(values, n, v)) return SC_ERROR_INVALID_ARGUMENT;
  Placement next = placement;
  if (!apply(next, type, v)) return SC_ERROR_INVALID_ARGUMENT;
  if (!withinCoordinateLimit(next.world_center) || !withinCoordinateLimit(next.local_center)) {
    return SC_ERROR_INVALID_ARGUMENT;
  }
  placement = next;
  return SC_NO_ERROR;
}

template <class Real>
SCint getTransformation(const Placement& placement, SCenum type, Real* values) {
  if (values == nullptr) return SC_ERROR_INVALID_ARGUMENT;
  double v[kMaxArraySize];
  int n = 0;
  switch (type) {
    case SC_POSITION_ORIGIN:
      n = store(placement.origin(), v);
      break;
    case SC_POSITION_WORLD_CENTER:
      n = store(placement.world_center, v);
      break;
    case SC_POSITION_LOCAL_CENTER:
      n = store(placement.local_center, v);
      break;
    case SC_ORIENTATION_QUATERNION:
      v[0] = placement.orientation.w();
      v[1] = placement.orientation.x();
      v[2] = placement.orientation.y();
      v[3] = placement.orientation.z();
      n = 4;
      break;
    case SC_ORIENTATION_MATRIX:
      n = store(placement.rotation(), v);
      break;
    case SC_TRANSFORMATION_MATRIX:
      n = store(placement.matrix(), v);
      break;
    // SC_POSITION_NEW_WORLD_CENTER / NEW_LOCAL_CENTER are set-only operations (they
    // move r_LC or r_WC while keeping r_O): there is no value to read. Table 7-2
    // does not list them.
    default:
      return SC_ERROR_INVALID_ARGUMENT;
  }
  // A stored double beyond the range of float cannot be returned as float
  // (the conversion would be undefined); report it rather than write inf.
  for (int i = 0; i < n; ++i) {
    if (!(std::abs(v[i]) <= static_cast<double>(std::numeric_limits<Real>::max()))) {
      return SC_ERROR_INVALID_ARGUMENT;
    }
  }
  for (int i = 0; i < n; ++i) values[i] = static_cast<Real>(v[i]);
  return SC_NO_ERROR;
}

template SCint setTransformation<float>(Placement&, SCenum, const float*);
template SCint setTransformation<double>(Placement&, SCenum, const double*);
template SCint getTransformation<float>(const Placement&, SCenum, float*);
template SCint getTransformation<double>(const Placement&, SCenum, double*);

}  // namespace sc::detail
