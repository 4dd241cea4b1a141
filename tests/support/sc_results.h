// SPDX-License-Identifier: MIT
// sc.h scenes in tests: a mesh added as a piece, the scene of one moving and one
// static object, and every direction of the last UpdateStatus that has a result.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sc.h"
#include "smartcollision/mesh.h"

namespace sc::test {

/// Adds `m` to `o` as one piece through sc.h's flat arrays (`cache_file`: optional).
inline SCint addPiece(SCObject& o, const MeshData& m, const char* cache_file = nullptr) {
  std::vector<double> xyz;
  for (const Vec3& v : m.vertices) xyz.insert(xyz.end(), {v.x(), v.y(), v.z()});
  std::vector<SCint> ids;
  for (const Tri& t : m.triangles) ids.insert(ids.end(), {t[0], t[1], t[2]});
  return o.AddTriangles(xyz.data(), static_cast<SCint>(m.vertices.size()), ids.data(),
                        static_cast<SCint>(m.triangles.size()), cache_file);
}

/// `moving` (object 1) in group 0 and `fixed` (object 2) static, updated once: the
/// scene's one pair, group 0 -> static, is listed first and forward.
struct PairScene {
  SCSceneManager manager{SC_SCENE_MANAGER_CLOSED_POLYHEDRA};

  PairScene(SCObject& moving, SCObject& fixed) {
    EXPECT_EQ(manager.AddObject(1, &moving), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObject(2, &fixed), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObjectToGroup(0, 1), SC_NO_ERROR);
    EXPECT_EQ(manager.UpdateStatus(), SC_NO_ERROR);
  }

  /// The pair's distance; NaN, with a failure, when it has none.
  double distance() {
    double d = std::nan("");
    EXPECT_EQ(manager.GetStatus(SC_DISTANCE, &d, 0, false), SC_NO_ERROR);
    return d;
  }
};

/// Calls fn(index, reverse) for each direction of the last UpdateStatus whose
/// SC_STATUS_RESULT is SC_NO_ERROR.
template <class Fn>
void forEachOkDirection(SCSceneManager& scene, Fn fn) {
  SCint count = 0;
  ASSERT_EQ(scene.GetStatus(SC_STATUS_COUNT, &count), SC_NO_ERROR);
  for (SCint i = 0; i < count; ++i) {
    for (bool reverse : {false, true}) {
      SCint code = -1;
      ASSERT_EQ(scene.GetStatus(SC_STATUS_RESULT, &code, i, reverse), SC_NO_ERROR);
      if (code == SC_NO_ERROR) fn(i, reverse);
    }
  }
}

/// A double attribute of `scene`: `initial` read first, `bad` refused, `good` set and
/// read back.
inline void expectDoubleAttribute(SCSceneManager& scene, SCenum attribute, double initial,
                                  double bad, double good) {
  double value = 0.0;
  ASSERT_EQ(scene.GetAttributeDouble(attribute, &value), SC_NO_ERROR);
  EXPECT_EQ(value, initial);
  EXPECT_EQ(scene.SetAttributeDouble(attribute, bad), SC_ERROR_INVALID_ARGUMENT);
  ASSERT_EQ(scene.SetAttributeDouble(attribute, good), SC_NO_ERROR);
  ASSERT_EQ(scene.GetAttributeDouble(attribute, &value), SC_NO_ERROR);
  EXPECT_EQ(value, good);
}

}  // namespace sc::test
