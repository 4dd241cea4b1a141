// SPDX-License-Identifier: MIT
// Range checks of PairSettings (the first bad field is named).
#include "smartcollision/pair_settings.h"

#include <cmath>

namespace sc {

Status validate(const PairSettings& s) {
  auto bad = [](const char* what) { return Status(ErrorCode::InvalidArgument, what); };
  if (std::isnan(s.max_distance) || s.max_distance < 0.0)
    return bad("max_distance must be >= 0 (+inf allowed)");
  if (!std::isfinite(s.tolerance) || s.tolerance <= 0.0)
    return bad("tolerance must be finite and > 0");
  if (!std::isfinite(s.safety_coefficient) || s.safety_coefficient <= 0.0 ||
      s.safety_coefficient >= 1.0)
    return bad("safety_coefficient must be in (0, 1)");
  if (s.max_iterations < 1) return bad("max_iterations must be >= 1");
  if (!std::isfinite(s.force_stiffness) || s.force_stiffness <= 0.0)
    return bad("force_stiffness must be finite and > 0");
  if (!std::isfinite(s.torque_stiffness) || s.torque_stiffness <= 0.0)
    return bad("torque_stiffness must be finite and > 0");
  if (std::isnan(s.teleport_distance) || s.teleport_distance <= 0.0)
    return bad("teleport_distance must be > 0 (+inf allowed)");
  // Below 1 a proxy in contact could not keep up with a target merely sliding along.
  if (std::isnan(s.proxy_travel_ratio) || s.proxy_travel_ratio < 1.0)
    return bad("proxy_travel_ratio must be >= 1 (+inf allowed)");
  switch (s.rotation_mode) {
    case RotationMode::None:
    case RotationMode::Input:
    case RotationMode::Free:
    case RotationMode::Mix:
      return {};
  }
  return bad("unknown rotation mode");
}

}  // namespace sc
