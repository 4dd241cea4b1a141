// SPDX-License-Identifier: MIT
// Range checks of SceneSettings: its pair settings, then the scene's own fields.
#include "smartcollision/settings.h"

namespace sc {

Status validate(const SceneSettings& s) {
  Status pair = validate(static_cast<const PairSettings&>(s));
  if (!pair.ok()) return pair;
  auto bad = [](const char* what) { return Status(ErrorCode::InvalidArgument, what); };
  if (s.threads < 0 || s.threads > kMaxThreads) return bad("threads must be in [0, 256]");
  if (s.broadphase != Broadphase::Tree && s.broadphase != Broadphase::BruteForce)
    return bad("unknown broadphase");
  return {};
}

}  // namespace sc
