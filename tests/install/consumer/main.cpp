// SPDX-License-Identifier: MIT
// Uses the installed SmartCollision through both APIs: sc.h and the modern one.
#include <cmath>
#include <cstdio>

#include "sc.h"
#include "smartcollision/smartcollision.h"

int main() {
  const double vertices[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const int triangles[12] = {0, 2, 1, 1, 3, 0, 0, 3, 2, 1, 2, 3};
  SCSceneManager manager(SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
  SCObject a(SC_OBJECT_TYPE_CLOSED_POLYHEDRON), b(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  if (a.AddTriangles(vertices, 4, triangles, 4) != SC_NO_ERROR) return 1;
  if (b.AddTriangles(vertices, 4, triangles, 4) != SC_NO_ERROR) return 1;
  manager.AddObject(1, &a);
  manager.AddObject(2, &b);
  manager.AddObjectToGroup(0, 1);
  const double origin[3] = {1, 1, 1};
  manager.SetTransformation(0, SC_POSITION_ORIGIN, origin);
  manager.UpdateStatus();
  double distance = 0;
  if (manager.GetStatus(SC_DISTANCE, &distance, 0, false) != SC_NO_ERROR) return 1;
  std::printf("distance %.9f (%s)\n", distance, SCGetErrorString(SC_NO_ERROR));

  const sc::Scene scene(sc::ModelKind::ClosedPolyhedron);
  const bool ok = std::abs(distance - std::sqrt(4.0 / 3.0)) < 1e-9 &&
                  scene.kind() == sc::ModelKind::ClosedPolyhedron;
  return ok ? 0 : 1;
}
