// SPDX-License-Identifier: MIT
// Conversions between numpy arrays and the library's types, and the error that
// carries a library status to a Python exception.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>

#include "smartcollision/smartcollision.h"

namespace scpy {

namespace py = pybind11;

/// A library status on its way to Python: the module's translator raises the
/// exception class of `code` with `message`.
struct Error : std::runtime_error {
  Error(sc::ErrorCode c, const std::string& message) : std::runtime_error(message), code(c) {}
  sc::ErrorCode code;
};

[[noreturn]] void fail(sc::ErrorCode code, const std::string& message);
/// Raises unless `status` is Ok.
void check(const sc::Status& status);

/// An argument taken as any Python object and checked by the conversions below,
/// named in signatures (help()) as the stubs name it.
template <int Kind>
struct Arg {
  py::object value;
  operator const py::object&() const { return value; }  // NOLINT: reads as the object
};
using PoseArg = Arg<0>;      ///< "Pose"
using ArrayArg = Arg<1>;     ///< "ArrayLike"
using OptArrayArg = Arg<2>;  ///< "Optional[ArrayLike]"

/// vertices: real array of shape (n, 3); triangles: integer array of shape (m, 3).
sc::MeshData meshFrom(const py::handle& vertices, const py::handle& triangles);

/// A pose of a model frame in the world: a 4x4 homogeneous matrix, a position (3,),
/// position and quaternion w, x, y, z as one (7,) array or a pair. `local_center` is
/// the model-frame centre of rotation kept in the placement.
sc::Placement placementFrom(const py::handle& pose, const sc::Vec3& local_center);
/// A finite 3-vector (None: zero).
sc::Vec3 vec3From(const py::handle& value, const char* what);

/// Fresh numpy arrays.
py::array_t<double> toArray(const sc::Vec3& v);
py::array_t<double> toArray(const sc::Quat& q);  ///< w, x, y, z
/// 4x4 homogeneous matrix of world_from_model for a placement.
py::array_t<double> poseMatrix(const sc::Placement& p);

}  // namespace scpy

namespace pybind11::detail {

template <int Kind>
struct type_caster<scpy::Arg<Kind>> {
  PYBIND11_TYPE_CASTER(scpy::Arg<Kind>,
                       _<Kind == 0>(_("Pose"),
                                    _<Kind == 1>(_("ArrayLike"), _("Optional[ArrayLike]"))));
  bool load(handle src, bool) {
    value.value = reinterpret_borrow<object>(src);
    return true;
  }
  static handle cast(const scpy::Arg<Kind>& a, return_value_policy, handle) {
    return a.value.inc_ref();
  }
};

}  // namespace pybind11::detail
