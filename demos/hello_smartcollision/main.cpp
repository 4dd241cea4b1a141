// SPDX-License-Identifier: MIT
// HelloSmartCollision (manual 10.2, List 10-1) on the real API: two unit-corner
// tetrahedra; the controlled group at {1,1,1} is sqrt(4/3) away, at {0,0,0.5} it
// penetrates by sqrt(1/12). With --check, exits non-zero unless both values are
// within 1e-9 of the exact ones.
#include <cmath>
#include <cstdio>
#include <cstring>

#include "sc.h"

namespace {

constexpr SCint kControlledGroupId = 0;

const double kVertices[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
const int kTriangles[12] = {0, 2, 1, 1, 3, 0, 0, 3, 2, 1, 2, 3};

}  // namespace

int main(int argc, char* argv[]) {
  const bool check = argc > 1 && std::strcmp(argv[1], "--check") == 0;
  SCSceneManager manager(SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
  SCObject object1(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  SCObject object2(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  const double position1[3] = {1.0, 1.0, 1.0};
  const double position2[3] = {0.0, 0.0, 0.5};
  double distance = 0.0;

  if (object1.AddTriangles(kVertices, 4, kTriangles, 4) != SC_NO_ERROR ||
      object2.AddTriangles(kVertices, 4, kTriangles, 4) != SC_NO_ERROR) {
    std::printf("Error: invalid geometry.\n");
    return 1;
  }
  manager.SetAttributeDouble(SC_SCENE_MANAGER_MAX_DISTANCE, 10.0);
  manager.SetAttributeDouble(SC_SCENE_MANAGER_TOLERANCE, 0.1);
  manager.SetAttributeInteger(SC_SCENE_MANAGER_MAX_ITERATION, 10);
  manager.AddObject(1000, &object1);
  manager.AddObject(2000, &object2);
  manager.AddObjectToGroup(kControlledGroupId, 1000);
  std::printf("Hello SmartCollision!\n");

  manager.SetTransformation(kControlledGroupId, SC_POSITION_ORIGIN, position1);
  manager.UpdateStatus();
  // One pair (controlled group, static group); the non-static group is the target.
  manager.GetStatus(SC_DISTANCE, &distance, 0, false);
  const double first = distance;
  std::printf("In position=%g,%g,%g\n", position1[0], position1[1], position1[2]);
  std::printf(" Distance=%g(=sqrt(4/3))\n", distance);

  manager.SetTransformation(kControlledGroupId, SC_POSITION_ORIGIN, position2);
  manager.UpdateStatus();
  int status_count = 0;
  manager.GetStatus(SC_STATUS_COUNT, &status_count);
  std::printf("In position=%g,%g,%g\n", position2[0], position2[1], position2[2]);
  double second = 0.0;
  for (int i = 0; i < status_count; ++i) {
    int result = 0, gids[2] = {0, 0};
    manager.GetStatus(SC_GROUP_ID, gids, i, false);
    const bool reverse = gids[0] != kControlledGroupId;
    manager.GetStatus(SC_STATUS_RESULT, &result, i, reverse);
    if (result == SC_NO_ERROR) {
      manager.GetStatus(SC_DISTANCE, &distance, i, reverse);
      // The manual's listing swaps the two labels; this is the intended reading.
      std::printf(" %s=%g(=sqrt(1/12))\n",
                  distance <= 0.0 ? "Penetration depth" : "Minimum distance", std::fabs(distance));
      second = distance;
    }
  }
  if (!check) return 0;
  const double e1 = std::fabs(first - std::sqrt(4.0 / 3.0));
  const double e2 = std::fabs(second + std::sqrt(1.0 / 12.0));
  std::printf("check: |error| = %.3g, %.3g\n", e1, e2);
  return e1 <= 1e-9 && e2 <= 1e-9 ? 0 : 1;
}
