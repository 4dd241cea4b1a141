// SPDX-License-Identifier: MIT
// Result invariants: each check reads finite inputs only (finiteness is checked
// first), and measures magnitudes with max-abs or stableNorm, so the checker itself
// never overflows, raises FE_INVALID or divides by zero.
#include "penetration/result_invariants.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <string>

#include "geometry/math_util.h"

namespace sc::detail {
namespace {


Status broken(const std::string& what) {
  return {ErrorCode::InvalidArgument, "result invariant broken: " + what};
}

bool isUnit(double length) { return std::abs(length - 1.0) <= kUnitLengthTolerance; }

/// A feature lists count() vertex indices >= 0 and -1 after them.
bool wellFormed(const Feature& f) {
  if (f.type != FeatureType::Vertex && f.type != FeatureType::Edge && f.type != FeatureType::Face)
    return false;
  for (int i = 0; i < 3; ++i) {
    if (i < f.count() ? f.vertices[i] < 0 : f.vertices[i] != -1) return false;
  }
  return true;
}

bool allFieldsFinite(const DirectedResult& r) {
  return std::isfinite(r.distance) && allFinite(r.normal) && allFinite(r.point_on_target) &&
         allFinite(r.point_on_opponent) && allFinite(r.tpdv) && allFinite(r.rpdv) &&
         allFinite(r.contact_position) && allFinite(r.contact_orientation.coeffs());
}

double maxAbs(const Vec3& v) { return v.cwiseAbs().maxCoeff(); }

/// Angle of the rotation taking unit quaternion b to unit quaternion a.
double angleBetween(const Quat& a, const Quat& b) {
  const Quat d = a * b.conjugate();
  return 2.0 * std::atan2(d.vec().stableNorm(), std::abs(d.w()));
}

/// The magnitudes a world position of this result is computed from: rounding of
/// the rigid transforms between the groups' frames is relative to them.
double positionScale(const DirectedResult& r, const Placement& target, const Placement& opponent) {
  double scale = 1.0;
  for (const Vec3* v :
       {&target.world_center, &target.local_center, &opponent.world_center, &opponent.local_center,
        &r.point_on_target, &r.point_on_opponent, &r.contact_position, &r.tpdv}) {
    scale = std::max(scale, maxAbs(*v));
  }
  return scale;
}

Status checkApart(const DirectedResult& r) {
  if (!r.tpdv.isZero(0.0) || !r.rpdv.isZero(0.0)) return broken("apart with non-zero TPDV/RPDV");
  return Status::success();
}

Status checkPenetrating(const DirectedResult& r) {
  const double depth = r.tpdv.stableNorm();
  if (std::abs(r.distance + depth) > kDepthRelativeTolerance * depth)
    return broken("penetrating distance " + std::to_string(r.distance) +
                  " is not -|TPDV| = " + std::to_string(-depth));
  return Status::success();
}

}  // namespace

Status checkResult(const DirectedResult& r) {
  if (r.code != ErrorCode::Ok && r.code != ErrorCode::NoResult &&
      r.code != ErrorCode::InvalidInitialTransformation)
    return broken("result code " + std::to_string(static_cast<int>(r.code)));
  if (r.code != ErrorCode::Ok) return Status::success();
  if (r.target_piece < 0 || r.opponent_piece < 0) return broken("negative piece index");
  if (!wellFormed(r.target_feature) || !wellFormed(r.opponent_feature))
    return broken("malformed feature");
  if (!allFieldsFinite(r)) return broken("non-finite field");
  if (!isUnit(r.normal.stableNorm())) return broken("normal is not unit");
  if (!isUnit(r.contact_orientation.coeffs().stableNorm()))
    return broken("contact orientation is not a unit quaternion");
  if (r.rpdv.stableNorm() > kPi + kAngleTolerance) return broken("|RPDV| beyond pi");
  return r.distance > 0.0 ? checkApart(r) : checkPenetrating(r);
}

Status checkResult(const DirectedResult& r, const Placement& target, const Placement& opponent) {
  if (Status s = checkResult(r); !s.ok() || r.code != ErrorCode::Ok) return s;
  if (!allFinite(target.world_center) || !allFinite(target.local_center) ||
      !allFinite(target.orientation.coeffs()) || !allFinite(opponent.world_center) ||
      !allFinite(opponent.local_center))
    return broken("non-finite placement given to the check");
  const double position_tolerance = kPositionRelativeTolerance * positionScale(r, target, opponent);
  const Quat current = target.orientation.normalized();
  if (r.distance > 0.0) {
    const Vec3 gap = r.point_on_target - r.point_on_opponent;
    if (maxAbs(gap - r.distance * r.normal) > position_tolerance)
      return broken("apart: point_on_target - point_on_opponent != distance * normal");
    if (maxAbs(r.contact_position - target.world_center) > position_tolerance)
      return broken("apart: contact position is not the target's centre");
    if (angleBetween(r.contact_orientation, current) > kAngleTolerance)
      return broken("apart: contact orientation is not the target's orientation");
    return Status::success();
  }
  if (maxAbs(r.contact_position - (target.world_center - r.tpdv)) > position_tolerance)
    return broken("penetrating: contact position is not centre - TPDV");
  const Quat expected = Quat(rotationFromVector(r.rpdv)) * r.contact_orientation;
  if (angleBetween(expected, current) > kAngleTolerance)
    return broken("penetrating: R(current) != Rot(RPDV) R(contact)");
  return Status::success();
}

void failResultInvariant(const Status& violation) {
  std::fprintf(stderr, "SmartCollision: %s\n", violation.message().c_str());
  std::abort();
}

}  // namespace sc::detail
