// SPDX-License-Identifier: MIT
// Placement: equation (7-1) and the operations of manual Tables 7-1 and 7-2.
#include "smartcollision/placement.h"

#include <cmath>

#include "geometry/math_util.h"
#include "geometry/placement_check.h"

namespace sc {
namespace {

/// q / |q| computed after scaling by the largest component, so neither tiny nor
/// huge components underflow or overflow the norm. False (and `out` untouched)
/// when q is zero or not finite.
bool safeNormalize(const Quat& q, Quat& out) {
  const Eigen::Vector4d c = q.coeffs();
  for (int i = 0; i < 4; ++i) {
    if (!std::isfinite(c[i])) return false;
  }
  const double scale = c.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) return false;
  const Eigen::Vector4d unit = (c / scale).normalized();  // norm of c/scale is >= 1
  out.coeffs() = unit;
  return true;
}

/// Unit quaternion of a matrix known to be (close to) a rotation; identity if even
/// that conversion fails, so the result is always a unit quaternion.
Quat quaternionOf(const Mat3& r) {
  Quat q;
  return safeNormalize(Quat(r), q) ? q : Quat::Identity();
}

}  // namespace

Eigen::Matrix4d Placement::matrix() const {
  // M = T_WC R T_LC^-1: rotation R and translation r_WC - R r_LC = r_O.
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = rotation();
  m.topRightCorner<3, 1>() = origin();
  return m;
}

void Placement::setOrigin(const Vec3& r_o) { world_center = r_o + rotation() * local_center; }

void Placement::setWorldCenter(const Vec3& r_wc) { world_center = r_wc; }

void Placement::setLocalCenter(const Vec3& r_lc) {
  // Literal Table 7-1: only r_WC changes, to where r_LC' was in the world.
  world_center = rotation() * (r_lc - local_center) + world_center;
}

void Placement::setNewWorldCenter(const Vec3& r_wc) {
  // Both assignments use the old r_WC; together they keep r_O = r_WC - R r_LC.
  local_center = rotation().transpose() * (r_wc - world_center) + local_center;
  world_center = r_wc;
}

void Placement::setNewLocalCenter(const Vec3& r_lc) {
  // r_WC first, with the old r_LC; together they keep r_O.
  world_center = rotation() * (r_lc - local_center) + world_center;
  local_center = r_lc;
}

void Placement::setOrientation(const Quat& q) {
  // A zero or non-finite q cannot be normalised: keep the current orientation
  // rather than store a non-unit one (the sc.h layer rejects such input first).
  Quat unit;
  if (safeNormalize(q, unit)) orientation = unit;
}

void Placement::setMatrix(const Mat3& rotation_part, const Vec3& translation) {
  orientation = quaternionOf(rotation_part);
  // r_WC = M' r_LC, using the stored unit q so that origin() is the translation.
  world_center = rotation() * local_center + translation;
}

Result<Quat> rotationToQuaternion(const Mat3& r, double tolerance) {
  // Element-wise isfinite: Eigen's allFinite() computes inf - inf, which raises
  // FE_INVALID (trapped in our tests). An orthonormal matrix within `tolerance` has
  // |entry| <= sqrt(1 + tolerance); rejecting larger entries first keeps R^T R from
  // overflowing.
  for (int i = 0; i < 9; ++i) {
    if (!std::isfinite(r.data()[i])) {
      return Status(ErrorCode::InvalidArgument, "rotation matrix has a non-finite entry");
    }
    if (!(std::abs(r.data()[i]) <= 1.0 + tolerance)) {
      return Status(ErrorCode::InvalidArgument, "matrix is not orthonormal");
    }
  }
  const double error = (r.transpose() * r - Mat3::Identity()).norm();
  if (!(error <= tolerance)) {
    return Status(ErrorCode::InvalidArgument, "matrix is not orthonormal");
  }
  if (!(r.determinant() > 0.0)) {
    return Status(ErrorCode::InvalidArgument, "matrix is a reflection, not a rotation");
  }
  return quaternionOf(r);
}

namespace detail {

Status checkPlacement(const Placement& p) {
  // allFinite first: comparing a NaN raises FE_INVALID (a trap where enabled).
  if (!allFinite(p.world_center) || !allFinite(p.local_center) ||
      !withinCoordinateLimit(p.world_center) || !withinCoordinateLimit(p.local_center))
    return Status(ErrorCode::InvalidArgument,
                  "placement not finite or a centre beyond 1e100 in magnitude");
  const Eigen::Vector4d q = p.orientation.coeffs();
  if (!allFinite(q)) return Status(ErrorCode::InvalidArgument, "orientation quaternion not finite");
  if (q.cwiseAbs().maxCoeff() == 0.0)
    return Status(ErrorCode::InvalidArgument, "orientation quaternion zero");
  return {};
}

Placement unitPlacement(const Placement& p) {
  // Eigen's normalize() in the usual range (bit for bit what setGroupPlacement always
  // did); a rescaling first where squaring the components would underflow or overflow.
  const double largest = p.orientation.coeffs().cwiseAbs().maxCoeff();
  Placement unit = p;
  if (largest > 1e-150 && largest < 1e150)
    unit.orientation.normalize();
  else
    unit.setOrientation(p.orientation);
  return unit;
}

Result<Placement> usablePlacement(const Placement& p) {
  if (Status s = checkPlacement(p); !s.ok()) return s;
  return unitPlacement(p);
}

bool unitToRounding(const Quat& q) {
  // Normalised in double precision, |q|^2 is within a few 1e-16 of 1.
  return std::abs(q.squaredNorm() - 1.0) <= 1e-12;
}

}  // namespace detail
}  // namespace sc
