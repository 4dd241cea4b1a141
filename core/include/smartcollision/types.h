// SPDX-License-Identifier: MIT
// Basic value types of the modern API: vectors, rigid transforms, statuses,
// features and the enums the scene speaks in.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "smartcollision/export.h"

namespace sc {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;
using Tri = Eigen::Vector3i;  ///< three vertex indices, counter-clockwise seen from outside

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr double kPi = 3.14159265358979323846;

/// Rigid transform p -> rotation * p + translation. Named `<to>_from_<from>`.
struct Rigid {
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();

  Vec3 operator*(const Vec3& p) const { return rotation * p + translation; }
  Rigid operator*(const Rigid& o) const {
    return {rotation * o.rotation, rotation * o.translation + translation};
  }
  Rigid inverse() const {
    const Mat3 rt = rotation.transpose();
    return {rt, -(rt * translation)};
  }
};

/// Axis-aligned box; empty when min > max.
struct Aabb {
  Vec3 min = Vec3::Constant(kInfinity);
  Vec3 max = Vec3::Constant(-kInfinity);

  bool empty() const { return (min.array() > max.array()).any(); }
  void extend(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void extend(const Aabb& b) {
    min = min.cwiseMin(b.min);
    max = max.cwiseMax(b.max);
  }
};

/// The tight world box of the local box `box` moved by `world_from_local`.
inline Aabb transformBox(const Aabb& box, const Rigid& world_from_local) {
  if (box.empty()) return box;
  const Vec3 c = world_from_local * Vec3(0.5 * (box.min + box.max));
  const Vec3 e = world_from_local.rotation.cwiseAbs() * Vec3(0.5 * (box.max - box.min));
  Aabb out;
  out.min = c - e;
  out.max = c + e;
  return out;
}

/// Euclidean distance between boxes (0 when they overlap); symmetric bit for bit.
inline double boxDistance(const Aabb& a, const Aabb& b) {
  return (a.min - b.max).cwiseMax(b.min - a.max).cwiseMax(Vec3::Zero()).norm();
}

/// What went wrong, or Ok. Each code has one SC_* code of sc.h, but not its number
/// (sc.h keeps the manual's SC_ERROR_INVALID_LICENSE = 3): never cast one to the other.
enum class ErrorCode : std::uint8_t {
  Ok,
  NoResult,                      ///< nothing computed in this direction (far, inactive)
  InvalidInitialTransformation,  ///< first seen intersecting: no dynamic depth yet
  InvalidGeometry,               ///< mesh breaks the closed-polyhedron rules
  InvalidArgument,               ///< non-finite number, bad count, null pointer, bad enum
  InvalidId,                     ///< unknown or duplicate object/group id
  InvalidOperation,              ///< call not allowed in the current state
  File,                          ///< cache file could not be read or written
};

/// Short English description of a code; never null.
SC_API const char* describe(ErrorCode code);

/// Outcome of work that can fail: a code plus a message for people.
class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(ErrorCode code, std::string message) : code_(code), message_(std::move(message)) {}
  static Status success() { return {}; }

  bool ok() const { return code_ == ErrorCode::Ok; }
  ErrorCode code() const { return code_; }
  const std::string& message() const { return message_; }

 private:
  ErrorCode code_ = ErrorCode::Ok;
  std::string message_;
};

/// A value and the status of producing it. `value` is meaningful when `hasValue()`;
/// a value may come with a non-Ok status that is only a warning (ErrorCode::File).
template <class T>
class [[nodiscard]] Result {
 public:
  Result(Status status) : status_(std::move(status)) {}  // NOLINT: implicit by design
  Result(T value, Status status = {})
      : status_(std::move(status)), value_(std::move(value)), has_value_(true) {}

  bool ok() const { return status_.ok() && has_value_; }
  bool hasValue() const { return has_value_; }
  const Status& status() const { return status_; }
  const T& value() const { return value_; }
  T& value() { return value_; }

 private:
  Status status_;
  T value_{};
  bool has_value_ = false;
};

enum class FeatureType : std::uint8_t { Vertex, Edge, Face };

/// A vertex, edge or face of a piece, as original vertex indices within the piece
/// (1, 2 or 3 of them, the rest -1). A virtual feature is spanned by real vertices
/// but is not an edge or triangle of the input mesh.
struct Feature {
  FeatureType type = FeatureType::Vertex;
  int vertices[3] = {-1, -1, -1};
  bool is_virtual = false;

  int count() const { return type == FeatureType::Vertex ? 1 : type == FeatureType::Edge ? 2 : 3; }
};

enum class ModelKind : std::uint8_t { ClosedPolyhedron, TriangleSoup };

/// Activity of an object (Active/Inactive only) or a group (manual Table 8-1).
enum class Activity : std::uint8_t { Active, Sleeping, Passive, Inactive };

/// Explicit setting of a group pair; one-way values set only the direction whose
/// target is the first group.
enum class PairActivity : std::uint8_t { Active, Inactive, OneWayActive, OneWayInactive };

/// How a penetrating pair splits its depth into translation and rotation (manual 8.8).
enum class RotationMode : std::uint8_t {
  None,   ///< contact orientation frozen at the impact (the first contact on the path)
  Input,  ///< rotation follows the input; translation resolves (the default)
  Free,   ///< translation minimised first; rotation resolves the rest
  Mix,    ///< minimise 1/2 kT |TPDV|^2 + 1/2 kR |RPDV|^2
};

}  // namespace sc
