// SPDX-License-Identifier: MIT
// Messages for every result code, shared by the modern API and sc.h.
#include "sc.h"
#include "smartcollision/types.h"

namespace sc {

const char* describe(ErrorCode code) {
  switch (code) {
    case ErrorCode::Ok:
      return "no error";
    case ErrorCode::NoResult:
      return "no result in this direction: the pair is beyond the maximum distance, "
             "inactive, or was not computed";
    case ErrorCode::InvalidInitialTransformation:
      return "the pair intersects and has never been seen apart, so its dynamic "
             "penetration depth has no starting point";
    case ErrorCode::InvalidGeometry:
      return "invalid geometry: a closed polyhedron piece must have every edge shared by "
             "exactly two triangles with opposite winding, no degenerate triangle, and "
             "one connected shell";
    case ErrorCode::InvalidArgument:
      return "invalid argument: a null pointer, negative count, out-of-range index, "
             "non-finite number, unknown enum value, or wrongly typed attribute";
    case ErrorCode::InvalidId:
      return "invalid id: unknown or duplicate object or group id";
    case ErrorCode::InvalidOperation:
      return "invalid operation in the current state (object already in a scene, wrong "
             "object type for this scene, static group, ...)";
    case ErrorCode::File:
      return "the preprocessing cache file could not be read or written; the geometry "
             "was preprocessed and added anyway";
  }
  return "unknown error code";
}

}  // namespace sc

const char* SCGetErrorString(SCint code) {
  switch (code) {
    case SC_NO_ERROR:
      return sc::describe(sc::ErrorCode::Ok);
    case SC_ERROR_NO_RESULT:
      return sc::describe(sc::ErrorCode::NoResult);
    case SC_ERROR_INVALID_INITIAL_TRANSFORMATION:
      return sc::describe(sc::ErrorCode::InvalidInitialTransformation);
    case SC_ERROR_INVALID_LICENSE:
      return "invalid license (never returned: SmartCollision needs no license)";
    case SC_ERROR_INVALID_GEOMETRY:
      return sc::describe(sc::ErrorCode::InvalidGeometry);
    case SC_ERROR_INVALID_ARGUMENT:
      return sc::describe(sc::ErrorCode::InvalidArgument);
    case SC_ERROR_INVALID_ID:
      return sc::describe(sc::ErrorCode::InvalidId);
    case SC_ERROR_INVALID_OPERATION:
      return sc::describe(sc::ErrorCode::InvalidOperation);
    case SC_ERROR_FILE:
      return sc::describe(sc::ErrorCode::File);
    default:
      return "unknown SmartCollision result code";
  }
}
