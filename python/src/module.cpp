// SPDX-License-Identifier: MIT
// The extension module smartcollision._core: enums, settings, the exception
// hierarchy and the translation of library statuses into it.
#include <pybind11/stl.h>

#include <string>

#include "bindings.h"

namespace scpy {
namespace {

// Exception classes by ErrorCode (owned by the module, which outlives every call).
PyObject* g_errors[8] = {};

PyObject* newError(py::module_& m, const char* name, const char* doc, PyObject* base,
                   PyObject* builtin) {
  const std::string qualified = std::string("smartcollision.") + name;
  py::tuple bases = builtin ? py::make_tuple(py::handle(base), py::handle(builtin))
                            : py::make_tuple(py::handle(base));
  PyObject* e = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (!e) throw py::error_already_set();
  m.add_object(name, py::handle(e));  // the module keeps a reference; we keep ours
  return e;
}

void bindErrors(py::module_& m) {
  PyObject* base =
      newError(m, "Error", "Base of every SmartCollision error.", PyExc_Exception, nullptr);
  using E = sc::ErrorCode;
  for (PyObject*& e : g_errors) e = base;
  g_errors[static_cast<int>(E::InvalidArgument)] =
      newError(m, "InvalidArgumentError",
               "Bad input: shape, non-finite number, bad index, out-of-range value.", base,
               PyExc_ValueError);
  g_errors[static_cast<int>(E::InvalidGeometry)] = newError(
      m, "InvalidGeometryError", "A closed polyhedron that is not closed, oriented and one shell.",
      base, PyExc_ValueError);
  g_errors[static_cast<int>(E::InvalidId)] = newError(
      m, "InvalidIdError", "Unknown or duplicate object or group id.", base, PyExc_LookupError);
  g_errors[static_cast<int>(E::InvalidOperation)] =
      newError(m, "InvalidOperationError", "A call not allowed in the current state.", base,
               PyExc_RuntimeError);
  g_errors[static_cast<int>(E::InvalidInitialTransformation)] =
      newError(m, "InitialIntersectionError",
               "The pair intersects and was never seen apart: no depth yet.", base, nullptr);
  g_errors[static_cast<int>(E::File)] =
      newError(m, "FileError", "A cache file could not be read or written.", base, PyExc_OSError);
  newError(m, "CacheFileWarning", "The model was built but its cache file could not be written.",
           PyExc_UserWarning, nullptr);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      PyErr_SetString(g_errors[static_cast<int>(e.code) & 7], e.what());
    }
  });
}

void bindEnums(py::module_& m) {
  py::enum_<sc::ErrorCode>(m, "Status",
                           "Outcome of a query direction (values of sc.h's SC_* codes).")
      .value("OK", sc::ErrorCode::Ok)
      .value("NO_RESULT", sc::ErrorCode::NoResult)
      .value("INVALID_INITIAL_TRANSFORMATION", sc::ErrorCode::InvalidInitialTransformation)
      .value("INVALID_GEOMETRY", sc::ErrorCode::InvalidGeometry)
      .value("INVALID_ARGUMENT", sc::ErrorCode::InvalidArgument)
      .value("INVALID_ID", sc::ErrorCode::InvalidId)
      .value("INVALID_OPERATION", sc::ErrorCode::InvalidOperation)
      .value("FILE", sc::ErrorCode::File);
  struct Named {
    const char* name;
    sc::DirectionStatus value;
    const char* doc;
  };
  using D = sc::DirectionStatus;
  const Named statuses[] = {
      {"NOT_COMPUTED", D::NotComputed,
       "Not updated (a static or passive target) or settings out of range."},
      {"BEYOND_MAX_DISTANCE", D::BeyondMaxDistance, "Apart by more than settings.max_distance."},
      {"FIRST_SEEN_INTERSECTING", D::FirstSeenIntersecting,
       "Intersecting with no free pose known yet."},
      {"SEPARATED", D::Separated, "Apart by more than the tolerance."},
      {"TOUCHING", D::Touching, "Apart or in contact within the tolerance; no depth."},
      {"PENETRATING", D::Penetrating, "A depth; the contact configuration is settled."},
      {"LAGGING", D::Lagging,
       "A depth, but the proxy ran out of iterations on its way (catches up later)."}};
  py::enum_<D> direction_status(m, "DirectionStatus",
                                "What a direction's update found (Result.direction_status).");
  for (const Named& s : statuses) direction_status.value(s.name, s.value, s.doc);
  py::enum_<sc::ModelKind>(m, "ModelKind")
      .value("CLOSED_POLYHEDRON", sc::ModelKind::ClosedPolyhedron,
             "Closed, oriented, one shell; has an inside.")
      .value("TRIANGLE_SOUP", sc::ModelKind::TriangleSoup, "Any triangles; no inside.");
  py::enum_<sc::RotationMode>(m, "RotationMode",
                              "How a penetration splits into translation and rotation.")
      .value("NONE", sc::RotationMode::None, "Contact orientation frozen at the last free pose.")
      .value("INPUT", sc::RotationMode::Input,
             "Rotation follows the input; translation resolves (default).")
      .value("FREE", sc::RotationMode::Free,
             "Translation minimised first; rotation resolves the rest.")
      .value("MIX", sc::RotationMode::Mix, "Minimise kT|TPDV|^2/2 + kR|RPDV|^2/2.");
  py::enum_<sc::Broadphase>(m, "Broadphase")
      .value("TREE", sc::Broadphase::Tree)
      .value("BRUTE_FORCE", sc::Broadphase::BruteForce);
  py::enum_<sc::Activity>(m, "Activity",
                          "Of an object (ACTIVE/INACTIVE) or a group (manual Table 8-1).")
      .value("ACTIVE", sc::Activity::Active)
      .value("SLEEPING", sc::Activity::Sleeping)
      .value("PASSIVE", sc::Activity::Passive)
      .value("INACTIVE", sc::Activity::Inactive);
  py::enum_<sc::PairActivity>(m, "PairActivity")
      .value("ACTIVE", sc::PairActivity::Active)
      .value("INACTIVE", sc::PairActivity::Inactive)
      .value("ONE_WAY_ACTIVE", sc::PairActivity::OneWayActive)
      .value("ONE_WAY_INACTIVE", sc::PairActivity::OneWayInactive);
  py::enum_<sc::FeatureType>(m, "FeatureType")
      .value("VERTEX", sc::FeatureType::Vertex)
      .value("EDGE", sc::FeatureType::Edge)
      .value("FACE", sc::FeatureType::Face);
}

void bindSettings(py::module_& m) {
  using S = sc::SceneSettings;
  const S d;
  py::class_<S>(m, "Settings", "Every tunable of a tracker or scene (validated when assigned).")
      .def(py::init([](double max_distance, double tolerance, double safety_coefficient,
                       int max_iterations, sc::RotationMode rotation_mode, double force_stiffness,
                       double torque_stiffness, int threads, sc::Broadphase broadphase,
                       bool resolve_initial_intersection, bool contact_points,
                       double teleport_distance, double proxy_travel_ratio) {
             const sc::PairSettings pair{max_distance,       tolerance,
                                         safety_coefficient, max_iterations,
                                         rotation_mode,      force_stiffness,
                                         torque_stiffness,   resolve_initial_intersection,
                                         teleport_distance,  proxy_travel_ratio};
             return S{pair, threads, broadphase, contact_points};
           }),
           py::kw_only(), py::arg("max_distance") = d.max_distance,
           py::arg("tolerance") = d.tolerance, py::arg("safety_coefficient") = d.safety_coefficient,
           py::arg("max_iterations") = d.max_iterations, py::arg("rotation_mode") = d.rotation_mode,
           py::arg("force_stiffness") = d.force_stiffness,
           py::arg("torque_stiffness") = d.torque_stiffness, py::arg("threads") = d.threads,
           py::arg("broadphase") = d.broadphase,
           py::arg("resolve_initial_intersection") = d.resolve_initial_intersection,
           py::arg("contact_points") = d.contact_points,
           py::arg("teleport_distance") = d.teleport_distance,
           py::arg("proxy_travel_ratio") = d.proxy_travel_ratio)
      .def_readwrite("max_distance", &S::max_distance,
                     "Pairs farther apart report NO_RESULT (inf: all).")
      .def_readwrite("tolerance", &S::tolerance,
                     "Accuracy of the penetration depth (model units, > 0).")
      .def_readwrite("safety_coefficient", &S::safety_coefficient,
                     "Fraction of the tolerance per rotational step.")
      .def_readwrite("max_iterations", &S::max_iterations,
                     "Proxy iterations per query and direction (>= 1).")
      .def_readwrite("rotation_mode", &S::rotation_mode)
      .def_readwrite("force_stiffness", &S::force_stiffness, "kT of RotationMode.MIX.")
      .def_readwrite("torque_stiffness", &S::torque_stiffness, "kR of RotationMode.MIX.")
      .def_readwrite("threads", &S::threads, "Scene threads (0: automatic, 1: serial).")
      .def_readwrite("broadphase", &S::broadphase)
      .def_readwrite("resolve_initial_intersection", &S::resolve_initial_intersection,
                     "Start a pair first seen intersecting from a nearby free pose.")
      .def_readwrite("contact_points", &S::contact_points,
                     "Scenes also list every contact within the tolerance.")
      .def_readwrite("teleport_distance", &S::teleport_distance,
                     "A motion moving a target point farther between updates restarts the "
                     "direction as first seen (inf: every motion is a path).")
      .def_readwrite("proxy_travel_ratio", &S::proxy_travel_ratio,
                     "Per update the proxy moves at most this many times as far as the "
                     "target (>= 1; inf: it settles every update; 2 keeps forces continuous).")
      .def(
          "validate", [](const S& s) { check(sc::validate(s)); },
          "Raises InvalidArgumentError naming the first field out of range.")
      .def("__repr__", [](const S& s) {
        return "Settings(tolerance=" + py::repr(py::float_(s.tolerance)).cast<std::string>() +
               ", max_distance=" + py::repr(py::float_(s.max_distance)).cast<std::string>() +
               ", rotation_mode=" + py::str(py::cast(s.rotation_mode)).cast<std::string>() +
               ", max_iterations=" + std::to_string(s.max_iterations) + ")";
      });
}

}  // namespace

void requireIdle(bool busy, const char* what) {
  if (busy)
    fail(sc::ErrorCode::InvalidOperation, std::string(what) + " is in use by another thread");
}

}  // namespace scpy

PYBIND11_MODULE(_core, m) {
  m.doc() = "SmartCollision: distance and dynamic penetration depth between meshes.";
  // Classes and signatures name the package users import, not this extension.
  m.attr("__name__") = "smartcollision";
  scpy::bindErrors(m);
  scpy::bindEnums(m);
  scpy::bindSettings(m);
  scpy::bindModel(m);
  scpy::bindResults(m);
  scpy::bindTracker(m);
  scpy::bindScene(m);
  m.attr("STATIC_GROUP") = sc::kStaticGroup;
  m.attr("DEFAULT_TOLERANCE") = sc::kDefaultTolerance;
  m.attr("__name__") = "smartcollision._core";
}
