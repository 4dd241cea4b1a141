// SPDX-License-Identifier: MIT
// Mapping between the modern API's ErrorCode and the SC_* result codes.
#pragma once

#include "sc.h"
#include "smartcollision/types.h"

namespace sc::detail {

/// The SC_* code of `code` (one to one; see error_strings.cpp).
SCint toScCode(ErrorCode code);

inline SCint toScCode(const Status& status) { return toScCode(status.code()); }

}  // namespace sc::detail
