// SPDX-License-Identifier: MIT
#include "convert.h"

#include <climits>
#include <cmath>
#include <string>
#include <utility>

namespace scpy {
namespace {

// Coordinates beyond this overflow squared distances; the sc.h layer refuses them too.
constexpr double kMaxCoordinate = 1e100;

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Indices = py::array_t<long long, py::array::c_style | py::array::forcecast>;

std::string shapeOf(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// The dtype kind of a numpy array, or 0 for anything else (converted by numpy).
char kindOf(const py::handle& h) {
  return py::isinstance<py::array>(h) ? py::reinterpret_borrow<py::array>(h).dtype().kind() : 0;
}

void requireKind(const py::handle& h, const char* kinds, const char* what) {
  const char k = kindOf(h);
  if (k != 0 && std::string(kinds).find(k) == std::string::npos) {
    throw py::type_error(std::string(what) + ": dtype " +
                         py::str(py::reinterpret_borrow<py::array>(h).dtype()).cast<std::string>() +
                         " is not accepted");
  }
}

Doubles doublesFrom(const py::handle& h, const char* what) {
  // Already float64 and C-contiguous: used in place (the per-query path).
  if (py::isinstance<Doubles>(h)) return py::reinterpret_borrow<Doubles>(h);
  requireKind(h, "fiu", what);
  Doubles a = Doubles::ensure(h);
  if (!a) throw py::type_error(std::string(what) + ": not convertible to a float64 array");
  return a;
}

void requireFinite(const double* v, py::ssize_t n, const char* what) {
  for (py::ssize_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i]) || std::abs(v[i]) > kMaxCoordinate) {
      fail(sc::ErrorCode::InvalidArgument,
           std::string(what) + ": non-finite or beyond 1e100 in magnitude");
    }
  }
}

sc::Quat quatFrom(const double* wxyz) {
  const sc::Quat q(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
  if (!(q.norm() > 0.0)) fail(sc::ErrorCode::InvalidArgument, "pose: zero quaternion");
  return q;
}

sc::Placement placed(const sc::Vec3& origin, const sc::Quat& q, const sc::Vec3& local_center) {
  sc::Placement p;
  p.local_center = local_center;
  p.setOrientation(q);
  p.setOrigin(origin);
  requireFinite(p.world_center.data(), 3, "pose");
  return p;
}

sc::Placement fromMatrix(const double* m, const sc::Vec3& local_center) {
  const Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>> M(m);
  if (M(3, 0) != 0.0 || M(3, 1) != 0.0 || M(3, 2) != 0.0 || M(3, 3) != 1.0) {
    fail(sc::ErrorCode::InvalidArgument, "pose: a 4x4 matrix must end with the row 0 0 0 1");
  }
  const sc::Result<sc::Quat> q = sc::rotationToQuaternion(M.topLeftCorner<3, 3>());
  check(q.status());
  return placed(M.topRightCorner<3, 1>(), q.value(), local_center);
}

}  // namespace

void fail(sc::ErrorCode code, const std::string& message) { throw Error(code, message); }

void check(const sc::Status& status) {
  if (!status.ok()) fail(status.code(), status.message());
}

sc::MeshData meshFrom(const py::handle& vertices, const py::handle& triangles) {
  const Doubles v = doublesFrom(vertices, "vertices");
  requireKind(triangles, "iu", "triangles");
  const Indices t = Indices::ensure(triangles);
  if (!t) throw py::type_error("triangles: not convertible to an integer array");
  if (v.ndim() != 2 || v.shape(1) != 3) {
    fail(sc::ErrorCode::InvalidArgument, "vertices: shape " + shapeOf(v) + ", expected (n, 3)");
  }
  if (t.ndim() != 2 || t.shape(1) != 3) {
    fail(sc::ErrorCode::InvalidArgument, "triangles: shape " + shapeOf(t) + ", expected (m, 3)");
  }
  sc::MeshData mesh;
  mesh.vertices.resize(static_cast<size_t>(v.shape(0)));
  const double* pv = v.data();
  for (size_t i = 0; i < mesh.vertices.size(); ++i)
    mesh.vertices[i] = {pv[3 * i], pv[3 * i + 1], pv[3 * i + 2]};
  mesh.triangles.resize(static_cast<size_t>(t.shape(0)));
  const long long* pt = t.data();
  for (size_t i = 0; i < 3 * mesh.triangles.size(); ++i) {
    // Out-of-range indices that fit an int are left to the library's check.
    if (pt[i] < INT_MIN || pt[i] > INT_MAX) {  // where, not the value: int64 may wrap it
      fail(sc::ErrorCode::InvalidArgument, "triangles: index at [" + std::to_string(i / 3) + ", " +
                                               std::to_string(i % 3) + "] out of range");
    }
    mesh.triangles[i / 3][static_cast<int>(i % 3)] = static_cast<int>(pt[i]);
  }
  return mesh;
}

sc::Vec3 vec3From(const py::handle& value, const char* what) {
  if (value.is_none()) return sc::Vec3::Zero();
  const Doubles a = doublesFrom(value, what);
  if (a.ndim() != 1 || a.shape(0) != 3) {
    fail(sc::ErrorCode::InvalidArgument,
         std::string(what) + ": shape " + shapeOf(a) + ", expected (3,)");
  }
  requireFinite(a.data(), 3, what);
  return {a.data()[0], a.data()[1], a.data()[2]};
}

sc::Placement placementFrom(const py::handle& pose, const sc::Vec3& local_center) {
  constexpr const char* kForms =
      "expected a position (3,), position + quaternion (7,), a pair or a 4x4 matrix";
  if (pose.is_none()) fail(sc::ErrorCode::InvalidArgument, std::string("pose: None, ") + kForms);
  // A pair holds two sequences; [1, 0] is a (too short) position.
  if ((py::isinstance<py::tuple>(pose) || py::isinstance<py::list>(pose)) && py::len(pose) == 2 &&
      py::hasattr(py::reinterpret_borrow<py::sequence>(pose)[0], "__len__")) {
    const py::sequence pair = py::reinterpret_borrow<py::sequence>(pose);
    const sc::Vec3 origin = vec3From(pair[0], "pose position");
    const Doubles q = doublesFrom(pair[1], "pose quaternion");
    if (q.ndim() != 1 || q.shape(0) != 4) {
      fail(sc::ErrorCode::InvalidArgument,
           "pose quaternion: shape " + shapeOf(q) + ", expected (4,) as w, x, y, z");
    }
    requireFinite(q.data(), 4, "pose quaternion");
    return placed(origin, quatFrom(q.data()), local_center);
  }
  const Doubles a = doublesFrom(pose, "pose");
  const double* d = a.data();
  requireFinite(d, a.size(), "pose");
  if (a.ndim() == 1 && a.shape(0) == 3)
    return placed({d[0], d[1], d[2]}, sc::Quat::Identity(), local_center);
  if (a.ndim() == 1 && a.shape(0) == 7)
    return placed({d[0], d[1], d[2]}, quatFrom(d + 3), local_center);
  if (a.ndim() == 2 && a.shape(0) == 4 && a.shape(1) == 4) return fromMatrix(d, local_center);
  fail(sc::ErrorCode::InvalidArgument, "pose: shape " + shapeOf(a) + ", " + kForms);
}

py::array_t<double> toArray(const sc::Vec3& v) {
  py::array_t<double> a(3);
  std::copy(v.data(), v.data() + 3, a.mutable_data());
  return a;
}

py::array_t<double> toArray(const sc::Quat& q) {
  py::array_t<double> a(4);
  double* d = a.mutable_data();
  d[0] = q.w(), d[1] = q.x(), d[2] = q.y(), d[3] = q.z();
  return a;
}

py::array_t<double> poseMatrix(const sc::Placement& p) {
  py::array_t<double> a({4, 4});
  Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(a.mutable_data()) = p.matrix();
  return a;
}

}  // namespace scpy
