// SPDX-License-Identifier: MIT
// libccd's problem set-up, shared by the benches that call libccd.
#pragma once

#include <ccd/ccd.h>

namespace sc_bench {

/// libccd's defaults, over two objects of one kind: `support` and `center` for both.
inline ccd_t ccdProblem(ccd_support_fn support, ccd_center_fn center) {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = support;
  ccd.support2 = support;
  ccd.center1 = center;
  ccd.center2 = center;
  return ccd;
}

}  // namespace sc_bench
