// SPDX-License-Identifier: MIT
// Invariants every DirectedResult leaving the library must satisfy (issue 9, item 3):
// finite fields, unit normal and quaternion, distance sign consistent with TPDV/RPDV.
#pragma once

#include "smartcollision/pair_tracker.h"
#include "smartcollision/placement.h"

namespace sc::detail {

/// True in builds without NDEBUG: callers write `if constexpr (kCheckResultInvariants)`
/// (or call enforceResultInvariants), so no macro appears at the call site.
#ifdef NDEBUG
inline constexpr bool kCheckResultInvariants = false;
#else
inline constexpr bool kCheckResultInvariants = true;
#endif

/// Allowed deviation of |normal| and |contact_orientation| from 1.
inline constexpr double kUnitLengthTolerance = 1e-9;
/// Relative tolerance of distance == -|tpdv| when penetrating.
inline constexpr double kDepthRelativeTolerance = 1e-12;
/// Relative tolerance (of the magnitudes involved, at least 1) of positions that are
/// the same point computed along different chains of rigid transforms.
inline constexpr double kPositionRelativeTolerance = 1e-9;
/// Angle (radians) by which two orientations that should agree may differ.
inline constexpr double kAngleTolerance = 1e-9;

/// Checks one direction on its own. Any code other than Ok, NoResult and
/// InvalidInitialTransformation fails; a non-Ok code passes (its fields are not
/// defined). For Ok: piece indices >= 0; features well formed (type's count of
/// vertex indices >= 0, the rest -1); every real field finite; |normal| and
/// |contact_orientation| = 1 within kUnitLengthTolerance; |rpdv| <= pi.
/// Apart (distance > 0): tpdv = rpdv = 0 exactly and
/// point_on_target - point_on_opponent = distance * normal.
/// Penetrating (distance <= 0): distance = -|tpdv| within kDepthRelativeTolerance.
/// @return Ok, or InvalidArgument whose message names the first broken invariant.
Status checkResult(const DirectedResult& r);

/// checkResult, plus the contact configuration against the groups' current
/// placements (target = the group whose parts are r.target_object's, opponent the
/// other): apart, the contact centre and orientation are the target's current ones;
/// penetrating, contact_position = world_center - tpdv and
/// R(current) = Rot(rpdv) R(contact_orientation).
Status checkResult(const DirectedResult& r, const Placement& target, const Placement& opponent);

/// Prints the broken invariant to stderr and aborts.
[[noreturn]] void failResultInvariant(const Status& violation);

/// Debug builds: checkResult, aborting through failResultInvariant on a violation
/// (an assertion: the library broke its own contract). Release builds: nothing.
inline void enforceResultInvariants(const DirectedResult& r) {
  if constexpr (kCheckResultInvariants) {
    if (Status s = checkResult(r); !s.ok()) failResultInvariant(s);
  }
}

/// enforceResultInvariants with the placements of the two-placement checkResult.
inline void enforceResultInvariants(const DirectedResult& r, const Placement& target,
                                    const Placement& opponent) {
  if constexpr (kCheckResultInvariants) {
    if (Status s = checkResult(r, target, opponent); !s.ok()) failResultInvariant(s);
  }
}

}  // namespace sc::detail
