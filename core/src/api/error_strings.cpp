// SPDX-License-Identifier: MIT
// Messages for every result code, shared by the modern API and sc.h, and the one
// table of which SC_* code each ErrorCode is.
#include <cstddef>
#include <iterator>
#include <utility>

#include "api/error_codes.h"

namespace sc {
namespace {

/// Each ErrorCode and its SC_* code (one to one).
constexpr std::pair<ErrorCode, SCint> kScCodes[] = {
    {ErrorCode::Ok, SC_NO_ERROR},
    {ErrorCode::NoResult, SC_ERROR_NO_RESULT},
    {ErrorCode::InvalidInitialTransformation, SC_ERROR_INVALID_INITIAL_TRANSFORMATION},
    {ErrorCode::InvalidGeometry, SC_ERROR_INVALID_GEOMETRY},
    {ErrorCode::InvalidArgument, SC_ERROR_INVALID_ARGUMENT},
    {ErrorCode::InvalidId, SC_ERROR_INVALID_ID},
    {ErrorCode::InvalidOperation, SC_ERROR_INVALID_OPERATION},
    {ErrorCode::File, SC_ERROR_FILE},
};

/// Each ErrorCode's message, in the enum's order.
constexpr const char* kMessages[] = {
    // Ok
    "no error",
    // NoResult
    "no result in this direction: the pair is beyond the maximum distance, inactive, or was "
    "not computed",
    // InvalidInitialTransformation
    "the pair intersects and has never been seen apart, so its dynamic penetration depth has "
    "no starting point",
    // InvalidGeometry
    "invalid geometry: a closed polyhedron piece must have every edge shared by exactly two "
    "triangles with opposite winding, no degenerate triangle, and one connected shell",
    // InvalidArgument
    "invalid argument: a null pointer, negative count, out-of-range index, non-finite number, "
    "unknown enum value, or wrongly typed attribute",
    // InvalidId
    "invalid id: unknown or duplicate object or group id",
    // InvalidOperation
    "invalid operation in the current state (object already in a scene, wrong object type for "
    "this scene, static group, ...)",
    // File
    "the preprocessing cache file could not be read or written; the geometry was preprocessed "
    "and added anyway",
};
static_assert(std::size(kMessages) == std::size(kScCodes), "a message for every code");

}  // namespace

const char* describe(ErrorCode code) {
  const auto i = static_cast<std::size_t>(code);
  return i < std::size(kMessages) ? kMessages[i] : "unknown error code";
}

namespace detail {

SCint toScCode(ErrorCode code) {
  for (const auto& [modern, sc_code] : kScCodes)
    if (modern == code) return sc_code;
  return SC_ERROR_INVALID_ARGUMENT;
}

}  // namespace detail
}  // namespace sc

const char* SCGetErrorString(SCint code) {
  if (code == SC_ERROR_INVALID_LICENSE)
    return "invalid license (never returned: SmartCollision needs no license)";
  for (const auto& [modern, sc_code] : sc::kScCodes)
    if (sc_code == code) return sc::describe(modern);
  return "unknown SmartCollision result code";
}
