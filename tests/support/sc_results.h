// SPDX-License-Identifier: MIT
// Reading an sc.h scene's results in tests: every direction of the last UpdateStatus
// that has a result.
#pragma once

#include <gtest/gtest.h>

#include "sc.h"

namespace sc::test {

/// Calls fn(index, reverse) for each direction of the last UpdateStatus whose
/// SC_STATUS_RESULT is SC_NO_ERROR.
template <class Fn>
void forEachOkDirection(SCSceneManager& scene, Fn fn) {
  SCint count = 0;
  ASSERT_EQ(scene.GetStatus(SC_STATUS_COUNT, &count), SC_NO_ERROR);
  for (SCint i = 0; i < count; ++i) {
    for (bool reverse : {false, true}) {
      SCint code = -1;
      ASSERT_EQ(scene.GetStatus(SC_STATUS_RESULT, &code, i, reverse), SC_NO_ERROR);
      if (code == SC_NO_ERROR) fn(i, reverse);
    }
  }
}

}  // namespace sc::test
