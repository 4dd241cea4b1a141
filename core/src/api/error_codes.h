// SPDX-License-Identifier: MIT
// Mapping between the modern API's ErrorCode and the SC_* result codes.
#pragma once

#include "sc.h"
#include "smartcollision/types.h"

namespace sc::detail {

inline SCint toScCode(ErrorCode code) {
  switch (code) {
    case ErrorCode::Ok: return SC_NO_ERROR;
    case ErrorCode::NoResult: return SC_ERROR_NO_RESULT;
    case ErrorCode::InvalidInitialTransformation: return SC_ERROR_INVALID_INITIAL_TRANSFORMATION;
    case ErrorCode::InvalidGeometry: return SC_ERROR_INVALID_GEOMETRY;
    case ErrorCode::InvalidArgument: return SC_ERROR_INVALID_ARGUMENT;
    case ErrorCode::InvalidId: return SC_ERROR_INVALID_ID;
    case ErrorCode::InvalidOperation: return SC_ERROR_INVALID_OPERATION;
    case ErrorCode::File: return SC_ERROR_FILE;
  }
  return SC_ERROR_INVALID_ARGUMENT;
}

inline SCint toScCode(const Status& status) { return toScCode(status.code()); }

}  // namespace sc::detail
