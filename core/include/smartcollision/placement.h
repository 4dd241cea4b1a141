// SPDX-License-Identifier: MIT
// Where an object or group is: manual section 7, equation (7-1),
//   r_W = R(q) (r_L - r_LC) + r_WC,
// and the operations of manual Tables 7-1 (set) and 7-2 (get), literally.
#pragma once

#include "smartcollision/types.h"

namespace sc {

struct SC_API Placement {
  Vec3 world_center = Vec3::Zero();  ///< r_WC: centre of rotation in world coordinates
  Vec3 local_center = Vec3::Zero();  ///< r_LC: centre of rotation in local coordinates
  Quat orientation = Quat::Identity();  ///< q, unit

  Mat3 rotation() const { return orientation.toRotationMatrix(); }
  /// r_O = r_WC - R r_LC, where the local origin lands in the world (Table 7-2).
  Vec3 origin() const { return world_center - rotation() * local_center; }
  /// world_from_local as a rigid transform.
  Rigid worldFromLocal() const { return {rotation(), origin()}; }
  /// The placement about `local_center` whose world_from_local is `w` (normalised).
  static Placement fromRigid(const Rigid& w, const Vec3& local_center) {
    Placement p;
    p.local_center = local_center;
    p.orientation = Quat(w.rotation).normalized();
    p.world_center = w * p.local_center;
    return p;
  }
  /// M of (7-1), column-major 4x4 as in OpenGL (m12, m13, m14 = translation).
  Eigen::Matrix4d matrix() const;

  // Table 7-1. Inputs are assumed finite; the sc.h façade validates them.
  void setOrigin(const Vec3& r_o);               ///< SC_POSITION_ORIGIN: r_WC = r_O' + R r_LC
  void setWorldCenter(const Vec3& r_wc);         ///< SC_POSITION_WORLD_CENTER: r_WC = r_WC'
  void setLocalCenter(const Vec3& r_lc);         ///< SC_POSITION_LOCAL_CENTER: r_WC = R(r_LC' - r_LC) + r_WC
  void setNewWorldCenter(const Vec3& r_wc);      ///< SC_POSITION_NEW_WORLD_CENTER: moves r_LC, keeps r_O
  void setNewLocalCenter(const Vec3& r_lc);      ///< SC_POSITION_NEW_LOCAL_CENTER: moves r_WC, keeps r_O
  void setOrientation(const Quat& q);            ///< SC_ORIENTATION_QUATERNION (normalised here)
  /// SC_TRANSFORMATION_MATRIX: q from the rotation part, r_WC = M' r_LC.
  void setMatrix(const Mat3& rotation, const Vec3& translation);
};

/// Quaternion of a 3x3 matrix that must be a rotation: orthonormal within `tolerance`
/// (Frobenius norm of R^T R - I) and det > 0. InvalidArgument otherwise.
SC_API Result<Quat> rotationToQuaternion(const Mat3& r, double tolerance = 1e-4);

}  // namespace sc
