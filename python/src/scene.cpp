// SPDX-License-Identifier: MIT
// Scene: objects with ids, rigid groups, activities, update() without the GIL and
// the pairs' results as numpy arrays.
#include <pybind11/stl.h>

#include <array>
#include <limits>
#include <string>
#include <utility>

#include "bindings.h"

namespace scpy {
namespace {

struct PyScene {
  explicit PyScene(sc::ModelKind kind) : scene(kind) {}
  sc::Scene scene;
  bool busy = false;
  /// Each listed pair's target centres (model frame) at the last update: its results
  /// stay readable after a group is gone (removed objects) until the next update.
  std::vector<std::array<sc::Vec3, 2>> centers;

  /// The scene, after checking no update runs on another thread.
  sc::Scene& idle() {
    requireIdle(busy, "Scene");
    return scene;
  }
  const sc::PairStatus& pair(int index) {
    const auto& pairs = idle().pairs();
    if (index < 0 || index >= static_cast<int>(pairs.size())) {
      throw py::index_error("pair " + std::to_string(index) + " of " +
                            std::to_string(pairs.size()));
    }
    return pairs[static_cast<size_t>(index)];
  }
  void keepCenters();
};

template <class T>
T valueOf(const sc::Result<T>& r) {
  check(r.status());
  return r.value();
}

int direction(int d) {
  if (d != 0 && d != 1) fail(sc::ErrorCode::InvalidArgument, "direction must be 0 or 1");
  return d;
}

sc::Vec3 centerOf(PyScene& s, int gid) {
  if (gid == sc::kStaticGroup) return sc::Vec3::Zero();
  return valueOf(s.scene.groupPlacement(gid)).local_center;
}

void PyScene::keepCenters() {
  const auto& pairs = scene.pairs();
  centers.resize(pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) {
    for (int d = 0; d < 2; ++d) {
      const int gid = pairs[i].groups[d];
      const sc::Result<sc::Placement> p = scene.groupPlacement(gid);
      centers[i][d] = gid != sc::kStaticGroup && p.ok() ? p.value().local_center : sc::Vec3::Zero();
    }
  }
}

/// Rows of a (n, 2, k) array written from each direction's result.
template <class T>
py::array_t<T> perDirection(size_t n, py::ssize_t k) {
  if (k == 0) return py::array_t<T>({static_cast<py::ssize_t>(n), py::ssize_t{2}});
  return py::array_t<T>({static_cast<py::ssize_t>(n), py::ssize_t{2}, k});
}

void put(double* dst, const double* src, int k, bool ok) {
  for (int i = 0; i < k; ++i) dst[i] = ok ? src[i] : std::numeric_limits<double>::quiet_NaN();
}

py::dict resultArrays(const std::vector<sc::PairStatus>& pairs) {
  const size_t n = pairs.size();
  auto groups = perDirection<int>(n, 0), status = perDirection<int>(n, 0);
  auto direction_status = perDirection<int>(n, 0);
  auto t_obj = perDirection<int>(n, 0), o_obj = perDirection<int>(n, 0);
  auto t_piece = perDirection<int>(n, 0), o_piece = perDirection<int>(n, 0);
  auto dist = perDirection<double>(n, 0);
  py::array_t<double> vec[7] = {perDirection<double>(n, 3), perDirection<double>(n, 3),
                                perDirection<double>(n, 3), perDirection<double>(n, 3),
                                perDirection<double>(n, 3), perDirection<double>(n, 3),
                                perDirection<double>(n, 4)};
  for (size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 2; ++d) {
      const sc::DirectedResult& r = pairs[i].results[d];
      const bool ok = r.code == sc::ErrorCode::Ok;
      const auto row = static_cast<py::ssize_t>(2 * i + static_cast<size_t>(d));
      groups.mutable_data()[row] = pairs[i].groups[d];
      status.mutable_data()[row] = static_cast<int>(r.code);
      direction_status.mutable_data()[row] = static_cast<int>(r.status);
      t_obj.mutable_data()[row] = r.target_object, o_obj.mutable_data()[row] = r.opponent_object;
      t_piece.mutable_data()[row] = r.target_piece, o_piece.mutable_data()[row] = r.opponent_piece;
      put(dist.mutable_data() + row, &r.distance, 1, ok);
      const sc::Vec3* v[6] = {&r.normal, &r.point_on_target, &r.point_on_opponent, &r.tpdv,
                              &r.rpdv,   &r.contact_position};
      for (int k = 0; k < 6; ++k) put(vec[k].mutable_data() + 3 * row, v[k]->data(), 3, ok);
      const double q[4] = {r.contact_orientation.w(), r.contact_orientation.x(),
                           r.contact_orientation.y(), r.contact_orientation.z()};
      put(vec[6].mutable_data() + 4 * row, q, 4, ok);
    }
  }
  py::dict out;
  out["groups"] = groups, out["status"] = status, out["distance"] = dist;
  out["direction_status"] = direction_status;
  const char* names[7] = {"normal", "point_on_target",  "point_on_opponent",  "tpdv",
                          "rpdv",   "contact_position", "contact_orientation"};
  for (int k = 0; k < 7; ++k) out[names[k]] = vec[k];
  out["target_object"] = t_obj, out["opponent_object"] = o_obj;
  out["target_piece"] = t_piece, out["opponent_piece"] = o_piece;
  return out;
}

void bindObjects(py::class_<PyScene>& c) {
  c.def(
       "add_object",
       [](PyScene& s, int id, const PyModel& model, const PoseArg& pose,
          const OptArrayArg& center) {
         const sc::Vec3 local = vec3From(center, "center");
         sc::Placement p;
         p.local_center = local, p.world_center = local;  // identity pose
         if (!pose.value.is_none()) p = placementFrom(pose, local);
         check(s.idle().addObject(id, model.model, p));
       },
       py::arg("id"), py::arg("model"), py::arg("pose") = py::none(),
       py::arg("center") = py::none(),
       "Adds an object with the caller's id, in the static group, active. pose: world from\n"
       "model (default identity); center: its centre of rotation in the model frame.")
      .def(
          "remove_object", [](PyScene& s, int id) { check(s.idle().deleteObject(id)); },
          py::arg("id"))
      .def(
          "has_object", [](PyScene& s, int id) { return s.idle().hasObject(id); }, py::arg("id"))
      .def(
          "object_pose",
          [](PyScene& s, int id) { return poseMatrix(valueOf(s.idle().objectPlacement(id))); },
          py::arg("id"), "4x4 world-from-model matrix of an object (following its group).")
      .def(
          "group_of", [](PyScene& s, int id) { return valueOf(s.idle().groupOf(id)); },
          py::arg("id"), "The object's group id (STATIC_GROUP when in none).")
      .def(
          "set_object_activity",
          [](PyScene& s, int id, sc::Activity a) { check(s.idle().setObjectActivity(id, a)); },
          py::arg("id"), py::arg("activity"), "ACTIVE or INACTIVE.");
}

void bindGroups(py::class_<PyScene>& c) {
  c.def(
       "add_to_group",
       [](PyScene& s, int gid, int id) { check(s.idle().addObjectToGroup(gid, id)); },
       py::arg("group"), py::arg("id"),
       "Moves an object into a rigid group (created with it; its frame is its first object's),\n"
       "from the static group or another group (gone with its last object); it stays where\n"
       "it is. Its own group again: nothing changes.")
      .def(
          "remove_from_group",
          [](PyScene& s, int gid, int id) { check(s.idle().removeObjectFromGroup(gid, id)); },
          py::arg("group"), py::arg("id"), "The object stays where it is, in the static group.")
      .def(
          "has_group", [](PyScene& s, int gid) { return s.idle().hasGroup(gid); }, py::arg("group"))
      .def(
          "group_pose",
          [](PyScene& s, int gid) { return poseMatrix(valueOf(s.idle().groupPlacement(gid))); },
          py::arg("group"),
          "4x4 world-from-group matrix (the group's frame is its first object's).")
      .def(
          "set_group_pose",
          [](PyScene& s, int gid, const PoseArg& pose) {
            if (gid == sc::kStaticGroup) check(s.idle().setGroupPlacement(gid, {}));
            const sc::Placement p = placementFrom(pose, centerOf(s, gid));
            check(s.idle().setGroupPlacement(gid, p));
          },
          py::arg("group"), py::arg("pose"), "Moves a group: pose is world from group frame.")
      .def(
          "set_group_activity",
          [](PyScene& s, int gid, sc::Activity a) { check(s.idle().setGroupActivity(gid, a)); },
          py::arg("group"), py::arg("activity"),
          "ACTIVE, SLEEPING, PASSIVE or INACTIVE (manual Table 8-1).")
      .def(
          "set_pair_activity",
          [](PyScene& s, int target, int opponent, sc::PairActivity a) {
            check(s.idle().setPairActivity(target, opponent, a));
          },
          py::arg("target"), py::arg("opponent"), py::arg("activity"),
          "Overrides Table 8-1 for a group pair; ONE_WAY_* set only target -> opponent.");
}

void bindUpdate(py::class_<PyScene>& c) {
  c.def(
       "update",
       [](PyScene& s) {
         sc::Status status;
         {
           BusyScope scope(s.busy, "Scene");
           py::gil_scoped_release release;
           status = s.scene.update();
         }
         s.keepCenters();
         check(status);
         return s.scene.pairs().size();
       },
       "Computes every listed pair for the current poses (without the GIL); returns their count.")
      .def(
          "__len__", [](PyScene& s) { return s.idle().pairs().size(); },
          "Pairs of the last update.")
      .def(
          "results", [](PyScene& s) { return resultArrays(s.idle().pairs()); },
          R"(The last update's pairs as a dict of arrays, index [pair, direction]:
groups (n, 2): direction d has groups[i, d] as target (the static group is
always groups[i, 1]); status (n, 2) Status values; distance (n, 2); normal,
point_on_target, point_on_opponent, tpdv, rpdv, contact_position (n, 2, 3);
contact_orientation (n, 2, 4) w, x, y, z; target_object, opponent_object,
target_piece, opponent_piece (n, 2). Floats are NaN where status is not OK.
They stay as they were until the next update (result() and contacts() too), a
removed object's pair included.)")
      .def(
          "result",
          [](PyScene& s, int index, int d) {
            const sc::PairStatus& p = s.pair(index);
            const int dir = direction(d);  // checked before either array is read
            return resultOf(p.results[dir], s.centers[static_cast<size_t>(index)][dir]);
          },
          py::arg("index"), py::arg("direction") = 0, "One direction of one pair as a Result.")
      .def(
          "contacts",
          [](PyScene& s, int index, int d) {
            return contactArrays(s.pair(index).contacts[direction(d)]);
          },
          py::arg("index"), py::arg("direction") = 0,
          "Contacts of one direction (with settings.contact_points), as PairTracker.contacts.");
}

}  // namespace

void bindScene(py::module_& m) {
  py::class_<PyScene> c(m, "Scene",
                        R"(Objects with ids in rigid groups, moved together, queried pairwise.

Objects start in the static group (STATIC_GROUP, never moves); add_to_group makes
groups that move with set_group_pose. update() computes every group pair listed
by the activities (manual section 8) and results() gives them as arrays. Errors
raise InvalidIdError (unknown/duplicate id), InvalidOperationError (e.g. moving
the static group) or InvalidArgumentError, and change nothing.)");
  c.def(py::init<sc::ModelKind>(), py::arg("kind") = sc::ModelKind::ClosedPolyhedron)
      .def_property_readonly("kind", [](PyScene& s) { return s.idle().kind(); })
      .def_property(
          "settings", [](PyScene& s) { return s.idle().settings(); },
          [](PyScene& s, const sc::SceneSettings& v) { check(s.idle().setSettings(v)); },
          "A copy of the settings; assign a Settings to change them (validated).");
  bindObjects(c);
  bindGroups(c);
  bindUpdate(c);
}

}  // namespace scpy
