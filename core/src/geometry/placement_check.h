// SPDX-License-Identifier: MIT
// The one rule for a placement the queries can use: Scene, sc.h (through Scene) and
// PairTracker all apply it.
#pragma once

#include "smartcollision/placement.h"

namespace sc::detail {

/// Ok when the queries can use `p`: centres finite and within kMaxCoordinate (as
/// vertices are, so no distance or motion overflows), the quaternion finite and not
/// zero (any such one is normalised before use). InvalidArgument saying why otherwise.
Status checkPlacement(const Placement& p);

/// `p`, which passes checkPlacement, with its quaternion normalised.
Placement unitPlacement(const Placement& p);

/// `p` checked, then normalised: what the scene stores.
Result<Placement> usablePlacement(const Placement& p);

/// True when q is unit to rounding, as any quaternion normalised in double precision
/// is: used as given, so that results stay those of the caller's own quaternion.
bool unitToRounding(const Quat& q);

}  // namespace sc::detail
