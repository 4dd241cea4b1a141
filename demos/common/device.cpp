// SPDX-License-Identifier: MIT
// makeDevice: the device named on the command line; the pose all devices report.
#include "device.h"

#include <cstdio>

namespace sc::demo {

DevicePose devicePose(const Vec3& position, const Quat& orientation) {
  DevicePose out;
  for (int k = 0; k < 3; ++k) out.position[k] = position[k];
  out.orientation[0] = orientation.w();
  out.orientation[1] = orientation.x();
  out.orientation[2] = orientation.y();
  out.orientation[3] = orientation.z();
  return out;
}

std::unique_ptr<Device> makeDevice(const std::string& spec, std::string& error) {
  if (spec == "mouse") return makeMouseDevice();
  if (spec == "spacemouse") {
    std::unique_ptr<Device> d = makeSpaceMouseDevice(error);
    if (d) return d;
    std::fprintf(stderr, "spacemouse unavailable (%s); using the mouse\n", error.c_str());
    error.clear();
    return makeMouseDevice();
  }
  const std::string prefix = "script:";
  if (spec.compare(0, prefix.size(), prefix) == 0)
    return makeScriptDevice(spec.substr(prefix.size()), error);
  error = "unknown device '" + spec + "' (mouse, spacemouse, script:FILE)";
  return nullptr;
}

}  // namespace sc::demo
