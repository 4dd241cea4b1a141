// SPDX-License-Identifier: MIT
// Result, Feature and PairTracker: one pair of models followed across poses, queried
// without the GIL.
#include <pybind11/stl.h>

#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"

namespace scpy {
namespace {

/// A directed result and the target's model-frame centre of rotation (for its pose).
struct PyResult {
  sc::DirectedResult r;
  sc::Vec3 local_center = sc::Vec3::Zero();
};

struct PyTracker {
  sc::ModelPtr models[2];
  sc::Part parts[2];
  sc::Vec3 centers[2];
  sc::SceneSettings settings;
  sc::PairTracker tracker;
  sc::DirectedResult out[2];
  std::vector<sc::ContactPoint> contacts;
  bool busy = false;

  PyTracker(const PyModel& a, const PyModel& b, const std::optional<sc::SceneSettings>& settings_,
            const OptArrayArg& center_a, const OptArrayArg& center_b)
      : models{a.model, b.model} {
    for (int i = 0; i < 2; ++i) parts[i] = {models[i].get(), sc::Rigid(), i};
    centers[0] = vec3From(center_a, "center_a");
    centers[1] = vec3From(center_b, "center_b");
    if (settings_) setSettings(*settings_);
  }

  void setSettings(const sc::SceneSettings& s) {
    requireIdle(busy, "PairTracker");
    check(sc::validate(s));
    settings = s;
  }

  void run(const PoseArg& pose_a, const PoseArg& pose_b, sc::Directions directions) {
    const sc::GroupView a{&parts[0], 1, placementFrom(pose_a, centers[0])};
    const sc::GroupView b{&parts[1], 1, placementFrom(pose_b, centers[1])};
    BusyScope scope(busy, "PairTracker");
    py::gil_scoped_release release;
    tracker.update(a, b, directions, settings, out);
  }

  int direction(int d) const {
    if (d != 0 && d != 1)
      fail(sc::ErrorCode::InvalidArgument, "direction must be 0 (a target) or 1 (b target)");
    return d;
  }
};

double distanceOf(PyTracker& t, const PoseArg& pose_a, const PoseArg& pose_b) {
  t.run(pose_a, pose_b, {true, false});
  const sc::DirectedResult& r = t.out[0];
  if (r.code == sc::ErrorCode::Ok) return r.distance;
  if (r.code == sc::ErrorCode::NoResult) return std::numeric_limits<double>::infinity();
  fail(r.code, "the pair intersects and was never seen apart: no penetration depth yet");
}

py::tuple featureVertices(const sc::Feature& f) {
  py::tuple t(static_cast<size_t>(f.count()));
  for (int i = 0; i < f.count(); ++i) t[static_cast<size_t>(i)] = f.vertices[i];
  return t;
}

void bindFeature(py::module_& m) {
  py::class_<sc::Feature>(
      m, "Feature", "A vertex, edge or face of a piece, as input vertex indices within the piece.")
      .def_property_readonly("type", [](const sc::Feature& f) { return f.type; })
      .def_property_readonly("vertices", &featureVertices, "1, 2 or 3 vertex indices.")
      .def_readonly("is_virtual", &sc::Feature::is_virtual,
                    "Spanned by input vertices but not an input edge or triangle (a hull feature).")
      .def("__repr__", [](const sc::Feature& f) {
        return "Feature(" + py::str(py::cast(f.type)).cast<std::string>() + ", " +
               py::repr(featureVertices(f)).cast<std::string>() +
               (f.is_virtual ? ", virtual)" : ")");
      });
}

template <class F>
auto field(F f) {
  return [f](const PyResult& p) { return f(p.r); };
}

void bindResult(py::module_& m) {
  using R = sc::DirectedResult;
  py::class_<PyResult>(m, "Result", R"(One direction of a pair: a target moved against an opponent.

World coordinates. Apart (distance > 0): closest points, tpdv = rpdv = 0.
Penetrating (distance <= 0, = -|tpdv|): the contact pose is the last free pose the
target can reach, current centre = contact_position + tpdv, R(current) =
Rot(rpdv) R(contact); points are contact points with the target there. Fields
other than status are meaningful only when ok.)")
      .def_property_readonly(
          "status", field([](const R& r) { return r.code; }),
          "OK, NO_RESULT (not computed, beyond max_distance) or INVALID_INITIAL_TRANSFORMATION.")
      .def_property_readonly(
          "direction_status", field([](const R& r) { return r.status; }),
          "What happened: SEPARATED, TOUCHING and PENETRATING told apart (both of the last can\n"
          "have distance 0), LAGGING from a settled depth, and why there is no result.")
      .def_property_readonly("has_depth", field([](const R& r) { return r.hasDepth(); }),
                             "direction_status is PENETRATING or LAGGING: tpdv/rpdv are a depth.")
      .def_property_readonly("ok", field([](const R& r) { return r.code == sc::ErrorCode::Ok; }),
                             "status is OK: the other fields are meaningful.")
      .def_property_readonly("penetrating", field([](const R& r) { return r.penetrating(); }),
                             "ok and distance <= 0.")
      .def_property_readonly("distance", field([](const R& r) { return r.distance; }),
                             "> 0: the minimum distance; <= 0: -|tpdv|.")
      .def_property_readonly("normal", field([](const R& r) { return toArray(r.normal); }),
                             "Unit, from the opponent towards the target.")
      .def_property_readonly(
          "point_on_target", field([](const R& r) { return toArray(r.point_on_target); }),
          "Closest point (apart) or contact point at the contact pose, on the target.")
      .def_property_readonly("point_on_opponent",
                             field([](const R& r) { return toArray(r.point_on_opponent); }),
                             "The same on the opponent.")
      .def_property_readonly(
          "tpdv", field([](const R& r) { return toArray(r.tpdv); }),
          "Translational penetration depth vector: current centre minus contact centre.")
      .def_property_readonly("rpdv", field([](const R& r) { return toArray(r.rpdv); }),
                             "Rotational penetration depth vector (rotation vector, radians).")
      .def_property_readonly("contact_position",
                             field([](const R& r) { return toArray(r.contact_position); }),
                             "The target's world centre of rotation at contact.")
      .def_property_readonly("contact_orientation",
                             field([](const R& r) { return toArray(r.contact_orientation); }),
                             "The target's orientation at contact, quaternion w, x, y, z.")
      .def_property_readonly(
          "contact_pose",
          [](const PyResult& p) {
            sc::Placement c;
            c.local_center = p.local_center;
            c.world_center = p.r.contact_position;
            c.orientation = p.r.contact_orientation;
            return poseMatrix(c);
          },
          "4x4 world-from-model matrix of the target at contact.")
      .def_property_readonly("target_object", field([](const R& r) { return r.target_object; }),
                             "Object id of the target (a tracker: 0 for a, 1 for b).")
      .def_property_readonly("opponent_object", field([](const R& r) { return r.opponent_object; }),
                             "Object id of the opponent.")
      .def_property_readonly("target_piece", field([](const R& r) { return r.target_piece; }),
                             "Piece of the target's model holding the contact.")
      .def_property_readonly("opponent_piece", field([](const R& r) { return r.opponent_piece; }),
                             "Piece of the opponent's model holding the contact.")
      .def_property_readonly("target_feature", field([](const R& r) { return r.target_feature; }),
                             "Closest feature of the target (vertex indices within its piece).")
      .def_property_readonly("opponent_feature",
                             field([](const R& r) { return r.opponent_feature; }),
                             "Closest feature of the opponent.")
      .def("__repr__", [](const PyResult& p) {
        return "Result(" + py::str(py::cast(p.r.code)).cast<std::string>() +
               ", distance=" + py::repr(py::float_(p.r.distance)).cast<std::string>() + ")";
      });
}

}  // namespace

py::object resultOf(const sc::DirectedResult& r, const sc::Vec3& local_center) {
  return py::cast(PyResult{r, local_center});
}

py::dict contactArrays(const std::vector<sc::ContactPoint>& points) {
  const auto n = static_cast<py::ssize_t>(points.size());
  py::array_t<double> pt({n, py::ssize_t{3}}), po({n, py::ssize_t{3}}), nn({n, py::ssize_t{3}});
  py::array_t<double> sep(n);
  py::array_t<int> ids[4] = {py::array_t<int>(n), py::array_t<int>(n), py::array_t<int>(n),
                             py::array_t<int>(n)};
  for (py::ssize_t i = 0; i < n; ++i) {
    const sc::ContactPoint& c = points[static_cast<size_t>(i)];
    std::copy(c.point_on_target.data(), c.point_on_target.data() + 3, pt.mutable_data(i));
    std::copy(c.point_on_opponent.data(), c.point_on_opponent.data() + 3, po.mutable_data(i));
    std::copy(c.normal.data(), c.normal.data() + 3, nn.mutable_data(i));
    sep.mutable_at(i) = c.separation;
    const int v[4] = {c.target_object, c.opponent_object, c.target_piece, c.opponent_piece};
    for (int k = 0; k < 4; ++k) ids[k].mutable_at(i) = v[k];
  }
  py::dict d;
  d["point_on_target"] = pt, d["point_on_opponent"] = po, d["normal"] = nn, d["separation"] = sep;
  d["target_object"] = ids[0], d["opponent_object"] = ids[1];
  d["target_piece"] = ids[2], d["opponent_piece"] = ids[3];
  return d;
}

void bindResults(py::module_& m) {
  bindFeature(m);
  bindResult(m);
}

void bindTracker(py::module_& m) {
  py::class_<PyTracker>(m, "PairTracker",
                        R"(Two models followed across poses: minimum distance when apart, dynamic
penetration depth (TPDV, RPDV) when penetrating.

The depth of a penetrating pair follows its motion: the tracker keeps the last
free pose of the target (a in distance/penetration, each model in update) and must
first see the pair apart. Poses are world-from-model: a 4x4 matrix, a position
(3,), a (7,) array or a pair (position, quaternion w, x, y, z). center_a, center_b:
each model's centre of rotation in its own frame (default: its origin). Queries
run without the GIL; one tracker must not be used by two threads at once
(InvalidOperationError), separate trackers may.)")
      .def(py::init<const PyModel&, const PyModel&, const std::optional<sc::SceneSettings>&,
                    const OptArrayArg&, const OptArrayArg&>(),
           py::arg("a"), py::arg("b"), py::arg("settings") = py::none(),
           py::arg("center_a") = py::none(), py::arg("center_b") = py::none())
      .def_property(
          "settings", [](const PyTracker& t) { return t.settings; }, &PyTracker::setSettings,
          "A copy of the settings; assign a Settings to change them (validated).")
      .def("distance", &distanceOf, py::arg("pose_a"), py::arg("pose_b"),
           R"(Signed distance with a as target: > 0 apart, <= 0 penetrating (-|tpdv|).

inf beyond settings.max_distance. Raises InitialIntersectionError when the pair
intersects and has never been seen apart (unless settings.resolve_initial_intersection).)")
      .def(
          "penetration",
          [](PyTracker& t, const PoseArg& pa, const PoseArg& pb) {
            t.run(pa, pb, {true, false});
            return resultOf(t.out[0], t.centers[0]);
          },
          py::arg("pose_a"), py::arg("pose_b"),
          "Full result with a as target and b as opponent (see Result).")
      .def(
          "update",
          [](PyTracker& t, const PoseArg& pa, const PoseArg& pb) {
            t.run(pa, pb, {true, true});
            return py::make_tuple(resultOf(t.out[0], t.centers[0]),
                                  resultOf(t.out[1], t.centers[1]));
          },
          py::arg("pose_a"), py::arg("pose_b"), "Both directions: (a as target, b as target).")
      .def(
          "contacts",
          [](PyTracker& t, int direction, const py::object& margin) {
            requireIdle(t.busy, "PairTracker");
            const double mg = margin.is_none() ? t.settings.tolerance : margin.cast<double>();
            if (!(mg >= 0.0)) fail(sc::ErrorCode::InvalidArgument, "margin must be >= 0");
            t.tracker.contactPoints(t.direction(direction), mg, t.contacts);
            return contactArrays(t.contacts);
          },
          py::arg("direction") = 0, py::arg("margin") = py::none(),
          R"(Every contact of the last query's direction (0: a target, 1: b target) within
margin (default: the tolerance) at the contact pose, nearest first, as a dict of
arrays: point_on_target, point_on_opponent, normal (k, 3); separation (k,) at
the current pose (< 0 penetrating); target/opponent_object and _piece (k,).)")
      .def(
          "forget",
          [](PyTracker& t, const py::object& direction) {
            requireIdle(t.busy, "PairTracker");
            if (direction.is_none()) {
              t.tracker.forget(0), t.tracker.forget(1);
            } else {
              t.tracker.forget(t.direction(direction.cast<int>()));
            }
          },
          py::arg("direction") = py::none(),
          "Drops the tracking state (of one direction, or both).")
      .def(
          "tracking", [](const PyTracker& t, int d) { return t.tracker.tracking(t.direction(d)); },
          py::arg("direction") = 0,
          "True once the direction has seen the pair apart and follows it.");
}

}  // namespace scpy
